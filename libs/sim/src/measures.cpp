// Validation measures per frame and per sequence (see measures.h).
#include "layers/sim/measures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "layers/geometry/intersect.h"
#include "layers/geometry/nearest.h"
#include "layers/geometry/pinch.h"
#include "layers/geometry/topology.h"
#include "layers/sim/contact_topology.h"
#include "layers/sim/solver.h"
#include "surface_query.h"

namespace layers::sim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

geometry::Points stack(const std::vector<geometry::Points>& parts) {
  Eigen::Index rows = 0;
  for (const auto& p : parts) rows += p.rows();
  geometry::Points out(rows, 3);
  rows = 0;
  for (const auto& p : parts) {
    out.middleRows(rows, p.rows()) = p;
    rows += p.rows();
  }
  return out;
}

std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f%%", 100.0 * fraction);
  return buffer;
}

}  // namespace

double penetration_rate(const geometry::Points& points, const geometry::Surface& surface) {
  if (points.rows() == 0) return 0.0;
  return static_cast<double>(surface.count_behind(points)) / static_cast<double>(points.rows());
}

double h_penetration_rate(const std::vector<geometry::Points>& garments, const geometry::TriMesh& body) {
  return penetration_rate(stack(garments), geometry::Surface::from_mesh(body, "body"));
}

namespace {

// The inner layer (every inner garment together) as one surface to test
// outer vertices against.
class InnerSurface {
 public:
  explicit InnerSurface(const std::vector<geometry::TriMesh>& meshes) {
    Eigen::Index rows = 0, faces = 0;
    for (const geometry::TriMesh& m : meshes) {
      rows += m.vertices.rows();
      faces += m.faces.rows();
    }
    geometry::Points points(rows, 3);
    geometry::Faces all(faces, 3);
    rows = faces = 0;
    for (const geometry::TriMesh& m : meshes) {
      points.middleRows(rows, m.vertices.rows()) = m.vertices;
      all.middleRows(faces, m.faces.rows()) = m.faces.array() + static_cast<int>(rows);
      rows += m.vertices.rows();
      faces += m.faces.rows();
    }
    topology_ = ContactTopology::build(all, points, "inner garments");
    x_.reserve(static_cast<std::size_t>(points.rows()));
    for (Eigen::Index i = 0; i < points.rows(); ++i) x_.push_back(points.row(i).cast<double>().transpose());
    index_ = geometry::PointIndex(std::move(points));
    seen_.assign(topology_.faces.size(), 0);
  }

  // The closest point among the faces around the nearest inner vertex is
  // within `reach`, p is behind the surface there, and p is over (or under)
  // the surface rather than beside an open boundary (a hem, a cuff, a
  // neckline).
  bool behind(const Vec3& p, double reach) const {
    const geometry::Neighbour h = index_.nearest(p.cast<float>().transpose());
    if (h.index < 0) return false;
    detail::SurfaceHit hit;
    if (!detail::closest_around(topology_, x_, h.index, p, hit)) return false;
    return hit.offset < 0 && -hit.offset <= reach && (!hit.on_boundary || hit.facing);
  }

  // The first inner face that the ray p + t d (0 < t <= reach) meets is
  // crossed from its back (d . n > 0): p is under the inner layer.
  bool covered(const Vec3& p, const Vec3& d, double reach) {
    const float radius = static_cast<float>(reach + topology_.max_edge_length);
    double first = std::numeric_limits<double>::infinity();
    bool leaves = false;
    touched_.clear();
    for (const geometry::Neighbour& n : index_.within(p.cast<float>().transpose(), radius)) {
      for (int k = topology_.face_offsets[n.index]; k < topology_.face_offsets[n.index + 1]; ++k) {
        const int f = topology_.vertex_faces[k];
        if (seen_[f]) continue;
        seen_[f] = 1;
        touched_.push_back(f);
        const auto& v = topology_.faces[f];
        double t = 0;
        Vec3 normal;
        if (ray_hits(p, d, x_[v[0]], x_[v[1]], x_[v[2]], t, normal) && t <= reach && t < first) {
          first = t;
          leaves = d.dot(normal) > 0;
        }
      }
    }
    for (int f : touched_) seen_[f] = 0;
    return leaves;
  }

