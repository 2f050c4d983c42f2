// A user's body as a mesh sequence (a .pc2 cache with its OBJ, or a folder
// of OBJ frames) with its one-joint rig, and the body checks every
// imported body passes (see body_import.h, body_checks.h).
#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "body_checks.h"
#include "file_names.h"
#include "layers/core/error.h"
#include "layers/data/obj.h"
#include "layers/data/pc2.h"
#include "layers/import/body_import.h"

namespace layers::import {
namespace {

namespace fs = std::filesystem;

geometry::TriMesh read_obj_mesh(const std::string& path, double scale) {
  if (!fs::is_regular_file(path)) throw InputError(path, "", "an OBJ file", "no such file");
  const data::ObjMesh obj = data::read_obj(path);
  geometry::TriMesh m;
  m.vertices.resize(static_cast<Eigen::Index>(obj.positions.size() / 3), 3);
  for (std::size_t i = 0; i < obj.positions.size(); ++i)  // row-major, as the file lists them
    m.vertices.data()[i] = static_cast<float>(obj.positions[i] * scale);
  m.faces.resize(static_cast<Eigen::Index>(obj.faces.size() / 3), 3);
  std::copy(obj.faces.begin(), obj.faces.end(), m.faces.data());
  if (m.faces.rows() == 0) throw InputError(path, "", "a mesh with triangles", "no triangle in the file");
  return m;
}

// Name order with digit runs compared as numbers ("f2.obj" before "f10.obj").
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      const std::string x = a.substr(i, ei - i), y = b.substr(j, ej - j);
      const std::string xs = x.substr(std::min(x.find_first_not_of('0'), x.size())),
                        ys = y.substr(std::min(y.find_first_not_of('0'), y.size()));
      if (xs.size() != ys.size()) return xs.size() < ys.size();
      if (xs != ys) return xs < ys;
      i = ei, j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

void check_frame(const geometry::Points& v, const geometry::TriMesh& mesh, const std::string& file,
                 const std::string& what) {
  if (v.rows() != mesh.num_vertices())
    throw InputError(file, what, std::to_string(mesh.num_vertices()) + " vertices (the body mesh's)",
                     std::to_string(v.rows()));
  if (!v.allFinite()) throw InputError(file, what, "finite positions", "a non-finite value");
}

}  // namespace

void check_body_height(const geometry::TriMesh& mesh, const std::string& file) {
  if (!mesh.vertices.allFinite()) throw InputError(file, "vertices", "finite positions", "a non-finite value");
  const double height = mesh.vertices.col(1).maxCoeff() - mesh.vertices.col(1).minCoeff();
  if (!(height >= kMinBodyHeight && height <= kMaxBodyHeight))
    throw InputError(file, "height",
                     "a body " + std::to_string(kMinBodyHeight).substr(0, 3) + "-" +
                         std::to_string(kMaxBodyHeight).substr(0, 3) +
                         " m tall along y (set the file's scale to metres)",
                     std::to_string(height));
}

bool is_mesh_sequence(const std::string& path) { return fs::is_directory(path) || lower_extension(path) == ".pc2"; }

ImportedBody import_mesh_sequence(const std::string& path, const std::string& mesh, double scale) {
  if (!(scale > 0) || !std::isfinite(scale))
    throw InputError(path, "scale", "a positive factor to metres", std::to_string(scale));
  ImportedBody out;
  out.file = path;
  if (fs::is_directory(path)) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file() && lower_extension(e.path().string()) == ".obj") files.push_back(e.path().string());
    std::sort(files.begin(), files.end(), natural_less);
    if (files.empty()) throw InputError(path, "", "a folder of OBJ frames", "no .obj file");
    out.rest = read_obj_mesh(mesh.empty() ? files.front() : mesh, scale);
    for (const std::string& f : files) {
      const geometry::TriMesh frame = read_obj_mesh(f, scale);
      check_frame(frame.vertices, out.rest, f, "vertices");
      if (frame.faces.rows() != out.rest.faces.rows() || frame.faces != out.rest.faces)
        throw InputError(f, "faces", "the faces of " + (mesh.empty() ? files.front() : mesh), "other faces");
      out.vertices.push_back(frame.vertices);
    }
  } else if (lower_extension(path) == ".pc2") {
    if (!fs::is_regular_file(path)) throw InputError(path, "", "a POINTCACHE2 file", "no such file");
    if (mesh.empty()) throw InputError(path, "mesh", "an OBJ with the cache's faces and rest pose", "none given");
    out.rest = read_obj_mesh(mesh, scale);
    const data::Pc2Cache cache = data::read_pc2(path);
    if (cache.header.sample_rate != 1.0f)
      throw InputError(path, "sample rate", "1 (one sample per frame, at 30 fps)",
                       std::to_string(cache.header.sample_rate));
    if (cache.header.n_points != out.rest.num_vertices())
      throw InputError(path, "points", std::to_string(out.rest.num_vertices()) + " (the vertices of " + mesh + ")",
                       std::to_string(cache.header.n_points));
    const std::size_t per = static_cast<std::size_t>(cache.header.n_points) * 3;
    for (int s = 0; s < cache.header.n_samples; ++s) {
      geometry::Points v(cache.header.n_points, 3);
      for (std::size_t i = 0; i < per; ++i)
        v(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) =
            static_cast<float>(cache.positions[s * per + i] * scale);
      check_frame(v, out.rest, path, "sample " + std::to_string(s));
      out.vertices.push_back(std::move(v));
    }
    if (out.vertices.empty()) throw InputError(path, "samples", "at least one frame", "0");
  } else {
    throw InputError(path, "", "a .pc2 cache or a folder of OBJ frames", "'" + path + "'");
  }
  check_body_height(out.rest, mesh.empty() ? path : mesh);

  // One joint carrying every vertex, at the rest pose's centroid; per frame
  // the rigid motion closest to the vertices'.
  const Eigen::Matrix3Xd rest = out.rest.vertices.cast<double>().transpose();
  const Eigen::Vector3d centre = rest.rowwise().mean();
  out.joint_names = {"Root"};
  out.parents = {-1};
  out.joint_rest = {centre};
  const Eigen::Index nv = out.rest.num_vertices();
  out.skin_index = decltype(out.skin_index)::Zero(nv, 4);
  out.skin_weight = decltype(out.skin_weight)::Zero(nv, 4);
  out.skin_weight.col(0).setOnes();
  for (const geometry::Points& v : out.vertices) {
    const Eigen::Isometry3d fit(Eigen::umeyama(rest, Eigen::Matrix3Xd(v.cast<double>().transpose()), false));
    BodyFrame frame;
    frame.rotation.push_back(Eigen::Quaterniond(fit.rotation()).normalized());
    frame.position.push_back(fit * centre);
    out.frames.push_back(std::move(frame));
  }
  return out;
}

}  // namespace layers::import
