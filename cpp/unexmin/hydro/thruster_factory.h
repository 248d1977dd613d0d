// Thruster models by family name: the type of <dynamics type="..."> and <conversion type="..."> in the robot
// description. ThrusterFactory::builtin() registers the simulator's families (thruster_factory.cpp, one line
// each); a program or a test adds its own to a copy and hands it to sim::parseRobotDescription.
// See docs/adding_a_thruster.md.
#pragma once

#include <unexmin/hydro/thruster.h>
#include <unexmin/hydro/thruster_family_params.h>

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

/// The families of one kind of model, `Base` = ThrusterDynamics or ThrustConversion.
template <class Base>
class ThrusterFamilyFactory {
public:
  using Creator = std::function<std::unique_ptr<Base>(ThrusterFamilyParams&)>;

  /// `kind` names the models in messages: "thruster dynamics" or "thrust conversion".
  explicit ThrusterFamilyFactory(std::string kind) : kind_(std::move(kind)) {}

  /// Registers (or replaces) family `type`, built by `creator`. Throws ConfigError on an empty name or creator.
  void add(const std::string& type, Creator creator) {
    if (type.empty())
      throw ConfigError(kind_ + ": a family needs a non-empty type name");
    if (!creator)
      throw ConfigError(kind_ + ": family '" + type + "' has no creator");
    creators_[type] = std::move(creator);
  }
  /// Registers `Model` as family `type`: built as Model(ThrusterFamilyParams&), which reads and checks its
  /// parameters, or as Model() for a family without parameters.
  template <class Model>
  void add(const std::string& type) {
    static_assert(std::is_base_of<Base, Model>::value, "a family's model derives from the kind it is added to");
    add(type, [](ThrusterFamilyParams& params) -> std::unique_ptr<Base> {
      if constexpr (std::is_constructible<Model, ThrusterFamilyParams&>::value) {
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
    ThrusterFamilyParams reader(kind_ + " '" + type + "'", params);
    std::unique_ptr<Base> model = it->second(reader);
    reader.finish();
    return model;
  }

private:
  std::string kind_;
  std::map<std::string, Creator> creators_;
};

/// Both kinds of a thruster's models, by family name.
struct ThrusterFactory {
  ThrusterFamilyFactory<ThrusterDynamics> dynamics{"thruster dynamics"};
  ThrusterFamilyFactory<ThrustConversion> conversion{"thrust conversion"};

  /// The simulator's families: dynamics zero_order, first_order; conversion identity, basic, table
  /// (docs/hydrodynamics.md).
  static ThrusterFactory builtin();
};

}  // namespace hydro
}  // namespace unexmin
