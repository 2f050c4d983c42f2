// libs/dist/src/group_impl.h -- what a dist::Group holds (private to
// libs/dist): the TCPStore, the c10d process group and the device its
// tensors live on.
#pragma once

#include <ATen/ATen.h>
#include <torch/csrc/distributed/c10d/ProcessGroup.hpp>
#include <torch/csrc/distributed/c10d/Store.hpp>

#include "layers/dist/group.h"

namespace layers::dist {

struct Group::Impl {
  c10::intrusive_ptr<c10d::Store> store;
  c10::intrusive_ptr<c10d::ProcessGroup> group;
  at::Device device = at::Device(at::kCPU);
  const char* backend = "gloo";
};

}  // namespace layers::dist
