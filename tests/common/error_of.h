#pragma once
// The message of the exception a call throws, for tests that check what an error says.
#include <exception>
#include <functional>
#include <string>

namespace rockbench::testing_util {

/// What `f` throws (std::exception::what()), or "no error".
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace rockbench::testing_util
