// plugins/deepsd/src/factory.h -- the DeePSD model's registry entry: name,
// description and factory (torch-free, for the plugin's registration).
#pragma once

#include <memory>

namespace layers::cfg {
struct Node;
}
namespace layers::zoo {
class Model;
}

namespace layers::deepsd {

inline constexpr const char* kDeepsdName = "deepsd";
inline constexpr const char* kDeepsdDescription =
    "DeePSD: blend weights + pose-space deformations from garment graph descriptors, skinned with body/joints "
    "(static; wind input; deepsd+ = trained with the layer collision loss)";

// Builds the model from its `model.params`; bad parameters are
// layers::InputError naming the key.
std::shared_ptr<zoo::Model> make_deepsd_model(const cfg::Node& params);

}  // namespace layers::deepsd
