// Cloth construction: masses from areal density, membrane elements in the
// material frame, isometric bending stencils, two-rings; state accessors.
#include "layers/sim/cloth.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "layers/core/error.h"
#include "layers/geometry/topology.h"

namespace layers::sim {

namespace {

// Smallest triangle area accepted (m^2): a 0.1 mm x 0.1 mm sliver.

long next_revision() {
  static std::atomic<long> counter{0};
  return ++counter;
}

Vec3 row(const geometry::Points& p, int i) { return p.row(i).cast<double>().transpose(); }

double cot(const Vec3& a, const Vec3& b) {
  const double s = a.cross(b).norm();
  return a.dot(b) / std::max(s, 1e-300);
}

// A unit vector in the plane with normal n: `preferred` projected onto the
// plane, or (when that is nearly parallel to n) the world axis most
// perpendicular to n, projected.
Vec3 in_plane_axis(const Vec3& preferred, const Vec3& n) {
  Vec3 t = preferred - preferred.dot(n) * n;
  if (t.norm() >= 0.3 * preferred.norm() && preferred.norm() > 0) return t.normalized();
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
  }
  Vec3 e = Vec3::Zero();
  e[axis] = 1.0;
  return (e - e.dot(n) * n).normalized();
}

}  // namespace

Cloth::Cloth(const geometry::TriMesh& rest, const Material& material, ClothOptions options)
    : options_(std::move(options)), material_(material), rest_(rest.vertices), faces_(rest.faces) {
  const std::string& what = options_.name;
  topology_ = ContactTopology::build(faces_, rest_, what);
  if (rest_.rows() == 0 || faces_.rows() == 0) {
    throw InputError(what, "mesh", "at least one face", std::to_string(faces_.rows()) + " faces");
  }
  if (!(material_.density > 0) || material_.tension_modulus < 0 || material_.compression_modulus < 0 ||
      material_.shear_modulus < 0 || material_.bending_rigidity < 0 || material_.friction < 0 ||
      material_.self_friction < 0) {
    throw InputError::message(what, "material", "expected a positive density and non-negative moduli and friction");
  }
  if (options_.uv.rows() > 0 && options_.uv_faces.rows() != faces_.rows()) {
    throw InputError(what, "uv_faces", std::to_string(faces_.rows()) + " rows (one per face)",
                     std::to_string(options_.uv_faces.rows()));
  }
  if (options_.uv.rows() > 0) geometry::validate(options_.uv_faces, static_cast<int>(options_.uv.rows()), what + " uv");

  const int nv = static_cast<int>(rest_.rows());
  mass_ = Eigen::VectorXd::Zero(nv);
  for (int f = 0; f < faces_.rows(); ++f) {
    const Vec3 a = row(rest_, faces_(f, 0)), b = row(rest_, faces_(f, 1)), c = row(rest_, faces_(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (!(area >= geometry::kMinClothFaceArea)) {
      throw InputError(what, "face " + std::to_string(f), "a rest area of at least 1e-8 m^2",
                       std::to_string(area) + " m^2");
    }
    for (int k = 0; k < 3; ++k) mass_[faces_(f, k)] += material_.density * area / 3.0;
  }
  state_.x.resize(nv);
  state_.v.assign(nv, Vec3::Zero());
  state_.inv_mass.resize(nv);
  for (int i = 0; i < nv; ++i) {
    state_.x[i] = row(rest_, i);
    state_.inv_mass[i] = mass_[i] > 0 ? 1.0 / mass_[i] : 0.0;  // isolated vertices stay put
  }
  state_.x_start = state_.x;
  for (int p : options_.pinned) pin(p);

  edges_ = geometry::unique_edges(faces_);
  rest_lengths_ = geometry::edge_lengths(rest_, edges_);

  build_membrane();
  build_bending();
  if (options_.self_contact)
    build_two_ring();
  else
    two_ring_offsets_.assign(nv + 1, 0);
  revision_ = next_revision();
}

void Cloth::build_membrane() {
  const bool have_uv = options_.uv.rows() > 0;
  membrane_.resize(faces_.rows());
  for (int f = 0; f < faces_.rows(); ++f) {
    MembraneElement& m = membrane_[f];
    for (int k = 0; k < 3; ++k) m.v[k] = faces_(f, k);
    const Vec3 x0 = row(rest_, m.v[0]);
    const Vec3 e1 = row(rest_, m.v[1]) - x0, e2 = row(rest_, m.v[2]) - x0;
    const Vec3 n = e1.cross(e2).normalized();
    m.area = 0.5 * e1.cross(e2).norm();

    Vec3 preferred = options_.grain;
    if (have_uv) {
      // The in-plane gradient of u: g = a e1 + b e2 with e1.g = du1, e2.g = du2.
      const auto uv = [&](int k) { return options_.uv(options_.uv_faces(f, k), 0); };
      const double du1 = uv(1) - uv(0), du2 = uv(2) - uv(0);
      const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
      const double det = g11 * g22 - g12 * g12;
      const double a = (g22 * du1 - g12 * du2) / det, b = (g11 * du2 - g12 * du1) / det;
      const Vec3 g = a * e1 + b * e2;
      if (std::isfinite(g.squaredNorm()) && g.squaredNorm() > 0) preferred = g;
    }
    const Vec3 tu = in_plane_axis(preferred, n);
    const Vec3 tv = n.cross(tu);
    // Rest coordinates D (2x2) of e1, e2 in the (tu, tv) frame; F = [e1 e2] D^-1.
    const double d00 = e1.dot(tu), d01 = e2.dot(tu), d10 = e1.dot(tv), d11 = e2.dot(tv);
    const double det = d00 * d11 - d01 * d10;
    const double i00 = d11 / det, i01 = -d01 / det, i10 = -d10 / det, i11 = d00 / det;
    m.wu = {-(i00 + i10), i00, i10};
    m.wv = {-(i01 + i11), i01, i11};
  }
}

void Cloth::build_bending() {
  // Interior edges shared by exactly two faces; the other corner of each.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> by_edge;  // (lo,hi) -> (face, opposite)
  for (int f = 0; f < faces_.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces_(f, k), b = faces_(f, (k + 1) % 3), c = faces_(f, (k + 2) % 3);
      by_edge[{std::min(a, b), std::max(a, b)}].push_back({f, c});
    }
  }
  bending_.clear();
  for (const auto& [edge, sides] : by_edge) {
    if (sides.size() != 2) continue;
    BendingElement b;
    b.v = {edge.first, edge.second, sides[0].second, sides[1].second};
    const Vec3 x0 = row(rest_, b.v[0]), x1 = row(rest_, b.v[1]);
    const Vec3 x2 = row(rest_, b.v[2]), x3 = row(rest_, b.v[3]);
    const Vec3 e0 = x1 - x0, e1 = x2 - x0, e2 = x3 - x0, e3 = x2 - x1, e4 = x3 - x1;
    const double c01 = cot(e0, e1), c02 = cot(e0, e2), c03 = cot(-e0, e3), c04 = cot(-e0, e4);
    const double a0 = 0.5 * e0.cross(e1).norm(), a1 = 0.5 * e0.cross(e2).norm();
    b.k = {c03 + c04, c01 + c02, -c01 - c03, -c02 - c04};
    b.weight = 1.0 / (a0 + a1);
    bending_.push_back(b);
  }
}

void Cloth::build_two_ring() {
  const int nv = num_vertices();
  const geometry::Adjacency adj = geometry::vertex_adjacency(edges_, nv);
  two_ring_offsets_.assign(nv + 1, 0);
  two_ring_.clear();
  std::vector<int> ring;
  for (int v = 0; v < nv; ++v) {
    ring.clear();
    for (const int* n = adj.begin(v); n != adj.end(v); ++n) {
      ring.push_back(*n);
      ring.insert(ring.end(), adj.begin(*n), adj.end(*n));
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    ring.erase(std::remove(ring.begin(), ring.end(), v), ring.end());
    two_ring_.insert(two_ring_.end(), ring.begin(), ring.end());
    two_ring_offsets_[v + 1] = static_cast<int>(two_ring_.size());
  }
}

bool Cloth::in_two_ring(int v, int other) const {
  return std::binary_search(two_ring_begin(v), two_ring_end(v), other);
}

namespace {

geometry::Points to_points(const Vec3s& x) {
  geometry::Points p(static_cast<Eigen::Index>(x.size()), 3);
  for (std::size_t i = 0; i < x.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = x[i].cast<float>().transpose();
  return p;
}

void from_points(const geometry::Points& p, Vec3s& out, const std::string& what, const char* field) {
  if (static_cast<std::size_t>(p.rows()) != out.size()) {
    throw InputError(what, field, std::to_string(out.size()) + " rows", std::to_string(p.rows()));
  }
  if (!p.allFinite()) throw InputError(what, field, "finite values", "NaN or infinity");
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = p.row(static_cast<Eigen::Index>(i)).cast<double>().transpose();
}

}  // namespace

geometry::Points Cloth::positions() const { return to_points(state_.x); }
geometry::Points Cloth::velocities() const { return to_points(state_.v); }

void Cloth::set_positions(const geometry::Points& positions) {
  from_points(positions, state_.x, options_.name, "positions");
  state_.x_start = state_.x;
}

void Cloth::set_velocities(const geometry::Points& velocities) {
  from_points(velocities, state_.v, options_.name, "velocities");
}

void Cloth::pin(int vertex) {
  if (vertex < 0 || vertex >= num_vertices()) {
    throw InputError(options_.name, "pinned", "vertex indices in [0, " + std::to_string(num_vertices()) + ")",
                     std::to_string(vertex));
  }
  state_.inv_mass[vertex] = 0.0;
  state_.v[vertex] = Vec3::Zero();
  revision_ = next_revision();
}

}  // namespace layers::sim
