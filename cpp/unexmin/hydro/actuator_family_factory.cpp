#include <unexmin/hydro/actuator_family_factory.h>

namespace unexmin {
namespace hydro {

void throwUnknownFamily(const std::string& kind, const std::string& type, const std::vector<std::string>& known) {
  std::string list;
  for (const auto& t : known)
    list += (list.empty() ? "" : ", ") + t;
  throw ParameterError(kind + ": unknown type '" + type + "'; expected one of: " + (list.empty() ? "none" : list));
}

}  // namespace hydro
}  // namespace unexmin
