// A camera of the UX-1 (family "camera"): renders rgb8 images on the CPU by casting one ray per pixel of the
// published (distorted) image through the world's ray caster, lit only by the robot's own lights in the water of
// the world's visibility (ImageFormation), with its SLS unit's laser line (LaserLine) and sensor noise. Frame: the
// sensor link, the camera's REP-103 optical frame (z forward, x right, y down); rate = frames per second.
//
// Modes (SensorSetup::visual, /sim/mode): in visual mode a frame is rendered at each sample that is wanted (see
// setDemand: the ROS layer asks only when someone subscribes to the image); in operational mode nothing is
// rendered, the lights and the laser line are off, and a sample only moves the schedule (the ROS layer publishes
// camera_info alone). See docs/vision.md.
//
// Per pixel: the ray of the pixel centre (CameraModel::ray, distortion undone exactly), cast up to clip_far; the
// radiance at the lens L = direct + backscatter (ImageFormation; albedo and shading normal of the hit mesh from its
// material in the world file (SurfaceMaterials), of a robot hull SurfaceMaterials::kHullAlbedo); the laser line
// added; then the sensor: signal s = min(1, exposure L) in fractions of full well, shot noise sqrt(s / full_well)
// and read noise read_noise / full_well (Gaussian, seeded), times gain, clamped to [0, 1], gamma-encoded
// v^(1/gamma) and rounded to 8 bits per channel.
//
// Parameters (units; default):
//   width, height [px] (2054 x 1544), hfov [rad] (80 deg), distortion k1 k2 p1 p2 k3 (0), render_scale (1):
//       CameraModel::fromParams
//   clip_far [m] (20): pixel rays end here (open water beyond)
//   exposure [m^2 sr / W] (20): fraction of full well per unit radiance at the lens
//   gain [-] (1), gamma [-] (1: linear), noise gaussian|none (gaussian), full_well [e-] (10000),
//   read_noise [e-] (10)
//   vignetting v [-] in [0, 1] (0: none): the image plane receives L (1 - v + v cos^4 theta), theta the pixel ray's
//       angle to the optical axis (v = 1: the cos^4 law of a thin lens; applied at the sensor, after `radiance`)
//   auto_exposure true|false (false): after each rendered frame the exposure e is multiplied by
//       (auto_exposure_target / m)^auto_exposure_rate, m the frame's mean noise-free signal min(1, e V L) over pixels
//       and channels; auto_exposure_target [-] (0.4) in (0, 1), auto_exposure_rate [-] (0.5) in (0, 1], and the
//       exposure kept within [exposure / auto_exposure_range, exposure * auto_exposure_range] (range [-] 100, >= 1)
//   lights: links of the robot's LED lights (+x = beam axis; none by default); light_intensity I0 per channel
//       [W/sr] (1.5 1.5 1.5), light_cone full angle [rad] (90 deg), light_exponent m [-] (1)
//   shadows true|false (false): one shadow ray per lit pixel and light (ray cast; see docs/vision.md for its cost)
//   simd true|false (true): shade and sense eight pixels at a time in AVX2 lanes where the CPU has AVX2 and FMA
//       (ImageFormation::simdAvailable); false: one at a time. Same kernels, same images up to rounding.
//   forward_scatter true|false (true): the direct image blurred and brightened by the water's and the silt's
//       small-angle scattering (ForwardScatter; runs in water that scatters, and at visibility none only in frames
//       that see silt)
//   marine_snow true|false (true): suspended particles lit by the lights (MarineSnow; their density follows the
//       visibility level, none at none); exposure_time [s] (0.01): how long the shutter is open (their streaks)
//   laser_power [W] (0.05), laser_width [px] (1), laser_colour (0.05 1 0.15): the line of the SLS unit whose
//       <sensor type="sls"> names this camera's link as its camera_frame (none: no line)
#pragma once

#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/vision/camera_model.h>
#include <unexmin/sensors/vision/forward_scatter.h>
#include <unexmin/sensors/vision/image_formation.h>
#include <unexmin/sensors/vision/laser_line.h>
#include <unexmin/sensors/vision/marine_snow.h>
#include <unexmin/sensors/vision/silt_view.h>
#include <unexmin/sensors/vision/surface_materials.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

