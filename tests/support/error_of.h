// tests/support/error_of.h -- the message of the exception a call throws,
// for tests that check error texts.
#pragma once

#include <exception>
#include <functional>
#include <string>

namespace layers::test {

// The what() of the E that `f` throws; "(no error)" if it returns. Any
// other exception propagates and fails the test.
template <class E = std::exception>
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace layers::test
