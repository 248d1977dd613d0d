// The main() of a rostest gtest: gtest's arguments, then roscpp as node `node`, kept up between the tests.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>

namespace unexmin {
namespace test {

inline int runRosTests(int argc, char** argv, const std::string& node) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, node);
  ros::NodeHandle keep;  // keeps roscpp up between the tests
  return RUN_ALL_TESTS();
}

}  // namespace test
}  // namespace unexmin
