#include <unexmin/sensors/vision/camera_sensor.h>

#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/vision/parallel_rows.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unexmin {
namespace sensors {
namespace vision {
namespace {

constexpr double kDeg = M_PI / 180.0;
/// Side of a tile [px]: a tile's 8 x 8 pixels are one block of the ray caster.
constexpr int kTile = 8;
static_assert(static_cast<std::size_t>(kTile * kTile) == raycast::kBlock,
              "a tile is cast, shaded and encoded as one block");
/// Entries of the gamma table over [0, 1].
constexpr int kEncodeEntries = 4096;

/// splitmix64: a well-mixed 64-bit hash of z.
inline std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// 4096 standard normal quantiles at (i + 0.5) / 4096 (16 kB: stays in the L1 cache): a draw is a 12-bit index
/// into them, so its distribution is the normal one quantised to 4096 equiprobable values (tails cut at 3.7 sigma).
const std::vector<float>& normalTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t(4096);
    for (int i = 0; i < 4096; ++i) {
      // Inverse of the standard normal CDF by bisection on erfc (once, at start-up).
      const double q = (i + 0.5) / 4096.0;
      double lo = -10.0, hi = 10.0;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
      }
      t[static_cast<std::size_t>(i)] = static_cast<float>(0.5 * (lo + hi));
    }
    return t;
  }();
  return table;
}

bool isLink(const sim::RobotDescription& d, const std::string& link) {
  if (link == d.base_link)
    return true;
  for (const auto& j : d.joints)
    if (j.child == link)
      return true;
  return false;
}

}  // namespace

CameraSensor::CameraSensor(const sim::SensorSpec& spec, const SensorSetup& setup)
    : Sensor(spec, setup), visual_(setup.visual) {
  SensorParams p(spec, setup.robot);
  model_ = CameraModel::fromParams(p);
  clip_far_ = p.number("clip_far", 20.0, 0.1, 10000.0, "m");
  exposure_ = p.number("exposure", 20.0, 0.0, 1e12, "m^2 sr / W");
  gain_ = p.number("gain", 1.0, 0.0, 1e6, "");
  gamma_ = p.number("gamma", 1.0, 0.1, 10.0, "");
  noise_ = p.text("noise", "gaussian", {"gaussian", "none"}) == "gaussian";
  full_well_ = p.number("full_well", 10000.0, 1.0, 1e9, "e-");
  read_noise_ = p.number("read_noise", 10.0, 0.0, 1e9, "e-");
  vignetting_ = p.number("vignetting", 0.0, 0.0, 1.0, "");
  auto_exposure_ = p.flag("auto_exposure", false);
  ae_target_ = p.number("auto_exposure_target", 0.4, 1e-6, 1.0 - 1e-6, "");
  ae_rate_ = p.number("auto_exposure_rate", 0.5, 1e-6, 1.0, "");
  ae_range_ = p.number("auto_exposure_range", 100.0, 1.0, 1e12, "");
  exposure_now_ = exposure_;
  const std::vector<std::string> light_links = p.words("lights");
  const Eigen::Vector3d intensity = p.vec3("light_intensity", Eigen::Vector3d(1.5, 1.5, 1.5));
  for (int k = 0; k < 3; ++k)
    if (!(intensity[k] >= 0.0) || !std::isfinite(intensity[k]))
      p.fail("light_intensity", formatNumber(intensity[k]), "three finite numbers >= 0 W/sr");
  const double cone = p.number("light_cone", 90.0 * kDeg, 1e-3, M_PI, "rad");
  const double exponent = p.number("light_exponent", 1.0, 0.0, 1000.0, "");
  shadows_ = p.flag("shadows", false);
  simd_ = p.flag("simd", true);
  forward_scatter_ = p.flag("forward_scatter", true);
  marine_snow_ = p.flag("marine_snow", true);
  exposure_time_ = p.number("exposure_time", 0.01, 0.0, 10.0, "s");
  const double laser_power = p.number("laser_power", 0.05, 0.0, 1000.0, "W");
  const double laser_width = p.number("laser_width", 1.0, 0.1, 100.0, "px");
  const Eigen::Vector3d laser_colour = p.vec3("laser_colour", Eigen::Vector3d(0.05, 1.0, 0.15));
  for (int k = 0; k < 3; ++k)
    if (!(laser_colour[k] >= 0.0) || !std::isfinite(laser_colour[k]))
      p.fail("laser_colour", formatNumber(laser_colour[k]), "three finite numbers >= 0");
  p.finish();

  if (light_links.size() > 32)
    p.fail("lights", formatNumber(light_links.size()) + " links", "at most 32 lights");
  const Eigen::Isometry3d to_camera = spec.pose.inverse();
  for (const auto& link : light_links) {
    if (!isLink(setup.description, link))
      p.fail("lights", "'" + link + "'", "links of the robot (the LED lights)");
    const Eigen::Isometry3d pose = to_camera * setup.description.linkPose(link);
    LedLight l;
    l.position = pose.translation();
    l.axis = pose.linear().col(0);
    l.intensity = intensity;
    l.cone = cone;
    l.exponent = exponent;
    lights_.push_back(l);
  }

  // The SLS unit that names this camera's link as the camera that sees its laser.
  const sim::SensorSpec* sls = nullptr;
  for (const auto& s : setup.description.sensors) {
    const auto it = s.text.find("camera_frame");
    if (s.type != "sls" || it == s.text.end() || it->second != spec.link)
      continue;
    if (sls)
      throw ConfigError(p.where() + ": SLS units '" + sls->name + "' and '" + s.name +
                        "' both name it as their camera (camera_frame " + spec.link + "); expected at most one");
    sls = &s;
  }
  if (sls)
    laser_ = std::make_unique<LaserLine>(std::make_unique<SlsSensor>(*sls, setup), spec.pose, model_, laser_power,
                                         laser_width, laser_colour, clip_far_, SurfaceMaterials::kHullAlbedo.y());
}

