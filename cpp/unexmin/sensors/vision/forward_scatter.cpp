#include <unexmin/sensors/vision/forward_scatter.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

constexpr int kWeightEntries = 4096;  ///< halo weight table over [0, max_range]
constexpr int kLobeSteps = 4000;      ///< Simpson steps of the lobe integrals (even)

}  // namespace

bool ForwardScatter::needed(const WaterOptics& water) {
  return water.b.maxCoeff() >= kMinScattering;
}

void ForwardScatter::lobe(double g, double lobe, double& eta, double& mean_square) {
  // int_0^lobe p(theta) 2 pi sin(theta) {1, theta^2} dtheta by Simpson's rule.
  double s0 = 0.0, s2 = 0.0;
  const double h = lobe / kLobeSteps;
  for (int i = 0; i <= kLobeSteps; ++i) {
    const double t = i * h;
    const double w = (i == 0 || i == kLobeSteps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const double d = 1.0 + g * g - 2.0 * g * std::cos(t);
    const double f = (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d)) * 2.0 * M_PI * std::sin(t);
    s0 += w * f;
    s2 += w * f * t * t;
  }
  eta = s0 * h / 3.0;
  mean_square = eta > 0.0 ? (s2 * h / 3.0) / eta : 0.0;
}

ForwardScatter::ForwardScatter(const WaterOptics& water, double max_range, double focal, int width, int height,
                               int cell)
    : water_(water), max_range_(max_range), focal_(focal), width_(width), height_(height), cell_(cell) {
  if (!(max_range > 0.0) || !std::isfinite(max_range) || !(focal > 0.0) || width < 1 || height < 1 || cell < 1)
    throw ParameterError("forward scatter: max_range " + formatNumber(max_range) + " m, focal " + formatNumber(focal) +
                         " px, image " + formatNumber(width) + " x " + formatNumber(height) + ", cell " +
                         formatNumber(cell) + ": expected positive numbers");
  lobe(water.g, kLobe, eta_, theta2_);
  cols_ = (width + cell - 1) / cell;
  rows_ = (height + cell - 1) / cell;
  for (int k = 0; k < kBands; ++k) {
    const double mid = max_range * ((k + 0.5) / kBands) * ((k + 0.5) / kBands);
    band_sigma_px_[static_cast<std::size_t>(k)] = haloSigma(mid) * focal;
  }
  weight_.assign(4 * (kWeightEntries + 2), 0.0f);
  weight_scale_ = kWeightEntries / max_range;
  band_.resize(kWeightEntries + 2);
  for (int i = 0; i <= kWeightEntries + 1; ++i) {
    // The band of a range in [i, i + 1) table steps: that of its start (edges fall on steps within 1 / 4096).
    band_[i] = static_cast<std::uint8_t>(
        std::min(kBands - 1, static_cast<int>(kBands * std::sqrt(std::min(1.0, i / double(kWeightEntries))))));
    const Eigen::Array3d w = haloWeight(std::min(max_range, i / weight_scale_));
    for (int c = 0; c < 3; ++c)
      weight_[4 * i + c] = static_cast<float>(w[c]);
  }
  sums_.assign(static_cast<std::size_t>(kBands) * cols_ * rows_ * 3, 0.0f);
}

Eigen::Array3d ForwardScatter::scatterings(double range) const {
  return eta_ * water_.b.array() * range;
}

Eigen::Array3d ForwardScatter::haloWeight(double range) const {
  return scatterings(range).exp() - 1.0;
}

double ForwardScatter::haloSigma(double range) const {
  const double lambda = scatterings(range)[1];
  const double mean = lambda > 1e-12 ? lambda / -std::expm1(-lambda) : 1.0;  // scatterings of the scattered light
  return std::sqrt(theta2_ / 6.0 * mean);
}

double ForwardScatter::psfSigma(double range) const {
  return std::sqrt(std::max(0.0, scatterings(range)[1]) * theta2_ / 6.0);
}

void ForwardScatter::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0f);
}

void ForwardScatter::accumulate(int cu, int cv, int n, const float* const direct[3], const float* range,
                                const float* extra) {
  if (n <= 0)
    return;
  const float inv_n = 1.0f / static_cast<float>(n), far = static_cast<float>(max_range_);
  const std::size_t cells = static_cast<std::size_t>(cols_) * rows_;
  const std::size_t cell = static_cast<std::size_t>(cv) * cols_ + cu;
  for (int i = 0; i < n; ++i) {
    const float r = range[i];
    if (!(r < far) || !(r >= 0.0f))
      continue;  // open water: no direct light to scatter
    const float x = r * static_cast<float>(weight_scale_);
    const int j = std::min(static_cast<int>(x), kWeightEntries);
    const float t = x - static_cast<float>(j);
    float* out = &sums_[(static_cast<std::size_t>(band_[j]) * cells + cell) * 3];
    const float* a = &weight_[4 * j];
    if (extra == nullptr) {
      for (int c = 0; c < 3; ++c)
        out[c] += direct[c][i] * (a[c] + t * (a[4 + c] - a[c])) * inv_n;
      continue;
    }
    const float more = std::exp(extra[i]);  // exp(lambda + x) - 1 = (w + 1) exp(x) - 1, w = exp(lambda) - 1
    for (int c = 0; c < 3; ++c)
      out[c] += direct[c][i] * ((a[c] + t * (a[4 + c] - a[c]) + 1.0f) * more - 1.0f) * inv_n;
  }
}

