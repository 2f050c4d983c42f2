// Finding and running Blender (see blender_runner.h).
#include "blender_runner.h"

#include "child_command.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"

namespace layers::app {

namespace {

bool executable(const std::string& path) { return !path.empty() && ::access(path.c_str(), X_OK) == 0; }

}  // namespace

std::string find_blender(const std::string& explicit_path) {
  if (!explicit_path.empty()) {
    if (!executable(explicit_path))
      throw InputError::message("--blender", "", explicit_path + " is not an executable file");
    return explicit_path;
  }
  const char* env = std::getenv("LAYERS_BLENDER");
  if (env && *env) {
    if (!executable(env))
      throw InputError::message("LAYERS_BLENDER", "", std::string(env) + " is not an executable file");
    return env;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/blender";
    if (executable(candidate)) return candidate;
  }
  throw InputError::message(
      "blender", "", "not found on PATH: install Debian's blender (apt-get install blender) or pass --blender PATH");
}

int run_blender(const std::string& blender, int threads, const std::string& script, const std::string& args,
                const std::string& log) {
  return run_logged(shell_quote(blender) + " -b -t " + std::to_string(threads) +
                        " --factory-startup --python-exit-code 1 --python " + shell_quote(script) + " -- " + args,
                    log);
}

std::string blender_failure(const std::string& log) {
  std::ifstream in(log);
  std::string script_error, blender_error, last;
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    last = line;
    if (line.find("crosscheck_sim:") != std::string::npos && line.find("error") != std::string::npos)
      script_error = line;
    else if (line.find("Error") != std::string::npos)
      blender_error = line;
  }
  if (!script_error.empty()) return script_error;
  if (!blender_error.empty()) return blender_error;
  return last.empty() ? "no output" : last;
}

}  // namespace layers::app