CameraSensor::~CameraSensor() = default;

void CameraSensor::onReset() {
  exposure_now_ = exposure_;
  snow_.reset();
  frame_.time = -1.0;
  frame_.rendered = false;
}

void CameraSensor::sample(const SensorContext& ctx) {
  frame_.time = ctx.world.time();
  frame_.rendered = false;
  // One draw per sample, rendered or not: the stream does not depend on who watches.
  const auto seed = static_cast<std::uint64_t>(random().uniform() * 9007199254740992.0);
  if (!visual_ || !rendering_ || (demand_ && !demand_()))
    return;
  prepare(ctx);
  render(ctx, seed);
  frame_.rendered = true;
}

void CameraSensor::prepare(const SensorContext& ctx) {
  const sim::WorldConfig& config = ctx.world.config();
  const Eigen::Vector3d lens = (ctx.state.pose * spec().pose).translation();
  const double turbidity = opticalTurbidity(config, lens, ctx.world.time());  // -1 but for level "water"
  const std::string key = config.visibility + " " + formatNumber(config.visibility_colour.x()) + " " +
                          formatNumber(config.visibility_colour.y()) + " " +
                          formatNumber(config.visibility_colour.z()) + " " + formatNumber(turbidity);
  if (!formation_ || key != water_key_) {
    formation_ =
        std::make_unique<ImageFormation>(model_, lights_, WaterOptics::fromWorld(config, turbidity), clip_far_);
    water_key_ = key;
    scatter_.reset();
    snow_.reset();
    silt_.reset();
  }
  const int w = model_.width(), h = model_.height();
  const std::size_t n = static_cast<std::size_t>(w) * h;
  if (dirs_.size() != n) {
    scatter_.reset();
    silt_.reset();
    dirs_.resize(n);
    parallelRows(h, [&](int v0, int v1) {
      for (int v = v0; v < v1; ++v)
        for (int u = 0; u < w; ++u)
          dirs_[static_cast<std::size_t>(v) * w + u] = model_.ray(u, v).cast<float>();
    });
    vignette_.clear();
    if (vignetting_ > 0.0) {
      vignette_.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const double c = dirs_[i].z() / dirs_[i].norm();  // cos theta
        vignette_[i] = static_cast<float>(1.0 - vignetting_ + vignetting_ * c * c * c * c);
      }
    }
    frame_.width = w;
    frame_.height = h;
    frame_.rgb.assign(3 * n, 0);
    frame_.radiance.assign(3 * n, 0.0f);
    frame_.range.assign(n, std::numeric_limits<float>::infinity());
    encode_.resize(kEncodeEntries + 1);
    for (int i = 0; i <= kEncodeEntries; ++i)
      encode_[i] = static_cast<std::int32_t>(std::lround(255.0 * std::pow(i / double(kEncodeEntries), 1.0 / gamma_)));
    response_.exposure = static_cast<float>(exposure_);
    response_.gain = static_cast<float>(gain_);
    response_.shot = static_cast<float>(1.0 / full_well_);
    response_.read2 = static_cast<float>((read_noise_ / full_well_) * (read_noise_ / full_well_));
    response_.normal = normalTable().data();
    response_.encode = encode_.data();
    response_.encode_last = static_cast<float>(kEncodeEntries);
  }
  const double density = marine_snow_ ? MarineSnow::density(config.visibility, turbidity) : 0.0;
  if (snow_) {
    snow_->advance(lens, ctx.world.water().current, ctx.world.time() - snow_time_);
  } else if (density > 0.0) {
    const std::uint64_t seed = Random::streamSeed(ctx.world.seed(), ctx.robot.name(), spec().name + "/marine_snow");
    snow_ = std::make_unique<MarineSnow>(density, seed, lens);
  }
  snow_time_ = ctx.world.time();
  SurfaceMaterials::of(ctx.world, materials_);
}

