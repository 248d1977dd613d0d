#include <unexmin/sim/robot.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>

namespace unexmin {
namespace sim {
namespace {

btVector3 toBt(const Eigen::Vector3d& v) {
  return btVector3(v.x(), v.y(), v.z());
}
Eigen::Vector3d toEigen(const btVector3& v) {
  return Eigen::Vector3d(v.x(), v.y(), v.z());
}

btTransform toBt(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), toBt(pose.translation()));
}

/// Visual propeller speed for a thrust [N] when the conversion has no rotor speed [rad/s].
constexpr double kPropellerRadPerSqrtNewton = 10.0;

}  // namespace

Robot::Robot(const RobotDescription& description, const RobotSpawn& spawn)
    : name_(spawn.name),
      description_(description),
      spawn_pose_(spawn.pose),
      model_(description.hydro),
      vbs_(description.vbs) {
  for (const auto& tp : description.thrusters) {
    thrusters_.push_back(std::make_unique<hydro::Thruster>(tp, description.thruster_families));
    rotor_speed_state_.push_back(thrusters_.back()->stateIsRotorSpeed());
  }
  propeller_angle_.assign(thrusters_.size(), 0.0);
  for (const auto& fp : description.fins)
    fins_.push_back(std::make_unique<hydro::Fin>(fp, description.fin_families));
  if (!description.pendulum_joint.empty())
    pendulum_ = std::make_unique<hydro::Pendulum>(description.pendulum);

  const double radius = description.hydro.radius > 0.0 ? description.hydro.radius
                                                       : std::cbrt(3.0 * description.hydro.volume / (4.0 * M_PI));
  shape_ = std::make_unique<btSphereShape>(radius);
  motion_state_ = std::make_unique<btDefaultMotionState>(toBt(spawn_pose_));
  btRigidBody::btRigidBodyConstructionInfo info(1.0, motion_state_.get(), shape_.get(), btVector3(1, 1, 1));
  info.m_friction = 0.5;
  info.m_restitution = 0.0;
  info.m_linearDamping = 0.0;
  info.m_angularDamping = 0.0;
  body_ = std::make_unique<btRigidBody>(info);
  body_->setActivationState(DISABLE_DEACTIVATION);
  body_->setFlags(body_->getFlags() | BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
  // Never tunnel through thin walls: continuous collision detection below the radius.
  body_->setCcdMotionThreshold(static_cast<btScalar>(0.5 * radius));
  body_->setCcdSweptSphereRadius(static_cast<btScalar>(0.9 * radius));
  updateMassProperties();
}

Robot::~Robot() = default;

double Robot::totalMass() const {
  return description_.hydro.mass + vbs_.mass() + payload_mass_;
}

Eigen::Vector3d Robot::centerOfGravity() const {
  const auto& h = description_.hydro;
  double pend_mass = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  if (pendulum_) {
    pend_mass = pendulum_->params().mass;
    moment += pend_mass * pendulum_->massPosition();
  }
  moment += (h.mass - pend_mass) * h.center_of_gravity;
  moment += vbs_.mass() * vbs_.params().position;
  moment += payload_mass_ * payload_centre_;
  return moment / totalMass();
}

double Robot::engineMass() const {
  return totalMass() + model_.foldedMass();
}

void Robot::setPayloadMass(double mass, const Eigen::Vector3d& centre) {
  payload_mass_ = std::isfinite(mass) && mass > 0.0 ? mass : 0.0;
  payload_centre_ = centre;
}

void Robot::updateMassProperties() {
  engine_vbs_mass_ = vbs_.mass();
  engine_payload_mass_ = payload_mass_;
  const Eigen::Vector3d inertia = description_.hydro.inertia + model_.foldedInertia();
  body_->setMassProps(static_cast<btScalar>(engineMass()), toBt(inertia));
  body_->updateInertiaTensor();
  body_->setGravity(btVector3(0, 0, 0));  // weight and buoyancy are ours (restoring forces)
}

void Robot::applyForces(double t, double dt, const WaterState& water) {
  if (vbs_.mass() != engine_vbs_mass_ || payload_mass_ != engine_payload_mass_)
    updateMassProperties();

  const btTransform& tf = body_->getCenterOfMassTransform();
  const btQuaternion bq = tf.getRotation();
  const Eigen::Quaterniond q(bq.w(), bq.x(), bq.y(), bq.z());
  const Eigen::Matrix3d R = q.toRotationMatrix();
  const Eigen::Vector3d position = toEigen(tf.getOrigin());
  const Eigen::Vector3d v_world = toEigen(body_->getLinearVelocity());
  const Eigen::Vector3d w_world = toEigen(body_->getAngularVelocity());

  nu_r_.head<3>() = R.transpose() * (v_world - water.current);
  nu_r_.tail<3>() = R.transpose() * w_world;
  if (have_prev_ && dt > 0.0)
    nu_r_dot_ = (nu_r_ - nu_r_prev_) / dt;
  nu_r_prev_ = nu_r_;
  have_prev_ = true;

  hydro_wrench_ = model_.wrench(nu_r_, nu_r_dot_, R.transpose() * water.current_accel);

  if (pendulum_)
    pendulum_->update(dt);
  const auto& h = description_.hydro;
  const double submerged = hydro::submergedFraction(position.z(), water.surface_z, h.radius);
  restoring_wrench_ = hydro::restoringWrench(q, totalMass(), centerOfGravity(), submerged * h.volume,
                                             h.center_of_buoyancy, water.density, water.gravity);

  thrust_wrench_.setZero();
  for (auto& th : thrusters_) {
    th->update(t, dt);
    thrust_wrench_ += th->wrench();
  }

  hydro::Vector6d total = hydro_wrench_ + restoring_wrench_ + thrust_wrench_;
  if (!fins_.empty()) {
    fin_wrench_.setZero();
    for (auto& fin : fins_) {
      fin->update(t, dt);
      fin_wrench_ += fin->wrench(nu_r_, water.density);
    }
    total += fin_wrench_;
  }
  body_->applyCentralForce(toBt(R * total.head<3>()));
  body_->applyTorque(toBt(R * total.tail<3>()));
  velocity_before_ = v_world;
}

void Robot::afterStep(double dt) {
  if (dt > 0.0)
    acceleration_ = (toEigen(body_->getLinearVelocity()) - velocity_before_) / dt;
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    const auto& th = *thrusters_[i];
    const double rate = rotor_speed_state_[i]
                            ? th.state()
                            : std::copysign(kPropellerRadPerSqrtNewton * std::sqrt(std::abs(th.thrust())), th.thrust());
    propeller_angle_[i] = std::remainder(propeller_angle_[i] + rate * dt, 2.0 * M_PI);
  }
}

