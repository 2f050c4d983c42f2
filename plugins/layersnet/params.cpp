// Reading and checking LayersNet's parameters (see params.h).
#include "params.h"

#include "layers/core/error.h"

namespace layers::layersnet {

Base base_from_name(const std::string& name) {
  if (name == "body") return Base::body;
  if (name == "bones") return Base::bones;
  if (name == "skin") return Base::skin;
  if (name == "inertial") return Base::inertial;
  throw InputError("layersnet params", "base", "inertial, body, bones or skin", name);
}

Params read_params(const cfg::Node& node) {
  Params p = node.kind == cfg::Node::Kind::Null ? Params{} : cfg::read<Params>(node);
  const cfg::Node* heads = node.find("heads");
  const std::string where = heads ? heads->where() : node.where();
  if (p.heads % 2 != 0)
    throw InputError(where, "heads", "an even number (half the heads use E^M, half E^W)", std::to_string(p.heads));
  if (p.width % p.heads != 0)
    throw InputError(where, "heads", "a divisor of width (" + std::to_string(p.width) + ")", std::to_string(p.heads));
  if (p.blend == "learned" && p.base == "inertial") {
    const cfg::Node* blend = node.find("blend");
    throw InputError(blend ? blend->where() : node.where(), "blend",
                     "radius with base inertial (a learned blend needs base body, bones or skin)", p.blend);
  }
  return p;
}

}  // namespace layers::layersnet
