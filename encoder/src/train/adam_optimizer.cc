#include "train/adam_optimizer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "train/row_edit.h"

namespace m4d {

int AdamOptimizer::AddParameter(int width) {
  Parameter p;
  p.width = width;
  p.m.assign(rows_ * width, 0.0f);
  p.v.assign(rows_ * width, 0.0f);
  params_.push_back(std::move(p));
  return static_cast<int>(params_.size()) - 1;
}

int AdamOptimizer::AddGroup(std::string name, int parameter, int first_column, int column_count,
                            float lr) {
  Group g;
  g.name = std::move(name);
  g.parameter = parameter;
  g.first_column = first_column;
  g.column_count = column_count;
  g.lr = lr;
  groups_.push_back(std::move(g));
  return static_cast<int>(groups_.size()) - 1;
}

int AdamOptimizer::FindGroup(const std::string& name) const {
  for (size_t g = 0; g < groups_.size(); ++g) {
    if (groups_[g].name == name) return static_cast<int>(g);
  }
  return -1;
}

void AdamOptimizer::ResizeRows(size_t rows) {
  for (Parameter& p : params_) {
    p.m.resize(rows * p.width, 0.0f);
    p.v.resize(rows * p.width, 0.0f);
  }
  rows_ = rows;
}

void AdamOptimizer::AppendZeroRows(size_t count) {
  for (Parameter& p : params_) {
    m4d::AppendZeroRows(count, p.width, &p.m);
    m4d::AppendZeroRows(count, p.width, &p.v);
  }
  rows_ += count;
}

void AdamOptimizer::KeepRows(const std::vector<uint8_t>& keep) {
  for (Parameter& p : params_) {
    m4d::KeepRows(keep, p.width, &p.m);
    m4d::KeepRows(keep, p.width, &p.v);
  }
  rows_ = static_cast<size_t>(std::count(keep.begin(), keep.end(), uint8_t{1}));
}

void AdamOptimizer::ResetMoments(int parameter) {
  Parameter& p = params_[parameter];
  std::fill(p.m.begin(), p.m.end(), 0.0f);
  std::fill(p.v.begin(), p.v.end(), 0.0f);
}

void AdamOptimizer::Step(int parameter, float* values, const float* gradients, ThreadPool* pool) {
  for (Group& g : groups_) {
    if (g.parameter == parameter && !g.frozen) StepGroup(&g, values, gradients, pool);
  }
}

void AdamOptimizer::StepGroup(Group* group, float* values, const float* gradients,
                              ThreadPool* pool) {
  ++group->steps;
  // PyTorch's Adam: p -= lr / (1 - b1^t) * m / (sqrt(v) / sqrt(1 - b2^t) + eps).
  const double t = static_cast<double>(group->steps);
  const double beta1 = settings_.beta1, beta2 = settings_.beta2;
  const float b1 = static_cast<float>(beta1), b2 = static_cast<float>(beta2);
  const float c1 = static_cast<float>(1.0 - beta1), c2 = static_cast<float>(1.0 - beta2);
  const float eps = static_cast<float>(settings_.epsilon);
  const float step_size = static_cast<float>(group->lr / (1.0 - std::pow(beta1, t)));
  const float inv_bias2_sqrt = static_cast<float>(1.0 / std::sqrt(1.0 - std::pow(beta2, t)));
  Parameter& p = params_[group->parameter];
  const size_t width = static_cast<size_t>(p.width);
  const size_t first = static_cast<size_t>(group->first_column);
  const size_t columns = static_cast<size_t>(group->column_count);
  float* m = p.m.data();
  float* v = p.v.data();
  auto update = [=](size_t begin, size_t end, int) {
    for (size_t r = begin; r < end; ++r) {
      const size_t base = r * width + first;
      for (size_t c = base; c < base + columns; ++c) {
        const float g = gradients[c];
        m[c] = b1 * m[c] + c1 * g;
        v[c] = b2 * v[c] + c2 * g * g;
        values[c] -= step_size * m[c] / (std::sqrt(v[c]) * inv_bias2_sqrt + eps);
      }
    }
  };
  constexpr size_t kRowsPerTask = 8192;
  if (pool == nullptr || rows_ <= kRowsPerTask) {
    update(0, rows_, 0);
  } else {
    ParallelForChunks(pool, rows_, kRowsPerTask, update);
  }
}

}  // namespace m4d