RobotState Robot::state() const {
  RobotState s;
  const btTransform& tf = body_->getCenterOfMassTransform();
  const btQuaternion bq = tf.getRotation();
  s.pose.linear() = Eigen::Quaterniond(bq.w(), bq.x(), bq.y(), bq.z()).toRotationMatrix();
  s.pose.translation() = toEigen(tf.getOrigin());
  s.linear_velocity = toEigen(body_->getLinearVelocity());
  s.angular_velocity = toEigen(body_->getAngularVelocity());
  s.linear_acceleration = acceleration_;
  return s;
}

void Robot::setPose(const Eigen::Isometry3d& pose) {
  const btTransform tf = toBt(pose);
  body_->setCenterOfMassTransform(tf);
  body_->setInterpolationWorldTransform(tf);
  motion_state_->setWorldTransform(tf);
  body_->setLinearVelocity(btVector3(0, 0, 0));
  body_->setAngularVelocity(btVector3(0, 0, 0));
  body_->setInterpolationLinearVelocity(btVector3(0, 0, 0));
  body_->setInterpolationAngularVelocity(btVector3(0, 0, 0));
  body_->clearForces();
  nu_r_.setZero();
  nu_r_prev_.setZero();
  nu_r_dot_.setZero();
  have_prev_ = false;
  acceleration_.setZero();
  velocity_before_.setZero();
}

void Robot::reset() {
  for (auto& th : thrusters_)
    th->reset();
  for (auto& fin : fins_)
    fin->reset();
  propeller_angle_.assign(thrusters_.size(), 0.0);
  if (pendulum_)
    pendulum_->reset();
  vbs_.reset();
  payload_mass_ = 0.0;
  payload_centre_.setZero();
  updateMassProperties();
  setPose(spawn_pose_);
}

}  // namespace sim
}  // namespace unexmin
