// layers/core/progress.h -- wall-clock timer and a terminal progress line
// (done/total, rate, ETA) for long-running verbs.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace layers {

class Timer {
 public:
  Timer() : start_(std::chrono::steady_clock::now()) {}
  void reset() { start_ = std::chrono::steady_clock::now(); }
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Prints "label  done/total  rate/s  ETA mm:ss [extra]" to stderr, at most a
// few times per second; redraws in place on a terminal and prints plain
// lines otherwise (CI logs).
class Progress {
 public:
  Progress(std::string label, std::size_t total, std::string unit = "items");
  void advance(std::size_t n = 1, const std::string& extra = "");
  void finish(const std::string& extra = "");
  std::size_t done() const { return done_; }

  // "mm:ss" or "h:mm:ss".
  static std::string format_duration(double seconds);

 private:
  void print(bool final, const std::string& extra);
  std::string label_, unit_;
  std::size_t total_, done_ = 0;
  Timer timer_;
  double last_print_ = -1.0;
  bool tty_;
};

}  // namespace layers
