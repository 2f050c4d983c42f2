// The measures of the evaluation metrics (see measures.h).
#include "layers/metrics/measures.h"

#include <cmath>
#include <cstdio>

#include "layers/core/error.h"
#include "layers/geometry/topology.h"

namespace layers::metrics {

double euclidean_error_mm(const geometry::Points& predicted, const geometry::Points& truth) {
  if (predicted.rows() != truth.rows()) {
    throw Error("euclidean_error_mm: " + std::to_string(predicted.rows()) + " predicted vertices but " +
                std::to_string(truth.rows()) + " ground-truth vertices");
  }
  if (truth.rows() == 0) throw Error("euclidean_error_mm: no vertices");
  double sum = 0.0;
  for (Eigen::Index i = 0; i < truth.rows(); ++i)
    sum += (predicted.row(i).cast<double>() - truth.row(i).cast<double>()).norm();
  return 1000.0 * sum / static_cast<double>(truth.rows());
}

double behind_share(const geometry::Points& points, const geometry::Surface& surface) {
  if (points.rows() == 0) throw Error("collision rate: no vertices to test");
  return static_cast<double>(surface.count_behind(points)) / static_cast<double>(points.rows());
}

double h_collision_rate(const geometry::Points& garment, const geometry::TriMesh& body) {
  return behind_share(garment, geometry::Surface::from_mesh(body, "body"));
}

LCollisionRates l_collision_rates(const geometry::Points& outer, const geometry::TriMesh& inner) {
  if (outer.rows() == 0) throw Error("collision rate: no vertices to test");
  const geometry::Surface surface = geometry::Surface::from_mesh(inner, "inner garment");
  const std::vector<char> open = geometry::boundary_vertices(inner.faces, inner.num_vertices());
  Eigen::Index plain = 0, ours = 0;
  for (Eigen::Index i = 0; i < outer.rows(); ++i) {
    const Eigen::RowVector3f x = outer.row(i);
    const geometry::Neighbour h = surface.index().nearest(x);
    if (h.index < 0) continue;
    // Behind the nearest vertex's normal plane (a NaN offset is not behind).
    if (!((x - surface.vertices().row(h.index)).dot(surface.normals().row(h.index)) < 0.0f)) continue;
    ++plain;
    ours += open[static_cast<std::size_t>(h.index)] ? 0 : 1;
  }
  const double n = static_cast<double>(outer.rows());
  return {static_cast<double>(plain) / n, static_cast<double>(ours) / n};
}

double l_collision_plain_rate(const geometry::Points& outer, const geometry::TriMesh& inner) {
  return l_collision_rates(outer, inner).plain;
}

double l_collision_rate(const geometry::Points& outer, const geometry::TriMesh& inner) {
  return l_collision_rates(outer, inner).ours;
}

MeanStd mean_std(const std::vector<double>& values) {
  MeanStd out;
  out.count = values.size();
  if (values.empty()) return out;
  double sum = 0.0;
  for (double v : values) sum += v;
  out.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - out.mean) * (v - out.mean);
  out.std = values.size() < 2 ? std::nan("") : std::sqrt(squares / static_cast<double>(values.size() - 1));
  return out;
}

std::string format(const MeanStd& value, int decimals) {
  char buffer[96];
  if (!std::isfinite(value.std))  // one value: no spread measured
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value.mean);
  else
    std::snprintf(buffer, sizeof buffer, "%.*f +- %.*f", decimals, value.mean, decimals, value.std);
  return buffer;
}

double sequence_mean(const std::vector<double>& per_frame) {
  if (per_frame.empty()) throw Error("sequence_mean: no frames");
  return mean_std(per_frame).mean;
}

}  // namespace layers::metrics
