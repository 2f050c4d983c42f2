// Accounting of in-memory sequence data (see sequence.h).
#include "layers/data/sequence.h"

namespace layers::data {
namespace {

template <class T>
std::size_t vector_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t strings_bytes(const std::vector<std::string>& v) {
  std::size_t total = vector_bytes(v);
  for (const auto& s : v) total += s.capacity();
  return total;
}

}  // namespace

std::size_t SequenceStatic::bytes() const {
  std::size_t total = sizeof(*this) + id.capacity();
  total += vector_bytes(body.faces) + strings_bytes(body.joint_names) + vector_bytes(body.joint_parents) +
           vector_bytes(body.skin_index) + vector_bytes(body.skin_weight) + vector_bytes(body.tpose_joints);
  for (const auto& g : garments) {
    total += sizeof(g) + g.name.capacity() + g.type.capacity() + g.attributes.size() * 64;
    total += vector_bytes(g.faces) + vector_bytes(g.rest) + vector_bytes(g.uv) + vector_bytes(g.uv_faces) +
             vector_bytes(g.panel);
  }
  return total;
}

}  // namespace layers::data
