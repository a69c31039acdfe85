// AdamOptimizer: Adam (Kingma and Ba) as the reference 3DGS trains with it (PyTorch's
// update, betas 0.9 / 0.999, epsilon 1e-15), over parameters stored as rows of floats (one
// row per Gaussian). Learning rates belong to groups, each a column range of one parameter
// (the SH DC and the higher bands of the SH array have different rates); a group can be
// frozen. Moments are kept per row so that densification can append and remove rows, and
// the step count per group as in PyTorch, where it survives those edits.
#ifndef M4D_ENCODER_TRAIN_ADAM_OPTIMIZER_H_
#define M4D_ENCODER_TRAIN_ADAM_OPTIMIZER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sdk/src/common/thread_pool.h"

namespace m4d {

// In double like PyTorch's hyperparameters; 1 - beta is rounded to float once.
struct AdamSettings {
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-15;
};

class AdamOptimizer {
 public:
  explicit AdamOptimizer(const AdamSettings& settings = AdamSettings()) : settings_(settings) {}

  // Registers a parameter of `width` floats per row (with rows() zero rows of moments);
  // returns its index.
  int AddParameter(int width);
  // Registers a group: columns [first_column, first_column + column_count) of `parameter`,
  // stepped with learning rate lr. Returns its index.
  int AddGroup(std::string name, int parameter, int first_column, int column_count, float lr);

  int group_count() const { return static_cast<int>(groups_.size()); }
  const std::string& group_name(int group) const { return groups_[group].name; }
  // The group of that name, or -1.
  int FindGroup(const std::string& name) const;
  float learning_rate(int group) const { return groups_[group].lr; }
  void SetLearningRate(int group, float lr) { groups_[group].lr = lr; }
  bool frozen(int group) const { return groups_[group].frozen; }
  void SetFrozen(int group, bool frozen) { groups_[group].frozen = frozen; }
  // Steps taken by the group (PyTorch's bias-correction step).
  int64_t step_count(int group) const { return groups_[group].steps; }

  size_t rows() const { return rows_; }
  // Sets the row count; new rows get zero moments.
  void ResizeRows(size_t rows);
  // Row edits that follow the model's (row_edit.h). New rows start with zero moments, as
  // the reference gives its densified Gaussians.
  void AppendZeroRows(size_t count);
  void KeepRows(const std::vector<uint8_t>& keep);
  // Zeroes every parameter's moments of the listed rows (a relocated Gaussian starts afresh).
  void ZeroRows(const std::vector<uint32_t>& rows);
  // Zeroes the moments of a parameter (the reference does so when it resets opacities).
  void ResetMoments(int parameter);

  // One step of every unfrozen group of `parameter`: values and gradients hold rows() rows
  // of its width. pool may be null (runs inline); results do not depend on it.
  void Step(int parameter, float* values, const float* gradients, ThreadPool* pool);

  const std::vector<float>& first_moment(int parameter) const { return params_[parameter].m; }
  const std::vector<float>& second_moment(int parameter) const { return params_[parameter].v; }

 private:
  struct Parameter {
    int width = 0;
    std::vector<float> m, v;
  };
  struct Group {
    std::string name;
    int parameter = 0;
    int first_column = 0;
    int column_count = 0;
    float lr = 0;
    bool frozen = false;
    int64_t steps = 0;
  };

  void StepGroup(Group* group, float* values, const float* gradients, ThreadPool* pool);

  AdamSettings settings_;
  size_t rows_ = 0;
  std::vector<Parameter> params_;
  std::vector<Group> groups_;
};

}  // namespace m4d

#endif  // M4D_ENCODER_TRAIN_ADAM_OPTIMIZER_H_
