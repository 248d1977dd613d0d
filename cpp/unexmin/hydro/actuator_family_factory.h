// One kind of actuator model by family name: the type the robot description writes for a thruster's
// <dynamics type="..."> and <conversion type="..."> (ThrusterFactory, thruster_factory.h) and a fin's
// <model type="..."> (FinFactory, fin_factory.h). A family is a creator registered under its name; create() builds
// it from the description's <param>s (ActuatorFamilyParams) and rejects a parameter it did not read.
// See docs/adding_a_thruster.md.
#pragma once

#include <unexmin/core/error.h>
#include <unexmin/hydro/actuator_family_params.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace unexmin {
namespace hydro {

/// "thruster dynamics: unknown type 'x'; expected one of: a, b" (or "none").
[[noreturn]] void throwUnknownFamily(const std::string& kind, const std::string& type,
                                     const std::vector<std::string>& known);

/// The families of one kind of actuator model, `Base` = ThrusterDynamics, ThrustConversion or FinLiftModel.
template <class Base>
class ActuatorFamilyFactory {
public:
  using Creator = std::function<std::unique_ptr<Base>(ActuatorFamilyParams&)>;

  /// `kind` names the models in messages: "thruster dynamics", "thrust conversion" or "fin model".
  explicit ActuatorFamilyFactory(std::string kind) : kind_(std::move(kind)) {}

  /// Registers (or replaces) family `type`, built by `creator`. Throws ConfigError on an empty name or creator.
  void add(const std::string& type, Creator creator) {
    if (type.empty())
      throw ConfigError(kind_ + ": a family needs a non-empty type name");
    if (!creator)
      throw ConfigError(kind_ + ": family '" + type + "' has no creator");
    creators_[type] = std::move(creator);
  }
  /// Registers `Model` as family `type`: built as Model(ActuatorFamilyParams&), which reads and checks its
  /// parameters, or as Model() for a family without parameters.
  template <class Model>
  void add(const std::string& type) {
    static_assert(std::is_base_of<Base, Model>::value, "a family's model derives from the kind it is added to");
    add(type, [](ActuatorFamilyParams& params) -> std::unique_ptr<Base> {
      if constexpr (std::is_constructible<Model, ActuatorFamilyParams&>::value) {
        return std::make_unique<Model>(params);
      } else {
        return std::make_unique<Model>();
      }
    });
  }

  bool has(const std::string& type) const { return creators_.count(type) > 0; }
  /// Family names, sorted.
  std::vector<std::string> types() const {
    std::vector<std::string> out;
    for (const auto& kv : creators_)
      out.push_back(kv.first);
    return out;
  }

  /// The model of family `type` with `params`. Throws ParameterError for an unknown type (listing the registered
  /// ones), a parameter the family rejects (naming it, its value and the accepted range) or one it does not read.
  std::unique_ptr<Base> create(const std::string& type, const ParamMap& params) const {
    const auto it = creators_.find(type);
    if (it == creators_.end())
      throwUnknownFamily(kind_, type, types());
    ActuatorFamilyParams reader(kind_ + " '" + type + "'", params);
    std::unique_ptr<Base> model = it->second(reader);
    reader.finish();
    return model;
  }

private:
  std::string kind_;
  std::map<std::string, Creator> creators_;
};

}  // namespace hydro
}  // namespace unexmin
