// Shared by the core's gtests: the message of an expected std::invalid_argument.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace unexmin {
namespace test {

/// The what() of the std::invalid_argument that f throws; a test failure if it throws none.
template <typename F>
std::string thrownMessage(F f)
{
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected std::invalid_argument";
  return "";
}

inline bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

}  // namespace test
}  // namespace unexmin
