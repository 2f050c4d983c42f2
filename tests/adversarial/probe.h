// tests/adversarial/probe.h -- runs the `layers` binary in its own
// process and measures its peak resident memory (wait4's rusage of that
// process alone), with its exit code and output. Speed is not measured
// here: that is for benchmarks.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

#include "file_bytes.h"
#include "test_paths.h"

namespace layers::test {

struct Probe {
  int exit_code = -1;
  std::string output;
  double peak_mib = 0;
};

inline constexpr double kMaxPeakMiB = 1024;

// Runs `layers <args>` with its output in `log`, and measures the peak
// resident memory of that process alone (wait4).
inline Probe probe(const std::string& args, const std::string& log, const std::string& env = "") {
  Probe p;
  const std::string command = env + " exec " + test::layers_bin() + " " + args + " > " + log + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return p;
  p.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  p.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
  p.output = read_bytes(log);
  return p;
}

}  // namespace layers::test
