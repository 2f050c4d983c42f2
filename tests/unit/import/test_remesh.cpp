// Remeshing a user's garment (import/remesh.h) on a tube made here whose
// top rings are millimetres apart (as a collar's edges are in real garment
// files), with a UV seam: the edges come to the target length, the open
// borders stay where they were, every vertex stays on the surface, the
// UVs are the surface's (two at the seam), the result passes the cloth
// checks; a side file asks for it by `remesh`.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/geometry/topology.h"
#include "layers/import/garment_file.h"
#include "layers/import/mesh_checks.h"
#include "layers/import/remesh.h"
#include "temp_dir.h"

namespace layers::import {
namespace {

constexpr double kRadius = 0.15, kHeight = 0.4;
constexpr int kColumns = 96;

// Ring heights: 2 mm apart in the top 10 mm, 25 mm below.
std::vector<double> ring_heights() {
  std::vector<double> y;
  for (double h = 0.0; h < kHeight - 0.01 - 1e-9; h += 0.025) y.push_back(h);
  for (double h = kHeight - 0.01; h <= kHeight + 1e-9; h += 0.002) y.push_back(h);
  return y;
}

// The tube as an ImportedMesh: outward faces, UVs u = angle x radius (the
// seam at angle 0 / 2 pi has two UVs), v = height.
ImportedMesh fine_collar_tube() {
  const std::vector<double> y = ring_heights();
  const int rows = static_cast<int>(y.size());
  ImportedMesh m;
  m.file = "tube.obj";
  m.mesh.vertices.resize(rows * kColumns, 3);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      const double a = 2 * M_PI * c / kColumns;
      m.mesh.vertices.row(r * kColumns + c) << static_cast<float>(kRadius * std::sin(a)), static_cast<float>(y[r]),
          static_cast<float>(kRadius * std::cos(a));
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c <= kColumns; ++c)
      m.uv.insert(m.uv.end(), {static_cast<float>(2 * M_PI * kRadius * c / kColumns), static_cast<float>(y[r])});
  std::vector<int> faces;
  const auto v = [&](int r, int c) { return r * kColumns + c % kColumns; };
  const auto t = [&](int r, int c) { return r * (kColumns + 1) + c; };
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      for (const auto& [rr, cc] : {std::pair{r, c}, {r, c + 1}, {r + 1, c + 1}, {r, c}, {r + 1, c + 1}, {r + 1, c}}) {
        faces.push_back(v(rr, cc));
        m.uv_faces.push_back(t(rr, cc));
      }
    }
  m.mesh.faces = Eigen::Map<geometry::Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
  m.file_vertices = static_cast<int>(m.mesh.vertices.rows());
  return m;
}

TEST(Remesh, MillimetreEdgesComeToTheTargetOnTheSameSurface) {
  const ImportedMesh in = fine_collar_tube();
  RemeshReport r;
  const ImportedMesh out = remesh(in, 0.025, 5, &r);
  EXPECT_LT(r.shortest_before, 0.0025);
  EXPECT_GT(r.shortest_after, 0.008) << "no edge far below the target";
  EXPECT_GT(r.mean_after, 0.6 * 0.025);
  EXPECT_LT(r.mean_after, 1.4 * 0.025);
  EXPECT_LT(r.faces_after, r.faces_before);
  EXPECT_NO_THROW(check_cloth_mesh(out.mesh, "tube.obj"));
  // On the tube (the polygon's chords sag by r (1 - cos(pi / 96)) < 0.1 mm),
  // within its height.
  for (Eigen::Index i = 0; i < out.mesh.vertices.rows(); ++i) {
    const double radius = std::hypot(out.mesh.vertices(i, 0), out.mesh.vertices(i, 2));
    EXPECT_NEAR(radius, kRadius, 2e-4) << "vertex " << i << " at y " << out.mesh.vertices(i, 1);
    EXPECT_GE(out.mesh.vertices(i, 1), -1e-6);
    EXPECT_LE(out.mesh.vertices(i, 1), kHeight + 1e-6);
  }
  // The two open borders stay at the bottom and the top.
  const geometry::Edges edges = geometry::unique_edges(out.mesh.faces);
  std::vector<int> uses(static_cast<std::size_t>(edges.rows()), 0);
  std::map<std::pair<int, int>, int> at;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) at[{edges(e, 0), edges(e, 1)}] = static_cast<int>(e);
  for (Eigen::Index f = 0; f < out.mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = out.mesh.faces(f, k), b = out.mesh.faces(f, (k + 1) % 3);
      ++uses[static_cast<std::size_t>(at.at({std::min(a, b), std::max(a, b)}))];
    }
  int border = 0;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    if (uses[static_cast<std::size_t>(e)] != 1) continue;
    ++border;
    for (int k = 0; k < 2; ++k) {
      const double y = out.mesh.vertices(edges(e, k), 1);
      EXPECT_TRUE(std::abs(y) < 1e-5 || std::abs(y - kHeight) < 1e-5) << "border vertex at y " << y;
    }
  }
  EXPECT_GT(border, 2 * 30);  // two loops of about 2 pi r / 25 mm edges each
  // UVs: v is the height, u the angle times the radius, from 0 to 2 pi r
  // (a face beside the seam takes its side's value there).
  ASSERT_EQ(out.uv_faces.size(), static_cast<std::size_t>(3 * out.mesh.faces.rows()));
  for (Eigen::Index f = 0; f < out.mesh.faces.rows(); ++f) {
    double u_min = 1e9, u_max = -1e9;
    for (int k = 0; k < 3; ++k) {
      const int v = out.mesh.faces(f, k), t = out.uv_faces[static_cast<std::size_t>(3 * f + k)];
      const float u = out.uv[static_cast<std::size_t>(2 * t)], w = out.uv[static_cast<std::size_t>(2 * t + 1)];
      EXPECT_NEAR(w, out.mesh.vertices(v, 1), 1e-4) << f;
      double a = std::atan2(out.mesh.vertices(v, 0), out.mesh.vertices(v, 2));
      if (a < 0) a += 2 * M_PI;
      const double expected = a * kRadius, period = 2 * M_PI * kRadius;
      const double off =
          std::min({std::abs(u - expected), std::abs(u - expected - period), std::abs(u - expected + period)});
      EXPECT_LT(off, 1e-3) << f;
      u_min = std::min<double>(u_min, u), u_max = std::max<double>(u_max, u);
    }
    EXPECT_LT(u_max - u_min, 0.1) << "face " << f << " spans the seam in UV";
  }
}

