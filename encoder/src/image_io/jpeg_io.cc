#include "encoder/src/image_io/jpeg_io.h"

#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE
#include <memory>

#include <jpeglib.h>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace {

// libjpeg reports errors through error_exit, which must not return: it records the message
// and longjmps back to the setjmp in RunDecode / RunEncode. Those functions keep their C++
// objects in the state structs below, so no object with a destructor lives in a frame the
// jump skips.
struct JpegErrorManager {
  jpeg_error_mgr pub;  // first: libjpeg only knows this part
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void OnJpegError(j_common_ptr cinfo) {
  auto* manager = reinterpret_cast<JpegErrorManager*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, manager->message);
  std::longjmp(manager->jump, 1);
}

// Level -1 is a corrupt-data warning, an error here; higher levels are traces.
void OnJpegMessage(j_common_ptr cinfo, int level) {
  if (level < 0) OnJpegError(cinfo);
}

void InitErrorManager(JpegErrorManager* manager) {
  jpeg_std_error(&manager->pub);
  manager->pub.error_exit = OnJpegError;
  manager->pub.emit_message = OnJpegMessage;
  manager->message[0] = '\0';
}

struct JpegDecodeState {
  const uint8_t* data = nullptr;
  size_t size = 0;
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<uint8_t> samples;
  Status refusal;  // why the reader refuses the image the header describes, if it does
};

