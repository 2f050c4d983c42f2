// Starting the ranks of a data-parallel run on this machine (see rank_launch.h).
#include "rank_launch.h"

#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "child_command.h"
#include "layers/core/error.h"

namespace layers::app {
namespace {

std::vector<pid_t> g_children;  // for the signal handler

void forward_signal(int sig) {
  for (pid_t pid : g_children)
    if (pid > 0) ::kill(pid, sig);
}

// A TCP port the kernel says is free now on the loopback interface.
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw Error(std::string("rank launch: socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw Error("rank launch: no free port on 127.0.0.1: " + why);
  }
  ::close(fd);
  return ntohs(addr.sin_port);
}

std::string exit_text(int status) {
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("was killed by signal ") + ::strsignal(WTERMSIG(status));
  return "stopped";
}

int exit_code(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace

int launch_ranks(const RankLaunch& launch, const std::string& verb) {
  const std::string self = this_executable(verb);
  const int port = launch.port > 0 ? launch.port : free_port();
  std::vector<std::string> argv_text{self};
  argv_text.insert(argv_text.end(), launch.args.begin(), launch.args.end());
  std::vector<char*> argv;
  for (std::string& s : argv_text) argv.push_back(s.data());
  argv.push_back(nullptr);

  std::fflush(stdout), std::fflush(stderr);
  struct sigaction forward {};
  forward.sa_handler = forward_signal;
  ::sigaction(SIGTERM, &forward, nullptr);
  ::sigaction(SIGINT, &forward, nullptr);
  g_children.assign(static_cast<std::size_t>(launch.ranks), -1);
  const pid_t launcher = ::getpid();
  for (int rank = 0; rank < launch.ranks; ++rank) {
    const pid_t pid = ::fork();
    if (pid < 0) {
      forward_signal(SIGTERM);
      throw Error(std::string("rank launch: fork: ") + std::strerror(errno));
    }
    if (pid == 0) {
      const std::string r = std::to_string(rank), n = std::to_string(launch.ranks), p = std::to_string(port);
      ::setenv("RANK", r.c_str(), 1), ::setenv("LOCAL_RANK", r.c_str(), 1);
      ::setenv("WORLD_SIZE", n.c_str(), 1), ::setenv("LOCAL_WORLD_SIZE", n.c_str(), 1);
      ::setenv("MASTER_ADDR", "127.0.0.1", 1), ::setenv("MASTER_PORT", p.c_str(), 1);
      for (const auto& [name, value] : launch.env) ::setenv(name.c_str(), value.c_str(), 1);
      ::signal(SIGTERM, SIG_DFL), ::signal(SIGINT, SIG_DFL);
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);       // the launcher killed: the ranks stop too
      if (::getppid() != launcher) ::_exit(1);  // ...even if that happened before prctl
      ::execv(self.c_str(), argv.data());
      std::fprintf(stderr, "layers %s: cannot start %s: %s\n", verb.c_str(), self.c_str(), std::strerror(errno));
      ::_exit(127);
    }
    g_children[static_cast<std::size_t>(rank)] = pid;
  }

  int code = 0, running = launch.ranks;
  bool stopping = false;
  std::chrono::steady_clock::time_point kill_at;
  while (running > 0) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, stopping ? WNOHANG : 0);
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0) break;
    if (pid == 0) {  // stopping: poll until the grace period ends
      if (std::chrono::steady_clock::now() >= kill_at) forward_signal(SIGKILL);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    int rank = 0;
    for (std::size_t k = 0; k < g_children.size(); ++k)
      if (g_children[k] == pid) rank = static_cast<int>(k), g_children[k] = -1;
    --running;
    if (exit_code(status) != 0 && !stopping) {
      code = exit_code(status);
      stopping = true;
      kill_at = std::chrono::steady_clock::now() + std::chrono::seconds(launch.grace_s);
      if (running > 0)
        std::fprintf(stderr, "layers %s: rank %d %s; stopping the other %d rank(s)\n", verb.c_str(), rank,
                     exit_text(status).c_str(), running);
      forward_signal(SIGTERM);
    }
  }
  return code;
}

}  // namespace layers::app