TEST(Remesh, ANonManifoldMeshIsOneLine) {
  ImportedMesh m;
  m.file = "fan.obj";
  m.mesh.vertices.resize(5, 3);
  m.mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0;
  m.mesh.faces.resize(3, 3);
  m.mesh.faces << 0, 1, 2, 0, 1, 3, 0, 1, 4;  // three faces on edge 0-1
  const std::string said = test::error_of<InputError>([&] { remesh(m, 0.1); });
  EXPECT_NE(said.find("fan.obj: remesh: expected a manifold surface"), std::string::npos) << said;
  EXPECT_NE(test::error_of<InputError>([&] { remesh(fine_collar_tube(), 0.0); }).find("a positive target"),
            std::string::npos);
}

TEST(Remesh, TheSideFileAsksForIt) {
  test::TempDir dir("remesh");
  const std::string mesh = dir.write("shirt.obj", "v 0 0 0\n");
  EXPECT_EQ(read_garment_file("file:" + mesh).remesh, 0.0);
  dir.write("shirt.yaml", "remesh: fit\n");
  EXPECT_EQ(read_garment_file("file:" + mesh).remesh, kRemeshToFit);
  dir.write("shirt.yaml", "remesh: 0.02\n");
  EXPECT_EQ(read_garment_file("file:" + mesh).remesh, 0.02);
  dir.write("shirt.yaml", "remesh: off\n");
  EXPECT_EQ(read_garment_file("file:" + mesh).remesh, 0.0);
  dir.write("shirt.yaml", "remesh: 2\n");
  const std::string said = test::error_of<InputError>([&] { read_garment_file("file:" + mesh); });
  EXPECT_NE(said.find("shirt.yaml: remesh: expected fit, off, or an edge length in metres"), std::string::npos) << said;
}

// The tube written as an OBJ, its positions times `scale`.
void write_tube(const std::string& path, float scale) {
  const ImportedMesh m = fine_collar_tube();
  std::ofstream out(path);
  for (int v = 0; v < m.mesh.num_vertices(); ++v)
    out << "v " << scale * m.mesh.vertices(v, 0) << ' ' << scale * m.mesh.vertices(v, 1) << ' '
        << scale * m.mesh.vertices(v, 2) << '\n';
  for (int f = 0; f < m.mesh.num_faces(); ++f)
    out << "f " << m.mesh.faces(f, 0) + 1 << ' ' << m.mesh.faces(f, 1) + 1 << ' ' << m.mesh.faces(f, 2) + 1 << '\n';
}

TEST(Remesh, AFileIsRemeshedOnceUntilItChanges) {
  test::TempDir dir("remesh");
  const std::string mesh = dir.file("collar.obj");
  write_tube(mesh, 1.0f);
  dir.write("collar.yaml", "remesh: 0.025\n");
  const GarmentFile file = read_garment_file("file:" + mesh);
  const ImportedMesh first = read_garment_mesh(file, 0.025);
  const ImportedMesh again = read_garment_mesh(file, 0.025);
  EXPECT_EQ(again.mesh.vertices, first.mesh.vertices);
  EXPECT_EQ(again.mesh.faces, first.mesh.faces);
  // The file changed (a wider tube): read and remeshed anew, not the first mesh.
  write_tube(mesh, 1.2f);
  const ImportedMesh wider = read_garment_mesh(read_garment_file("file:" + mesh), 0.025);
  EXPECT_NEAR(wider.mesh.vertices.col(0).maxCoeff(), 1.2f * first.mesh.vertices.col(0).maxCoeff(), 1e-3);
  // Another target: remeshed again.
  dir.write("collar.yaml", "remesh: 0.05\n");
  const ImportedMesh coarser = read_garment_mesh(read_garment_file("file:" + mesh), 0.025);
  EXPECT_LT(coarser.mesh.num_faces(), wider.mesh.num_faces());
}

}  // namespace
}  // namespace layers::import