/// One frame of a camera.
struct CameraFrame {
  double time = -1.0;             ///< sim time of the sample [s]
  bool rendered = false;          ///< false: no image at this sample (operational mode, or not wanted)
  int width = 0, height = 0;      ///< [px] of the published image
  std::vector<std::uint8_t> rgb;  ///< rgb8, row-major, 3 * width bytes per row
  /// Linear radiance at the lens per pixel and channel, before the sensor [W m^-2 sr^-1] (3 per pixel).
  std::vector<float> radiance;
  std::vector<float> range;  ///< distance from the lens to the surface per pixel [m]; +inf: none
};

class CameraSensor : public Sensor {
public:
  CameraSensor(const sim::SensorSpec& spec, const SensorSetup& setup);
  ~CameraSensor() override;

  /// The published image's geometry (render_scale applied): CameraInfo's K, D, P and size.
  const CameraModel& model() const { return model_; }
  /// Visual mode: images are rendered (when wanted), lights and laser on.
  bool visual() const { return visual_; }
  const CameraFrame& last() const { return frame_; }
  /// Renders only at samples where `wanted()` is true (e.g. the image topic has a subscriber); null: always.
  void setDemand(std::function<bool()> wanted) { demand_ = std::move(wanted); }
  /// Off: renders no frame whatever setDemand says (on by default; kept across reset()).
  void setRendering(bool on) override { rendering_ = on; }

  double clipFar() const { return clip_far_; }   ///< [m]
  double exposure() const { return exposure_; }  ///< [m^2 sr / W] (the parameter; the start of auto-exposure)
  /// The exposure the next frame is taken with [m^2 sr / W] (exposure() unless auto-exposure moved it).
  double currentExposure() const { return exposure_now_; }
  double vignetting() const { return vignetting_; }  ///< [-]
  double gain() const { return gain_; }              ///< [-]
  double gamma() const { return gamma_; }            ///< [-]
  bool shadows() const { return shadows_; }
  /// The lights in this camera's optical frame.
  const std::vector<LedLight>& lights() const { return lights_; }
  /// The laser line drawn in this camera's image (null: no SLS unit names this camera).
  const LaserLine* laser() const { return laser_.get(); }
  /// The image formation of the latest rendered frame's water (null before the first render).
  const ImageFormation* formation() const { return formation_.get(); }
  /// The forward scattering of the latest rendered frame (null: none in its water and no silt in view, or off).
  const ForwardScatter* forwardScatter() const { return scatter_on_ ? scatter_.get() : nullptr; }
  /// The suspended particles around the lens (null: none in the water, or off, or before the first render).
  const MarineSnow* marineSnow() const { return snow_.get(); }
  double exposureTime() const { return exposure_time_; }  ///< [s]
  /// The silt as the latest rendered frame saw it (null: it saw none).
  const SiltView* silt() const { return silt_on_ ? silt_.get() : nullptr; }
  /// The camera's optical frame in the base frame.
  const Eigen::Isometry3d& pose() const { return spec().pose; }

protected:
  void onReset() override;
  void sample(const SensorContext& ctx) override;
  void describeSample(SampleWriter& out) const override;

private:
  /// Builds what rendering needs (once, and again when the world's water changes).
  void prepare(const SensorContext& ctx);
  /// Renders frame_ (noise of frame seed `seed`).
  void render(const SensorContext& ctx, std::uint64_t seed);
  /// Radiance, range and rgb of the pixels [u0, u1) x [v0, v1) (at most one tile) of the camera at `cam` (world
  /// frame), on the calling thread, in stages passing one Tile along: castTile, shadowTile, surfaceTile,
  /// textureTile, shadeTile, then encode (or scatterTile when forward scattering runs: the sensor comes after it).
  void renderTile(const SensorContext& ctx, const Eigen::Isometry3d& cam, int u0, int v0, int u1, int v1,
                  std::uint64_t seed);
  struct Tile;
  /// The tile's pixels and their rays from the lens at `cam`, cast up to clip_far.
  void castTile(const SensorContext& ctx, const Eigen::Isometry3d& cam, int u0, int v0, int u1, int v1, Tile& t) const;
  /// Which lights reach each pixel's surface point: all, or (shadows on) those whose shadow ray meets nothing.
  void shadowTile(const SensorContext& ctx, Tile& t) const;
  /// The batch from the hits: each pixel's surface (point, face normal, one albedo: the hull's, the mesh's mean or
  /// mapped one) or open water; frame_.range; which pixels see a textured mesh.
  void surfaceTile(Tile& t);
  /// Albedo and shading normal of the pixels on textured meshes (SurfaceMaterials::shadeMany), into the batch.
  void textureTile(Tile& t) const;
  /// The batch's radiance at the lens (ImageFormation::radiance, the silt in view), into frame_.radiance.
  void shadeTile(Tile& t);
  /// The tile's direct light (and the silt's optical depth on its rays) into the forward scattering's buffer.
  void scatterTile(const Tile& t);
  /// The sensor at the n <= raycast::kBlock pixels `pixel` whose radiance per channel is radiance[c][0..n): noise,
  /// gain, gamma, 8 bits per channel into the image. `simd`: in AVX2 lanes (then radiance[c] holds n rounded up to
  /// a multiple of 8 finite values).
  void encode(int n, const std::size_t* pixel, float* const radiance[3], std::uint64_t seed, bool simd);
  /// Auto-exposure: the next frame's exposure from this one's mean signal (see the parameters above).
  void adjustExposure();
  /// The same for pixel i alone, from frame_.radiance.
  void encodePixel(std::size_t i, std::uint64_t seed);
  /// The sensor at every pixel, from frame_.radiance (after a pass over the whole image: forward scattering).
  void encodeAll(const SensorContext& ctx, std::uint64_t seed);

