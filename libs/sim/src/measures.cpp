// Validation measures per frame and per sequence (see measures.h).
#include "layers/sim/measures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

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

// One inner garment as a surface to test outer vertices against.
class InnerSurface {
 public:
  explicit InnerSurface(const geometry::TriMesh& mesh)
      : topology_(ContactTopology::build(mesh.faces, mesh.vertices, "inner garment")), index_(mesh.vertices) {
    x_.reserve(static_cast<std::size_t>(mesh.vertices.rows()));
    for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) x_.push_back(mesh.vertices.row(i).cast<double>().transpose());
  }

  // The closest point among the faces around the nearest vertex is behind
  // the surface, and p is over (or under) the surface rather than beside an
  // open boundary (a hem, a cuff, a neckline).
  bool behind(const Eigen::RowVector3f& p) const {
    const geometry::Neighbour h = index_.nearest(p);
    if (h.index < 0) return false;
    detail::SurfaceHit hit;
    if (!detail::closest_around(topology_, x_, h.index, p.cast<double>().transpose(), hit)) return false;
    return hit.offset < 0 && (!hit.on_boundary || hit.facing);
  }

 private:
  ContactTopology topology_;
  geometry::PointIndex index_;
  Vec3s x_;
};

}  // namespace

double l_penetration_rate(const std::vector<geometry::Points>& outer, const std::vector<geometry::TriMesh>& inner) {
  std::vector<InnerSurface> surfaces;
  surfaces.reserve(inner.size());
  for (const geometry::TriMesh& mesh : inner) {
    if (mesh.num_faces() > 0) surfaces.emplace_back(mesh);
  }
  const geometry::Points points = stack(outer);
  if (surfaces.empty() || points.rows() == 0) return 0.0;
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::RowVector3f p = points.row(i);
    for (const InnerSurface& s : surfaces) {
      if (s.behind(p)) {
        ++count;
        break;
      }
    }
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

FrameMeasures measure_frame(const geometry::TriMesh& body, const std::vector<MeasuredGarment>& garments) {
  FrameMeasures out;
  std::vector<geometry::Points> all, outer;
  std::vector<geometry::TriMesh> inner;
  for (const MeasuredGarment& g : garments) {
    out.nonfinite += count_nonfinite(g.positions);
    all.push_back(g.positions);
    if (g.outer) outer.push_back(g.positions);
    else inner.push_back({g.positions, g.faces});
  }
  if (out.nonfinite > 0) {
    out.h_penetration = out.l_penetration = out.max_stretch = kNaN;
    return out;
  }
  for (const MeasuredGarment& g : garments) {
    out.max_stretch = std::max(out.max_stretch, max_edge_stretch(g.positions, g.edges, g.rest_lengths));
  }
  out.h_penetration = body.num_faces() > 0 ? h_penetration_rate(all, body) : 0.0;
  out.l_penetration = outer.empty() ? 0.0 : l_penetration_rate(outer, inner);
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
    garments.push_back({c.positions(), c.faces(), c.edges(), c.rest_lengths(), top != bottom && c.layer() == top});
  }
  return measure_frame(solver.body(), garments);
}

void SequenceMeasures::add(const FrameMeasures& f) {
  ++frames_;
  nonfinite_ += f.nonfinite;
  if (std::isnan(f.h_penetration) || std::isnan(f.l_penetration) || std::isnan(f.max_stretch)) return;
  ++measured_;
  sum_h_ += f.h_penetration;
  sum_l_ += f.l_penetration;
  max_stretch_ = std::max(max_stretch_, f.max_stretch);
}

double SequenceMeasures::mean_h_penetration() const { return measured_ ? sum_h_ / measured_ : 0.0; }
double SequenceMeasures::mean_l_penetration() const { return measured_ ? sum_l_ / measured_ : 0.0; }

std::vector<std::string> SequenceMeasures::violations(const ValidationConfig& limits) const {
  std::vector<std::string> out;
  if (nonfinite_ > 0) out.push_back(std::to_string(nonfinite_) + " non-finite coordinates");
  if (mean_h_penetration() > limits.max_h_penetration) {
    out.push_back("mean H-penetration " + percent(mean_h_penetration()) + " exceeds " + percent(limits.max_h_penetration));
  }
  if (mean_l_penetration() > limits.max_l_penetration) {
    out.push_back("mean L-penetration " + percent(mean_l_penetration()) + " exceeds " + percent(limits.max_l_penetration));
  }
  if (max_stretch_ > limits.max_stretch) {
    out.push_back("maximum edge stretch " + percent(max_stretch_) + " exceeds " + percent(limits.max_stretch));
  }
  return out;
}

}  // namespace layers::sim
