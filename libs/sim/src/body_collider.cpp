// The moving body collider (see body_collider.h).
#include "body_collider.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>

#include "contact_response.h"
#include "layers/core/error.h"
#include "layers/geometry/topology.h"
#include "surface_query.h"

namespace layers::sim::detail {

namespace {

void copy_pose(const geometry::Points& pose, Vec3s& out, const char* field) {
  if (!pose.allFinite()) throw InputError("body", field, "finite vertex positions", "NaN or infinity");
  out.resize(pose.rows());
  for (Eigen::Index i = 0; i < pose.rows(); ++i) out[i] = pose.row(i).cast<double>().transpose();
}

}  // namespace

void BodyCollider::reset(const geometry::TriMesh& body) {
  ContactTopology topology = ContactTopology::build(body.faces, body.vertices, "body");
  copy_pose(body.vertices, start_, "vertices");
  topology_ = std::move(topology);
  end_ = current_ = previous_ = start_;
  edges_ = geometry::unique_edges(body.faces);
  std::unordered_map<std::uint64_t, int> index;
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
  };
  for (Eigen::Index e = 0; e < edges_.rows(); ++e) index.emplace(key(edges_(e, 0), edges_(e, 1)), static_cast<int>(e));
  // Each edge's faces (counting sort by edge).
  edge_face_start_.assign(static_cast<std::size_t>(edges_.rows()) + 1, 0);
  for (const auto& v : topology_.faces)
    for (int k = 0; k < 3; ++k) ++edge_face_start_[index.at(key(v[k], v[(k + 1) % 3])) + 1];
  for (std::size_t e = 0; e + 1 < edge_face_start_.size(); ++e) edge_face_start_[e + 1] += edge_face_start_[e];
  edge_faces_.resize(static_cast<std::size_t>(edge_face_start_.back()));
  std::vector<int> fill(edge_face_start_.begin(), edge_face_start_.end() - 1);
  for (std::size_t f = 0; f < topology_.faces.size(); ++f) {
    const auto& v = topology_.faces[f];
    for (int k = 0; k < 3; ++k) edge_faces_[fill[index.at(key(v[k], v[(k + 1) % 3]))]++] = static_cast<int>(f);
  }
  edge_normals_.assign(static_cast<std::size_t>(edges_.rows()), Vec3::Zero());
  edge_normal_stamp_.assign(static_cast<std::size_t>(edges_.rows()), -1);
  ++sweep_revision_;
}

void BodyCollider::set_pose(const geometry::Points& pose) {
  if (pose.rows() != num_vertices()) {
    throw InputError("body", "positions", std::to_string(num_vertices()) + " vertices", std::to_string(pose.rows()));
  }
  copy_pose(pose, start_, "positions");
  end_ = current_ = previous_ = start_;
  ++sweep_revision_;
}

void BodyCollider::begin_frame(const geometry::Points* next) {
  ++sweep_revision_;
  if (next == nullptr) {
    end_ = start_;
    return;
  }
  if (next->rows() != num_vertices()) {
    throw InputError("body", "next positions", std::to_string(num_vertices()) + " vertices",
                     std::to_string(next->rows()));
  }
  copy_pose(*next, end_, "next positions");
}

void BodyCollider::begin_substep(double s, double cloth_step, double thickness) {
  std::swap(previous_, current_);
  double motion2 = 0;
  for (std::size_t i = 0; i < start_.size(); ++i) {
    current_[i] = start_[i] + s * (end_[i] - start_[i]);
    motion2 = std::max(motion2, (current_[i] - previous_[i]).squaredNorm());
  }
  radius_ = 1.5 * thickness + topology_.reach() + std::sqrt(motion2) + cloth_step;
  grid_.build(current_, radius_);
  ++substep_;
}

void BodyCollider::end_frame() {
  ++sweep_revision_;
  start_ = end_;
  current_ = previous_ = end_;
}

void BodyCollider::Memory::resize(int n) {
  nearest.assign(n, -1);
  face.assign(n, -1);
  touching.assign(n, 0);
  wanted.assign(n, 0);
  support.assign(n, 0.0);
  point.assign(n, Vec3::Zero());
  normal.assign(n, Vec3::Zero());
  target.assign(n, Vec3::Zero());
}

bool BodyCollider::nearest_point(const Vec3& p, int& nearest, SurfaceHit& hit) const {
  // Warm start from the cached nearest vertex: only closer ones count.
  int best_index = -1;
  double best = radius_ * radius_;
  if (nearest >= 0) {
    const double d2 = (current_[nearest] - p).squaredNorm();
    if (d2 < best) {
      best = d2;
      best_index = nearest;
    }
  }
  grid_.visit(p, std::sqrt(best), [&](int j) {
    const double d2 = (current_[j] - p).squaredNorm();
    if (d2 < best) {
      best = d2;
      best_index = j;
    }
  });
  nearest = best_index;
  return best_index >= 0 && closest_around(topology_, current_, best_index, p, hit) && !hit.on_boundary;
}

