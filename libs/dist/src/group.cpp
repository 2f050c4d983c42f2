// The c10d process group behind dist::Group (see group.h): TCPStore
// rendezvous, ProcessGroupGloo (or NCCL), and the collectives on doubles
// and bytes that metrics and evaluation results need.
#include "layers/dist/group.h"

#include <c10/util/Exception.h>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>
#ifdef LAYERS_DIST_NCCL
#include <torch/csrc/distributed/c10d/ProcessGroupNCCL.hpp>
#endif

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "group_impl.h"

namespace layers::dist {

std::string first_line_of_current_exception() {
  std::string text;
  try {
    throw;
  } catch (const c10::Error& e) {
    text = e.what_without_backtrace();
  } catch (const std::exception& e) {
    text = e.what();
  } catch (...) {
    text = "unknown error";
  }
  const std::size_t end = text.find('\n');
  return end == std::string::npos ? text : text.substr(0, end);
}

Group::Group(const DistEnv& env, std::chrono::seconds timeout, bool cuda)
    : env_(env), timeout_(timeout), impl_(std::make_unique<Impl>()) {
#ifndef LAYERS_DIST_NCCL
  if (cuda)
    throw InputError("run.device", "device", "cpu for a distributed run on this build (LibTorch without NCCL)", "cuda");
#endif
  const std::string where = "rendezvous with " + std::to_string(env.world_size) + " ranks at " + env.master_addr + ":" +
                            std::to_string(env.master_port);
  collective(where.c_str(), [&] {
    c10d::TCPStoreOptions o;
    o.port = static_cast<std::uint16_t>(env.master_port);
    o.isServer = env.rank == 0;
    o.numWorkers = static_cast<std::size_t>(env.world_size);
    o.waitWorkers = true;
    o.timeout = std::chrono::duration_cast<std::chrono::milliseconds>(timeout);
    impl_->store = c10::make_intrusive<c10d::TCPStore>(env.master_addr, o);
#ifdef LAYERS_DIST_NCCL
    if (cuda) {
      ::setenv("NCCL_ASYNC_ERROR_HANDLING", "1", /*overwrite=*/0);  // NCCL honours the timeout only with it
      auto options = c10d::ProcessGroupNCCL::Options::create();
      options->timeout = o.timeout;
      impl_->group = c10::make_intrusive<c10d::ProcessGroupNCCL>(impl_->store, env.rank, env.world_size, options);
      impl_->device = at::Device(at::kCUDA, static_cast<c10::DeviceIndex>(env.local_rank));
      impl_->backend = "nccl";
      return;
    }
#endif
    auto options = c10d::ProcessGroupGloo::Options::create(o.timeout);
    const char* ifname = std::getenv("GLOO_SOCKET_IFNAME");
    if (ifname && *ifname)
      options->devices.push_back(c10d::ProcessGroupGloo::createDeviceForInterface(ifname));
    else if (env.master_addr == "127.0.0.1" || env.master_addr == "localhost")
      options->devices.push_back(c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1"));
    else
      options->devices.push_back(c10d::ProcessGroupGloo::createDefaultDevice());
    impl_->group = c10::make_intrusive<c10d::ProcessGroupGloo>(impl_->store, env.rank, env.world_size, options);
  });
}

Group::~Group() = default;

const char* Group::backend() const { return impl_->backend; }

void Group::fail(const char* name, double seconds, const std::string& detail) const {
  char took[32];
  std::snprintf(took, sizeof took, "%.1f", seconds);
  throw Error("rank " + std::to_string(env_.rank) + " of " + std::to_string(env_.world_size) + ": " + name +
              " failed after " + took + " s: " + detail + " (a rank stopped or did not answer within " +
              std::to_string(timeout_.count()) + " s; see the other ranks' output)");
}

void Group::allreduce_sum(std::vector<double>& values) {
  if (values.empty()) return;
  collective("allreduce", [&] {
    at::Tensor t = at::from_blob(values.data(), {static_cast<std::int64_t>(values.size())}, at::kDouble)
                       .to(impl_->device, /*non_blocking=*/false, /*copy=*/true);
    std::vector<at::Tensor> ts{t};
    impl_->group->allreduce(ts)->wait();
    const at::Tensor back = ts[0].cpu().contiguous();
    std::memcpy(values.data(), back.data_ptr<double>(), values.size() * sizeof(double));
  });
}

std::vector<std::string> Group::gather(const std::string& bytes) {
  return collective("gather", [&] {
    const auto on = at::TensorOptions().device(impl_->device);
    std::vector<at::Tensor> mine_size{at::full({1}, static_cast<std::int64_t>(bytes.size()), on.dtype(at::kLong))};
    std::vector<std::vector<at::Tensor>> sizes(1);
    for (int r = 0; r < this->size(); ++r) sizes[0].push_back(at::empty({1}, on.dtype(at::kLong)));
    impl_->group->allgather(sizes, mine_size)->wait();
    std::vector<std::int64_t> n;
    std::int64_t most = 1;
    for (const at::Tensor& t : sizes[0]) n.push_back(t.cpu().item<std::int64_t>()), most = std::max(most, n.back());
    at::Tensor mine = at::zeros({most}, at::kByte);
    std::memcpy(mine.data_ptr<std::uint8_t>(), bytes.data(), bytes.size());
    std::vector<at::Tensor> in{mine.to(impl_->device)};
    std::vector<std::vector<at::Tensor>> out(1);
    for (int r = 0; r < this->size(); ++r) out[0].push_back(at::empty({most}, on.dtype(at::kByte)));
    impl_->group->allgather(out, in)->wait();
    std::vector<std::string> all;
    if (!is_root()) return all;
    for (int r = 0; r < this->size(); ++r) {
      const at::Tensor t = out[0][r].cpu().contiguous();
      all.emplace_back(reinterpret_cast<const char*>(t.data_ptr<std::uint8_t>()), static_cast<std::size_t>(n[r]));
    }
    return all;
  });
}

void Group::barrier() {
  collective("barrier", [&] { impl_->group->barrier()->wait(); });
}

std::unique_ptr<Group> join_from_environment(std::chrono::seconds timeout, bool cuda) {
  const std::optional<DistEnv> env = read_env();
  if (!env) return nullptr;
  return std::make_unique<Group>(*env, timeout, cuda);
}

}  // namespace layers::dist