 private:
  // Moeller-Trumbore: the ray p + t d meets triangle (a, b, c) at t > 0;
  // `normal` is the triangle's (unnormalised) normal.
  static bool ray_hits(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double& t,
                       Vec3& normal) {
    const Vec3 e1 = b - a, e2 = c - a;
    const Vec3 q = d.cross(e2);
    const double det = e1.dot(q);
    if (std::abs(det) < 1e-14) return false;
    const Vec3 s = p - a;
    const double u = s.dot(q) / det;
    if (u < 0 || u > 1) return false;
    const Vec3 r = s.cross(e1);
    const double v = d.dot(r) / det;
    if (v < 0 || u + v > 1) return false;
    t = e2.dot(r) / det;
    normal = e1.cross(e2);
    return t > 0;
  }

  ContactTopology topology_;
  geometry::PointIndex index_;
  Vec3s x_;
  std::vector<std::uint8_t> seen_;
  std::vector<int> touched_;
};

}  // namespace

double l_penetration_rate(const std::vector<geometry::Points>& outer, const std::vector<geometry::TriMesh>& inner,
                          double reach, const geometry::Surface* body) {
  std::vector<geometry::TriMesh> meshes;
  for (const geometry::TriMesh& mesh : inner) {
    if (mesh.num_faces() > 0) meshes.push_back(mesh);
  }
  const geometry::Points points = stack(outer);
  if (meshes.empty() || points.rows() == 0) return 0.0;
  InnerSurface surface(meshes);
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).cast<double>().transpose();
    if (!surface.behind(p, reach)) continue;
    if (body != nullptr && body->size() > 0) {
      // Confirmed only when the inner layer covers p along the body's
      // outward normal (folds of the inner garment fool the sign alone).
      const geometry::Neighbour h = body->index().nearest(points.row(i));
      if (h.index >= 0 && !surface.covered(p, body->normals().row(h.index).cast<double>().transpose(), reach)) continue;
    }
    ++count;
  }
  return static_cast<double>(count) / static_cast<double>(points.rows());
}

double max_edge_stretch(const geometry::Points& x, const geometry::Edges& edges, const Eigen::VectorXd& rest) {
  double worst = 0.0;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const double len = (x.row(edges(e, 0)) - x.row(edges(e, 1))).cast<double>().norm();
    const double strain = len / rest[e] - 1.0;
    if (std::isnan(strain)) return kNaN;
    worst = std::max(worst, strain);
  }
  return worst;
}

std::int64_t count_nonfinite(const geometry::Points& points) {
  return static_cast<std::int64_t>((!points.array().isFinite()).count());
}

std::int64_t cloth_crossings(const std::vector<MeasuredGarment>& garments) {
  std::int64_t pairs = 0;
  for (std::size_t a = 0; a < garments.size(); ++a) {
    const geometry::FaceTree tree({garments[a].positions, garments[a].faces});
    if (garments[a].self_contact) pairs += geometry::self_crossings(tree).pairs;
    for (std::size_t b = 0; b < a; ++b)
      pairs += geometry::crossings({garments[b].positions, garments[b].faces}, tree).pairs;
  }
  return pairs;
}

