// Row edits of per-Gaussian arrays (width values per Gaussian). Densification and pruning
// append copies of rows and remove rows; every per-Gaussian array (parameters, optimizer
// moments, densification statistics) goes through the same edit so that rows stay aligned.
#ifndef M4D_ENCODER_TRAIN_ROW_EDIT_H_
#define M4D_ENCODER_TRAIN_ROW_EDIT_H_

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace m4d {

// Appends a copy of each listed row, in list order.
template <typename T>
void AppendRowCopies(const std::vector<uint32_t>& rows, size_t width, std::vector<T>* values) {
  const size_t old_size = values->size();
  values->resize(old_size + rows.size() * width);
  T* data = values->data();
  for (size_t r = 0; r < rows.size(); ++r) {
    std::copy_n(data + rows[r] * width, width, data + old_size + r * width);
  }
}

// Appends `count` rows of zeros.
template <typename T>
void AppendZeroRows(size_t count, size_t width, std::vector<T>* values) {
  values->resize(values->size() + count * width, T{});
}

// Keeps the rows r with keep[r] != 0, in order (keep has one entry per row).
template <typename T>
void KeepRows(const std::vector<uint8_t>& keep, size_t width, std::vector<T>* values) {
  T* data = values->data();
  size_t out = 0;
  for (size_t r = 0; r < keep.size(); ++r) {
    if (!keep[r]) continue;
    if (out != r) std::copy_n(data + r * width, width, data + out * width);
    ++out;
  }
  values->resize(out * width);
}

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_ROW_EDIT_H_
