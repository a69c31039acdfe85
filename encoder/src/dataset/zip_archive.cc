#include "encoder/src/dataset/zip_archive.h"

#include <algorithm>
#include <climits>

#include <zlib.h>

#include "encoder/src/io/little_endian_reader.h"

namespace m4d {
namespace {

constexpr uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr uint32_t kDescriptorSignature = 0x08074b50;
constexpr uint16_t kZip64ExtraId = 0x0001;
constexpr uint16_t kFlagEncrypted = 1 << 0;
constexpr uint16_t kFlagDescriptor = 1 << 3;
constexpr uint16_t kMethodStored = 0;
constexpr uint16_t kMethodDeflate = 8;
constexpr uint32_t kZip64Marker = 0xffffffff;

struct LocalEntry {
  std::string name;
  uint16_t flags = 0;
  uint16_t method = 0;
  uint32_t crc = 0;
  uint64_t compressed_size = 0;
  uint64_t size = 0;
  bool zip64 = false;
};

Status Truncated() { return BitstreamError("zip: truncated or malformed archive"); }

// Replaces 32-bit size fields marked 0xffffffff by the ZIP64 extra field's 64-bit values.
Status ParseExtra(const uint8_t* extra, size_t length, LocalEntry* entry) {
  LittleEndianReader reader(extra, length);
  while (reader.remaining() >= 4) {
    uint16_t id = 0, field_length = 0;
    const uint8_t* field;
    reader.ReadU16(&id);
    reader.ReadU16(&field_length);
    if (!reader.ReadBytes(field_length, &field)) return Truncated();
    if (id != kZip64ExtraId) continue;
    LittleEndianReader values(field, field_length);
    entry->zip64 = true;
    if (entry->size == kZip64Marker && !values.ReadU64(&entry->size)) return Truncated();
    if (entry->compressed_size == kZip64Marker && !values.ReadU64(&entry->compressed_size)) {
      return Truncated();
    }
  }
  return Status::Ok();
}

Status ReadLocalHeader(LittleEndianReader* reader, LocalEntry* entry) {
  uint16_t version, time, date, name_length, extra_length;
  uint32_t compressed_size, size;
  const uint8_t *name, *extra;
  if (!reader->ReadU16(&version) || !reader->ReadU16(&entry->flags) ||
      !reader->ReadU16(&entry->method) || !reader->ReadU16(&time) || !reader->ReadU16(&date) ||
      !reader->ReadU32(&entry->crc) || !reader->ReadU32(&compressed_size) ||
      !reader->ReadU32(&size) || !reader->ReadU16(&name_length) ||
      !reader->ReadU16(&extra_length) || !reader->ReadBytes(name_length, &name) ||
      !reader->ReadBytes(extra_length, &extra)) {
    return Truncated();
  }
  entry->name.assign(reinterpret_cast<const char*>(name), name_length);
  entry->compressed_size = compressed_size;
  entry->size = size;
  M4D_RETURN_IF_ERROR(ParseExtra(extra, extra_length, entry));
  if (entry->flags & kFlagEncrypted) return Status(M4D_ERR_UNSUPPORTED, "zip: encrypted entry");
  if (entry->method != kMethodStored && entry->method != kMethodDeflate) {
    return Status(M4D_ERR_UNSUPPORTED, "zip: compression method " + std::to_string(entry->method));
  }
  return Status::Ok();
}

// Inflates raw deflate data from `in` until the end of the stream. expected is the
// declared size, or SIZE_MAX when a data descriptor gives it only afterwards; the output
// buffer stops one byte past what is allowed, which tells "too long" from "just right".
Status Inflate(const uint8_t* in, size_t in_size, size_t expected, size_t max_size,
               std::vector<uint8_t>* out, size_t* consumed) {
  const bool known = expected != SIZE_MAX;
  const size_t limit = (known ? expected : max_size) + 1;
  z_stream stream = {};
  if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) return Status(M4D_ERR_NOMEM, "zip: zlib");
  out->resize(known ? limit : std::min<size_t>(limit, size_t{1} << 16));
  size_t in_pos = 0, out_pos = 0;
  int result = Z_OK;
  while (result != Z_STREAM_END) {
    if (out_pos == out->size()) {
      if (out->size() == limit) break;
      out->resize(std::min(limit, 2 * out->size()));
    }
    const size_t in_chunk = std::min<size_t>(in_size - in_pos, UINT_MAX);
    const size_t out_chunk = std::min<size_t>(out->size() - out_pos, UINT_MAX);
    stream.next_in = const_cast<Bytef*>(in + in_pos);
    stream.avail_in = static_cast<uInt>(in_chunk);
    stream.next_out = out->data() + out_pos;
    stream.avail_out = static_cast<uInt>(out_chunk);
    result = inflate(&stream, Z_NO_FLUSH);
    const size_t used = in_chunk - stream.avail_in, produced = out_chunk - stream.avail_out;
    in_pos += used;
    out_pos += produced;
    if (result != Z_OK && result != Z_STREAM_END && result != Z_BUF_ERROR) break;
    if (result != Z_STREAM_END && used == 0 && produced == 0 && out_pos < out->size()) {
      break;  // no progress with room to write: the input ran out
    }
  }
  inflateEnd(&stream);
  if (out_pos >= limit && !known) return LimitError("zip: entry too large");
  if (result != Z_STREAM_END) return BitstreamError("zip: corrupt or truncated deflate data");
  out->resize(out_pos);
  *consumed = in_pos;
  return Status::Ok();
}

// Reads the entry's data at the reader's position into *contents and moves past it (and
// past its data descriptor).
Status ReadEntryData(LittleEndianReader* reader, LocalEntry* entry, size_t max_size,
                     std::vector<uint8_t>* contents) {
  const bool descriptor = (entry->flags & kFlagDescriptor) != 0;
  const bool size_known = !descriptor || entry->size != 0 || entry->compressed_size != 0;
  if (!size_known && entry->method == kMethodStored) {
    return Status(M4D_ERR_UNSUPPORTED, "zip: stored entry of unknown size");
  }
  if (size_known && entry->size > max_size) return LimitError("zip: entry too large");
  // Deflate expands at most about 1032 times; a larger claim would only waste memory.
  if (size_known && entry->method == kMethodDeflate &&
      entry->size / 1100 > entry->compressed_size + 1) {
    return BitstreamError("zip: implausible entry size");
  }
  if (entry->method == kMethodStored) {
    const uint8_t* bytes;
    if (entry->compressed_size != entry->size || !reader->ReadBytes(entry->size, &bytes)) {
      return Truncated();
    }
    contents->assign(bytes, bytes + entry->size);
  } else {
    const size_t available = size_known ? entry->compressed_size : reader->remaining();
    if (available > reader->remaining()) return Truncated();
    size_t consumed = 0;
    M4D_RETURN_IF_ERROR(Inflate(reader->cursor(), available, size_known ? entry->size : SIZE_MAX,
                                max_size, contents, &consumed));
    if (size_known && (consumed != entry->compressed_size || contents->size() != entry->size)) {
      return BitstreamError("zip: entry sizes do not match its data");
    }
    reader->Skip(size_known ? entry->compressed_size : consumed);
  }
  if (descriptor) {
    // An optional signature, then the CRC and both sizes (64-bit with ZIP64).
    uint32_t first;
    if (!reader->ReadU32(&first)) return Truncated();
    if (first == kDescriptorSignature && !reader->ReadU32(&first)) return Truncated();
    if (!size_known) entry->crc = first;
    if (!reader->Skip(entry->zip64 ? 16 : 8)) return Truncated();
  }
  return Status::Ok();
}

}  // namespace

