#include "hydro/types.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

std::string formatNumber(double x)
{
  std::ostringstream s;
  s << std::setprecision(12) << x;
  return s.str();
}

double requireScalar(const ParamMap& params, const std::string& key, const std::string& what)
{
  const auto it = params.find(key);
  if (it == params.end())
  {
    throw std::invalid_argument(what + ": missing parameter '" + key + "' (expected one number)");
  }
  if (it->second.size() != 1)
  {
    throw std::invalid_argument(what + ": parameter '" + key + "' has " +
                                std::to_string(it->second.size()) + " values, expected one number");
  }
  const double value = it->second.front();
  if (!std::isfinite(value))
  {
    std::ostringstream msg;
    msg << what << ": parameter '" << key << "' = " << std::setprecision(12) << value
        << " must be a finite number";
    throw std::invalid_argument(msg.str());
  }
  return value;
}

}  // namespace hydro
}  // namespace unexmin
