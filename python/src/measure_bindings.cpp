// The evaluation's measures (metrics/measures.h, geometry/intersect.h) and
// the generator's stretch (sim/measures.h) on
// numpy arrays: the same C++ functions `layers eval` calls, not a Python
// copy. Positions are [V,3] in metres (float32; others are converted),
// faces [F,3] integer vertex indices; rates are shares 0..1, errors mm.
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "bindings.h"
#include "layers/core/error.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/topology.h"
#include "layers/metrics/measures.h"
#include "layers/sim/measures.h"

namespace layers::python {
namespace {

using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;

geometry::Points points(const Floats& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(what, "shape", "[V,3]", "an array of " + std::to_string(a.ndim()) + " dimensions" +
                                                 (a.ndim() == 2 ? " x " + std::to_string(a.shape(1)) : ""));
  const float* x = a.data();
  for (py::ssize_t i = 0; i < 3 * a.shape(0); ++i)
    if (!std::isfinite(x[i]))
      throw InputError(what, "positions", "finite coordinates", "a non-finite value in vertex " + std::to_string(i / 3));
  return Eigen::Map<const geometry::Points>(a.data(), a.shape(0), 3);
}

// Integer indices only (a float array would be truncated), each within
// int32 (a larger one would wrap onto another vertex).
geometry::Faces faces(const py::array& given, const char* what) {
  const char kind = given.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InputError(what, "faces", "integer vertex indices", std::string("an array of dtype ") +
                                                                   py::str(given.dtype()).cast<std::string>());
  const auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(given);
  if (!a || a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(what, "shape", "[F,3]", "an array of " + std::to_string(given.ndim()) + " dimensions");
  geometry::Faces out(a.shape(0), 3);
  const std::int64_t* f = a.data();
  for (py::ssize_t i = 0; i < 3 * a.shape(0); ++i) {
    if (f[i] < 0 || f[i] > std::numeric_limits<std::int32_t>::max())  // (a uint64 past 2^63 reads negative)
      throw InputError(what, "faces", "vertex indices from 0 to 2^31 - 1", std::to_string(f[i]));
    out(i / 3, i % 3) = static_cast<int>(f[i]);
  }
  return out;
}

geometry::TriMesh mesh(const Floats& v, const py::array& f, const char* what) {
  geometry::TriMesh m{points(v, what), faces(f, what)};
  geometry::validate(m, what);
  return m;
}

std::vector<geometry::TriMesh> meshes(const std::vector<std::pair<Floats, py::array>>& list, const char* what) {
  std::vector<geometry::TriMesh> out;
  for (const auto& [v, f] : list) out.push_back(mesh(v, f, what));
  return out;
}

}  // namespace

void bind_measures(py::module_& m) {
  m.def(
      "error_mm",
      [](const Floats& predicted, const Floats& truth) {
        const geometry::Points p = points(predicted, "predicted"), t = points(truth, "truth");
        if (p.rows() != t.rows())
          throw InputError("predicted", "shape", std::to_string(t.rows()) + " vertices as truth",
                           std::to_string(p.rows()));
        return metrics::euclidean_error_mm(p, t);
      },
      "mean over vertices of |predicted - truth|, in mm (the evaluation's error)", py::arg("predicted"),
      py::arg("truth"));
  m.def(
      "h_collision",
      [](const Floats& garment, const Floats& body_vertices, const py::array& body_faces) {
        return metrics::h_collision_rate(points(garment, "garment"), mesh(body_vertices, body_faces, "body"));
      },
      "H-collision: share of garment vertices behind the body (nearest-vertex test)", py::arg("garment"),
      py::arg("body_vertices"), py::arg("body_faces"));
  m.def(
      "l_collision",
      [](const Floats& outer, const Floats& inner_vertices, const py::array& inner_faces) {
        const metrics::LCollisionRates r =
            metrics::l_collision_rates(points(outer, "outer"), mesh(inner_vertices, inner_faces, "inner"));
        py::dict d;
        d["ours"] = r.ours;
        d["plain"] = r.plain;
        return d;
      },
      "L-collision of outer vertices against the inner garments (one mesh): {'ours': open-edge rule, 'plain': the "
      "paper's}",
      py::arg("outer"), py::arg("inner_vertices"), py::arg("inner_faces"));
  m.def(
      "h_crossing",
      [](const std::vector<std::pair<Floats, py::array>>& garments, const Floats& body_vertices, const py::array& body_faces) {
        return geometry::body_crossings(meshes(garments, "garment"), mesh(body_vertices, body_faces, "body"))
            .a_vertex_share();
      },
      "H-crossing: share of garment vertices on a face through the body (exact); garments: [(vertices, faces)]",
      py::arg("garments"), py::arg("body_vertices"), py::arg("body_faces"));
  m.def(
      "l_crossing",
      [](const std::vector<std::pair<Floats, py::array>>& outer, const std::vector<std::pair<Floats, py::array>>& inner) {
        return geometry::layer_crossings(meshes(outer, "outer"), meshes(inner, "inner")).a_vertex_share();
      },
      "L-crossing: share of outer vertices on a face through an inner garment (exact)", py::arg("outer"),
      py::arg("inner"));
  m.def(
      "stretch",
      [](const Floats& positions, const Floats& rest, const py::array& garment_faces) {
        const geometry::TriMesh at_rest = mesh(rest, garment_faces, "rest");
        const geometry::Points now = points(positions, "positions");
        if (now.rows() != at_rest.vertices.rows())
          throw InputError("positions", "shape", std::to_string(at_rest.vertices.rows()) + " vertices as the rest shape",
                           std::to_string(now.rows()));
        const geometry::Edges edges = geometry::unique_edges(at_rest.faces);
        return sim::max_edge_stretch(now, edges, geometry::edge_lengths(at_rest.vertices, edges));
      },
      "largest edge stretch max(0, max |l| / l0 - 1) of a garment against its rest shape (the generator's measure)",
      py::arg("positions"), py::arg("rest"), py::arg("faces"));
}

}  // namespace layers::python