Status ReadZipEntry(const uint8_t* data, size_t size, const std::string& name, size_t max_size,
                    std::vector<uint8_t>* contents) {
  LittleEndianReader reader(data, size);
  std::vector<uint8_t> skipped;
  while (true) {
    uint32_t signature;
    // The central directory (or the end) follows the last local entry.
    if (!reader.ReadU32(&signature) || signature != kLocalHeaderSignature) break;
    LocalEntry entry;
    M4D_RETURN_IF_ERROR(ReadLocalHeader(&reader, &entry));
    const bool wanted = entry.name == name;
    std::vector<uint8_t>* target = wanted ? contents : &skipped;
    if (!wanted && !(entry.flags & kFlagDescriptor)) {
      // The size is known: jump over the data without decompressing it.
      if (!reader.Skip(entry.compressed_size)) return Truncated();
      continue;
    }
    M4D_RETURN_IF_ERROR(ReadEntryData(&reader, &entry, max_size, target));
    if (!wanted) continue;
    const uLong crc = crc32_z(crc32(0, Z_NULL, 0), contents->data(), contents->size());
    if (crc != entry.crc) return BitstreamError("zip: CRC mismatch in '" + name + "'");
    return Status::Ok();
  }
  return Status(M4D_ERR_INVALID_ARG, "zip: no entry '" + name + "'");
}

}  // namespace m4d
