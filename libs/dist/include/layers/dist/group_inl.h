// layers/dist/group_inl.h -- Group::collective (see group.h): times a
// collective and turns any exception it throws into one dist::Error line.
#pragma once

#include <chrono>
#include <exception>
#include <string>
#include <type_traits>

namespace layers::dist {

std::string first_line_of_current_exception();

template <class F>
auto Group::collective(const char* name, F&& what) -> decltype(what()) {
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  try {
    if constexpr (std::is_void_v<decltype(what())>) {
      what();
      comm_seconds_ += seconds();
    } else {
      auto result = what();
      comm_seconds_ += seconds();
      return result;
    }
  } catch (const dist::Error&) {
    throw;
  } catch (...) {
    fail(name, seconds(), first_line_of_current_exception());
  }
}

}  // namespace layers::dist
