// layers/zoo/plugin_abi_of.h -- fills a PluginAbi (plugin_abi.h) with what
// the including translation unit was compiled against. The host fills its
// record with it in libs/zoo, every plugin fills its own through
// LAYERS_PLUGIN: both read the same list of crossing types.
//
// LAYERS_PLUGIN_TORCH_VERSION may be defined only by the test plugin that
// claims another LibTorch (tests/plugins); never override it otherwise.
#pragma once

#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <torch/version.h>

#include "layers/core/config_node.h"
#include "layers/zoo/api_version.h"
#include "layers/zoo/model.h"
#include "layers/zoo/plugin_abi.h"
#include "layers/zoo/registry.h"

#ifndef LAYERS_PLUGIN_TORCH_VERSION
#define LAYERS_PLUGIN_TORCH_VERSION TORCH_VERSION
#endif

namespace layers::zoo::plugin_detail {

template <class T>
inline void add_abi_type(PluginAbi& abi, const char* name) {
  if (abi.type_count >= static_cast<std::uint32_t>(kPluginAbiTypes)) return;
  PluginAbiType& t = abi.types[abi.type_count++];
  std::strncpy(t.name, name, sizeof(t.name) - 1);
  t.size = static_cast<std::uint32_t>(sizeof(T));
  t.align = static_cast<std::uint32_t>(alignof(T));
}

// Internal linkage: each plugin reports its own compilation.
static inline void fill_plugin_abi(PluginAbi& abi) noexcept {
  std::memset(&abi, 0, sizeof(abi));
  abi.record_size = static_cast<std::uint32_t>(sizeof(PluginAbi));
  abi.api_version = LAYERS_ZOO_API_VERSION;
  abi.cxx11_abi = _GLIBCXX_USE_CXX11_ABI;
  abi.pointer_size = static_cast<std::uint32_t>(sizeof(void*));
  std::strncpy(abi.torch_version, LAYERS_PLUGIN_TORCH_VERSION, sizeof(abi.torch_version) - 1);
  add_abi_type<Registry>(abi, "layers::zoo::Registry");
  add_abi_type<ModelEntry>(abi, "layers::zoo::ModelEntry");
  add_abi_type<ModelFactory>(abi, "layers::zoo::ModelFactory");
  add_abi_type<cfg::Node>(abi, "layers::cfg::Node");
  add_abi_type<Model>(abi, "layers::zoo::Model");
  add_abi_type<torch::nn::Module>(abi, "torch::nn::Module");
  add_abi_type<at::Tensor>(abi, "at::Tensor");
  add_abi_type<SequenceStatic>(abi, "layers::zoo::SequenceStatic");
  add_abi_type<GarmentStatic>(abi, "layers::zoo::GarmentStatic");
  add_abi_type<StepInput>(abi, "layers::zoo::StepInput");
  add_abi_type<StepOutput>(abi, "layers::zoo::StepOutput");
  add_abi_type<LossTerm>(abi, "layers::zoo::LossTerm");
  add_abi_type<Normalization>(abi, "layers::zoo::Normalization");
  add_abi_type<std::string>(abi, "std::string");
  add_abi_type<std::shared_ptr<Model>>(abi, "std::shared_ptr<Model>");
  add_abi_type<std::vector<at::Tensor>>(abi, "std::vector<at::Tensor>");
}

}  // namespace layers::zoo::plugin_detail
