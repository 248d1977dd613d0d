#include <unexmin/ros_layer/robot_ros.h>

#include <unexmin/sim/contacts.h>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>
#include <unexmin/Contacts.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace ros_layer {
namespace {

/// Command subscriber whose callback sees the publisher's name (to count applied commands).
ros::Subscriber subscribeCommand(ros::NodeHandle& nh, const std::string& topic,
                                 const boost::function<void(const Float64Event&)>& callback) {
  return nh.subscribe<std_msgs::Float64, const Float64Event&>(topic, 10, callback, ros::VoidConstPtr(),
                                                              ros::TransportHints().tcpNoDelay());
}

}  // namespace

RobotRos::RobotRos(sim::World& world, sim::Robot& robot, sensors::SensorSuite& suite, ros::NodeHandle& command_nh,
                   ros::NodeHandle& nh, const PublishRates& rates, double physics_rate,
                   std::map<std::string, std::uint64_t>& received, const SensorRegistry& registry,
                   const sensors::SensorSelection& selection)
    : world_(world), robot_(robot), received_(received) {
  const std::string ns = "/" + robot.name() + "/";
  for (std::size_t i = 0; i < robot.thrusterCount(); ++i) {
    const std::string base = ns + "thrusters/" + std::to_string(i) + "/";
    subs_.push_back(
        subscribeCommand(command_nh, base + "input", [this, i](const Float64Event& e) { onThrusterInput(i, e); }));
    thrust_pubs_.push_back(nh.advertise<std_msgs::Float64>(base + "thrust", queueSize(rates.thrust)));
  }
  for (std::size_t i = 0; i < robot.finCount(); ++i)
    subs_.push_back(subscribeCommand(command_nh, ns + "fins/" + std::to_string(i) + "/input",
                                     [this, i](const Float64Event& e) { onFinInput(i, e); }));
  subs_.push_back(subscribeCommand(command_nh, ns + "pendulum", [this](const Float64Event& e) { onPendulum(e); }));
  subs_.push_back(subscribeCommand(command_nh, ns + "vbs", [this](const Float64Event& e) { onVbs(e); }));
  odom_pub_ = nh.advertise<nav_msgs::Odometry>(ns + "odom", queueSize(rates.odom));
  joint_pub_ = nh.advertise<sensor_msgs::JointState>(ns + "joint_states", queueSize(rates.joint_states));
  contacts_pub_ = nh.advertise<unexmin::Contacts>(ns + "contacts", queueSize(rates.contacts));
  // One publication per topic and node, its queue set by the first robot: room for every robot's (up to 8)
  // samples of 20 s of simulated time, like a sensor stream's queue.
  tf_pub_ = nh.advertise<tf2_msgs::TFMessage>("/tf", 8 * queueSize(rates.odom));
  odom_every_ = every(physics_rate, rates.odom);
  joint_every_ = every(physics_rate, rates.joint_states);
  thrust_every_ = every(physics_rate, rates.thrust);
  contacts_every_ = every(physics_rate, rates.contacts);
  joint_names_ = robot.description().movableJoints();
  sensors_ = std::make_unique<SensorsRos>(world, robot, suite, registry, selection, nh);
}

bool RobotRos::finite(const std::string& topic, double value) const {
  if (std::isfinite(value))
    return true;
  ROS_WARN_STREAM_THROTTLE(1.0, "/" << robot_.name() << "/" << topic << ": rejected non-finite command " << value);
  return false;
}

void RobotRos::record(const std::string& topic, const Float64Event& event) const {
  if (recorder_ && recorder_->active())
    recorder_->write("/" + robot_.name() + "/" + topic, *event.getConstMessage());
}

