#include <unexmin/sensors/sonar/waterfall.h>

#include <algorithm>
#include <cstring>

namespace unexmin {
namespace sensors {
namespace sonar {

Waterfall::Waterfall(std::size_t lines, std::size_t bins)
    : lines_(std::max<std::size_t>(1, lines)), bins_(std::max<std::size_t>(1, bins)), rows_(lines_ * 2 * bins_, 0) {}

void Waterfall::clear() {
  filled_ = 0;
  newest_ = 0;
  std::fill(rows_.begin(), rows_.end(), 0);
}

std::uint8_t* Waterfall::next() {
  newest_ = filled_ == 0 ? 0 : (newest_ + 1) % lines_;
  filled_ = std::min(lines_, filled_ + 1);
  return &rows_[newest_ * width()];
}

void Waterfall::addBlank() {
  std::uint8_t* row = next();
  std::fill(row, row + width(), std::uint8_t{0});
}

void Waterfall::add(const std::uint8_t* port, const std::uint8_t* starboard) {
  std::uint8_t* row = next();
  std::reverse_copy(port, port + bins_, row);
  std::copy(starboard, starboard + bins_, row + bins_);
}

void Waterfall::image(std::vector<std::uint8_t>& out) const {
  out.assign(lines_ * width(), 0);
  for (std::size_t r = 0; r < filled_; ++r) {  // row r: the ping r pings before the newest
    const std::size_t ring = (newest_ + lines_ - r) % lines_;
    std::memcpy(&out[r * width()], &rows_[ring * width()], width());
  }
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
