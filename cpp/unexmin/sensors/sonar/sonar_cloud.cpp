#include <unexmin/sensors/sonar/sonar_cloud.h>

#include <unexmin/core/error.h>

#include <array>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace sonar {
namespace {

std::vector<double> azimuthsOf(const ImagingSonarSensor& s) {
  std::vector<double> a(s.beams());
  for (std::size_t k = 0; k < a.size(); ++k)
    a[k] = s.azimuth(k);
  return a;
}

std::vector<double> rangesOf(const ImagingSonarSensor& s) {
  std::vector<double> r(s.bins());
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = s.binCenter(i);
  return r;
}

}  // namespace

SonarCloud::SonarCloud(std::vector<double> azimuths, std::vector<double> ranges, double step, double threshold)
    : azimuths_(std::move(azimuths)), ranges_(std::move(ranges)), threshold_(threshold) {
  if (azimuths_.empty() || ranges_.empty())
    throw ParameterError("sonar cloud: " + formatNumber(azimuths_.size()) + " beams x " + formatNumber(ranges_.size()) +
                         " bins: expected at least one of each");
  if (!(step > 0.0) || !std::isfinite(step))
    throw ParameterError("sonar cloud: code step " + formatNumber(step) + " dB: expected > 0");
  if (!(threshold > 0.0) || !std::isfinite(threshold))
    throw ParameterError("sonar cloud: threshold " + formatNumber(threshold) + " dB: expected > 0");
  threshold_codes_ = static_cast<int>(std::ceil(threshold / step - 1e-9));
  for (double a : azimuths_) {
    cos_.push_back(static_cast<float>(std::cos(a)));
    sin_.push_back(static_cast<float>(std::sin(a)));
  }
  floor_.assign(ranges_.size(), 0);
  points_.reserve(azimuths_.size());
}

SonarCloud::SonarCloud(const ImagingSonarSensor& sensor, double threshold)
    : SonarCloud(azimuthsOf(sensor), rangesOf(sensor), sensor.receiver().echo().step(), threshold) {}

const std::vector<SonarPoint>& SonarCloud::build(const PolarImage& image) {
  const std::size_t beams = azimuths_.size(), bins = ranges_.size();
  if (image.beams != beams || image.bins != bins || image.codes.size() != beams * bins)
    throw ParameterError("sonar cloud: image of " + formatNumber(image.bins) + " bins x " + formatNumber(image.beams) +
                         " beams: expected " + formatNumber(bins) + " x " + formatNumber(beams));
  // The median of each row (its ceil(beams / 2)-th smallest code) by its histogram of codes (256 counts).
  const std::size_t half = (beams + 1) / 2;
  for (std::size_t i = 0; i < bins; ++i) {
    std::array<std::uint32_t, 256> count{};
    const std::uint8_t* row = image.codes.data() + i * beams;
    for (std::size_t k = 0; k < beams; ++k)
      ++count[row[k]];
    std::size_t seen = 0;
    int q = 0;
    while ((seen += count[q]) < half)
      ++q;
    floor_[i] = static_cast<std::uint8_t>(q);
  }
  points_.clear();
  for (std::size_t k = 0; k < beams; ++k) {
    for (std::size_t i = 0; i < bins; ++i) {
      const int code = image.codes[i * beams + k];
      if (code < floor_[i] + threshold_codes_)
        continue;
      const float r = static_cast<float>(ranges_[i]);
      points_.push_back({Eigen::Vector3f(r * cos_[k], r * sin_[k], 0.0f), static_cast<std::uint8_t>(code), k, i});
      break;
    }
  }
  return points_;
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
