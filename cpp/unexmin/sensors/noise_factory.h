// Noise families, chosen by name in the robot description (<param name="noise" value="gaussian"/>):
//   gaussian  white noise + bias random walk + turn-on bias (the usual inertial-sensor model)
//   none      the true value, exactly
// One NoiseModel (sensors/noise_model.h) corrupts one scalar channel.
#pragma once

#include <unexmin/sensors/noise_model.h>

#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

/// Names of the families, for messages and documentation.
const std::vector<std::string>& noiseFamilies();

/// The model `family` with `params`; throws ParameterError for an unknown family or a
/// negative figure (the message names the family or the figure).
std::unique_ptr<NoiseModel> createNoise(const std::string& family, const NoiseParams& params);

}  // namespace sensors
}  // namespace unexmin
