#include <unexmin/sensors/noise_factory.h>

#include <unexmin/sensors/gaussian_noise.h>

#include <stdexcept>

namespace unexmin {
namespace sensors {
namespace {

/// The "none" family: the truth, no bias, no random draw.
class NoNoise : public NoiseModel {
public:
  void reset(Random&) override {}
  double apply(double truth, Random&) override { return truth; }
  double bias() const override { return 0.0; }
  double whiteStd() const override { return 0.0; }
};

}  // namespace

const std::vector<std::string>& noiseFamilies() {
  static const std::vector<std::string> names{"gaussian", "none"};
  return names;
}

std::unique_ptr<NoiseModel> createNoise(const std::string& family, const NoiseParams& params) {
  if (family == "gaussian")
    return std::make_unique<GaussianNoise>(params);
  if (family == "none")
    return std::make_unique<NoNoise>();
  std::string list;
  for (const auto& n : noiseFamilies())
    list += (list.empty() ? "" : "|") + n;
  throw ParameterError("unknown noise model '" + family + "', expected " + list);
}

}  // namespace sensors
}  // namespace unexmin