void ForwardScatter::blur(const float* in, float* out, double sigma_cells, std::vector<float>& tmp) const {
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigma_cells)));
  std::vector<float> kernel(static_cast<std::size_t>(2 * radius + 1));
  for (int d = -radius; d <= radius; ++d)
    kernel[static_cast<std::size_t>(d + radius)] =
        static_cast<float>(std::exp(-0.5 * d * d / (sigma_cells * sigma_cells)));
  tmp.assign(sums_.size() / kBands, 0.0f);
  // Along rows, then along columns; each output the weighted mean of the inputs inside the grid.
  for (int v = 0; v < rows_; ++v)
    for (int u = 0; u < cols_; ++u) {
      float acc[3] = {0, 0, 0}, norm = 0.0f;
      for (int d = std::max(-radius, -u); d <= std::min(radius, cols_ - 1 - u); ++d) {
        const float k = kernel[static_cast<std::size_t>(d + radius)];
        const float* p = &in[(static_cast<std::size_t>(v) * cols_ + u + d) * 3];
        acc[0] += k * p[0], acc[1] += k * p[1], acc[2] += k * p[2];
        norm += k;
      }
      float* q = &tmp[(static_cast<std::size_t>(v) * cols_ + u) * 3];
      for (int c = 0; c < 3; ++c)
        q[c] = acc[c] / norm;
    }
  for (int v = 0; v < rows_; ++v)
    for (int u = 0; u < cols_; ++u) {
      float acc[3] = {0, 0, 0}, norm = 0.0f;
      for (int d = std::max(-radius, -v); d <= std::min(radius, rows_ - 1 - v); ++d) {
        const float k = kernel[static_cast<std::size_t>(d + radius)];
        const float* p = &tmp[(static_cast<std::size_t>(v + d) * cols_ + u) * 3];
        acc[0] += k * p[0], acc[1] += k * p[1], acc[2] += k * p[2];
        norm += k;
      }
      float* q = &out[(static_cast<std::size_t>(v) * cols_ + u) * 3];
      for (int c = 0; c < 3; ++c)
        q[c] += acc[c] / norm;
    }
}

void ForwardScatter::apply(std::vector<float>& radiance, const raycast::RayCaster* pool) const {
  const std::size_t cells = static_cast<std::size_t>(cols_) * rows_;
  std::vector<float> total(cells * 3, 0.0f), tmp;
  for (int k = 0; k < kBands; ++k) {
    const float* band = &sums_[k * cells * 3];
    if (std::all_of(band, band + cells * 3, [](float x) { return x == 0.0f; }))
      continue;
    blur(band, total.data(), band_sigma_px_[static_cast<std::size_t>(k)] / cell_, tmp);
  }
  // Bilinear between cell centres, clamped at the edges.
  const float inv_cell = 1.0f / static_cast<float>(cell_), half = 0.5f * static_cast<float>(cell_ - 1);
  const auto strip = [&](std::size_t k) {
    const int v0 = static_cast<int>(k) * kStripRows, v1 = std::min(v0 + kStripRows, height_);
    for (int v = v0; v < v1; ++v) {
      const float y = std::min(static_cast<float>(rows_ - 1), std::max(0.0f, (v - half) * inv_cell));
      const int r0 = std::min(static_cast<int>(y), std::max(0, rows_ - 2));
      const float ty = rows_ > 1 ? y - r0 : 0.0f;
      const int r1 = std::min(r0 + 1, rows_ - 1);
      for (int u = 0; u < width_; ++u) {
        const float x = std::min(static_cast<float>(cols_ - 1), std::max(0.0f, (u - half) * inv_cell));
        const int c0 = std::min(static_cast<int>(x), std::max(0, cols_ - 2));
        const float tx = cols_ > 1 ? x - c0 : 0.0f;
        const int c1 = std::min(c0 + 1, cols_ - 1);
        const float* a = &total[(static_cast<std::size_t>(r0) * cols_ + c0) * 3];
        const float* b = &total[(static_cast<std::size_t>(r0) * cols_ + c1) * 3];
        const float* c = &total[(static_cast<std::size_t>(r1) * cols_ + c0) * 3];
        const float* d = &total[(static_cast<std::size_t>(r1) * cols_ + c1) * 3];
        float* out = &radiance[(static_cast<std::size_t>(v) * width_ + u) * 3];
        for (int ch = 0; ch < 3; ++ch) {
          const float top = a[ch] + tx * (b[ch] - a[ch]), bottom = c[ch] + tx * (d[ch] - c[ch]);
          out[ch] += top + ty * (bottom - top);
        }
      }
    }
  };
  const std::size_t strips = static_cast<std::size_t>((height_ + kStripRows - 1) / kStripRows);
  if (pool)
    pool->parallelFor(strips, strip);
  else
    for (std::size_t k = 0; k < strips; ++k)
      strip(k);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
