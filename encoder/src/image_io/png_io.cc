#include "encoder/src/image_io/png_io.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "encoder/src/image_io/byte_samples.h"
#include "encoder/src/image_io/file_bytes.h"

namespace m4d {
namespace {

// libpng reports errors through a callback that must not return: it records the message and
// longjmps back to the setjmp in RunDecode / RunEncode. Those functions keep their C++
// objects in the state structs below, so no object with a destructor lives in a frame the
// jump skips.
struct PngMessage {
  char text[200] = "";
};

[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
  auto* out = static_cast<PngMessage*>(png_get_error_ptr(png));
  std::snprintf(out->text, sizeof(out->text), "%s", message);
  png_longjmp(png, 1);
}

// Warnings are about ancillary chunks (profiles, text) that the reader does not use.
void OnPngWarning(png_structp, png_const_charp) {}

struct PngDecodeState {
  const uint8_t* data = nullptr;
  size_t size = 0;
  size_t position = 0;
  int width = 0;
  int height = 0;
  int channels = 0;
  int bytes_per_sample = 0;
  std::vector<uint8_t> samples;  // as libpng returns them: 16-bit samples big-endian
  std::vector<png_bytep> rows;
  Status refusal;  // why the reader refuses the image the header describes, if it does
};

void ReadFromMemory(png_structp png, png_bytep out, png_size_t count) {
  auto* state = static_cast<PngDecodeState*>(png_get_io_ptr(png));
  if (count > state->size - state->position) png_error(png, "file is truncated");
  std::memcpy(out, state->data + state->position, count);
  state->position += count;
}

// Sets the transforms that bring every colour type to 8- or 16-bit gray, RGB or RGBA, and
// the output shape they give.
void SetTransforms(png_structp png, png_infop info, PngDecodeState* state) {
  const int color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  const bool gray = (color_type & PNG_COLOR_MASK_COLOR) == 0;
  const bool transparency = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  const bool alpha = (color_type & PNG_COLOR_MASK_ALPHA) != 0 || transparency;
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (gray && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (transparency) png_set_tRNS_to_alpha(png);
  if (gray && alpha) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  state->width = static_cast<int>(png_get_image_width(png, info));
  state->height = static_cast<int>(png_get_image_height(png, info));
  state->channels = alpha ? 4 : (gray ? 1 : 3);
  state->bytes_per_sample = bit_depth == 16 ? 2 : 1;
}

// Returns false after a libpng error (message in the PngMessage) or a refused shape.
bool RunDecode(png_structp png, png_infop info, PngDecodeState* state) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, state, ReadFromMemory);
  // The shape check below decides; this only keeps libpng from refusing first.
  png_set_user_limits(png, PNG_UINT_31_MAX, PNG_UINT_31_MAX);
  png_read_info(png, info);
  SetTransforms(png, info, state);
  state->refusal = CheckImageShape(state->width, state->height, state->channels, "png");
  if (!state->refusal.ok()) return false;
  png_read_update_info(png, info);
  const size_t row_bytes = static_cast<size_t>(state->width) * state->channels *
                           static_cast<size_t>(state->bytes_per_sample);
  if (png_get_rowbytes(png, info) != row_bytes) png_error(png, "unexpected row layout");
  state->samples.resize(row_bytes * state->height);
  state->rows.resize(state->height);
  for (int y = 0; y < state->height; ++y) state->rows[y] = &state->samples[y * row_bytes];
  png_read_image(png, state->rows.data());
  png_read_end(png, nullptr);
  return true;
}

void SamplesToImage(const PngDecodeState& state, Image* image) {
  *image = Image(state.width, state.height, state.channels);
  const uint8_t* in = state.samples.data();
  float* out = image->pixels.data();
  const size_t n = image->pixels.size();
  if (state.bytes_per_sample == 1) {
    for (size_t i = 0; i < n; ++i) out[i] = ByteToFloat(in[i]);
  } else {
    for (size_t i = 0; i < n; ++i) {
      out[i] = static_cast<float>((in[2 * i] << 8) | in[2 * i + 1]) / 65535.0f;
    }
  }
}

struct PngEncodeState {
  std::vector<uint8_t>* bytes = nullptr;
  std::vector<uint8_t> samples;
  std::vector<png_bytep> rows;
};

void WriteToVector(png_structp png, png_bytep data, png_size_t count) {
  auto* state = static_cast<PngEncodeState*>(png_get_io_ptr(png));
  state->bytes->insert(state->bytes->end(), data, data + count);
}

void FlushNothing(png_structp) {}

bool RunEncode(png_structp png, png_infop info, const Image& image, PngEncodeState* state) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, state, WriteToVector, FlushNothing);
  const int color_type = image.channels == 1   ? PNG_COLOR_TYPE_GRAY
                         : image.channels == 3 ? PNG_COLOR_TYPE_RGB
                                               : PNG_COLOR_TYPE_RGBA;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, state->rows.data());
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

Status DecodePng(const uint8_t* data, size_t size, Image* image) {
  if (size < 8 || png_sig_cmp(data, 0, 8) != 0) {
    return Status(M4D_ERR_UNSUPPORTED, "png: not a PNG file (no PNG signature)");
  }
  PngMessage message;
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &message, OnPngError, OnPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return Status(M4D_ERR_NOMEM, "png: cannot create the decoder");
  }
  PngDecodeState state;
  state.data = data;
  state.size = size;
  const bool ok = RunDecode(png, info, &state);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!state.refusal.ok()) return state.refusal;
  if (!ok) return BitstreamError(std::string("png: ") + message.text);
  SamplesToImage(state, image);
  return Status::Ok();
}

Status ReadPng(const std::string& path, Image* image) {
  return DecodeImageFile(path, DecodePng, image);
}

Status EncodePng(const Image& image, std::vector<uint8_t>* bytes) {
  M4D_RETURN_IF_ERROR(CheckImage(image, "png"));
  PngEncodeState state;
  state.bytes = bytes;
  state.samples.resize(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) state.samples[i] = FloatToByte(image.pixels[i]);
  state.rows.resize(image.height);
  for (int y = 0; y < image.height; ++y) state.rows[y] = &state.samples[y * image.row_size()];

  PngMessage message;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &message, OnPngError, OnPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return Status(M4D_ERR_NOMEM, "png: cannot create the encoder");
  }
  bytes->clear();
  const bool ok = RunEncode(png, info, image, &state);
  png_destroy_write_struct(&png, &info);
  if (!ok) return Status(M4D_ERR_INVALID_ARG, std::string("png: ") + message.text);
  return Status::Ok();
}

Status WritePng(const std::string& path, const Image& image) {
  std::vector<uint8_t> bytes;
  M4D_RETURN_IF_ERROR(EncodePng(image, &bytes));
  return WriteFileBytes(path, bytes);
}

}  // namespace m4d