  CameraModel model_;
  bool visual_ = false;
  double clip_far_ = 20.0, exposure_ = 20.0, gain_ = 1.0, gamma_ = 1.0;
  bool noise_ = true, shadows_ = false, simd_ = true;
  bool forward_scatter_ = true, marine_snow_ = true;
  double exposure_time_ = 0.01;  ///< [s] (marine snow streaks)
  double full_well_ = 10000.0, read_noise_ = 10.0;
  double vignetting_ = 0.0;
  bool auto_exposure_ = false;
  double ae_target_ = 0.4, ae_rate_ = 0.5, ae_range_ = 100.0;
  double exposure_now_ = 20.0;   ///< the exposure of the next frame [m^2 sr / W]
  std::vector<float> vignette_;  ///< per pixel: 1 - v + v cos^4 theta (empty: no vignetting)
  std::vector<LedLight> lights_;
  std::unique_ptr<LaserLine> laser_;
  std::function<bool()> demand_;
  bool rendering_ = true;  ///< setRendering

  // Built at the first render (visual mode only).
  std::unique_ptr<ImageFormation> formation_;
  std::unique_ptr<ForwardScatter> scatter_;      ///< made when first needed (ForwardScatter::needed, or silt in view)
  bool scatter_on_ = false;                      ///< this frame runs forward scattering
  std::unique_ptr<MarineSnow> snow_;             ///< null in water without particles
  std::unique_ptr<SiltView> silt_;               ///< made when the world first holds silt
  bool silt_on_ = false;                         ///< this frame sees silt
  double snow_time_ = 0.0;                       ///< sim time the particles were last moved to [s]
  std::string water_key_;                        ///< visibility level, colour and turbidity the formation was built for
  std::vector<Eigen::Vector3f> dirs_;            ///< per pixel: unit ray direction in the optical frame
  std::unique_ptr<SurfaceMaterials> materials_;  ///< per world mesh: albedo, texture (docs/vision.md)
  std::vector<std::int32_t> encode_;             ///< gamma table: signal in [0, 1] -> 8 bits
  shading::SensorResponse response_;             ///< the sensor's constants as the kernel reads them
  std::vector<std::size_t> touched_;             ///< pixels the laser line lit this frame
  CameraFrame frame_;
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
