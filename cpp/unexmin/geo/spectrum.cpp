#include <unexmin/geo/spectrum.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace geo {

Spectrum Spectrum::fromKnots(const std::vector<double>& nm, const std::vector<double>& reflectance) {
  Spectrum s;
  for (int i = 0; i < kSize; ++i) {
    const double x = kFirst + kStep * i;
    if (x <= nm.front()) {
      s.values_[i] = reflectance.front();
      continue;
    }
    if (x >= nm.back()) {
      s.values_[i] = reflectance.back();
      continue;
    }
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(nm.begin(), nm.end(), x) - nm.begin());
    const double w = (x - nm[k - 1]) / (nm[k] - nm[k - 1]);
    s.values_[i] = reflectance[k - 1] + w * (reflectance[k] - reflectance[k - 1]);
  }
  return s;
}

double Spectrum::at(double nm) const {
  const double u = (std::clamp(nm, kFirst, kLast) - kFirst) / kStep;
  const int i = std::min(static_cast<int>(u), kSize - 2);
  const double w = u - i;
  return values_[i] + w * (values_[i + 1] - values_[i]);
}

Eigen::Vector3d Spectrum::rgb() const {
  // trapezoid mean over the 10 grid steps of each 100 nm band: blue from index 0, green 10, red 20
  auto band = [this](int first) {
    double sum = 0.5 * (values_[first] + values_[first + 10]);
    for (int i = first + 1; i < first + 10; ++i)
      sum += values_[i];
    return sum / 10.0;
  };
  return Eigen::Vector3d(band(20), band(10), band(0));
}

void Spectrum::addScaled(const Spectrum& other, double w) {
  for (int i = 0; i < kSize; ++i)
    values_[i] += w * other.values_[i];
}

}  // namespace geo
}  // namespace unexmin
