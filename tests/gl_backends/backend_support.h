#pragma once
// Helpers for the tests that choose GL back ends themselves (this folder runs once, not once per
// back end): which back ends this build and machine have, the EGL choice that runs on llvmpipe,
// and environment variables set for one scope (the `vsil` processes a test starts inherit them).
#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "slicing/gl_context.h"

namespace vsil::test {

class ScopedEnvironment {
 public:
  // Sets `name` to `value`, or unsets it when `value` is null, until the end of the scope.
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      setenv(name, value, 1);
    } else {
      unsetenv(name);
    }
  }
  ~ScopedEnvironment() {
    if (old_) {
      setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      unsetenv(name_.c_str());
    }
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

// Why `backend` cannot run here (not built, its library missing), or nothing.
inline std::optional<std::string> missingBackend(gl::Backend backend) {
  const auto built = gl::builtBackends();
  const std::string name = gl::backendName(backend);
  if (std::find(built.begin(), built.end(), backend) == built.end()) {
    return "this vsil was built without " + name;
  }
  if (!gl::backendLibraryLoads(backend)) return name + "'s library is not installed here";
  return std::nullopt;
}

// CI sets VSIL_TEST_ALL_GL_BACKENDS=1: there a missing back end fails the test instead of
// skipping it, so a CI run never passes by skipping.
inline bool allBackendsRequired() {
  const char* value = std::getenv("VSIL_TEST_ALL_GL_BACKENDS");
  return value && std::string(value) == "1";
}

// The number of Mesa's software EGL device ("N: software" in describeEglDevices), if any.
inline std::optional<int> softwareEglDevice() {
  for (const std::string& line : gl::describeEglDevices()) {
    const auto colon = line.find(':');
    if (colon != std::string::npos && line.substr(colon) == ": software") {
      return std::stoi(line.substr(0, colon));
    }
  }
  return std::nullopt;
}

// Any EGL device that is not Mesa's software one: a GPU.
inline bool hardwareEglDevice() {
  for (const std::string& line : gl::describeEglDevices()) {
    if (line.find(": software") == std::string::npos) return true;
  }
  return false;
}

}  // namespace vsil::test

// Skips the test when `backend` is absent here (not built, library missing), naming why; fails
// instead where VSIL_TEST_ALL_GL_BACKENDS=1 (CI).
#define VSIL_REQUIRE_GL_BACKEND(backend)                          \
  do {                                                            \
    if (const auto why = ::vsil::test::missingBackend(backend)) { \
      if (::vsil::test::allBackendsRequired()) FAIL() << *why;    \
      GTEST_SKIP() << *why;                                       \
    }                                                             \
  } while (0)
