#include <unexmin/hydro/fossen_model.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace unexmin {
namespace hydro {

namespace {

const char* const kWhat = "hydro";

std::string num(double x) {
  return formatNumber(x);
}

[[noreturn]] void fail(const std::string& name, double value, const std::string& expected) {
  throw ParameterError(std::string(kWhat) + ": parameter '" + name + "' = " + num(value) + " " + expected);
}

void requireFinite(const std::string& name, double value, const std::string& unit) {
  if (!std::isfinite(value)) {
    fail(name, value, "must be finite " + unit);
  }
}

void requirePositive(const std::string& name, double value, const std::string& unit) {
  requireFinite(name, value, unit);
  if (!(value > 0.0)) {
    fail(name, value, "must be > 0 " + unit);
  }
}

void requireNonNegative(const std::string& name, double value, const std::string& unit) {
  requireFinite(name, value, unit);
  if (!(value >= 0.0)) {
    fail(name, value, "must be >= 0 " + unit);
  }
}

std::string indexed(const std::string& name, int i) {
  return name + "[" + formatNumber(i) + "]";
}

std::string indexed(const std::string& name, int i, int j) {
  return name + "(" + formatNumber(i) + "," + formatNumber(j) + ")";
}

}  // namespace

void validate(const HydroParams& params) {
  requirePositive("mass", params.mass, "[kg]");
  requirePositive("volume", params.volume, "[m^3]");
  requireNonNegative("radius", params.radius, "[m]");
  for (int i = 0; i < 3; ++i) {
    requireFinite(indexed("center_of_gravity", i), params.center_of_gravity[i], "[m]");
    requireFinite(indexed("center_of_buoyancy", i), params.center_of_buoyancy[i], "[m]");
    requirePositive(indexed("inertia", i), params.inertia[i], "[kg m^2]");
  }

  const Matrix6d& ma = params.added_mass;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      requireFinite(indexed("added_mass", i, j), ma(i, j), "[kg | kg m | kg m^2]");
    }
  }
  const double tolerance = 1e-9 * ma.cwiseAbs().maxCoeff();
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      if (std::abs(ma(i, j) - ma(j, i)) > tolerance) {
        fail(indexed("added_mass", i, j), ma(i, j),
             "must equal added_mass(" + formatNumber(j) + "," + formatNumber(i) + ") = " + num(ma(j, i)) +
                 " (M_A must be symmetric)");
      }
    }
    requireNonNegative(indexed("added_mass", i, i), ma(i, i), "[kg | kg m^2]");
  }

  for (int i = 0; i < 6; ++i) {
    requireNonNegative(indexed("linear_damping", i), params.linear_damping[i], "[N s/m | N m s/rad]");
    requireNonNegative(indexed("quadratic_damping", i), params.quadratic_damping[i], "[N s^2/m^2 | N m s^2/rad^2]");
  }
}

FossenModel::FossenModel(const HydroParams& params) : params_(params) {
  validate(params_);
  const Matrix6d& ma = params_.added_mass;
  folded_mass_ = (ma(0, 0) + ma(1, 1) + ma(2, 2)) / 3.0;
  folded_inertia_ = Eigen::Vector3d(ma(3, 3), ma(4, 4), ma(5, 5));
  Vector6d diagonal;
  diagonal << folded_mass_, folded_mass_, folded_mass_, folded_inertia_;
  folded_ = diagonal.asDiagonal();
  residual_ = ma - folded_;
}

Matrix6d FossenModel::coriolisAddedMass(const Matrix6d& added_mass, const Vector6d& nu_r) {
  const Eigen::Vector3d nu1 = nu_r.head<3>();
  const Eigen::Vector3d nu2 = nu_r.tail<3>();
  const Eigen::Vector3d a = added_mass.topLeftCorner<3, 3>() * nu1 + added_mass.topRightCorner<3, 3>() * nu2;
  const Eigen::Vector3d b = added_mass.bottomLeftCorner<3, 3>() * nu1 + added_mass.bottomRightCorner<3, 3>() * nu2;
  Matrix6d c = Matrix6d::Zero();
  c.topRightCorner<3, 3>() = -skew(a);
  c.bottomLeftCorner<3, 3>() = -skew(a);
  c.bottomRightCorner<3, 3>() = -skew(b);
  return c;
}

Vector6d FossenModel::damping(const Vector6d& nu_r) const {
  return params_.linear_damping.cwiseProduct(nu_r) +
         params_.quadratic_damping.cwiseProduct(nu_r.cwiseAbs()).cwiseProduct(nu_r);
}

Vector6d FossenModel::wrench(const Vector6d& nu_r, const Vector6d& nu_r_dot,
                             const Eigen::Vector3d& current_accel_body) const {
  Vector6d tau = -damping(nu_r) - coriolisAddedMass(residual_, nu_r) * nu_r - residual_ * nu_r_dot;
  tau.head<3>() += folded_mass_ * current_accel_body;
  return tau;
}

double submergedFraction(double z_centre, double z_surface, double radius) {
  if (radius <= 0.0) {
    return z_centre < z_surface ? 1.0 : 0.0;
  }
  const double h = std::clamp(z_surface - (z_centre - radius), 0.0, 2.0 * radius);
  const double cap = M_PI * h * h * (3.0 * radius - h) / 3.0;
  const double sphere = 4.0 / 3.0 * M_PI * radius * radius * radius;
  return std::clamp(cap / sphere, 0.0, 1.0);
}

Vector6d restoringWrench(const Eigen::Quaterniond& q_world_body, double weight_mass, const Eigen::Vector3d& cog,
                         double buoyancy_volume, const Eigen::Vector3d& cob, double rho, double gravity) {
  const Eigen::Matrix3d r_world_body = q_world_body.normalized().toRotationMatrix();
  const Eigen::Vector3d f_weight = r_world_body.transpose() * Eigen::Vector3d(0.0, 0.0, -weight_mass * gravity);
  const Eigen::Vector3d f_buoyancy =
      r_world_body.transpose() * Eigen::Vector3d(0.0, 0.0, rho * buoyancy_volume * gravity);
  Vector6d tau;
  tau.head<3>() = f_weight + f_buoyancy;
  tau.tail<3>() = cog.cross(f_weight) + cob.cross(f_buoyancy);
  return tau;
}

}  // namespace hydro
}  // namespace unexmin