void CameraSensor::encode(int n, const std::size_t* pixel, float* const radiance[3], std::uint64_t seed, bool simd) {
  alignas(32) std::int32_t noise[3][raycast::kBlock];
  alignas(32) std::int32_t code[3][raycast::kBlock];
  simd = simd && ImageFormation::simdAvailable();
  const int padded = simd ? (n + 7) / 8 * 8 : n;  // the padding's radiance is there (PixelBatch), its codes unused
  if (!vignette_.empty())
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < n; ++i)
        radiance[c][i] *= vignette_[pixel[i]];
  const std::int32_t* draws[3] = {nullptr, nullptr, nullptr};
  if (noise_) {
    // One hash per pixel: three 12-bit indices into the normal quantiles, a pure function of (seed, pixel), so
    // the image does not depend on the thread count or on how often a pixel is encoded.
    for (int i = 0; i < n; ++i) {
      const std::uint64_t hash = mix(seed + 0x9e3779b97f4a7c15ull * pixel[i]);
      noise[0][i] = static_cast<std::int32_t>(hash & 0xfff);
      noise[1][i] = static_cast<std::int32_t>((hash >> 12) & 0xfff);
      noise[2][i] = static_cast<std::int32_t>((hash >> 24) & 0xfff);
    }
    for (int c = 0; c < 3; ++c) {
      std::fill(noise[c] + n, noise[c] + padded, 0);
      draws[c] = noise[c];
    }
  }
  std::int32_t* const codes[3] = {code[0], code[1], code[2]};
  if (simd)
    shading::sensorResponseAvx2(response_, padded, radiance, draws, codes);
  else
    shading::sensorResponse<lanes::F1>(response_, n, radiance, draws, codes);
  for (int i = 0; i < n; ++i) {
    std::uint8_t* px = &frame_.rgb[3 * pixel[i]];
    for (int c = 0; c < 3; ++c)
      px[c] = static_cast<std::uint8_t>(code[c][i]);
  }
}

void CameraSensor::encodePixel(std::size_t i, std::uint64_t seed) {
  float rad[3] = {frame_.radiance[3 * i], frame_.radiance[3 * i + 1], frame_.radiance[3 * i + 2]};
  float* const channels[3] = {&rad[0], &rad[1], &rad[2]};
  encode(1, &i, channels, seed, false);
}

