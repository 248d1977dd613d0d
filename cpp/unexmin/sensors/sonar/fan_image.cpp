#include <unexmin/sensors/sonar/fan_image.h>

#include <unexmin/core/error.h>

#include <cmath>

namespace unexmin {
namespace sensors {
namespace sonar {

FanImage::FanImage(std::size_t beams, double fov_h, std::size_t bins, double range_min, double range_max, int height)
    : height_(height) {
  const auto check = [](bool ok, const char* name, double value, const char* expected) {
    if (!ok)
      throw ParameterError(std::string("fan image: ") + name + " = " + formatNumber(value) + ": expected " + expected);
  };
  check(beams >= 1, "beams", static_cast<double>(beams), ">= 1");
  check(fov_h > 0.0 && fov_h <= M_PI, "fov_h", fov_h, "in (0, pi] rad");
  check(bins >= 1, "bins", static_cast<double>(bins), ">= 1");
  check(range_min >= 0.0 && range_max > range_min, "range_max", range_max, "> range_min >= 0 m");
  check(height >= 1, "height", height, ">= 1 px");
  pixel_ = range_max / height;
  width_ = 2 * static_cast<int>(std::ceil(range_max * std::sin(fov_h / 2.0) / pixel_ - 1e-9));
  source_.assign(static_cast<std::size_t>(width_) * height_, -1);
  const double beam_width = fov_h / static_cast<double>(beams);
  const double bin_width = (range_max - range_min) / static_cast<double>(bins);
  for (int row = 0; row < height_; ++row) {
    const double x = (height_ - row - 0.5) * pixel_;
    for (int col = 0; col < width_; ++col) {
      const double y = (width_ / 2.0 - col - 0.5) * pixel_;
      const double k = std::floor((fov_h / 2.0 - std::atan2(y, x)) / beam_width);
      const double i = std::floor((std::hypot(x, y) - range_min) / bin_width);
      if (k < 0.0 || k >= static_cast<double>(beams) || i < 0.0 || i >= static_cast<double>(bins))
        continue;
      source_[static_cast<std::size_t>(row) * width_ + col] =
          static_cast<long>(i) * static_cast<long>(beams) + static_cast<long>(k);
    }
  }
}

void FanImage::render(const std::vector<std::uint8_t>& polar, std::vector<std::uint8_t>& out) const {
  out.resize(source_.size());
  for (std::size_t p = 0; p < source_.size(); ++p)
    out[p] = source_[p] < 0 ? 0 : polar[static_cast<std::size_t>(source_[p])];
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
