// Shared by the core's gtests: the message of an expected ParameterError.
#pragma once

#include <unexmin/core/error.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <typeinfo>

namespace unexmin {
namespace test {

/// The what() of the error of type E (ParameterError unless given) that f throws; a test failure if it throws
/// none.
template <typename E = ParameterError, typename F>
std::string thrownMessage(F f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an error of the expected type (" << typeid(E).name() << ")";
  return "";
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace test
}  // namespace unexmin