void RobotRos::onActuatorInput(const std::string& topic, const Float64Event& event,
                               const std::function<bool(double)>& set, double min, double max, const char* what,
                               const char* unit) {
  ++received_[event.getPublisherName()];
  const auto& msg = event.getConstMessage();
  record(topic, event);
  if (!finite(topic, msg->data))
    return;
  if (!set(msg->data))
    ROS_WARN_STREAM_THROTTLE(1.0, "/" << robot_.name() << "/" << topic << ": rejected " << what << " " << msg->data
                                      << unit << ", expected [" << min << ", " << max << "]");
}

void RobotRos::onThrusterInput(std::size_t i, const Float64Event& event) {
  auto& th = robot_.thruster(i);
  onActuatorInput(
      "thrusters/" + std::to_string(i) + "/input", event, [&](double command) { return th.setCommand(command, now_); },
      th.params().min_command, th.params().max_command, "command", "");
}

void RobotRos::onFinInput(std::size_t i, const Float64Event& event) {
  auto& fin = robot_.fin(i);
  onActuatorInput(
      "fins/" + std::to_string(i) + "/input", event, [&](double angle) { return fin.setCommand(angle, now_); },
      fin.params().min_angle, fin.params().max_angle, "angle", " rad");
}

void RobotRos::onPendulum(const Float64Event& event) {
  ++received_[event.getPublisherName()];
  record("pendulum", event);
  const auto& msg = event.getConstMessage();
  if (!finite("pendulum", msg->data))
    return;
  if (!robot_.hasPendulum()) {
    ROS_WARN_STREAM_THROTTLE(1.0, "/" << robot_.name() << "/pendulum: this robot has no pendulum");
    return;
  }
  const auto& p = robot_.pendulum().params();
  if (!robot_.pendulum().setTarget(msg->data))
    ROS_WARN_STREAM_THROTTLE(1.0, "/" << robot_.name() << "/pendulum: rejected angle " << msg->data
                                      << " rad, expected [" << p.min_angle << ", " << p.max_angle << "]");
}

void RobotRos::onVbs(const Float64Event& event) {
  ++received_[event.getPublisherName()];
  record("vbs", event);
  const auto& msg = event.getConstMessage();
  if (!finite("vbs", msg->data))
    return;
  const auto& p = robot_.vbs().params();
  if (!robot_.vbs().setMass(msg->data))
    ROS_WARN_STREAM_THROTTLE(1.0, "/" << robot_.name() << "/vbs: rejected ballast mass " << msg->data
                                      << " kg, expected [" << p.min_mass << ", " << p.max_mass << "]");
}

nav_msgs::Odometry RobotRos::odometry(const ros::Time& stamp) const {
  const sim::RobotState s = robot_.state();
  const Eigen::Quaterniond q(s.pose.linear());
  nav_msgs::Odometry o;
  o.header.stamp = stamp;
  o.header.frame_id = "world";
  o.child_frame_id = robot_.description().base_link;
  o.pose.pose.position.x = s.pose.translation().x();
  o.pose.pose.position.y = s.pose.translation().y();
  o.pose.pose.position.z = s.pose.translation().z();
  o.pose.pose.orientation.x = q.x();
  o.pose.pose.orientation.y = q.y();
  o.pose.pose.orientation.z = q.z();
  o.pose.pose.orientation.w = q.w();
  // REP-105: twist in the child (body) frame.
  const Eigen::Matrix3d Rt = s.pose.linear().transpose();
  const Eigen::Vector3d v = Rt * s.linear_velocity, w = Rt * s.angular_velocity;
  o.twist.twist.linear.x = v.x();
  o.twist.twist.linear.y = v.y();
  o.twist.twist.linear.z = v.z();
  o.twist.twist.angular.x = w.x();
  o.twist.twist.angular.y = w.y();
  o.twist.twist.angular.z = w.z();
  return o;
}