void CameraSensor::encodeAll(const SensorContext& ctx, std::uint64_t seed) {
  const int w = model_.width(), h = model_.height();
  const bool simd = simd_ && ImageFormation::simdAvailable();
  const auto strip = [&](std::size_t k) {
    const int v0 = static_cast<int>(k) * kTile, v1 = std::min(v0 + kTile, h);
    for (int u0 = 0; u0 < w; u0 += kTile) {
      alignas(32) float rad[3][raycast::kBlock] = {};
      std::size_t pixel[raycast::kBlock];
      int n = 0;
      for (int v = v0; v < v1; ++v)
        for (int u = u0; u < std::min(u0 + kTile, w); ++u, ++n) {
          pixel[n] = static_cast<std::size_t>(v) * w + u;
          for (int c = 0; c < 3; ++c)
            rad[c][n] = frame_.radiance[3 * pixel[n] + c];
        }
      float* const radiance[3] = {rad[0], rad[1], rad[2]};
      encode(n, pixel, radiance, seed, simd);
    }
  };
  const std::size_t strips = static_cast<std::size_t>((h + kTile - 1) / kTile);
  if (ctx.rays)
    ctx.rays->parallelFor(strips, strip);
  else
    for (std::size_t k = 0; k < strips; ++k)
      strip(k);
}

void CameraSensor::render(const SensorContext& ctx, std::uint64_t seed) {
  const int w = model_.width(), h = model_.height();
  const Eigen::Isometry3d cam = ctx.state.pose * spec().pose;
  const std::size_t strips = static_cast<std::size_t>((h + kTile - 1) / kTile);
  response_.exposure = static_cast<float>(exposure_now_);
  silt_on_ = false;
  if (!ctx.world.sediment().empty()) {
    if (!silt_)
      silt_ = std::make_unique<SiltView>(model_, *formation_);
    silt_on_ = silt_->update(ctx.world.sediment(), cam);
  }
  // Forward scattering in water that scatters enough, and wherever the view holds silt (which scatters forward too).
  scatter_on_ = forward_scatter_ && (ForwardScatter::needed(formation_->water()) || silt_on_);
  if (scatter_on_ && !scatter_)
    scatter_ = std::make_unique<ForwardScatter>(formation_->water(), clip_far_, model_.fx(), w, h, kTile);
  if (scatter_on_)
    scatter_->clear();
  // Every tile alone: its rays, their cast, its pixels' shading and sensor (the pixels do not depend on which thread
  // renders them, nor on the order). A thread takes a whole strip of kTile rows at a time: two threads never write
  // to the same cache line of the image but at a strip's first and last row (neighbouring tiles on two threads
  // would share one at every row of every tile's edge).
  const auto strip = [&](std::size_t k) {
    const int v0 = static_cast<int>(k) * kTile, v1 = std::min(v0 + kTile, h);
    for (int u0 = 0; u0 < w; u0 += kTile)
      renderTile(ctx, cam, u0, v0, std::min(u0 + kTile, w), v1, seed);
  };
  if (ctx.rays)
    ctx.rays->parallelFor(strips, strip);
  else
    for (std::size_t k = 0; k < strips; ++k)
      strip(k);
  if (scatter_on_)  // the tiles kept their direct light: blur it over the whole image
    scatter_->apply(frame_.radiance, ctx.rays);
  touched_.clear();
  if (snow_) {
    MarineSnow::Motion motion;
    motion.pose = cam;
    motion.base = ctx.state.pose.translation();
    motion.velocity = ctx.state.linear_velocity;
    motion.angular = ctx.state.angular_velocity;
    motion.current = ctx.world.water().current;
    motion.exposure_time = exposure_time_;
    snow_->draw(model_, *formation_, motion, frame_.range, frame_.radiance, touched_);
  }
  if (scatter_on_)  // then the sensor, at every pixel
    encodeAll(ctx, seed);
  else
    for (std::size_t i : touched_)
      encodePixel(i, seed);
  if (laser_) {
    // The line adds light to a few pixels: encode those again (noise is a function of seed and pixel alone).
    touched_.clear();
    laser_->draw(ctx, formation_->water(), frame_.range, frame_.radiance, touched_);
    for (std::size_t i : touched_)
      encodePixel(i, seed);
  }
  if (auto_exposure_)
    adjustExposure();
}

