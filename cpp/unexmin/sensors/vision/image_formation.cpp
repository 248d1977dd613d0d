#include <unexmin/sensors/vision/image_formation.h>

#include <unexmin/core/error.h>
#include <unexmin/sensors/vision/parallel_rows.h>
#include <unexmin/sensors/vision/shading_kernels.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

constexpr int kPowEntries = ImageFormation::kPowEntries;
constexpr int kExpEntries = ImageFormation::kExpEntries;
constexpr int kBins = 64;                           ///< backscatter table: range bins
constexpr int kSimpson = 4;                         ///< Simpson sub-intervals per range bin (even)
constexpr int kMaxNodesU = 65;                      ///< backscatter table: pixel nodes across ...
constexpr int kMaxNodesV = 49;                      ///< ... and down
constexpr double kConeMargin = 5.0 * M_PI / 180.0;  ///< [rad] a light is kept if a grid ray passes this close

/// Copies the direct term (batch.out after the direct kernel) into batch.direct when the batch asks for it.
void keepDirect(PixelBatch& batch) {
  if (!batch.keep_direct)
    return;
  for (int c = 0; c < 3; ++c)
    std::copy(batch.out[c], batch.out[c] + batch.n, batch.direct[c]);
}

}  // namespace

double LedLight::profile(double cos_theta) const {
  const double half = std::min(cone / 2.0, M_PI / 2.0);
  const double theta = std::acos(std::max(-1.0, std::min(1.0, cos_theta)));
  if (!(theta < half))
    return 0.0;
  const double x = std::min(1.0, (half - theta) / (kEdge * half));  // 0 at the cone's edge, 1 inside the rim
  return std::pow(cos_theta, exponent) * x * x * (3.0 - 2.0 * x);
}

Eigen::Vector3d LedLight::at(double cos_theta) const {
  return intensity * profile(cos_theta);
}

ImageFormation::ImageFormation(const CameraModel& camera, std::vector<LedLight> lights, const WaterOptics& water,
                               double max_range, int threads)
    : water_(water), lights_(std::move(lights)), max_range_(max_range) {
  if (!(max_range > 0.0) || !std::isfinite(max_range))
    throw ParameterError("image formation: max_range = " + formatNumber(max_range) + " m: expected > 0");
  if (lights_.size() > 32)
    throw ParameterError("image formation: at most 32 lights");
  pow_m_.resize(lights_.size());
  for (std::size_t k = 0; k < lights_.size(); ++k) {
    LedLight& l = lights_[k];
    l.axis.normalize();
    shading::Light f;
    const Eigen::Vector3d i0 = l.intensity / M_PI;
    for (int c = 0; c < 3; ++c) {
      f.position[c] = static_cast<float>(l.position[c]);
      f.axis[c] = static_cast<float>(l.axis[c]);
      f.intensity[c] = static_cast<float>(i0[c]);
    }
    const double cos_half = std::max(0.0, std::cos(l.cone / 2.0));
    f.cos_half = static_cast<float>(cos_half);
    f.cos_half2 = f.cos_half * f.cos_half;
    std::vector<float>& pow_m = pow_m_[k];
    pow_m.resize(kPowEntries + 2);
    for (int i = 0; i <= kPowEntries + 1; ++i)
      pow_m[i] = static_cast<float>(l.profile(std::min(1.0, cos_half + (1.0 - cos_half) * i / kPowEntries)));
    f.pow_scale = static_cast<float>(kPowEntries / std::max(1e-9, 1.0 - cos_half));
    f.pow_m = pow_m.data();
    f.bit = 1u << k;
    light_f_.push_back(f);
    reach_cos_.push_back(std::cos(std::min(M_PI, l.cone / 2.0 + kConeMargin)));
  }
  // Longest light path: to the farthest surface and back to a light beside the lens.
  double reach = 0.0;
  for (const auto& l : lights_)
    reach = std::max(reach, l.position.norm());
  const double x_max = 2.0 * max_range + 2.0 * reach + 1.0;
  exp_.assign(4 * (kExpEntries + 2), 0.0f);
  const Eigen::Vector3d c = water_.c();
  for (int i = 0; i <= kExpEntries + 1; ++i)
    for (int k = 0; k < 3; ++k)
      exp_[4 * i + k] = static_cast<float>(std::exp(-c[k] * x_max * i / kExpEntries));
  tables_.exp = exp_.data();
  tables_.exp_scale = static_cast<float>(kExpEntries / x_max);
  tables_.exp_last = static_cast<float>(kExpEntries);
  tables_.pow_last = static_cast<float>(kPowEntries);
  buildTable(camera, threads);

  for (int k : active_)
    kernel_lights_.push_back(light_f_[static_cast<std::size_t>(k)]);
}

bool ImageFormation::canLight(int k, const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
  const shading::Light& l = light_f_[static_cast<std::size_t>(k)];
  const Eigen::Vector3f v = p - Eigen::Vector3f(l.position[0], l.position[1], l.position[2]);
  const float r = v.norm();
  return Eigen::Vector3f(l.axis[0], l.axis[1], l.axis[2]).dot(v) > l.cos_half * r && n.dot(v) < 0.0f;
}

