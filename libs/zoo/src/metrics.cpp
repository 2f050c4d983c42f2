// Evaluation metrics (see metrics.h).
#include "layers/zoo/metrics.h"

#include <cmath>
#include <cstdio>

#include "layers/core/error.h"

namespace layers::zoo {

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

namespace {

// Share of outer vertices behind the inner garment; `open` says whether a
// nearest inner vertex on an open edge gives a verdict (the two L rules).
double layer_behind_share(const geometry::Points& outer, const geometry::TriMesh& inner,
                          geometry::Surface::OpenEdges open) {
  return behind_share(outer, geometry::Surface::from_mesh(inner, "inner garment", open));
}

}  // namespace

double l_collision_plain_rate(const geometry::Points& outer, const geometry::TriMesh& inner) {
  return layer_behind_share(outer, inner, geometry::Surface::OpenEdges::Count);
}

double l_collision_rate(const geometry::Points& outer, const geometry::TriMesh& inner) {
  return layer_behind_share(outer, inner, geometry::Surface::OpenEdges::Ignore);
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
  out.std = std::sqrt(squares / static_cast<double>(values.size()));
  return out;
}

std::string format(const MeanStd& value, int decimals) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%.*f +- %.*f", decimals, value.mean, decimals, value.std);
  return buffer;
}

double sequence_mean(const std::vector<double>& per_frame) {
  if (per_frame.empty()) throw Error("sequence_mean: no frames");
  return mean_std(per_frame).mean;
}

}  // namespace layers::zoo
