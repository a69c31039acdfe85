#include "encoder/src/train/adam_optimizer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "encoder/src/train/row_edit.h"

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

void AdamOptimizer::ZeroRows(const std::vector<uint32_t>& rows) {
  for (Parameter& p : params_) {
    const size_t width = static_cast<size_t>(p.width);
    for (uint32_t r : rows) {
      std::fill_n(p.m.begin() + static_cast<std::ptrdiff_t>(r * width), width, 0.0f);
      std::fill_n(p.v.begin() + static_cast<std::ptrdiff_t>(r * width), width, 0.0f);
    }
  }
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

namespace {

struct AdamConstants {
  float b1, b2, c1, c2;  // betas and 1 - betas
  float step_size;       // lr / (1 - beta1^t)
  float inv_bias2_sqrt;  // 1 / sqrt(1 - beta2^t)
  float eps;
};

// The update of a contiguous span; restrict-qualified so that it vectorises.
void AdamSpan(const AdamConstants& k, size_t count, const float* __restrict__ gradients,
              float* __restrict__ values, float* __restrict__ m, float* __restrict__ v) {
  for (size_t i = 0; i < count; ++i) {
    const float g = gradients[i];
    const float mi = k.b1 * m[i] + k.c1 * g;
    const float vi = k.b2 * v[i] + k.c2 * g * g;
    m[i] = mi;
    v[i] = vi;
    values[i] -= k.step_size * mi / (std::sqrt(vi) * k.inv_bias2_sqrt + k.eps);
  }
}

}  // namespace

void AdamOptimizer::StepGroup(Group* group, float* values, const float* gradients,
                              ThreadPool* pool) {
  ++group->steps;
  // PyTorch's Adam: p -= lr / (1 - b1^t) * m / (sqrt(v) / sqrt(1 - b2^t) + eps).
  const double t = static_cast<double>(group->steps);
  const double beta1 = settings_.beta1, beta2 = settings_.beta2;
  AdamConstants k;
  k.b1 = static_cast<float>(beta1);
  k.b2 = static_cast<float>(beta2);
  k.c1 = static_cast<float>(1.0 - beta1);
  k.c2 = static_cast<float>(1.0 - beta2);
  k.step_size = static_cast<float>(group->lr / (1.0 - std::pow(beta1, t)));
  k.inv_bias2_sqrt = static_cast<float>(1.0 / std::sqrt(1.0 - std::pow(beta2, t)));
  k.eps = static_cast<float>(settings_.epsilon);
  Parameter& p = params_[group->parameter];
  const size_t width = static_cast<size_t>(p.width);
  const size_t first = static_cast<size_t>(group->first_column);
  const size_t columns = static_cast<size_t>(group->column_count);
  float* m = p.m.data();
  float* v = p.v.data();
  // A group spanning whole rows is one contiguous span per task; others go row by row.
  auto update = [&](size_t begin, size_t end, int) {
    if (columns == width) {
      const size_t a = begin * width, count = (end - begin) * width;
      AdamSpan(k, count, gradients + a, values + a, m + a, v + a);
      return;
    }
    for (size_t r = begin; r < end; ++r) {
      const size_t a = r * width + first;
      AdamSpan(k, columns, gradients + a, values + a, m + a, v + a);
    }
  };
  // Fixed task boundaries: the same split whatever the pool.
  constexpr size_t kRowsPerTask = 8192;
  if (pool == nullptr || rows_ <= kRowsPerTask) {
    update(0, rows_, 0);
  } else {
    ParallelForChunks(pool, rows_, kRowsPerTask, update);
  }
}

}  // namespace m4d
