// The waterfall image of a side-scan sonar (docs/sonars.md "Side-scan sonar"): the latest pings' lines stacked,
// row 0 the newest ping; each row is the port line reversed (its far range at column 0) followed by the starboard
// line, so the nadir is the middle of the row and range grows outwards on both sides. Rows not yet filled, and
// the rows of pings that were not built, are 0. Knows no ROS.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace unexmin {
namespace sensors {
namespace sonar {

class Waterfall {
public:
  /// `lines` rows of 2 x `bins` columns (both >= 1).
  Waterfall(std::size_t lines, std::size_t bins);

  std::size_t lines() const { return lines_; }     ///< rows [-]
  std::size_t width() const { return 2 * bins_; }  ///< columns [-]
  std::size_t filled() const { return filled_; }   ///< pings held, at most lines()
  /// Forgets every ping.
  void clear();
  /// Adds one ping: `port` and `starboard` of bins() codes each, bin 0 the nearest.
  void add(const std::uint8_t* port, const std::uint8_t* starboard);
  /// Adds a ping with no lines (one that was not built): a row of zeros.
  void addBlank();
  /// The image, row-major, lines() x width() (resized).
  void image(std::vector<std::uint8_t>& out) const;

private:
  /// The row of a new ping (the oldest dropped when full).
  std::uint8_t* next();

  std::size_t lines_, bins_;
  std::size_t filled_ = 0;
  std::size_t newest_ = 0;          ///< ring index of the newest row
  std::vector<std::uint8_t> rows_;  ///< ring of rows, each already in the image's column order
};

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
