// Reading and checking LayersNet's parameters (see params.h).
#include "params.h"

#include "layers/core/error.h"

namespace layers::layersnet {

Params read_params(const cfg::Node& node) {
  Params p = node.kind == cfg::Node::Kind::Null ? Params{} : cfg::read<Params>(node);
  const cfg::Node* heads = node.find("heads");
  const std::string where = heads ? heads->where() : node.where();
  if (p.heads % 2 != 0)
    throw InputError(where, "heads", "an even number (half the heads use E^M, half E^W)", std::to_string(p.heads));
  if (p.width % p.heads != 0)
    throw InputError(where, "heads", "a divisor of width (" + std::to_string(p.width) + ")", std::to_string(p.heads));
  if (p.blend == Blend::learned && p.base == Base::inertial) {
    const cfg::Node* blend = node.find("blend");
    throw InputError(blend ? blend->where() : node.where(), "blend",
                     "radius with base inertial (a learned blend needs base body, bones or skin)", "learned");
  }
  return p;
}

}  // namespace layers::layersnet
