// Autoregressive rollouts with per-frame metrics (see rollout.h).
#include "layers/train/rollout.h"

#include <torch/csrc/autograd/grad_mode.h>

#include <cmath>
#include <cstring>

#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/penetration.h"
#include "layers/zoo/metrics.h"

namespace layers::train {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

geometry::Points points_of(const at::Tensor& t) {
  const at::Tensor c = t.detach().to(at::kCPU, at::kFloat).contiguous();
  geometry::Points p(c.size(0), 3);
  std::memcpy(p.data(), c.data_ptr<float>(), sizeof(float) * static_cast<std::size_t>(c.numel()));
  return p;
}

geometry::Faces faces_of(const at::Tensor& t) {
  const at::Tensor c = t.to(at::kCPU, at::kInt).contiguous();
  geometry::Faces f(c.size(0), 3);
  std::memcpy(f.data(), c.data_ptr<int>(), sizeof(int) * static_cast<std::size_t>(c.numel()));
  return f;
}

// The inner garments of one frame as one mesh (empty when none).
geometry::TriMesh inner_mesh(const zoo::SequenceStatic& seq, const std::vector<at::Tensor>& garments) {
  std::vector<at::Tensor> v, f;
  std::int64_t offset = 0;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    if (seq.garments[k].layer != 0) continue;
    v.push_back(garments[k]);
    f.push_back(seq.garments[k].faces + offset);
    offset += garments[k].size(0);
  }
  geometry::TriMesh mesh;
  if (v.empty()) return mesh;
  mesh.vertices = points_of(at::cat(v));
  mesh.faces = faces_of(at::cat(f));
  return mesh;
}

at::Tensor outer_points(const zoo::SequenceStatic& seq, const std::vector<at::Tensor>& garments) {
  std::vector<at::Tensor> v;
  for (std::size_t k = 0; k < garments.size(); ++k)
    if (seq.garments[k].layer != 0) v.push_back(garments[k]);
  return v.empty() ? at::Tensor() : at::cat(v);
}

// The rates of one frame's garments (shares 0..1; L: NaN without an inner
// and an outer garment).
struct FrameRates {
  double h_collision = 0, l_collision = kNaN, l_collision_plain = kNaN, h_crossing = 0, l_crossing = kNaN;
  std::vector<double> garment_h_collision, garment_h_crossing;
};

// The paper's vertex-normal H- and L-collision, our L-collision (open-edge
// rule) and the exact H- and L-crossing (geometry/intersect.h) of one frame. `faces`: each garment's
// faces; outer garments are those of a layer other than 0, as for
// L-collision. `body_tree`: the body's faces, built once per frame for the
// prediction and the ground truth.
FrameRates frame_rates(const zoo::SequenceStatic& seq, const std::vector<geometry::Faces>& faces,
                       const std::vector<at::Tensor>& garments, const geometry::FaceTree& body_tree,
                       const geometry::Surface& body) {
  FrameRates r;
  double behind = 0, total = 0;
  std::vector<geometry::TriMesh> meshes, outer, inner;
  for (std::size_t k = 0; k < garments.size(); ++k) {
    geometry::TriMesh mesh{points_of(garments[k]), faces[k]};
    const double share = zoo::behind_share(mesh.vertices, body);
    r.garment_h_collision.push_back(share);
    behind += share * static_cast<double>(mesh.num_vertices());
    total += static_cast<double>(mesh.num_vertices());
    (seq.garments[k].layer != 0 ? outer : inner).push_back(mesh);
    meshes.push_back(std::move(mesh));
  }
  r.h_collision = total > 0 ? behind / total : 0.0;
  const at::Tensor outer_p = outer_points(seq, garments);
  if (outer_p.defined()) {
    geometry::TriMesh inner_m = inner_mesh(seq, garments);
    if (inner_m.num_vertices() > 0) {
      const geometry::Points outer_v = points_of(outer_p);
      const zoo::LCollisionRates l = zoo::l_collision_rates(outer_v, inner_m);
      r.l_collision = l.ours;
      r.l_collision_plain = l.plain;
    }
  }
  // body_crossings() takes the garments as one mesh, vertices in order:
  // each garment's share is its slice of the per-vertex flags.
  const geometry::MeshCrossings h = geometry::body_crossings(meshes, body_tree);
  r.h_crossing = h.a_vertex_share();
  std::size_t first = 0;
  for (const geometry::TriMesh& m : meshes) {
    const std::size_t n = static_cast<std::size_t>(m.num_vertices());
    std::int64_t on = 0;
    for (std::size_t v = first; v < first + n && v < h.a_vertices.size(); ++v) on += h.a_vertices[v] ? 1 : 0;
    r.garment_h_crossing.push_back(n ? static_cast<double>(on) / static_cast<double>(n) : 0.0);
    first += n;
  }
  if (!outer.empty() && !inner.empty()) r.l_crossing = geometry::layer_crossings(outer, inner).a_vertex_share();
  return r;
}

}  // namespace