void CameraSensor::adjustExposure() {
  // The frame's mean noise-free signal, then one step of the exposure towards the target (in log: the error shrinks
  // by the factor 1 - rate per frame while nothing saturates).
  const std::size_t n = frame_.range.size();
  const float e = static_cast<float>(exposure_now_);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const float v = vignette_.empty() ? 1.0f : vignette_[i];
    for (int c = 0; c < 3; ++c)
      sum += std::min(1.0f, e * v * frame_.radiance[3 * i + c]);
  }
  const double mean = n ? sum / (3.0 * static_cast<double>(n)) : 0.0;
  const double next = mean > 0.0 ? exposure_now_ * std::pow(ae_target_ / mean, ae_rate_) : exposure_ * ae_range_;
  exposure_now_ = std::min(exposure_ * ae_range_, std::max(exposure_ / ae_range_, next));
}

/// One tile on its way through renderTile's stages: its pixels and their rays and hits (castTile), which lights reach
/// each pixel (shadowTile), the surface each sees as the shading kernels read it (surfaceTile, textureTile), its
/// radiance (shadeTile).
struct CameraSensor::Tile {
  int u0 = 0, v0 = 0;                              ///< first pixel [px]
  int n = 0;                                       ///< pixels in use
  Eigen::Matrix3f rot;                             ///< optical frame -> world
  Eigen::Vector3f origin;                          ///< the lens, world frame [m]
  float far = 0.0f;                                ///< clip_far [m]
  bool simd = false;                               ///< shade and sense in AVX2 lanes
  std::size_t pixel[raycast::kBlock];              ///< index of each pixel in the image
  float pu[raycast::kBlock], pv[raycast::kBlock];  ///< pixel coordinates [px]
  raycast::Ray rays[raycast::kBlock];
  raycast::Hit hits[raycast::kBlock];
  unsigned lit[raycast::kBlock];                         ///< bit k: light k reaches the pixel's surface point
  static constexpr std::size_t kNone = ~std::size_t(0);  ///< material_of: no textured mesh
  std::size_t material_of[raycast::kBlock];              ///< the textured mesh each pixel sees, or kNone
  int textured = 0;                                      ///< pixels that see a textured mesh
  bool one_mesh = true;                                  ///< all of them see the same one
  PixelBatch batch;                                      ///< what the shading kernels read and write
};

void CameraSensor::renderTile(const SensorContext& ctx, const Eigen::Isometry3d& cam, int u0, int v0, int u1, int v1,
                              std::uint64_t seed) {
  Tile tile;
  castTile(ctx, cam, u0, v0, u1, v1, tile);
  shadowTile(ctx, tile);
  surfaceTile(tile);
  textureTile(tile);
  shadeTile(tile);
  if (scatter_on_) {  // the sensor comes after the whole image's forward scattering (encodeAll)
    scatterTile(tile);
    return;
  }
  float* const radiance[3] = {tile.batch.out[0], tile.batch.out[1], tile.batch.out[2]};
  encode(tile.n, tile.pixel, radiance, seed, tile.simd);
}

void CameraSensor::castTile(const SensorContext& ctx, const Eigen::Isometry3d& cam, int u0, int v0, int u1, int v1,
                            Tile& t) const {
  const int w = model_.width();
  t.u0 = u0;
  t.v0 = v0;
  t.rot = cam.linear().cast<float>();
  t.origin = cam.translation().cast<float>();
  t.far = static_cast<float>(clip_far_);
  t.simd = simd_ && ImageFormation::simdAvailable();
  int n = 0;
  for (int v = v0; v < v1; ++v)
    for (int u = u0; u < u1; ++u, ++n) {
      t.pixel[n] = static_cast<std::size_t>(v) * w + u;
      t.pu[n] = static_cast<float>(u);
      t.pv[n] = static_cast<float>(v);
      t.rays[n].origin = t.origin;
      t.rays[n].direction = t.rot * dirs_[t.pixel[n]];
      t.rays[n].max_range = t.far;
    }
  t.n = n;
  // Shading uses the normal, not the angle.
  if (ctx.rays)
    ctx.rays->cast(t.rays, t.hits, static_cast<std::size_t>(n), ctx.robot_index, raycast::Incidence::skip,
                   raycast::SeenBy::cameras);
}

