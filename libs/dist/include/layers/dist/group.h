// layers/dist/group.h -- one data-parallel process group (torch-free API;
// the work is c10d's, in group.cpp): rendezvous through a c10d::TCPStore
// served by rank 0 at MASTER_ADDR:MASTER_PORT, then ProcessGroupGloo on
// CPU (ProcessGroupNCCL for CUDA tensors on builds with NCCL).
//
// Every collective, the rendezvous included, waits at most `timeout`: a
// rank that died, or never came, makes the others throw dist::Error with
// one line ("rank 1 of 2: allreduce failed after 0.1 s: ... (a rank stopped
// or did not answer within 60 s; see the other ranks' output)"), never a
// hang. Time spent inside collectives is summed (comm_seconds) for the
// training log and the benchmark.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "layers/core/error.h"
#include "layers/dist/env.h"

namespace layers::dist {

// A collective that failed: a peer stopped, timed out or never joined.
class Error : public layers::Error {
 public:
  explicit Error(const std::string& message) : layers::Error(message) {}
};

class Group {
 public:
  // Rendezvous of `env.world_size` ranks; `cuda` asks for NCCL (refused
  // with an InputError naming run.device on a build without it).
  Group(const DistEnv& env, std::chrono::seconds timeout, bool cuda = false);
  ~Group();
  Group(const Group&) = delete;
  Group& operator=(const Group&) = delete;

  int rank() const { return env_.rank; }
  int size() const { return env_.world_size; }
  int local_rank() const { return env_.local_rank; }
  bool is_root() const { return env_.rank == 0; }
  const DistEnv& env() const { return env_; }
  std::chrono::seconds timeout() const { return timeout_; }
  const char* backend() const;  // "gloo" or "nccl"

  // Element-wise sums over the ranks, in place (every rank the same size).
  void allreduce_sum(std::vector<double>& values);
  // Every rank's bytes in rank order at rank 0; empty on the others.
  std::vector<std::string> gather(const std::string& bytes);
  void barrier();

  // Seconds spent inside collectives since construction.
  double comm_seconds() const { return comm_seconds_; }

  // Runs `what` (a collective named `name`), counts its time, and turns any
  // c10d failure into one dist::Error line.
  template <class F>
  auto collective(const char* name, F&& what) -> decltype(what());

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  [[noreturn]] void fail(const char* name, double seconds, const std::string& detail) const;
  DistEnv env_;
  std::chrono::seconds timeout_;
  double comm_seconds_ = 0;
  std::unique_ptr<Impl> impl_;
};

// The group of this process from the environment (read_env()), or null
// when it names no distributed run.
std::unique_ptr<Group> join_from_environment(std::chrono::seconds timeout, bool cuda = false);

}  // namespace layers::dist

#include "layers/dist/group_inl.h"