void RobotRos::publishContacts(const ros::Time& stamp) {
  const std::vector<sim::Contact> found = sim::contacts(world_, robot_);
  unexmin::Contacts m;
  m.header.stamp = stamp;
  m.header.frame_id = "world";
  m.position.resize(found.size());
  m.normal.resize(found.size());
  m.depth.resize(found.size());
  m.impulse.resize(found.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    m.position[i].x = found[i].position.x();
    m.position[i].y = found[i].position.y();
    m.position[i].z = found[i].position.z();
    m.normal[i].x = found[i].normal.x();
    m.normal[i].y = found[i].normal.y();
    m.normal[i].z = found[i].normal.z();
    m.depth[i] = found[i].depth;
    m.impulse[i] = found[i].impulse;
  }
  publishRecorded(contacts_pub_, recorder_, m);
}

void RobotRos::publish(std::uint64_t step, const ros::Time& stamp, bool all) {
  now_ = stamp.toSec();
  sensors_->publish(step);  // the samples of this step (nothing extra when `all`)
  // A stream is published when its schedule says so or when `all` asks, once per step at most.
  auto due = [&](std::uint64_t every, std::uint64_t& last) {
    if (!every || last == step || !(all || step % every == 0))
      return false;
    last = step;
    return true;
  };
  if (due(odom_every_, last_odom_)) {
    const bool tf_wanted = tf_pub_.subscribers() > 0;
    const bool odom_wanted = wanted(odom_pub_, recorder_);
    if (tf_wanted || odom_wanted) {
      const nav_msgs::Odometry o = odometry(stamp);
      if (tf_wanted) {
        geometry_msgs::TransformStamped t;
        t.header = o.header;
        t.child_frame_id = o.child_frame_id;
        t.transform.translation.x = o.pose.pose.position.x;
        t.transform.translation.y = o.pose.pose.position.y;
        t.transform.translation.z = o.pose.pose.position.z;
        t.transform.rotation = o.pose.pose.orientation;
        tf2_msgs::TFMessage m;
        m.transforms.push_back(t);
        tf_pub_.publish(m);
      }
      if (odom_wanted)
        publishRecorded(odom_pub_, recorder_, o);
    }
  }
  if (due(thrust_every_, last_thrust_)) {
    for (std::size_t i = 0; i < thrust_pubs_.size(); ++i) {
      if (!wanted(thrust_pubs_[i], recorder_))
        continue;
      std_msgs::Float64 m;
      m.data = robot_.thruster(i).thrust();
      publishRecorded(thrust_pubs_[i], recorder_, m);
    }
  }
  if (due(contacts_every_, last_contacts_) && wanted(contacts_pub_, recorder_))
    publishContacts(stamp);
  const bool joint_wall_ok = all || (wall_now_ - last_joint_wall_).toSec() >= min_wall_period_;
  if (joint_wall_ok && due(joint_every_, last_joint_) && joint_pub_.subscribers() > 0) {
    last_joint_wall_ = wall_now_;
    sensor_msgs::JointState js;
    js.header.stamp = stamp;
    const auto& d = robot_.description();
    const std::vector<sensors::MovedJoint> moved = sensors_->suite().movedJoints();  // MSIS head, SLS motors
    for (const auto& name : joint_names_) {
      double position = 0.0, velocity = 0.0;
      for (std::size_t i = 0; i < d.thruster_joints.size(); ++i)
        if (d.thruster_joints[i] == name)
          position = robot_.propellerAngle(i);
      for (std::size_t i = 0; i < d.fin_joints.size(); ++i)
        if (d.fin_joints[i] == name)
          position = robot_.fin(i).angle();
      if (name == d.pendulum_joint && robot_.hasPendulum()) {
        position = robot_.pendulum().angle();
        velocity = robot_.pendulum().velocity();
      }
      for (const auto& m : moved)
        if (m.name == name) {
          position = m.position;
          velocity = m.velocity;
        }
      js.name.push_back(name);
      js.position.push_back(position);
      js.velocity.push_back(velocity);
    }
    publishRecorded(joint_pub_, recorder_, js);
  }
}

}  // namespace ros_layer
}  // namespace unexmin