FrameMeasures measure_frame(const geometry::TriMesh& body, const std::vector<MeasuredGarment>& garments, double l_reach,
                            bool body_self, double pinch_distance) {
  FrameMeasures out;
  if (!body_self || body.num_faces() == 0) {
    out.body_self_crossing = out.body_pinch = out.h_crossing_clear = out.h_crossing_pinch = kNaN;
  }
  std::vector<geometry::Points> all, outer;
  std::vector<geometry::TriMesh> meshes, inner, outer_meshes;
  for (const MeasuredGarment& g : garments) {
    out.nonfinite += count_nonfinite(g.positions);
    all.push_back(g.positions);
    meshes.push_back({g.positions, g.faces});
    if (g.outer) {
      outer.push_back(g.positions);
      outer_meshes.push_back({g.positions, g.faces});
    } else {
      inner.push_back({g.positions, g.faces});
    }
  }
  if (out.nonfinite > 0) {
    out.h_penetration = out.l_penetration = out.max_stretch = kNaN;
    out.h_crossing = out.l_crossing = out.body_self_crossing = out.h_crossing_clear = kNaN;
    out.body_pinch = out.h_crossing_pinch = kNaN;
    return out;
  }
  if (body.num_faces() > 0) {
    const geometry::FaceTree body_tree(body);
    const geometry::MeshCrossings h = geometry::body_crossings(meshes, body_tree);
    out.h_crossing = h.a_vertex_share();
    out.h_crossing_pairs = h.pairs;
    if (body_self) {
      const geometry::MeshCrossings self = geometry::self_crossings(body_tree);
      out.body_self_crossing = static_cast<double>(self.a_faces_crossing()) / body.num_faces();
      // Pinch zones among the body vertices under the garments; their
      // share of the body faces under the garments.
      const geometry::PinchZones zones = geometry::pinch_zones_under(
          body, self.pairs > 0 ? self.a_faces : std::vector<char>{}, pinch_distance, meshes);
      const std::vector<char>& pinch = zones.faces;
      const std::vector<char>& covered = zones.covered;
      const auto in_pinch = std::count(pinch.begin(), pinch.end(), 1);
      long under = 0, under_pinched = 0;
      for (int f = 0; f < body.num_faces(); ++f) {
        if (!covered[body.faces(f, 0)] && !covered[body.faces(f, 1)] && !covered[body.faces(f, 2)]) continue;
        ++under;
        under_pinched += pinch[f];
      }
      out.body_pinch = under > 0 ? static_cast<double>(under_pinched) / under : 0.0;
      if (h.pairs == 0 || in_pinch == 0) {
        out.h_crossing_clear = out.h_crossing;
        out.h_crossing_pinch = 0;
      } else {
        std::vector<char> clear(pinch.size());
        for (std::size_t f = 0; f < pinch.size(); ++f) clear[f] = pinch[f] ? 0 : 1;
        out.h_crossing_clear = geometry::body_crossings(meshes, body_tree, pinch).a_vertex_share();
        out.h_crossing_pinch = geometry::body_crossings(meshes, body_tree, clear).a_vertex_share();
      }
    }
  }
  if (!outer_meshes.empty() && !inner.empty()) {
    const geometry::MeshCrossings l = geometry::layer_crossings(outer_meshes, inner);
    out.l_crossing = l.a_vertex_share();
    out.l_crossing_pairs = l.pairs;
  }
  out.cloth_crossing_pairs = cloth_crossings(garments);
  for (const MeasuredGarment& g : garments) {
    out.max_stretch = std::max(out.max_stretch, max_edge_stretch(g.positions, g.edges, g.rest_lengths));
  }
  const geometry::Surface body_surface =
      body.num_faces() > 0 ? geometry::Surface::from_mesh(body, "body") : geometry::Surface();
  out.h_penetration = body.num_faces() > 0 ? penetration_rate(stack(all), body_surface) : 0.0;
  out.l_penetration = outer.empty() ? 0.0 : l_penetration_rate(outer, inner, l_reach, &body_surface);
  return out;
}

FrameMeasures measure_frame(const Solver& solver) {
  // With more than one layer, the cloths of the top layer are the outer
  // garments; a single layer has no L-penetration.
  int top = std::numeric_limits<int>::min(), bottom = std::numeric_limits<int>::max();
  for (int i = 0; i < solver.num_cloths(); ++i) {
    top = std::max(top, solver.cloth(i).layer());
    bottom = std::min(bottom, solver.cloth(i).layer());
  }
  std::vector<MeasuredGarment> garments;
  for (int i = 0; i < solver.num_cloths(); ++i) {
    const Cloth& c = solver.cloth(i);
    garments.push_back(
        {c.positions(), c.faces(), c.edges(), c.rest_lengths(), top != bottom && c.layer() == top, c.self_contact()});
  }
  const ValidationConfig& v = solver.config().validation;
  return measure_frame(solver.body(), garments, v.l_reach, v.max_h_crossing_clear < 1, v.pinch_distance);
}

void SequenceMeasures::add(const FrameMeasures& f) {
  ++frames_;
  nonfinite_ += f.nonfinite;
  if (std::isnan(f.h_penetration) || std::isnan(f.l_penetration) || std::isnan(f.max_stretch)) return;
  ++measured_;
  sum_h_ += f.h_penetration;
  sum_l_ += f.l_penetration;
  max_stretch_ = std::max(max_stretch_, f.max_stretch);
  sum_hx_ += f.h_crossing;
  sum_lx_ += f.l_crossing;
  max_h_crossing_ = std::max(max_h_crossing_, f.h_crossing);
  max_l_crossing_ = std::max(max_l_crossing_, f.l_crossing);
  max_cloth_crossings_ = std::max(max_cloth_crossings_, f.cloth_crossing_pairs);
  if (std::isnan(f.body_self_crossing)) return;
  ++measured_self_;
  sum_self_ += f.body_self_crossing;
  sum_hx_clear_ += f.h_crossing_clear;
  max_h_crossing_clear_ = std::max(max_h_crossing_clear_, f.h_crossing_clear);
  sum_pinch_ += f.body_pinch;
  sum_hx_pinch_ += f.h_crossing_pinch;
  max_h_crossing_pinch_ = std::max(max_h_crossing_pinch_, f.h_crossing_pinch);
}

