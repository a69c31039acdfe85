#include "encoder/src/dataset/npy_array.h"

#include <cstring>

#include "encoder/src/image_io/file_bytes.h"
#include "encoder/src/io/little_endian_reader.h"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "npy export assumes a little-endian host");

namespace m4d {
namespace {

constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;
constexpr size_t kMaxHeaderBytes = size_t{1} << 20;
constexpr size_t kMaxDimensions = 8;

struct NpyHeader {
  std::string descr;
  bool fortran_order = false;
  bool has_descr = false, has_order = false, has_shape = false;
  std::vector<size_t> shape;
};

// A recursive-descent reader for the Python dict literal of a .npy header.
class HeaderParser {
 public:
  explicit HeaderParser(const std::string& text) : text_(text) {}

  Status Parse(NpyHeader* header) {
    if (!Consume('{')) return Malformed();
    while (!Consume('}')) {
      std::string key;
      if (!ReadString(&key) || !Consume(':')) return Malformed();
      if (key == "descr") {
        if (!ReadString(&header->descr)) return Malformed();
        header->has_descr = true;
      } else if (key == "fortran_order") {
        if (!ReadBool(&header->fortran_order)) return Malformed();
        header->has_order = true;
      } else if (key == "shape") {
        M4D_RETURN_IF_ERROR(ReadShape(&header->shape));
        header->has_shape = true;
      } else {
        return BitstreamError("npy: unknown header key '" + key + "'");
      }
      if (!Consume(',') && !Peek('}')) return Malformed();
    }
    SkipSpace();
    if (pos_ != text_.size()) return Malformed();
    if (!header->has_descr || !header->has_order || !header->has_shape) {
      return BitstreamError("npy: header lacks descr, fortran_order or shape");
    }
    return Status::Ok();
  }

 private:
  static Status Malformed() { return BitstreamError("npy: malformed header"); }

  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n')) ++pos_;
  }
  bool Peek(char c) {
    SkipSpace();
    return pos_ < text_.size() && text_[pos_] == c;
  }
  bool Consume(char c) {
    if (!Peek(c)) return false;
    ++pos_;
    return true;
  }
  bool ReadString(std::string* s) {
    SkipSpace();
    if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) return false;
    const char quote = text_[pos_++];
    const size_t end = text_.find(quote, pos_);
    if (end == std::string::npos) return false;
    *s = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return true;
  }
  bool ReadBool(bool* b) {
    SkipSpace();
    for (const char* word : {"True", "False"}) {
      const size_t n = std::strlen(word);
      if (text_.compare(pos_, n, word) == 0) {
        *b = word[0] == 'T';
        pos_ += n;
        return true;
      }
    }
    return false;
  }
  Status ReadShape(std::vector<size_t>* shape) {
    if (!Consume('(')) return Malformed();
    while (!Consume(')')) {
      SkipSpace();
      size_t value = 0;
      int digits = 0;
      while (pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '9') {
        if (++digits > 12) return LimitError("npy: dimension too large");
        value = value * 10 + static_cast<size_t>(text_[pos_++] - '0');
      }
      if (digits == 0) return Malformed();
      if (shape->size() >= kMaxDimensions) return LimitError("npy: more than 8 dimensions");
      shape->push_back(value);
      if (!Consume(',') && !Peek(')')) return Malformed();
    }
    return Status::Ok();
  }

  const std::string& text_;
  size_t pos_ = 0;
};

}  // namespace

Status ParseNpy(const uint8_t* data, size_t size, NpyArray* array) {
  LittleEndianReader reader(data, size);
  const uint8_t* magic;
  uint8_t major, minor;
  if (!reader.ReadBytes(kMagicSize, &magic) || std::memcmp(magic, kMagic, kMagicSize) != 0 ||
      !reader.ReadU8(&major) || !reader.ReadU8(&minor)) {
    return Status(M4D_ERR_UNSUPPORTED, "npy: not a .npy file");
  }
  if (major < 1 || major > 3) {
    return Status(M4D_ERR_UNSUPPORTED, "npy: format version " + std::to_string(major));
  }
  uint32_t header_length = 0;
  uint16_t short_length;
  if (major == 1 ? !reader.ReadU16(&short_length) : !reader.ReadU32(&header_length)) {
    return BitstreamError("npy: truncated header");
  }
  if (major == 1) header_length = short_length;
  if (header_length > kMaxHeaderBytes) return LimitError("npy: header larger than 1 MiB");
  const uint8_t* text;
  if (!reader.ReadBytes(header_length, &text)) return BitstreamError("npy: truncated header");

  NpyHeader header;
  const std::string header_text(reinterpret_cast<const char*>(text), header_length);
  M4D_RETURN_IF_ERROR(HeaderParser(header_text).Parse(&header));
  if (header.descr != "<f4" && header.descr != "<f8") {
    return Status(M4D_ERR_UNSUPPORTED, "npy: dtype '" + header.descr + "' (need <f4 or <f8)");
  }
  if (header.fortran_order) return Status(M4D_ERR_UNSUPPORTED, "npy: Fortran order");
  const size_t item = header.descr == "<f4" ? 4 : 8;
  size_t count = 1;
  for (size_t dimension : header.shape) {
    if (dimension != 0 && count > kMaxNpyBytes / item / dimension) {
      return LimitError("npy: array larger than 1 GiB");
    }
    count *= dimension;
  }
  if (reader.remaining() != count * item) {
    return BitstreamError("npy: data size does not match the shape");
  }
  array->shape = header.shape;
  array->values.resize(count);
  for (size_t i = 0; i < count; ++i) {
    if (item == 4) {
      float v;
      reader.ReadF32(&v);
      array->values[i] = v;
    } else {
      reader.ReadF64(&array->values[i]);
    }
  }
  return Status::Ok();
}

Status ReadNpyFile(const std::string& path, NpyArray* array) {
  std::vector<uint8_t> bytes;
  Status status = ReadFileBytes(path, kMaxNpyBytes + kMaxHeaderBytes, &bytes);
  if (status.ok()) status = ParseNpy(bytes.data(), bytes.size(), array);
  if (status.ok()) return status;
  return Status(status.code(), status.message() + " (" + path + ")");
}

Status EncodeNpy(const std::vector<size_t>& shape, const std::vector<double>& values,
                 std::vector<uint8_t>* bytes) {
  size_t count = 1;
  for (size_t dimension : shape) count *= dimension;
  if (count != values.size()) return Status(M4D_ERR_INVALID_ARG, "npy: shape does not match");
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (";
  for (size_t dimension : shape) dict += std::to_string(dimension) + ", ";
  if (!shape.empty()) dict.resize(dict.size() - (shape.size() == 1 ? 1 : 2));
  dict += "), }";
  // The header is padded with spaces and a newline so the data starts 64-byte aligned.
  const size_t unpadded = kMagicSize + 4 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  bytes->assign(kMagic, kMagic + kMagicSize);
  bytes->insert(bytes->end(), {1, 0, static_cast<uint8_t>(dict.size() & 0xff),
                               static_cast<uint8_t>(dict.size() >> 8)});
  bytes->insert(bytes->end(), dict.begin(), dict.end());
  const size_t start = bytes->size();
  bytes->resize(start + 8 * count);
  std::memcpy(bytes->data() + start, values.data(), 8 * count);
  return Status::Ok();
}

}  // namespace m4d
