// Weighted shared losses of one frame (see frame_loss.h).
#include "layers/train/frame_loss.h"

#include "layers/zoo/losses.h"

namespace layers::train {
namespace {

constexpr double kCm = 100.0;  // metres -> centimetres

void add(LossSum& sum, const std::string& name, double weight, const at::Tensor& value) {
  sum.terms[name] += value.item<double>();
  if (weight <= 0) return;
  at::Tensor w = value * weight;
  sum.total = sum.total.defined() ? sum.total + w : w;
}

}  // namespace

LossSum frame_loss(const zoo::SequenceStatic& seq, const std::vector<at::Tensor>& pred,
                   const std::vector<at::Tensor>& truth, const at::Tensor& body, const LossConfig& w) {
  LossSum sum;
  const double n = static_cast<double>(pred.size());
  std::vector<at::Tensor> inner, inner_faces, outer, all;
  std::int64_t inner_offset = 0;
  for (std::size_t k = 0; k < pred.size(); ++k) {
    const zoo::GarmentStatic& g = seq.garments[k];
    const at::Tensor p = pred[k] * kCm, t = truth[k] * kCm;
    add(sum, "position", w.position / n, zoo::position_mse(p, t));
    if (w.normal > 0) {
      add(sum, "normal", w.normal / n,
          w.normals == "face" ? zoo::normal_loss(p, t, g.faces) : zoo::vertex_normal_loss(p, t, g.faces));
    }
    all.push_back(p);
    if (g.layer == 0) {
      inner.push_back(p);
      inner_faces.push_back(g.faces + inner_offset);
      inner_offset += p.size(0);
    } else {
      outer.push_back(p);
    }
  }
  // One body query for all garments (the k-d tree of the body is built once).
  if (w.body_collision > 0)
    add(sum, "body_collision", w.body_collision,
        zoo::body_collision_loss(at::cat(all), body * kCm, seq.body_faces, w.collision_eps * kCm));
  if (w.layer_collision > 0 && !inner.empty() && !outer.empty()) {
    add(sum, "layer_collision", w.layer_collision,
        zoo::layer_collision_loss(at::cat(outer), at::cat(inner), at::cat(inner_faces), w.collision_eps * kCm));
  }
  return sum;
}

}  // namespace layers::train
