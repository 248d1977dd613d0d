#include <unexmin/hydro/types.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

double requireScalar(const ParamMap& params, const std::string& key, const std::string& what) {
  const auto it = params.find(key);
  if (it == params.end()) {
    throw ParameterError(what + ": missing parameter '" + key + "' (expected one number)");
  }
  if (it->second.size() != 1) {
    throw ParameterError(what + ": parameter '" + key + "' has " + formatNumber(it->second.size()) +
                         " values, expected one number");
  }
  const double value = it->second.front();
  if (!std::isfinite(value)) {
    throw ParameterError(what + ": parameter '" + key + "' = " + formatNumber(value) + " must be a finite number");
  }
  return value;
}

}  // namespace hydro
}  // namespace unexmin
