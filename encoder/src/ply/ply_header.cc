#include "encoder/src/ply/ply_header.h"

#include <cstring>
#include <sstream>

namespace m4d {
namespace {

constexpr size_t kMaxHeaderBytes = size_t{1} << 20;
constexpr size_t kMaxElements = 256;
constexpr size_t kMaxProperties = 4096;

struct TypeName {
  const char* name;
  PlyType type;
};

// Both spellings of each type, from the original PLY description and its later revision.
constexpr TypeName kTypeNames[] = {
    {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
    {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
    {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
    {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
    {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
    {"float64", PlyType::kFloat64}};

bool ParseType(const std::string& name, PlyType* type) {
  for (const TypeName& entry : kTypeNames) {
    if (name == entry.name) {
      *type = entry.type;
      return true;
    }
  }
  return false;
}

bool IsIntegerType(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

Status Malformed(const std::string& line) {
  return BitstreamError("ply: malformed header line '" + line.substr(0, 80) + "'");
}

Status ParseFormat(std::istringstream& words, const std::string& line, PlyFormat* format) {
  std::string name, version, extra;
  if (!(words >> name >> version) || (words >> extra)) return Malformed(line);
  if (version != "1.0") return Status(M4D_ERR_UNSUPPORTED, "ply: format version " + version);
  if (name == "ascii") {
    *format = PlyFormat::kAscii;
  } else if (name == "binary_little_endian") {
    *format = PlyFormat::kBinaryLittleEndian;
  } else if (name == "binary_big_endian") {
    *format = PlyFormat::kBinaryBigEndian;
  } else {
    return Status(M4D_ERR_UNSUPPORTED, "ply: format " + name);
  }
  return Status::Ok();
}

Status ParseElement(std::istringstream& words, const std::string& line, PlyElement* element) {
  std::string count, extra;
  if (!(words >> element->name >> count) || (words >> extra)) return Malformed(line);
  // Digits only: no sign, no exponent, at most 19 digits so the value fits 64 bits.
  if (count.empty() || count.size() > 19 ||
      count.find_first_not_of("0123456789") != std::string::npos) {
    return Malformed(line);
  }
  element->count = std::stoull(count);
  return Status::Ok();
}

Status ParseProperty(std::istringstream& words, const std::string& line, PlyProperty* property) {
  std::string type, extra;
  if (!(words >> type)) return Malformed(line);
  if (type == "list") {
    std::string count_type, item_type;
    if (!(words >> count_type >> item_type)) return Malformed(line);
    property->is_list = true;
    if (!ParseType(count_type, &property->count_type) || !IsIntegerType(property->count_type) ||
        !ParseType(item_type, &property->type)) {
      return Malformed(line);
    }
  } else if (!ParseType(type, &property->type)) {
    return Malformed(line);
  }
  if (!(words >> property->name) || (words >> extra)) return Malformed(line);
  return Status::Ok();
}

Status ParseLine(const std::string& line, bool* saw_format, PlyHeader* header) {
  std::istringstream words(line);
  std::string keyword;
  if (!(words >> keyword)) return Malformed(line);  // blank lines are not allowed either
  if (keyword == "comment" || keyword == "obj_info") return Status::Ok();
  if (keyword == "format") {
    if (*saw_format) return Malformed(line);
    *saw_format = true;
    return ParseFormat(words, line, &header->format);
  }
  if (keyword == "element") {
    if (!*saw_format) return BitstreamError("ply: element before the format line");
    if (header->elements.size() >= kMaxElements) return LimitError("ply: too many elements");
    header->elements.emplace_back();
    return ParseElement(words, line, &header->elements.back());
  }
  if (keyword == "property") {
    if (header->elements.empty()) return Malformed(line);
    PlyElement& element = header->elements.back();
    if (element.properties.size() >= kMaxProperties) return LimitError("ply: too many properties");
    PlyProperty property;
    M4D_RETURN_IF_ERROR(ParseProperty(words, line, &property));
    if (element.Find(property.name) >= 0) {
      return BitstreamError("ply: property '" + property.name + "' declared twice");
    }
    element.properties.push_back(property);
    return Status::Ok();
  }
  return Malformed(line);
}

}  // namespace

int PlyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

const char* PlyTypeName(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
      return "char";
    case PlyType::kUint8:
      return "uchar";
    case PlyType::kInt16:
      return "short";
    case PlyType::kUint16:
      return "ushort";
    case PlyType::kInt32:
      return "int";
    case PlyType::kUint32:
      return "uint";
    case PlyType::kFloat32:
      return "float";
    case PlyType::kFloat64:
      return "double";
  }
  return "";
}

int PlyElement::Find(const std::string& property) const {
  for (size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property) return static_cast<int>(i);
  }
  return -1;
}

int PlyHeader::Find(const std::string& element) const {
  for (size_t i = 0; i < elements.size(); ++i) {
    if (elements[i].name == element) return static_cast<int>(i);
  }
  return -1;
}

Status ParsePlyHeader(const uint8_t* data, size_t size, PlyHeader* header) {
  *header = PlyHeader();
  if (size < 4 || std::memcmp(data, "ply", 3) != 0 || (data[3] != '\n' && data[3] != '\r')) {
    return Status(M4D_ERR_UNSUPPORTED, "ply: not a PLY file");
  }
  const size_t limit = size < kMaxHeaderBytes ? size : kMaxHeaderBytes;
  size_t pos = data[3] == '\r' && size > 4 && data[4] == '\n' ? 5 : 4;
  bool saw_format = false;
  while (true) {
    const void* newline = std::memchr(data + pos, '\n', limit - pos);
    if (!newline) {
      return size > kMaxHeaderBytes ? LimitError("ply: header larger than 1 MiB")
                                    : BitstreamError("ply: header without end_header");
    }
    const size_t end = static_cast<const uint8_t*>(newline) - data;
    std::string line(reinterpret_cast<const char*>(data + pos), end - pos);
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find('\0') != std::string::npos) return BitstreamError("ply: NUL in header");
    if (line == "end_header") break;
    M4D_RETURN_IF_ERROR(ParseLine(line, &saw_format, header));
  }
  if (!saw_format) return BitstreamError("ply: header without a format line");
  header->data_offset = pos;
  return Status::Ok();
}

}  // namespace m4d