void CameraSensor::shadowTile(const SensorContext& ctx, Tile& t) const {
  std::fill(t.lit, t.lit + t.n, ~0u);
  if (!shadows_)
    return;
  // One ray from each light towards every surface point it would light; a hit before the point shadows it.
  thread_local std::vector<raycast::Ray> shadow_rays;
  thread_local std::vector<raycast::Hit> shadow_hits;
  thread_local std::vector<std::pair<int, int>> pairs;  // (pixel of the tile, light)
  shadow_rays.clear();
  pairs.clear();
  for (int i = 0; i < t.n; ++i) {
    if (!t.hits[i].hit())
      continue;
    const Eigen::Vector3f p = t.hits[i].range * dirs_[t.pixel[i]];
    const Eigen::Vector3f nrm = t.rot.transpose() * t.hits[i].normal;
    for (int k : formation_->activeLights()) {
      if (!formation_->canLight(k, p, nrm))
        continue;
      const Eigen::Vector3f from = t.rot * lights_[static_cast<std::size_t>(k)].position.cast<float>() + t.origin;
      const Eigen::Vector3f to = t.hits[i].point(t.rays[i]) - from;
      const float len = to.norm();
      if (!(len > 2e-3f))
        continue;
      raycast::Ray r;
      r.origin = from;
      r.direction = to / len;
      r.max_range = len * 0.999f - 1e-3f;
      shadow_rays.push_back(r);
      pairs.emplace_back(i, k);
    }
  }
  if (ctx.rays && !shadow_rays.empty()) {
    ctx.rays->cast(shadow_rays, shadow_hits, ctx.robot_index, raycast::Incidence::skip, raycast::SeenBy::cameras);
    for (std::size_t s = 0; s < pairs.size(); ++s)
      if (shadow_hits[s].hit())
        t.lit[pairs[s].first] &= ~(1u << pairs[s].second);
  }
}

void CameraSensor::surfaceTile(Tile& t) {
  // Every pixel as if plain (the hull's or the mesh's one albedo, the face's normal); textureTile then the textured.
  const Eigen::Matrix3f to_camera = t.rot.transpose();
  const float hull[3] = {static_cast<float>(SurfaceMaterials::kHullAlbedo.x()),
                         static_cast<float>(SurfaceMaterials::kHullAlbedo.y()),
                         static_cast<float>(SurfaceMaterials::kHullAlbedo.z())};
  PixelBatch& batch = t.batch;
  batch.n = t.n;
  batch.keep_direct = scatter_on_ || silt_on_;  // read by scatterTile and by the silt (shadeTile)
  t.textured = 0;
  t.one_mesh = true;
  for (int i = 0; i < t.n; ++i) {
    const raycast::Hit& hit = t.hits[i];
    t.material_of[i] = Tile::kNone;
    if (hit.hit()) {
      const auto mesh = static_cast<std::size_t>(hit.index);
      const bool is_mesh = hit.kind == raycast::HitKind::mesh;
      float mapped[3];
      const float* albedo = !is_mesh                   ? hull
                            : materials_->mapped(mesh) ? materials_->mappedAlbedo(hit, mapped)
                                                       : materials_->meanAlbedo(mesh).data();
      batch.set(i, t.pu[i], t.pv[i], hit.range, hit.range * dirs_[t.pixel[i]], to_camera * hit.normal, albedo,
                t.lit[i]);
      frame_.range[t.pixel[i]] = hit.range;
      if (is_mesh && materials_->textured(mesh)) {
        t.material_of[i] = mesh;
        t.one_mesh = t.one_mesh && mesh == t.material_of[0];
        ++t.textured;
      }
    } else {
      batch.setWater(i, t.pu[i], t.pv[i], t.far);
      frame_.range[t.pixel[i]] = std::numeric_limits<float>::infinity();
    }
  }
}

