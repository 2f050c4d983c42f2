// MGNet parameter checks that involve several fields (see params.h).
#include "layers/mgnet/params.h"

#include <string>

#include "layers/core/error.h"

namespace layers::mgnet {
namespace {

std::string where_of(const cfg::Node& params, const char* key) {
  const cfg::Node* n = params.kind == cfg::Node::Kind::Map ? params.find(key) : nullptr;
  const std::string where = n ? n->where() : params.where();
  return where.empty() ? std::string("mgnet parameters") : where;
}

}  // namespace

Params read_params(const cfg::Node& node) {
  // An absent `params:` section means all defaults.
  Params p = node.kind == cfg::Node::Kind::Null ? Params{} : cfg::read<Params>(node);
  if (p.channels.empty())
    throw InputError(where_of(node, "channels"), "channels", "at least one encoder stage", "an empty list");
  const std::int64_t stages = static_cast<std::int64_t>(p.channels.size());
  if (stages > 20 || p.resolution % (std::int64_t{1} << stages) != 0) {
    throw InputError(where_of(node, "resolution"), "resolution",
                     "a multiple of 2^" + std::to_string(stages) + " (one halving per entry of channels)",
                     std::to_string(p.resolution));
  }
  return p;
}

}  // namespace layers::mgnet
