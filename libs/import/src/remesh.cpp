// Isotropic remeshing of a garment mesh with its borders, seams and UVs
// kept (see remesh.h). CGAL is used here only.
#include "layers/import/remesh.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "layers/core/error.h"
#include "layers/geometry/topology.h"

namespace layers::import {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;
using EdgeIndex = Mesh::Edge_index;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_cgal(const geometry::TriMesh& m, const std::string& file) {
  Mesh out;
  std::vector<VertexIndex> v(static_cast<std::size_t>(m.vertices.rows()));
  for (Eigen::Index i = 0; i < m.vertices.rows(); ++i)
    v[static_cast<std::size_t>(i)] = out.add_vertex(Point(m.vertices(i, 0), m.vertices(i, 1), m.vertices(i, 2)));
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const FaceIndex added =
        out.add_face(v[static_cast<std::size_t>(m.faces(f, 0))], v[static_cast<std::size_t>(m.faces(f, 1))],
                     v[static_cast<std::size_t>(m.faces(f, 2))]);
    if (added == Mesh::null_face())
      throw InputError(file, "remesh",
                       "a manifold surface to remesh (each edge in at most two faces, one fan of faces per vertex)",
                       "face " + std::to_string(f) + " cannot be joined to its neighbours");
  }
  return out;
}

// Barycentric coordinates of p's projection onto triangle (a, b, c).
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0)) return {1.0, 0.0, 0.0};
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return {1.0 - v - w, v, w};
}

}  // namespace

void edge_lengths(const geometry::TriMesh& mesh, double& shortest, double& mean) {
  const geometry::Edges edges = geometry::unique_edges(mesh.faces);
  shortest = edges.rows() ? 1e30 : 0.0;
  double sum = 0.0;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const double l = (mesh.vertices.row(edges(e, 0)) - mesh.vertices.row(edges(e, 1))).cast<double>().norm();
    shortest = std::min(shortest, l);
    sum += l;
  }
  mean = edges.rows() ? sum / static_cast<double>(edges.rows()) : 0.0;
}

ImportedMesh remesh(const ImportedMesh& in, double edge_length, int iterations, RemeshReport* report) {
  if (!(edge_length > 0) || !std::isfinite(edge_length))
    throw InputError(in.file, "remesh", "a positive target edge length (m)", std::to_string(edge_length));
  const geometry::TriMesh& src = in.mesh;
  const bool has_uv = !in.uv.empty();
  Mesh mesh = to_cgal(src, in.file);
  // Constrained: open borders, and the edges where the two faces beside
  // them use different UVs for an end (a seam of the UV layout).
  auto constrained = mesh.add_property_map<EdgeIndex, bool>("e:constrained", false).first;
  {
    std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> corners;  // edge -> (uv of lo, uv of hi) per face
    if (has_uv) {
      for (Eigen::Index f = 0; f < src.faces.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
          const int a = src.faces(f, k), b = src.faces(f, (k + 1) % 3);
          const int ua = in.uv_faces[static_cast<std::size_t>(3 * f + k)];
          const int ub = in.uv_faces[static_cast<std::size_t>(3 * f + (k + 1) % 3)];
          corners[{std::min(a, b), std::max(a, b)}].emplace_back(a < b ? ua : ub, a < b ? ub : ua);
        }
    }
    for (EdgeIndex e : mesh.edges()) {
      if (mesh.is_border(e)) {
        constrained[e] = true;
        continue;
      }
      if (!has_uv) continue;
      const int a = static_cast<int>(mesh.vertex(e, 0)), b = static_cast<int>(mesh.vertex(e, 1));
      const auto& c = corners[{std::min(a, b), std::max(a, b)}];
      constrained[e] = c.size() == 2 && c[0] != c[1];
    }
  }
  // The original surface, for the UVs.
  const Mesh original = mesh;
  Tree tree(faces(original).first, faces(original).second, original);
  tree.accelerate_distance_queries();

  PMP::isotropic_remeshing(faces(mesh), edge_length, mesh,
                           CGAL::parameters::number_of_iterations(iterations)
                               .edge_is_constrained_map(constrained)
                               .protect_constraints(false)
                               .relax_constraints(false));
  mesh.collect_garbage();

  ImportedMesh out;
  out.file = in.file;
  out.file_vertices = in.file_vertices;
  std::map<VertexIndex, int> index;
  out.mesh.vertices.resize(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (VertexIndex v : mesh.vertices()) {
    const int i = static_cast<int>(index.size());
    index[v] = i;
    const Point& p = mesh.point(v);
    out.mesh.vertices.row(i) << static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z());
  }
  out.mesh.faces.resize(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  std::map<std::pair<float, float>, int> uv_index;
  int row = 0;
  for (FaceIndex f : mesh.faces()) {
    std::array<VertexIndex, 3> corner{};
    int k = 0;
    for (VertexIndex v : vertices_around_face(mesh.halfedge(f), mesh)) corner[static_cast<std::size_t>(k++)] = v;
    for (int c = 0; c < 3; ++c) out.mesh.faces(row, c) = index.at(corner[static_cast<std::size_t>(c)]);
    if (has_uv) {
      // The original face this one lies on: the one nearest its centroid.
      const Point centroid = CGAL::centroid(mesh.point(corner[0]), mesh.point(corner[1]), mesh.point(corner[2]));
      const FaceIndex under = tree.closest_point_and_primitive(centroid).second;
      std::array<Eigen::Vector3d, 3> at{};
      std::array<int, 3> uv_of{};
      int j = 0;
      for (auto h : halfedges_around_face(original.halfedge(under), original)) {
        const Point& p = original.point(original.target(h));
        at[static_cast<std::size_t>(j)] = {p.x(), p.y(), p.z()};
        // The UV index of that corner in the source face.
        const int fi = static_cast<int>(under), vi = static_cast<int>(original.target(h));
        int uv = -1;
        for (int c = 0; c < 3; ++c)
          if (src.faces(fi, c) == vi) uv = in.uv_faces[static_cast<std::size_t>(3 * fi + c)];
        uv_of[static_cast<std::size_t>(j++)] = uv;
      }
      for (int c = 0; c < 3; ++c) {
        const Point& p = mesh.point(corner[static_cast<std::size_t>(c)]);
        const Eigen::Vector3d w = barycentric({p.x(), p.y(), p.z()}, at[0], at[1], at[2]);
        float uv[2] = {0.0f, 0.0f};
        for (int d = 0; d < 2; ++d)
          for (int q = 0; q < 3; ++q)
            uv[d] +=
                static_cast<float>(w[q]) * in.uv[static_cast<std::size_t>(2 * uv_of[static_cast<std::size_t>(q)] + d)];
        const auto [it, fresh] = uv_index.emplace(std::make_pair(uv[0], uv[1]), static_cast<int>(uv_index.size()));
        if (fresh) out.uv.insert(out.uv.end(), {uv[0], uv[1]});
        out.uv_faces.push_back(it->second);
      }
    }
    ++row;
  }
  if (report) {
    report->faces_before = static_cast<int>(src.faces.rows());
    report->faces_after = static_cast<int>(out.mesh.faces.rows());
    edge_lengths(src, report->shortest_before, report->mean_before);
    edge_lengths(out.mesh, report->shortest_after, report->mean_after);
  }
  return out;
}

}  // namespace layers::import