double SequenceMeasures::mean_h_penetration() const { return measured_ ? sum_h_ / measured_ : 0.0; }
double SequenceMeasures::mean_l_penetration() const { return measured_ ? sum_l_ / measured_ : 0.0; }
double SequenceMeasures::mean_h_crossing() const { return measured_ ? sum_hx_ / measured_ : 0.0; }
double SequenceMeasures::mean_l_crossing() const { return measured_ ? sum_lx_ / measured_ : 0.0; }
double SequenceMeasures::mean_body_self_crossing() const { return measured_self_ ? sum_self_ / measured_self_ : kNaN; }
double SequenceMeasures::mean_h_crossing_clear() const {
  return measured_self_ ? sum_hx_clear_ / measured_self_ : kNaN;
}
double SequenceMeasures::mean_body_pinch() const { return measured_self_ ? sum_pinch_ / measured_self_ : kNaN; }
double SequenceMeasures::mean_h_crossing_pinch() const {
  return measured_self_ ? sum_hx_pinch_ / measured_self_ : kNaN;
}

std::vector<Violation> frame_violations(const FrameMeasures& f, const ValidationConfig& limits) {
  std::vector<Violation> out;
  if (f.nonfinite > 0) out.push_back({"non_finite", std::to_string(f.nonfinite) + " non-finite coordinates"});
  // NaN measures compare false: a frame not measurable breaks only the
  // non-finite rule, and a frame whose pinch zones were not measured not
  // the rule outside them.
  if (f.h_crossing > limits.max_h_crossing) {
    out.push_back({"h_crossing",
                   "H-crossing " + percent(f.h_crossing) + " in a frame exceeds " + percent(limits.max_h_crossing)});
  }
  if (f.h_crossing_clear > limits.max_h_crossing_clear) {
    out.push_back({"h_crossing_clear", "H-crossing outside pinch zones " + percent(f.h_crossing_clear) +
                                           " in a frame exceeds " + percent(limits.max_h_crossing_clear)});
  }
  if (f.l_crossing > limits.max_l_crossing) {
    out.push_back({"l_crossing",
                   "L-crossing " + percent(f.l_crossing) + " in a frame exceeds " + percent(limits.max_l_crossing)});
  }
  if (f.cloth_crossing_pairs > limits.max_cloth_crossings) {
    out.push_back({"cloth_crossings", std::to_string(f.cloth_crossing_pairs) +
                                          " crossing face pairs between garments in a frame exceed " +
                                          std::to_string(limits.max_cloth_crossings)});
  }
  if (f.max_stretch > limits.max_stretch) {
    out.push_back(
        {"stretch", "maximum edge stretch " + percent(f.max_stretch) + " exceeds " + percent(limits.max_stretch)});
  }
  return out;
}

std::vector<std::string> SequenceMeasures::violations(const ValidationConfig& limits) const {
  std::vector<std::string> out;
  for (const Violation& v : broken(limits)) out.push_back(v.sentence);
  return out;
}

std::vector<Violation> SequenceMeasures::broken(const ValidationConfig& limits) const {
  // The means over frames, then the per-frame rules on the worst frame.
  std::vector<Violation> all;
  if (mean_h_penetration() > limits.max_h_penetration) {
    all.push_back({"h_penetration", "mean H-penetration " + percent(mean_h_penetration()) + " exceeds " +
                                        percent(limits.max_h_penetration)});
  }
  if (mean_l_penetration() > limits.max_l_penetration) {
    all.push_back({"l_penetration", "mean L-penetration " + percent(mean_l_penetration()) + " exceeds " +
                                        percent(limits.max_l_penetration)});
  }
  FrameMeasures worst;
  worst.nonfinite = nonfinite_;
  worst.h_crossing = max_h_crossing_;
  worst.h_crossing_clear = measured_self_ > 0 ? max_h_crossing_clear_ : kNaN;
  worst.l_crossing = max_l_crossing_;
  worst.cloth_crossing_pairs = max_cloth_crossings_;
  worst.max_stretch = max_stretch_;
  const std::vector<Violation> framed = frame_violations(worst, limits);
  // The non-finite count (frame_violations' first, when there is one)
  // before the means, as it always came.
  std::vector<Violation> out = framed;
  const bool nonfinite_first = !out.empty() && std::string(out.front().rule) == "non_finite";
  out.insert(out.begin() + (nonfinite_first ? 1 : 0), all.begin(), all.end());
  return out;
}

}  // namespace layers::sim
