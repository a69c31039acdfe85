#include "encoder/src/dataset/file_listing.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace m4d {
namespace {

bool IsDigit(char c) { return c >= '0' && c <= '9'; }

size_t RunEnd(const std::string& s, size_t i) {
  while (i < s.size() && IsDigit(s[i])) ++i;
  return i;
}

// The start of the run [i, end) without leading zeros (keeping one digit of "000").
size_t SkipZeros(const std::string& s, size_t i, size_t end) {
  while (i + 1 < end && s[i] == '0') ++i;
  return i;
}

std::string LowerExtension(const std::string& name) {
  const size_t dot = name.rfind('.');
  std::string extension = dot == std::string::npos ? "" : name.substr(dot + 1);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

}  // namespace

bool IsDirectory(const std::string& path) {
  std::error_code error;
  return std::filesystem::is_directory(path, error);
}

bool IsRegularFile(const std::string& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

bool FrameNameLess(const std::string& a, const std::string& b) {
  // Natural order: digit runs compare as numbers, everything else character by character.
  // A non-digit sorts against a run as against the run's first digit, which keeps this a
  // strict weak ordering since the digits are contiguous in the character set.
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (IsDigit(a[i]) && IsDigit(b[j])) {
      const size_t run_a = RunEnd(a, i), run_b = RunEnd(b, j);
      const size_t za = SkipZeros(a, i, run_a), zb = SkipZeros(b, j, run_b);
      if (run_a - za != run_b - zb) return run_a - za < run_b - zb;
      const int order = a.compare(za, run_a - za, b, zb, run_b - zb);
      if (order != 0) return order < 0;
      i = run_a;
      j = run_b;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if ((a.size() - i == 0) != (b.size() - j == 0)) return a.size() - i == 0;
  return a < b;  // equal but for leading zeros
}

Status ListDirectory(const std::string& dir, EntryKind kind, std::vector<std::string>* names) {
  names->clear();
  std::error_code error;
  std::filesystem::directory_iterator it(dir, error), end;
  for (; !error && it != end; it.increment(error)) {
    std::error_code type_error;
    const bool is_dir = it->is_directory(type_error);
    const bool is_file = it->is_regular_file(type_error);
    if (kind == EntryKind::kDirectories ? is_dir : is_file) {
      names->push_back(it->path().filename().string());
    }
  }
  if (error) {
    return Status(M4D_ERR_INVALID_ARG, "cannot list '" + dir + "': " + error.message());
  }
  std::sort(names->begin(), names->end(), FrameNameLess);
  return Status::Ok();
}

Status ListImageFiles(const std::string& dir, std::vector<std::string>* names) {
  M4D_RETURN_IF_ERROR(ListDirectory(dir, EntryKind::kFiles, names));
  names->erase(std::remove_if(names->begin(), names->end(),
                              [](const std::string& name) {
                                const std::string e = LowerExtension(name);
                                return e != "png" && e != "jpg" && e != "jpeg";
                              }),
               names->end());
  return Status::Ok();
}

}  // namespace m4d