void CameraSensor::textureTile(Tile& t) const {
  // Albedo and shading normal of the textured pixels evaluated into the batch itself, one textured mesh at a time
  // (eight pixels in lanes).
  PixelBatch& batch = t.batch;
  const int n = t.n;
  if (t.textured == n && t.one_mesh) {  // the usual tile: one textured wall
    float* const albedo[3] = {batch.albedo[0], batch.albedo[1], batch.albedo[2]};
    materials_->shadeMany(t.material_of[0], t.rot, t.origin, n, batch.px, batch.py, batch.pz, batch.nx, batch.ny,
                          batch.nz, albedo, t.simd);
    return;
  }
  if (t.textured == 0)
    return;
  for (int first = 0; first < n; ++first) {
    const std::size_t mesh = t.material_of[first];
    if (mesh == Tile::kNone || std::find(t.material_of, t.material_of + first, mesh) != t.material_of + first)
      continue;  // not textured, or this mesh is done
    // The pixels of this mesh, gathered, evaluated and put back.
    alignas(32) float x[3][raycast::kBlock], nrm[3][raycast::kBlock], albedo[3][raycast::kBlock];
    int which[raycast::kBlock], count = 0;
    for (int i = first; i < n; ++i)
      if (t.material_of[i] == mesh) {
        x[0][count] = batch.px[i], x[1][count] = batch.py[i], x[2][count] = batch.pz[i];
        nrm[0][count] = batch.nx[i], nrm[1][count] = batch.ny[i], nrm[2][count] = batch.nz[i];
        which[count++] = i;
      }
    float* const out[3] = {albedo[0], albedo[1], albedo[2]};
    materials_->shadeMany(mesh, t.rot, t.origin, count, x[0], x[1], x[2], nrm[0], nrm[1], nrm[2], out, t.simd);
    for (int j = 0; j < count; ++j) {
      const int i = which[j];
      batch.nx[i] = nrm[0][j], batch.ny[i] = nrm[1][j], batch.nz[i] = nrm[2][j];
      for (int c = 0; c < 3; ++c)
        batch.albedo[c][i] = albedo[c][j];
    }
  }
}

void CameraSensor::shadeTile(Tile& t) {
  formation_->radiance(t.batch, t.simd);
  if (silt_on_)
    silt_->apply(t.batch, t.batch.direct);
  for (int i = 0; i < t.n; ++i) {
    float* out = &frame_.radiance[3 * t.pixel[i]];
    for (int c = 0; c < 3; ++c)
      out[c] = t.batch.out[c][i];
  }
}

void CameraSensor::scatterTile(const Tile& t) {
  const PixelBatch& batch = t.batch;
  const float* const direct[3] = {batch.direct[0], batch.direct[1], batch.direct[2]};
  if (!silt_on_) {
    scatter_->accumulate(t.u0 / kTile, t.v0 / kTile, t.n, direct, batch.range);
    return;
  }
  // The silt on the camera leg scatters forward as the water does: its forward scatterings eta tau(R).
  float silt[raycast::kBlock];
  const float eta = static_cast<float>(scatter_->eta());
  for (int i = 0; i < t.n; ++i)
    silt[i] = eta * static_cast<float>(silt_->opticalDepth(batch.u[i], batch.v[i], batch.range[i]));
  scatter_->accumulate(t.u0 / kTile, t.v0 / kTile, t.n, direct, batch.range, silt);
}

void CameraSensor::describeSample(SampleWriter& out) const {
  out.flag("rendered", frame_.rendered);
  // CameraInfo's numbers of the published image: K (3 x 3, row-major) and D (plumb_bob k1 k2 p1 p2 k3).
  const auto k = model_.K();
  out.array("K", "px", std::vector<double>(k.begin(), k.end()), {3, 3});
  const auto& d = model_.distortion();
  out.array("D", "-", std::vector<double>(d.begin(), d.end()));
  if (frame_.rendered)  // rgb8; kept by the camera until its next sample
    out.array("image", "-", frame_.rgb,
              {static_cast<std::size_t>(frame_.height), static_cast<std::size_t>(frame_.width), 3}, true);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
