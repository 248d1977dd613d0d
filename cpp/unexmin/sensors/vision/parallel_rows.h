// Splits rows [0, n) into one contiguous band per hardware thread and runs `band(begin, end)` on each, the
// calling thread taking the first band. For per-pixel work whose result does not depend on how the rows are
// shared out (every pixel is computed alone), so images are the same on any machine. Knows no ROS.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

/// Runs band(begin, end) over [0, n) on up to `threads` threads (0 = std::thread::hardware_concurrency()).
/// Bands smaller than `min_rows` are not split further. Returns when every band is done.
template <class Band>
void parallelRows(int n, const Band& band, int threads = 0, int min_rows = 8) {
  if (threads <= 0)
    threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::max(1, std::min(threads, n / std::max(1, min_rows)));
  if (threads <= 1) {
    if (n > 0)
      band(0, n);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t)
    pool.emplace_back([&band, n, t, threads] { band(n * t / threads, n * (t + 1) / threads); });
  band(0, n / threads);
  for (auto& th : pool)
    th.join();
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
