#include "encoder/src/metrics/ssim.h"

#include <cstddef>

#include "encoder/src/metrics/gaussian_filter.h"
#include "encoder/src/metrics/parallel_rows.h"

// The gradient. With m = G*x, e_xx = G*(x^2), e_xy = G*(x y) at each pixel p, SSIM(p) =
// A1 A2 / (B1 B2) where A1 = 2 m m_y + C1, A2 = 2 (e_xy - m m_y) + C2, B1 = m^2 + m_y^2 + C1,
// B2 = e_xx - m^2 + e_yy - m_y^2 + C2. Its partial derivatives are
//   dS/dm    = (2 m_y (A2 - A1) - 2 m S (B2 - B1)) / (B1 B2),
//   dS/de_xx = -S / B2,
//   dS/de_xy = 2 A1 / (B1 B2).
// Each of m, e_xx, e_xy at p is sum_q G(p - q) f(x(q)), so for the mean over N samples
//   d(mean SSIM)/dx(q) = (1/N) [ (G*dS/dm)(q) + 2 x(q) (G*dS/de_xx)(q) + y(q) (G*dS/de_xy)(q) ]
// where G* is again the zero-padded filter: the adjoint of a zero-padded filter is the
// zero-padded filter with the flipped window, and the window is symmetric.
//
// Each output row is filtered vertically first, straight from the 11 input rows around it,
// then horizontally within the row: the filtered moments never leave the cache, and only the
// three partial-derivative planes of the gradient go through memory.

namespace m4d {
namespace {

enum Moment { kMuX, kMuY, kXX, kYY, kXY, kMoments };
enum Partial { kDMu, kDXX, kDXY, kPartials };

// Vertical pass of x, y, x^2, y^2 and x y over gathered rows of x and y.
void FilterMomentRows(const float* const xs[kGaussianTaps], const float* const ys[kGaussianTaps],
                      size_t n, float* __restrict mu_x, float* __restrict mu_y,
                      float* __restrict e_xx, float* __restrict e_yy, float* __restrict e_xy) {
  const std::array<float, kGaussianTaps>& g = GaussianWindow();
  for (size_t i = 0; i < n; ++i) {
    float mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
    for (int k = 0; k < kGaussianTaps; ++k) {
      const float a = xs[k][i], b = ys[k][i];
      mx += g[k] * a;
      my += g[k] * b;
      xx += g[k] * (a * a);
      yy += g[k] * (b * b);
      xy += g[k] * (a * b);
    }
    mu_x[i] = mx;
    mu_y[i] = my;
    e_xx[i] = xx;
    e_yy[i] = yy;
    e_xy[i] = xy;
  }
}

// The SSIM map at sample i of a row from its filtered moments m, and its partial derivatives
// (see above). Inlined into both callers; the one that drops the derivatives loses them.
inline float SsimPixel(const float* const* m, size_t i, float* d_mu, float* d_xx, float* d_xy) {
  const float mx = m[kMuX][i], my = m[kMuY][i];
  const float a1 = 2.0f * mx * my + kSsimC1;
  const float a2 = 2.0f * (m[kXY][i] - mx * my) + kSsimC2;
  const float b1 = mx * mx + my * my + kSsimC1;
  const float b2 = (m[kXX][i] - mx * mx) + (m[kYY][i] - my * my) + kSsimC2;
  const float inv = 1.0f / (b1 * b2);
  const float s = a1 * a2 * inv;
  *d_mu = (2.0f * my * (a2 - a1) - 2.0f * mx * s * (b2 - b1)) * inv;
  *d_xx = -s / b2;
  *d_xy = 2.0f * a1 * inv;
  return s;
}

// Row buffers of one thread: zeros for rows outside the image, rows padded for the
// horizontal pass, and filtered rows.
class RowScratch {
 public:
  RowScratch(size_t row_size, size_t margin, int padded_rows, int rows)
      : row_size_(row_size),
        padded_size_(row_size + 2 * margin),
        margin_(margin),
        padded_rows_(padded_rows),
        buffer_(row_size + padded_rows * padded_size_ + rows * row_size, 0.0f) {}

  const float* zeros() const { return buffer_.data(); }
  // The start of padded row k and of its interior, where the vertical pass writes.
  const float* padded(int k) const { return &buffer_[row_size_ + k * padded_size_]; }
  float* padded_interior(int k) { return &buffer_[row_size_ + k * padded_size_ + margin_]; }
  float* row(int k) { return &buffer_[row_size_ + padded_rows_ * padded_size_ + k * row_size_]; }

 private:
  const size_t row_size_, padded_size_, margin_;
  const int padded_rows_;
  std::vector<float> buffer_;
};

// One SSIM evaluation over x and y. Each pass handles a range of rows; the gradient pass
// needs the partial derivatives of the rows around its own, so it runs after the first pass
// has finished every row.
class SsimPasses {
 public:
  SsimPasses(const Image& x, const Image& y, SsimWorkspace* workspace)
      : x_(x),
        y_(y),
        row_size_(x.row_size()),
        plane_size_(row_size_ * x.height),
        margin_(static_cast<size_t>(kGaussianRadius) * x.channels),
        ws_(workspace) {
    ws_->row_sums.assign(x.height, 0.0);
  }

