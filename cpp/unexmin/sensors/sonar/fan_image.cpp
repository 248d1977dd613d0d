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
  const double beam_width = fov_h / static_cast<double>(beams);
  const double bin_width = (range_max - range_min) / static_cast<double>(bins);
  for (int row = 0; row < height_; ++row) {
    row_run_.push_back(static_cast<std::uint32_t>(runs_.size()));
    const double x = (height_ - row - 0.5) * pixel_;
    bool inside = false;
    for (int col = 0; col < width_; ++col) {
      const double y = (width_ / 2.0 - col - 0.5) * pixel_;
      const double k = std::floor((fov_h / 2.0 - std::atan2(y, x)) / beam_width);
      const double i = std::floor((std::hypot(x, y) - range_min) / bin_width);
      const bool in = k >= 0.0 && k < static_cast<double>(beams) && i >= 0.0 && i < static_cast<double>(bins);
      if (in && !inside) {
        Run run;
        run.pixel = static_cast<std::uint32_t>(static_cast<std::size_t>(row) * width_ + col);
        run.first = static_cast<std::uint32_t>(index_.size());
        runs_.push_back(run);
      }
      inside = in;
      if (!in)
        continue;
      ++runs_.back().length;
      index_.push_back(static_cast<std::uint32_t>(i) * static_cast<std::uint32_t>(beams) +
                       static_cast<std::uint32_t>(k));
    }
  }
  row_run_.push_back(static_cast<std::uint32_t>(runs_.size()));
}

long FanImage::source(int row, int col) const {
  const std::uint32_t pixel = static_cast<std::uint32_t>(static_cast<std::size_t>(row) * width_ + col);
  for (std::uint32_t r = row_run_[row]; r < row_run_[row + 1]; ++r)
    if (pixel >= runs_[r].pixel && pixel < runs_[r].pixel + runs_[r].length)
      return static_cast<long>(index_[runs_[r].first + (pixel - runs_[r].pixel)]);
  return -1;
}

void FanImage::render(const std::vector<std::uint8_t>& polar, std::vector<std::uint8_t>& out) const {
  out.assign(static_cast<std::size_t>(width_) * height_, 0);
  const std::uint8_t* in = polar.data();
  for (const Run& run : runs_) {
    const std::uint32_t* index = &index_[run.first];
    std::uint8_t* o = &out[run.pixel];
    for (std::uint32_t j = 0; j < run.length; ++j)
      o[j] = in[index[j]];
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
