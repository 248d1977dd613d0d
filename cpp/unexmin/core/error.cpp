#include <unexmin/core/error.h>

#include <iomanip>
#include <sstream>

namespace unexmin {

std::string formatNumber(double x) {
  std::ostringstream s;
  s << std::setprecision(12) << x;
  return s.str();
}

}  // namespace unexmin