  // The SSIM map of rows [begin, end); sums samples [first, last) of each row into row_sums
  // and, with partials, stores the three partial derivatives in the workspace.
  void EvaluateRows(int begin, int end, size_t first, size_t last, bool partials) {
    RowScratch scratch(row_size_, margin_, kMoments, kMoments + 1);
    const float* xs[kGaussianTaps];
    const float* ys[kGaussianTaps];
    float* m[kMoments];
    for (int k = 0; k < kMoments; ++k) m[k] = scratch.row(k);
    float* ssim = scratch.row(kMoments);
    for (int r = begin; r < end; ++r) {
      GatherWindowRows(x_.pixels.data(), row_size_, x_.height, r, scratch.zeros(), xs);
      GatherWindowRows(y_.pixels.data(), row_size_, y_.height, r, scratch.zeros(), ys);
      FilterMomentRows(xs, ys, row_size_, scratch.padded_interior(kMuX),
                       scratch.padded_interior(kMuY), scratch.padded_interior(kXX),
                       scratch.padded_interior(kYY), scratch.padded_interior(kXY));
      for (int k = 0; k < kMoments; ++k) {
        FilterPaddedRow(scratch.padded(k), x_.width, x_.channels, m[k]);
      }
      if (partials) {
        float* d[kPartials];
        for (int k = 0; k < kPartials; ++k) d[k] = PartialRow(k, r);
        for (size_t i = 0; i < row_size_; ++i) {
          ssim[i] = SsimPixel(m, i, &d[kDMu][i], &d[kDXX][i], &d[kDXY][i]);
        }
      } else {
        float unused[kPartials];
        for (size_t i = 0; i < row_size_; ++i) {
          ssim[i] = SsimPixel(m, i, &unused[kDMu], &unused[kDXX], &unused[kDXY]);
        }
      }
      double sum = 0;
      for (size_t i = first; i < last; ++i) sum += ssim[i];
      ws_->row_sums[r] = sum;
    }
  }

  // The filtered partial derivatives of rows [begin, end), combined into the gradient.
  void GradientRows(int begin, int end, float scale, Image* grad) {
    RowScratch scratch(row_size_, margin_, kPartials, kPartials);
    const float* window[kGaussianTaps];
    float* f[kPartials];
    for (int k = 0; k < kPartials; ++k) f[k] = scratch.row(k);
    for (int r = begin; r < end; ++r) {
      for (int k = 0; k < kPartials; ++k) {
        GatherWindowRows(PartialRow(k, 0), row_size_, x_.height, r, scratch.zeros(), window);
        FilterWindowRows(window, row_size_, scratch.padded_interior(k));
        FilterPaddedRow(scratch.padded(k), x_.width, x_.channels, f[k]);
      }
      const float* xr = x_.row(r);
      const float* yr = y_.row(r);
      float* g = grad->row(r);
      for (size_t i = 0; i < row_size_; ++i) {
        g[i] = scale * (f[kDMu][i] + 2.0f * xr[i] * f[kDXX][i] + yr[i] * f[kDXY][i]);
      }
    }
  }

 private:
  float* PartialRow(int k, int r) { return &ws_->partials[k * plane_size_ + r * row_size_]; }

  const Image& x_;
  const Image& y_;
  const size_t row_size_;
  const size_t plane_size_;
  const size_t margin_;
  SsimWorkspace* ws_;
};

double SumRows(const std::vector<double>& row_sums) {
  double sum = 0;
  for (double s : row_sums) sum += s;
  return sum;
}

}  // namespace

Status SsimZeroPadded(const Image& x, const Image& y, double* ssim, Image* grad_x,
                      SsimWorkspace* workspace) {
  M4D_RETURN_IF_ERROR(CheckSameShape(x, y, "ssim"));
  SsimWorkspace local;
  SsimWorkspace* ws = workspace ? workspace : &local;
  SsimPasses passes(x, y, ws);
  const bool gradient = grad_x != nullptr;
  const size_t n = x.row_size();
  if (gradient) ws->partials.resize(kPartials * n * x.height);
  ParallelForRows(x.height, n, [&](int b, int e) { passes.EvaluateRows(b, e, 0, n, gradient); });
  const double count = static_cast<double>(n) * x.height;
  *ssim = SumRows(ws->row_sums) / count;
  if (!gradient) return Status::Ok();

  Reshape(x.width, x.height, x.channels, grad_x);
  const float scale = static_cast<float>(1.0 / count);
  ParallelForRows(x.height, n, [&](int b, int e) { passes.GradientRows(b, e, scale, grad_x); });
  return Status::Ok();
}

Status SsimValid(const Image& x, const Image& y, double* ssim, SsimWorkspace* workspace) {
  M4D_RETURN_IF_ERROR(CheckSameShape(x, y, "ssim"));
  if (x.width < kGaussianTaps || x.height < kGaussianTaps) {
    return Status(M4D_ERR_INVALID_ARG, "ssim: the valid convention needs at least 11 x 11 pixels");
  }
  SsimWorkspace local;
  SsimWorkspace* ws = workspace ? workspace : &local;
  SsimPasses passes(x, y, ws);
  // Inside the border the zero-padded filter equals the 'valid' one: evaluate only there.
  const size_t n = x.row_size();
  const size_t margin = static_cast<size_t>(kGaussianRadius) * x.channels;
  const int rows = x.height - 2 * kGaussianRadius;
  ParallelForRows(rows, n, [&](int b, int e) {
    passes.EvaluateRows(b + kGaussianRadius, e + kGaussianRadius, margin, n - margin, false);
  });
  *ssim = SumRows(ws->row_sums) / (static_cast<double>(n - 2 * margin) * rows);
  return Status::Ok();
}

}  // namespace m4d