// Returns false after a libjpeg error (message in the error manager) or a refused shape.
bool RunDecode(jpeg_decompress_struct* cinfo, JpegErrorManager* errors, JpegDecodeState* state) {
  if (setjmp(errors->jump)) return false;
  jpeg_create_decompress(cinfo);
  jpeg_mem_src(cinfo, state->data, state->size);
  jpeg_read_header(cinfo, TRUE);
  if (cinfo->jpeg_color_space == JCS_GRAYSCALE) {
    state->channels = 1;
  } else if (cinfo->jpeg_color_space == JCS_YCbCr || cinfo->jpeg_color_space == JCS_RGB) {
    state->channels = 3;
    cinfo->out_color_space = JCS_RGB;
  } else {
    state->refusal = Status(M4D_ERR_UNSUPPORTED, "jpeg: CMYK and YCCK are not supported");
    return false;
  }
  state->width = static_cast<int>(cinfo->image_width);
  state->height = static_cast<int>(cinfo->image_height);
  state->refusal = CheckImageShape(state->width, state->height, state->channels, "jpeg");
  if (!state->refusal.ok()) return false;
  jpeg_start_decompress(cinfo);
  const size_t row_bytes = static_cast<size_t>(state->width) * state->channels;
  if (cinfo->output_components != state->channels || cinfo->output_width != cinfo->image_width) {
    state->refusal = BitstreamError("jpeg: unexpected decoder output layout");
    return false;
  }
  state->samples.resize(row_bytes * state->height);
  while (cinfo->output_scanline < cinfo->output_height) {
    JSAMPROW row = &state->samples[cinfo->output_scanline * row_bytes];
    jpeg_read_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_decompress(cinfo);
  return true;
}

// Collects the compressed bytes in a std::vector, in 16 KiB steps.
struct VectorDestination {
  jpeg_destination_mgr pub;  // first: libjpeg only knows this part
  std::vector<uint8_t>* bytes;
  JOCTET buffer[1 << 14];
};

void InitDestination(j_compress_ptr cinfo) {
  auto* dest = reinterpret_cast<VectorDestination*>(cinfo->dest);
  dest->pub.next_output_byte = dest->buffer;
  dest->pub.free_in_buffer = sizeof(dest->buffer);
}

boolean EmptyDestination(j_compress_ptr cinfo) {
  auto* dest = reinterpret_cast<VectorDestination*>(cinfo->dest);
  dest->bytes->insert(dest->bytes->end(), dest->buffer, dest->buffer + sizeof(dest->buffer));
  InitDestination(cinfo);
  return TRUE;
}

void TermDestination(j_compress_ptr cinfo) {
  auto* dest = reinterpret_cast<VectorDestination*>(cinfo->dest);
  const size_t used = sizeof(dest->buffer) - dest->pub.free_in_buffer;
  dest->bytes->insert(dest->bytes->end(), dest->buffer, dest->buffer + used);
}

struct JpegEncodeState {
  VectorDestination destination;
  std::vector<uint8_t> samples;
};

bool RunEncode(jpeg_compress_struct* cinfo, JpegErrorManager* errors, const Image& image,
               int quality, JpegEncodeState* state) {
  if (setjmp(errors->jump)) return false;
  jpeg_create_compress(cinfo);
  cinfo->dest = &state->destination.pub;
  cinfo->image_width = static_cast<JDIMENSION>(image.width);
  cinfo->image_height = static_cast<JDIMENSION>(image.height);
  cinfo->input_components = image.channels;
  cinfo->in_color_space = image.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(cinfo);
  jpeg_set_quality(cinfo, quality, TRUE);
  for (int c = 0; c < cinfo->num_components; ++c) {
    cinfo->comp_info[c].h_samp_factor = 1;
    cinfo->comp_info[c].v_samp_factor = 1;
  }
  jpeg_start_compress(cinfo, TRUE);
  const size_t row_bytes = image.row_size();
  while (cinfo->next_scanline < cinfo->image_height) {
    JSAMPROW row = &state->samples[cinfo->next_scanline * row_bytes];
    jpeg_write_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_compress(cinfo);
  return true;
}

}  // namespace

Status DecodeJpeg(const uint8_t* data, size_t size, Image* image) {
  JpegErrorManager errors;
  InitErrorManager(&errors);
  jpeg_decompress_struct cinfo = {};
  cinfo.err = &errors.pub;
  JpegDecodeState state;
  state.data = data;
  state.size = size;
  const bool ok = RunDecode(&cinfo, &errors, &state);
  jpeg_destroy_decompress(&cinfo);
  if (!state.refusal.ok()) return state.refusal;
  if (!ok) return BitstreamError(std::string("jpeg: ") + errors.message);

  *image = Image(state.width, state.height, state.channels);
  for (size_t i = 0; i < image->pixels.size(); ++i) {
    image->pixels[i] = ByteToFloat(state.samples[i]);
  }
  return Status::Ok();
}

Status ReadJpeg(const std::string& path, Image* image) {
  return DecodeImageFile(path, DecodeJpeg, image);
}

Status EncodeJpeg(const Image& image, int quality, std::vector<uint8_t>* bytes) {
  M4D_RETURN_IF_ERROR(CheckImage(image, "jpeg"));
  if (image.channels == 4) {
    return Status(M4D_ERR_INVALID_ARG, "jpeg: no alpha channel in JPEG; convert to RGB first");
  }
  if (quality < 1 || quality > 100) {
    return Status(M4D_ERR_INVALID_ARG,
                  "jpeg: quality " + std::to_string(quality) + " not in 1..100");
  }
  auto state = std::make_unique<JpegEncodeState>();  // the 16 KiB buffer stays off the stack
  state->destination.pub.init_destination = InitDestination;
  state->destination.pub.empty_output_buffer = EmptyDestination;
  state->destination.pub.term_destination = TermDestination;
  state->destination.bytes = bytes;
  state->samples.resize(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) state->samples[i] = FloatToByte(image.pixels[i]);

  JpegErrorManager errors;
  InitErrorManager(&errors);
  jpeg_compress_struct cinfo = {};
  cinfo.err = &errors.pub;
  bytes->clear();
  const bool ok = RunEncode(&cinfo, &errors, image, quality, state.get());
  jpeg_destroy_compress(&cinfo);
  // What the checks above let through fails only on sizes libjpeg refuses (over 65500).
  if (!ok) return Status(M4D_ERR_INVALID_ARG, std::string("jpeg: ") + errors.message);
  return Status::Ok();
}

Status WriteJpeg(const std::string& path, const Image& image, int quality) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodeJpeg(image, quality, &bytes));
  return WriteFileBytes(path, bytes);
}

}  // namespace m4d
