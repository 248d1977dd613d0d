#include <unexmin/sensors/vision/silt_view.h>

#include <unexmin/sensors/vision/parallel_rows.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {

SiltView::SiltView(const CameraModel& camera, const ImageFormation& formation)
    : formation_(formation), width_(camera.width()), height_(camera.height()), max_range_(formation.maxRange()) {
  nu_ = (width_ - 1 + kStep - 1) / kStep + 1;
  nv_ = (height_ - 1 + kStep - 1) / kStep + 1;
  edge_.resize(kBins + 1);
  for (int j = 0; j <= kBins; ++j)
    edge_[j] = static_cast<float>(max_range_ * (j / double(kBins)) * (j / double(kBins)));
  ray_.resize(static_cast<std::size_t>(nu_) * nv_);
  unit_b_.assign(ray_.size() * (kBins + 1) * 3, 0.0f);
  table_.assign(ray_.size() * (kBins + 1) * 4, 0.0f);
  const Eigen::Vector3d b = formation.water().b;
  for (int iv = 0; iv < nv_; ++iv)
    for (int iu = 0; iu < nu_; ++iu) {
      const float u = static_cast<float>(std::min(iu * kStep, width_ - 1));
      const float v = static_cast<float>(std::min(iv * kStep, height_ - 1));
      const std::size_t n = static_cast<std::size_t>(iv) * nu_ + iu;
      ray_[n] = camera.ray(u, v);
      for (int j = 0; j <= kBins; ++j) {
        const Eigen::Array3f e = formation.backscatter(u, v, edge_[j]);
        for (int c = 0; c < 3; ++c)
          unit_b_[(n * (kBins + 1) + j) * 3 + c] = b[c] > 0.0 ? static_cast<float>(e[c] / b[c]) : 0.0f;
      }
    }
}

bool SiltView::update(const sim::SedimentField& field, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d origin = pose.translation();
  if (field.empty() || !field.near(origin, max_range_))
    return false;
  const Eigen::Vector3d b = formation_.water().b;
  parallelRows(
      nv_,
      [&](int v0, int v1) {
        double tau[kBins + 1];
        for (int iv = v0; iv < v1; ++iv)
          for (int iu = 0; iu < nu_; ++iu) {
            const std::size_t n = static_cast<std::size_t>(iv) * nu_ + iu;
            const Eigen::Vector3d d = pose.linear() * ray_[n];
            field.opticalDepths(origin, d, edge_.data(), kBins + 1, tau);
            float* out = node(iu, iv, 0);
            const float* unit = &unit_b_[n * (kBins + 1) * 3];
            double extra[3] = {0.0, 0.0, 0.0};
            out[0] = 0.0f;
            out[1] = out[2] = out[3] = 0.0f;
            for (int j = 0; j < kBins; ++j) {
              const double ds = edge_[j + 1] - edge_[j];
              const double db = ds > 0.0 ? (tau[j + 1] - tau[j]) / ds : 0.0;
              const double att = std::exp(-(tau[j] + tau[j + 1]));  // exp(-2 tau) at the bin's middle
              for (int c = 0; c < 3; ++c) {
                const double d_unit = unit[(j + 1) * 3 + c] - unit[j * 3 + c];  // the water's dB_j / b
                extra[c] += d_unit * ((b[c] + db) * att - b[c]);
              }
              float* o = out + (j + 1) * 4;
              o[0] = static_cast<float>(tau[j + 1]);
              for (int c = 0; c < 3; ++c)
                o[1 + c] = static_cast<float>(extra[c]);
            }
          }
      },
      0, 4);
  return true;
}

void SiltView::lookup(float u, float v, float r, float out[4]) const {
  const float fu = std::min(static_cast<float>(nu_ - 1), std::max(0.0f, u / kStep));
  const float fv = std::min(static_cast<float>(nv_ - 1), std::max(0.0f, v / kStep));
  const int iu = std::min(static_cast<int>(fu), nu_ - 2), iv = std::min(static_cast<int>(fv), nv_ - 2);
  const float tu = fu - iu, tv = fv - iv;
  const float rr = std::min(std::max(0.0f, r), edge_.back());
  const int j = std::min(kBins - 1, static_cast<int>(kBins * std::sqrt(rr / edge_.back())));
  const float tr = std::min(1.0f, std::max(0.0f, (rr - edge_[j]) / std::max(1e-9f, edge_[j + 1] - edge_[j])));
  const float wn[4] = {(1 - tu) * (1 - tv), tu * (1 - tv), (1 - tu) * tv, tu * tv};
  const int du[4] = {0, 1, 0, 1}, dv[4] = {0, 0, 1, 1};
  for (int k = 0; k < 4; ++k)
    out[k] = 0.0f;
  for (int q = 0; q < 4; ++q) {
    const float* a = &table_[((static_cast<std::size_t>(iv + dv[q]) * nu_ + iu + du[q]) * (kBins + 1) + j) * 4];
    for (int k = 0; k < 4; ++k)
      out[k] += wn[q] * (a[k] + tr * (a[4 + k] - a[k]));
  }
}

double SiltView::opticalDepth(float u, float v, float r) const {
  float out[4];
  lookup(u, v, r, out);
  return out[0];
}

void SiltView::apply(PixelBatch& batch, float (*direct)[raycast::kBlock]) const {
  for (int i = 0; i < batch.n; ++i) {
    float s[4];
    lookup(batch.u[i], batch.v[i], batch.range[i], s);
    const float att = std::exp(-2.0f * s[0]);
    for (int c = 0; c < 3; ++c) {
      const float d = direct[c][i];
      direct[c][i] = d * att;
      batch.out[c][i] += d * (att - 1.0f) + s[1 + c];
    }
  }
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