RolloutResult rollout(zoo::Model& model, const zoo::SequenceStatic& seq, const FrameTensors& frames,
                      const RolloutOptions& options) {
  const std::int64_t last = frames.frames() - 1;
  const std::int64_t steps = options.steps < 0 ? last - options.start : options.steps;
  if (options.start < 1 || steps < 1 || options.start + steps > last)
    throw Error("rollout of sequence '" + seq.id + "': start row " + std::to_string(options.start) + " and " +
                std::to_string(steps) + " steps do not fit a window of " + std::to_string(frames.frames()) + " frames");
  torch::NoGradGuard no_grad;
  const geometry::Faces body_faces = faces_of(seq.body_faces);
  std::vector<geometry::Faces> garment_faces;
  for (const zoo::GarmentStatic& g : seq.garments) garment_faces.push_back(faces_of(g.faces));
  RolloutResult result;
  std::vector<std::vector<at::Tensor>> kept(seq.garments.size());
  std::vector<zoo::GarmentState> states = true_states(frames, options.start);
  for (std::int64_t s = 0; s < steps; ++s) {
    const std::int64_t i = options.start + s;  // predicting row i + 1
    FrameMetrics m;
    m.frame = frames.first_frame + i + 1;
    std::vector<at::Tensor> truth;
    for (const at::Tensor& g : frames.garments) truth.push_back(g[i + 1]);
    // A frame at or after the divergence: the bound as its error, no collision rates.
    const auto record_diverged = [&] {
      m.diverged = true;
      m.error_mm = options.diverge_mm;
      m.garment_error_mm.assign(seq.garments.size(), options.diverge_mm);
      m.h_collision = m.l_collision = m.l_collision_plain = kNaN;
      m.h_crossing = m.l_crossing = kNaN;
      result.frames.push_back(m);
    };
    if (result.diverged_at >= 0) {
      record_diverged();
      continue;
    }
    Timer timer;
    zoo::StepOutput out = model.step(step_input(frames, i, states));
    result.model_seconds += timer.seconds();
    double err_sum = 0, n_sum = 0;
    for (std::size_t k = 0; k < out.garments.size(); ++k) {
      const double e = zoo::euclidean_error_mm(points_of(out.garments[k]), points_of(truth[k]));
      m.garment_error_mm.push_back(e);
      err_sum += e * static_cast<double>(truth[k].size(0));
      n_sum += static_cast<double>(truth[k].size(0));
    }
    m.error_mm = err_sum / n_sum;
    if (!std::isfinite(m.error_mm) || m.error_mm > options.diverge_mm) {
      result.diverged_at = m.frame;
      result.diverge_reason = std::isfinite(m.error_mm)
                                  ? "error " + std::to_string(m.error_mm) + " mm above the bound " +
                                        std::to_string(options.diverge_mm) + " mm"
                                  : "non-finite prediction";
      record_diverged();
      continue;
    }
    if (options.rates) {
      geometry::TriMesh body_mesh{points_of(frames.body[i + 1]), body_faces};
      const geometry::Surface body = geometry::Surface::from_mesh(body_mesh, "body");
      const geometry::FaceTree body_tree(body_mesh);
      FrameRates predicted = frame_rates(seq, garment_faces, out.garments, body_tree, body);
      m.h_collision = predicted.h_collision, m.l_collision = predicted.l_collision;
      m.l_collision_plain = predicted.l_collision_plain;
      m.h_crossing = predicted.h_crossing, m.l_crossing = predicted.l_crossing;
      m.garment_h_collision = std::move(predicted.garment_h_collision);
      m.garment_h_crossing = std::move(predicted.garment_h_crossing);
      if (options.truth_collisions) {
        const FrameRates t = frame_rates(seq, garment_faces, truth, body_tree, body);
        m.truth_h_collision = t.h_collision, m.truth_l_collision = t.l_collision;
        m.truth_l_collision_plain = t.l_collision_plain;
        m.truth_h_crossing = t.h_crossing, m.truth_l_crossing = t.l_crossing;
      }
    } else {
      m.h_collision = m.h_crossing = kNaN;
    }
    result.frames.push_back(m);
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (options.keep_predictions) kept[k].push_back(out.garments[k].detach());
      states[k] = {states[k].current, out.garments[k].detach()};
    }
  }
  if (options.keep_predictions) {
    // From the divergence on, the last finite prediction is held (the
    // metrics record the divergence; the file stays valid and viewable).
    for (std::size_t k = 0; k < kept.size(); ++k) {
      while (static_cast<std::int64_t>(kept[k].size()) < steps) kept[k].push_back(states[k].current);
      result.predictions.push_back(at::stack(kept[k]).to(at::kCPU));
    }
  }
  return result;
}

}  // namespace layers::train
