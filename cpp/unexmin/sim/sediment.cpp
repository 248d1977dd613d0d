#include <unexmin/sim/sediment.h>

#include <unexmin/core/error.h>
#include <unexmin/sim/robot.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sim {
namespace {

constexpr double kFloorSearch = 100.0;  ///< [m] how far below a new puff its floor is looked for

/// Standard normal CDF.
double normalCdf(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

/// The nearest static surface along from -> to (fraction of the way, normal), or false.
bool castStatic(const btCollisionWorld& world, const Eigen::Vector3d& from, const Eigen::Vector3d& to, double& fraction,
                Eigen::Vector3d& normal) {
  const btVector3 a(static_cast<btScalar>(from.x()), static_cast<btScalar>(from.y()), static_cast<btScalar>(from.z()));
  const btVector3 b(static_cast<btScalar>(to.x()), static_cast<btScalar>(to.y()), static_cast<btScalar>(to.z()));
  btCollisionWorld::ClosestRayResultCallback hit(a, b);
  hit.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;  // the meshes, not the robots
  world.rayTest(a, b, hit);
  if (!hit.hasHit())
    return false;
  fraction = hit.m_closestHitFraction;
  normal = Eigen::Vector3d(hit.m_hitNormalWorld.x(), hit.m_hitNormalWorld.y(), hit.m_hitNormalWorld.z()).normalized();
  return true;
}

}  // namespace

void validate(const SedimentParams& p, const std::string& file) {
  const auto check = [&](const char* key, double value, double lo, double hi, const char* unit) {
    if (!(value >= lo && value <= hi))
      throw ConfigError(file + ": 'sediment." + key + "' is " + formatNumber(value) + " " + unit + ", expected [" +
                        formatNumber(lo) + ", " + formatNumber(hi) + "]");
  };
  check("settling_speed", p.settling_speed, 0.0, 1.0, "m/s");
  check("raise", p.raise, 0.0, 100.0, "m^2/(N s)");
  check("reach", p.reach, 1e-3, 100.0, "m");
  check("puff_size", p.puff_size, 1e-3, 100.0, "m");
  check("diffusivity", p.diffusivity, 0.0, 10.0, "m^2/s");
  check("interval", p.interval, 1e-3, 100.0, "s");
  check("max_puffs", p.max_puffs, 1, 100000, "");
}

void SedimentField::clear() {
  puffs_.clear();
  impulse_.clear();
  next_ = 0.0;
}

void SedimentField::step(double t, double dt, const std::vector<Robot*>& robots, const btCollisionWorld& collision,
                         const Eigen::Vector3d& current) {
  if (!params_.enabled)
    return;
  // Each thruster's jet: the water pushed against its thrust, summed as a vector impulse over the interval.
  std::size_t count = 0;
  for (const Robot* r : robots)
    count += r->thrusterCount();
  if (impulse_.size() != 3 * count)
    impulse_.assign(3 * count, 0.0);
  std::size_t k = 0;
  for (const Robot* r : robots) {
    const Eigen::Matrix3d rot = r->state().pose.linear();
    for (std::size_t i = 0; i < r->thrusterCount(); ++i, ++k) {
      const hydro::Thruster& th = r->thruster(i);
      const Eigen::Vector3d jet = -th.thrust() * dt * (rot * th.params().axis);
      for (int a = 0; a < 3; ++a)
        impulse_[3 * k + a] += jet[a];
    }
  }
  evolve(dt, current);
  if (t + 1e-9 < next_)
    return;
  next_ = t + params_.interval;
  k = 0;
  for (const Robot* r : robots) {
    const Eigen::Isometry3d pose = r->state().pose;
    for (std::size_t i = 0; i < r->thrusterCount(); ++i, ++k) {
      const Eigen::Vector3d impulse(impulse_[3 * k], impulse_[3 * k + 1], impulse_[3 * k + 2]);
      std::fill(&impulse_[3 * k], &impulse_[3 * k] + 3, 0.0);
      const double magnitude = impulse.norm();  // [N s]
      if (!(magnitude > 0.0))
        continue;
      const Eigen::Vector3d from = pose * r->thruster(i).params().position;
      const Eigen::Vector3d dir = impulse / magnitude;
      double fraction = 0.0;
      Eigen::Vector3d normal;
      if (!castStatic(collision, from, from + params_.reach * dir, fraction, normal))
        continue;  // mid-water: the jet stirs nothing
      const double d = fraction * params_.reach;
      const double q = params_.raise * magnitude * (1.0 - d / params_.reach) * (1.0 - d / params_.reach);
      if (normal.dot(dir) > 0.0)
        normal = -normal;  // towards the water the jet came through
      const Eigen::Vector3d centre = from + d * dir + params_.puff_size * normal;
      double floor_z = centre.z() - kFloorSearch;
      double down = 0.0;
      Eigen::Vector3d up;
      if (castStatic(collision, centre, centre - Eigen::Vector3d(0, 0, kFloorSearch), down, up))
        floor_z = centre.z() - down * kFloorSearch;
      add(centre, q, floor_z);
    }
  }
}

void SedimentField::add(const Eigen::Vector3d& centre, double q, double floor_z) {
  if (!(q > 0.0))
    return;
  const double s0 = params_.puff_size;
  for (auto& p : puffs_) {
    if ((p.centre - centre).norm() >= s0)
      continue;
    // One puff of the two, by moments: strengths add, centre of strength, spread about it.
    const double total = p.strength + q;
    const Eigen::Vector3d c = (p.strength * p.centre + q * centre) / total;
    const double s2 = (p.strength * (p.sigma * p.sigma + (p.centre - c).squaredNorm() / 3.0) +
                       q * (s0 * s0 + (centre - c).squaredNorm() / 3.0)) /
                      total;
    p.centre = c;
    p.sigma = std::sqrt(s2);
    p.strength = total;
    p.floor_z = std::max(p.floor_z, floor_z);
    return;
  }
  SedimentPuff p;
  p.centre = centre;
  p.sigma = s0;
  p.strength = q;
  p.floor_z = floor_z;
  puffs_.push_back(p);
  if (static_cast<int>(puffs_.size()) > params_.max_puffs)
    puffs_.erase(std::min_element(puffs_.begin(), puffs_.end(), [](const SedimentPuff& a, const SedimentPuff& b) {
      return a.strength < b.strength;
    }));
}

void SedimentField::evolve(double dt, const Eigen::Vector3d& current) {
  for (auto& p : puffs_) {
    p.centre += current * dt;
    p.centre.z() -= params_.settling_speed * dt;
    p.sigma = std::sqrt(p.sigma * p.sigma + 2.0 * params_.diffusivity * dt);
  }
  puffs_.erase(std::remove_if(puffs_.begin(), puffs_.end(),
                              [](const SedimentPuff& p) {
                                return p.strength < kFaint || p.centre.z() < p.floor_z - kGone * p.sigma;
                              }),
               puffs_.end());
}

double SedimentField::scattering(const Eigen::Vector3d& x) const {
  double sum = 0.0;
  for (const auto& p : puffs_) {
    const double s = p.sigma;
    sum += p.strength / (std::pow(2.0 * M_PI, 1.5) * s * s * s) * std::exp(-(x - p.centre).squaredNorm() / (2 * s * s));
  }
  return sum;
}

double SedimentField::opticalDepth(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                   double length) const {
  double tau = 0.0;
  for (const auto& p : puffs_) {
    const Eigen::Vector3d w = p.centre - origin;
    const double t0 = w.dot(direction), s = p.sigma;
    const double rho2 = std::max(0.0, w.squaredNorm() - t0 * t0);
    if (rho2 > 36.0 * s * s || t0 < -6.0 * s || t0 > length + 6.0 * s)
      continue;  // beyond 6 sigma: below 1e-8 of the puff
    tau += p.strength / (2.0 * M_PI * s * s) * std::exp(-rho2 / (2.0 * s * s)) *
           (normalCdf((length - t0) / s) - normalCdf(-t0 / s));
  }
  return tau;
}

void SedimentField::opticalDepths(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const float* lengths,
                                  int n, double* out) const {
  std::fill(out, out + n, 0.0);
  if (n <= 0)
    return;
  for (const auto& p : puffs_) {
    const Eigen::Vector3d w = p.centre - origin;
    const double t0 = w.dot(direction), s = p.sigma;
    const double rho2 = std::max(0.0, w.squaredNorm() - t0 * t0);
    if (rho2 > 36.0 * s * s || t0 < -6.0 * s || t0 > lengths[n - 1] + 6.0 * s)
      continue;
    const double scale = p.strength / (2.0 * M_PI * s * s) * std::exp(-rho2 / (2.0 * s * s));
    const double start = normalCdf(-t0 / s);
    for (int j = 0; j < n; ++j) {
      const double x = (lengths[j] - t0) / s;
      if (x < -6.0)
        continue;  // the puff lies beyond this length
      out[j] += scale * ((x > 6.0 ? 1.0 : normalCdf(x)) - start);
    }
  }
}

bool SedimentField::near(const Eigen::Vector3d& point, double radius) const {
  for (const auto& p : puffs_)
    if ((p.centre - point).norm() < radius + 4.0 * p.sigma)
      return true;
  return false;
}

}  // namespace sim
}  // namespace unexmin
