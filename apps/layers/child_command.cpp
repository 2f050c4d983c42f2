// Running a command with its output in a log file (see child_command.h).
#include "child_command.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>

#include "layers/core/error.h"

namespace layers::app {

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

int run_logged(const std::string& command, const std::string& log, bool append) {
  const std::string line = command + (append ? " >> " : " > ") + shell_quote(log) + " 2>&1 < /dev/null";
  const int status = std::system(line.c_str());  // glibc's system() is thread-safe
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

std::string this_executable(const std::string& verb) {
  std::error_code ec;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw Error(verb + ": cannot find this binary (/proc/self/exe): " + ec.message());
  return self;
}

}  // namespace layers::app
