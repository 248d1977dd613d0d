// Shared by the core's gtests: the message of an expected ParameterError.
#pragma once

#include <unexmin/core/error.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace unexmin {
namespace test {

/// The what() of the ParameterError that f throws; a test failure if it throws none.
template <typename F>
std::string thrownMessage(F f)
{
  try {
    f();
  } catch (const ParameterError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected ParameterError";
  return "";
}

inline bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

}  // namespace test
}  // namespace unexmin