Eigen::Array3d ImageFormation::integrand(const Eigen::Vector3d& d, double s, std::vector<char>* reached) const {
  Eigen::Array3d sum = Eigen::Array3d::Zero();
  const Eigen::Vector3d x = s * d;
  const Eigen::Array3d c = water_.c().array(), b = water_.b.array();
  for (std::size_t k = 0; k < lights_.size(); ++k) {
    const LedLight& l = lights_[k];
    const Eigen::Vector3d w = x - l.position;
    const double r = w.norm();
    if (!(r > 1e-9))
      continue;
    const Eigen::Vector3d dir = w / r;  // the light's direction of travel
    const double cos_theta = l.axis.dot(dir);
    if (reached && cos_theta > reach_cos_[k])
      (*reached)[k] = 1;
    if (!(cos_theta > light_f_[k].cos_half) || !(cos_theta > 0.0))
      continue;
    const double p = water_.phase(-dir.dot(d));  // scattered back along -d, towards the lens
    const double geometry = p * l.profile(cos_theta) / (r * r);
    sum += b * l.intensity.array() * geometry * (-c * (s + r)).exp();
  }
  return sum;
}

bool ImageFormation::simdAvailable() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool available = shading::avx2Built() && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
#else
  return false;
#endif
}

void ImageFormation::radiance(PixelBatch& batch, bool simd) const {
  const int count = static_cast<int>(kernel_lights_.size());
  if (simd && simdAvailable()) {
    // Whole groups of 8 lanes: the padding is open water at range 0 (its results are never read).
    const int padded = (batch.n + 7) / 8 * 8;
    for (int i = batch.n; i < padded; ++i)
      batch.setWater(i, 0.0f, 0.0f, 0.0f);
    shading::directAvx2(batch, padded, kernel_lights_.data(), count, tables_);
    keepDirect(batch);
    shading::backscatterAvx2(batch, padded, backscatter_);
  } else {
    shading::direct<lanes::F1>(batch, batch.n, kernel_lights_.data(), count, tables_);
    keepDirect(batch);
    shading::backscatter<lanes::F1>(batch, batch.n, backscatter_);
  }
}

Eigen::Array3f ImageFormation::direct(const Eigen::Vector3f& p, float range, const Eigen::Vector3f& n,
                                      const Eigen::Array3f& albedo, unsigned lit) const {
  PixelBatch b;
  b.set(0, 0.0f, 0.0f, range, p, n, albedo.data(), lit);
  shading::direct<lanes::F1>(b, 1, kernel_lights_.data(), static_cast<int>(kernel_lights_.size()), tables_);
  return Eigen::Array3f(b.out[0][0], b.out[1][0], b.out[2][0]);
}

Eigen::Array3f ImageFormation::backscatter(float u, float v, float r) const {
  PixelBatch b;
  b.setWater(0, u, v, r);
  for (auto& o : b.out)
    o[0] = 0.0f;
  shading::backscatter<lanes::F1>(b, 1, backscatter_);
  return Eigen::Array3f(b.out[0][0], b.out[1][0], b.out[2][0]);
}

void ImageFormation::buildTable(const CameraModel& camera, int threads) {
  const int nu = std::max(2, std::min(kMaxNodesU, camera.width()));
  const int nv = std::max(2, std::min(kMaxNodesV, camera.height()));
  const int bins = kBins;
  const float step_u = static_cast<float>(std::max(1, camera.width() - 1)) / static_cast<float>(nu - 1);
  const float step_v = static_cast<float>(std::max(1, camera.height() - 1)) / static_cast<float>(nv - 1);
  s_.resize(static_cast<std::size_t>(bins + 1));
  for (int j = 0; j <= bins; ++j)
    s_[j] = static_cast<float>(max_range_ * (j / double(bins)) * (j / double(bins)));
  inv_bin_.resize(static_cast<std::size_t>(bins));
  for (int j = 0; j < bins; ++j)
    inv_bin_[j] = 1.0f / (s_[j + 1] - s_[j]);
  table_.assign(static_cast<std::size_t>(nu * nv * (bins + 1) * 4), 0.0f);
  backscatter_.table = table_.data();
  backscatter_.edge = s_.data();
  backscatter_.inv_bin = inv_bin_.data();
  backscatter_.nu = nu;
  backscatter_.nv = nv;
  backscatter_.bins = bins;
  backscatter_.inv_step_u = 1.0f / step_u;
  backscatter_.inv_step_v = 1.0f / step_v;
  backscatter_.inv_range = 1.0f / s_.back();
  std::vector<std::vector<char>> reached(static_cast<std::size_t>(nv), std::vector<char>(lights_.size(), 0));

  parallelRows(
      nv,
      [&](int v0, int v1) {
        for (int jv = v0; jv < v1; ++jv)
          for (int iu = 0; iu < nu; ++iu) {
            const Eigen::Vector3d d = camera.ray(iu * step_u, jv * step_v);
            float* out = &table_[static_cast<std::size_t>((jv * nu + iu) * (bins + 1) * 4)];
            Eigen::Array3d total = Eigen::Array3d::Zero();
            Eigen::Array3d f0 = integrand(d, 0.0, &reached[jv]);
            for (int j = 0; j < bins; ++j) {
              // Simpson over [s_j, s_j+1] in kSimpson sub-intervals.
              const double a = s_[j], h = (s_[j + 1] - s_[j]) / kSimpson;
              Eigen::Array3d acc = f0;
              Eigen::Array3d f = f0;
              for (int m = 1; m <= kSimpson; ++m) {
                f = integrand(d, a + m * h, &reached[jv]);
                acc += (m == kSimpson ? 1.0 : (m % 2 ? 4.0 : 2.0)) * f;
              }
              total += acc * (h / 3.0);
              f0 = f;
              for (int c = 0; c < 3; ++c)
                out[(j + 1) * 4 + c] = static_cast<float>(total[c]);
            }
          }
      },
      threads, 1);

  for (std::size_t k = 0; k < lights_.size(); ++k) {
    bool any = false;
    for (const auto& row : reached)
      any = any || row[k];
    if (any)
      active_.push_back(static_cast<int>(k));
  }
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
