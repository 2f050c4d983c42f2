// `layers launch --nproc N -- <verb> <args...>`: a data-parallel run on one
// machine. Starts N copies of this binary with the environment torchrun
// would give them (RANK, WORLD_SIZE, LOCAL_RANK, LOCAL_WORLD_SIZE,
// MASTER_ADDR=127.0.0.1, MASTER_PORT: a free port unless --master-port),
// waits for them, and when one fails stops the others (SIGTERM, SIGKILL
// after a grace period) and exits with the failed rank's code. Ranks stop
// when the launcher dies (PR_SET_PDEATHSIG); SIGINT/SIGTERM are forwarded.
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
#include "verbs.h"

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
  if (fd < 0) throw Error(std::string("launch: socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw Error("launch: no free port on 127.0.0.1: " + why);
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

VerbRun register_launch(CLI::App& app, const Global& global) {
  auto* cmd = app.add_subcommand(
      "launch", "Run a data-parallel `train` or `eval` as N processes on this machine (docs/training.md)");
  struct Args {
    int nproc = 2;
    int port = 0;
    int grace_s = 10;
    std::vector<std::string> command;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--nproc", a->nproc, "processes (ranks) to start")->check(CLI::Range(1, 1024))->capture_default_str();
  cmd->add_option("--master-port", a->port, "rendezvous port on 127.0.0.1 (default: a free one)")
      ->check(CLI::Range(1, 65535));
  cmd->add_option("--grace", a->grace_s, "seconds the other ranks get to stop after one failed, before SIGKILL")
      ->check(CLI::Range(0, 3600))
      ->capture_default_str();
  cmd->add_option("command", a->command, "the layers verb and its arguments, after --, e.g. -- train exp.yaml")
      ->required();
  cmd->footer("Example: layers launch --nproc 2 -- train configs/experiments/layersnet_tiny.yaml");
  return [a, &global]() {
    if (a->command.front() == "launch") throw UsageError("launch: the command after -- is a verb other than launch");
    const std::string self = this_executable("launch");
    const int port = a->port > 0 ? a->port : free_port();
    std::vector<std::string> argv_text{self, "--log-level", global.log_level};
    argv_text.insert(argv_text.end(), a->command.begin(), a->command.end());
    std::vector<char*> argv;
    for (std::string& s : argv_text) argv.push_back(s.data());
    argv.push_back(nullptr);

    std::fflush(stdout), std::fflush(stderr);
    struct sigaction forward {};
    forward.sa_handler = forward_signal;
    ::sigaction(SIGTERM, &forward, nullptr);
    ::sigaction(SIGINT, &forward, nullptr);
    g_children.assign(static_cast<std::size_t>(a->nproc), -1);
    const pid_t launcher = ::getpid();
    for (int rank = 0; rank < a->nproc; ++rank) {
      const pid_t pid = ::fork();
      if (pid < 0) {
        forward_signal(SIGTERM);
        throw Error(std::string("launch: fork: ") + std::strerror(errno));
      }
      if (pid == 0) {
        const std::string r = std::to_string(rank), n = std::to_string(a->nproc), p = std::to_string(port);
        ::setenv("RANK", r.c_str(), 1), ::setenv("LOCAL_RANK", r.c_str(), 1);
        ::setenv("WORLD_SIZE", n.c_str(), 1), ::setenv("LOCAL_WORLD_SIZE", n.c_str(), 1);
        ::setenv("MASTER_ADDR", "127.0.0.1", 1), ::setenv("MASTER_PORT", p.c_str(), 1);
        ::signal(SIGTERM, SIG_DFL), ::signal(SIGINT, SIG_DFL);
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);       // the launcher killed: the ranks stop too
        if (::getppid() != launcher) ::_exit(1);  // ...even if that happened before prctl
        ::execv(self.c_str(), argv.data());
        std::fprintf(stderr, "layers launch: cannot start %s: %s\n", self.c_str(), std::strerror(errno));
        ::_exit(127);
      }
      g_children[static_cast<std::size_t>(rank)] = pid;
    }

    int code = 0, running = a->nproc;
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
        kill_at = std::chrono::steady_clock::now() + std::chrono::seconds(a->grace_s);
        if (running > 0)
          std::fprintf(stderr, "layers launch: rank %d %s; stopping the other %d rank(s)\n", rank,
                       exit_text(status).c_str(), running);
        forward_signal(SIGTERM);
      }
    }
    return code;
  };
}

}  // namespace layers::app
