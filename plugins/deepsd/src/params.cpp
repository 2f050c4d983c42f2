// Reading the DeePSD parameters (see params.h).
#include "params.h"

#include "layers/core/error.h"

namespace layers::deepsd {

DeepsdParams read_params(const cfg::Node& params) {
  if (params.kind == cfg::Node::Kind::Null) return DeepsdParams{};
  DeepsdParams p = cfg::read<DeepsdParams>(params);
  if (p.graph_widths.empty()) {
    const cfg::Node* at = params.find("graph_widths");
    throw InputError(at ? at->where() : params.where(), "graph_widths", "at least one graph layer width",
                     "an empty list");
  }
  return p;
}

}  // namespace layers::deepsd