void BodyCollider::make_supports(const Cloth::State& state, Memory& memory) const {
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    memory.wanted[i] = memory.touching[i] && memory.face[i] >= 0 && state.inv_mass[i] != 0.0;
    memory.support[i] = 0.0;
  }
}

void BodyCollider::locate_supports(const Cloth::State& state, Memory& memory) const {
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    if (!memory.wanted[i]) continue;
    SurfaceHit hit;
    if (nearest_point(state.x[i], memory.nearest[i], hit)) {
      memory.point[i] = hit.point;
      memory.normal[i] = hit.normal;
    } else {
      memory.normal[i] = Vec3::Zero();
    }
  }
}

void BodyCollider::aim_supports(const Cloth::State& state, Memory& memory, const std::vector<double>& weights,
                                double thickness, Vec3s& rhs, std::vector<std::uint8_t>& claimed) const {
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    if (weights[i] == 0.0 || !memory.wanted[i]) continue;
    claimed[i] = 1;
    const Vec3& n = memory.normal[i];
    // The projection onto the half-space `thickness` outside the tangent
    // plane: it pushes, never pulls, and only by up to two thicknesses
    // (deeper cases are the projection pass's). Without a contact point
    // this substep (n = 0) the attachment just holds the vertex where it is.
    const double gap = thickness - (state.x[i] - memory.point[i]).dot(n);
    memory.target[i] = state.x[i] + (gap > 0 && gap < 2 * thickness ? gap : 0.0) * n;
    rhs[i] += weights[i] * memory.target[i];
  }
}

void BodyCollider::record_supports(const Cloth::State& state, Memory& memory, const std::vector<double>& weights,
                                   const std::vector<std::uint8_t>& claimed) const {
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    if (weights[i] == 0.0 || !memory.wanted[i] || !claimed[i]) continue;
    memory.support[i] = std::max(0.0, weights[i] * (memory.target[i] - state.x[i]).dot(memory.normal[i]));
  }
}

double BodyCollider::collide(Cloth::State& state, Memory& memory, double thickness, double mu, double h) const {
  double largest = 0;
  for (std::size_t i = 0; i < state.x.size(); ++i) {
    memory.touching[i] = 0;
    if (state.inv_mass[i] == 0.0) continue;
    SurfaceHit hit;
    if (!nearest_point(state.x[i], memory.nearest[i], hit)) {
      memory.face[i] = -1;
      continue;
    }
    memory.face[i] = hit.face;
    if (hit.offset < 1.5 * thickness) memory.touching[i] = 1;
    // A supported vertex's friction budget is what its support force would
    // move it in one substep.
    const double depth = std::max(thickness - hit.offset, 0.0);
    const double budget = std::max(depth, memory.support[i] * h * h * state.inv_mass[i]);
    if (budget <= 0.0) continue;
    const auto& f = topology_.faces[hit.face];
    Vec3 motion = Vec3::Zero();
    for (int k = 0; k < 3; ++k) motion += hit.bary[k] * (current_[f[k]] - previous_[f[k]]);
    state.x[i] += depth * hit.normal;
    state.x[i] -= friction_correction((state.x[i] - state.x_start[i]) - motion, hit.normal, budget, mu);
    largest = std::max(largest, depth);
  }
  return largest;
}

double BodyCollider::collide_edges(const Cloth& cloth, Cloth::State& state, double edge_thickness, Vec3s& push,
                                   const std::vector<std::array<int, 2>>& pairs) {
  if (edge_thickness <= 0 || edges_.rows() == 0 || pairs.empty()) return 0.0;
  // The outward direction of each listed body edge at this substep's pose:
  // the sum of its faces' area normals.
  for (const auto& pair : pairs) {
    const int e = pair[1];
    if (edge_normal_stamp_[e] == substep_) continue;
    edge_normal_stamp_[e] = substep_;
    Vec3 n = Vec3::Zero();
    for (int k = edge_face_start_[e]; k < edge_face_start_[e + 1]; ++k) {
      const auto& v = topology_.faces[edge_faces_[k]];
      n += (current_[v[1]] - current_[v[0]]).cross(current_[v[2]] - current_[v[0]]);
    }
    const double len = n.norm();
    edge_normals_[e] = len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
  const EdgeContact::Side body{&edges_, &previous_, nullptr, &current_, nullptr, nullptr, &edge_normals_};
  const EdgeContact::Side garment{&cloth.edges(), &state.x_start, &state.x, nullptr, &state.inv_mass, &push};
  return EdgeContact::collide(body, garment, edge_thickness, pairs);
}

}  // namespace layers::sim::detail
