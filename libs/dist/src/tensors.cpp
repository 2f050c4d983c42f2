// Parameter broadcast and gradient averaging over a dist::Group (see tensors.h).
#include "layers/dist/tensors.h"

#include <ATen/ATen.h>
#include <c10/core/GradMode.h>

#include "group_impl.h"
#include "layers/dist/group.h"

namespace layers::dist {
namespace {

// One flat buffer on the group's device (and back), so each exchange is
// one collective whatever the number of parameters.
at::Tensor flatten(const std::vector<at::Tensor>& parts, const at::Device& device) {
  std::vector<at::Tensor> flat;
  for (const at::Tensor& t : parts) flat.push_back(t.detach().reshape({-1}).to(device, at::kFloat));
  return at::cat(flat);
}

void unflatten_into(const at::Tensor& flat, const std::vector<at::Tensor>& targets) {
  std::int64_t offset = 0;
  for (const at::Tensor& t : targets) {
    const std::int64_t n = t.numel();
    t.copy_(flat.slice(0, offset, offset + n).view(t.sizes()));
    offset += n;
  }
}

}  // namespace

void broadcast_from_root(Group& group, const std::vector<at::Tensor>& tensors) {
  if (tensors.empty()) return;
  c10::AutoGradMode no_grad(false);
  Group::Impl& m = group.impl();
  group.collective("broadcast", [&] {
    std::vector<at::Tensor> flat{flatten(tensors, m.device)};
    c10d::BroadcastOptions options;
    options.rootRank = 0;
    m.group->broadcast(flat, options)->wait();
    unflatten_into(flat[0], tensors);
  });
}

void average_gradients(Group& group, const std::vector<at::Tensor>& params, std::vector<double>& sums) {
  c10::AutoGradMode no_grad(false);
  Group::Impl& m = group.impl();
  // Which ranks have a gradient for each parameter, with the caller's sums.
  std::vector<double> counts(params.size());
  std::vector<at::Tensor> grads;
  for (std::size_t i = 0; i < params.size(); ++i) {
    const at::Tensor& g = params[i].grad();
    counts[i] = g.defined() ? 1.0 : 0.0;
    grads.push_back(g.defined() ? g : at::zeros_like(params[i]));
  }
  counts.insert(counts.end(), sums.begin(), sums.end());
  group.allreduce_sum(counts);
  std::copy(counts.begin() + static_cast<std::ptrdiff_t>(params.size()), counts.end(), sums.begin());
  if (params.empty()) return;
  group.collective("allreduce of gradients", [&] {
    std::vector<at::Tensor> flat{flatten(grads, m.device)};
    m.group->allreduce(flat)->wait();
    flat[0].div_(static_cast<double>(group.size()));
    std::int64_t offset = 0;
    for (std::size_t i = 0; i < params.size(); ++i) {
      at::Tensor p = params[i];
      const std::int64_t n = p.numel();
      if (counts[i] == 0) {
        offset += n;
        continue;  // no rank has one: stays without a gradient
      }
      const at::Tensor part = flat[0].slice(0, offset, offset + n).view(p.sizes()).to(p.device(), p.scalar_type());
      if (p.grad().defined())
        p.mutable_grad().copy_(part);
      else
        p.mutable_grad() = part.clone();
      offset += n;
    }
  });
}

}  // namespace layers::dist
