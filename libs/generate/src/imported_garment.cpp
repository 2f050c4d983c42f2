// Users' garment meshes as a scene's outfit (see imported_garment.h).
#include "layers/generate/imported_garment.h"

#include <array>
#include <cmath>
#include <sstream>

#include "layers/core/checksum.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/generate/outfit.h"
#include "layers/generate/simulate.h"
#include "layers/geometry/penetration.h"
#include "layers/import/garment_file.h"
#include "layers/import/mesh_checks.h"
#include "layers/import/mesh_import.h"

namespace layers::generate {
namespace {

const char* part_name(garment::Part p) {
  static const char* names[] = {"torso",      "neck",     "head",      "left arm",  "right arm", "left hand",
                                "right hand", "left leg", "right leg", "left foot", "right foot"};
  return names[static_cast<int>(p)];
}

// "<n> vertices inside <what>, most near the <part>" or "" when none.
std::string inside_body(const geometry::Points& points, const garment::TPoseBody& body,
                        const geometry::Surface& surface) {
  const auto behind = surface.behind(points);
  std::array<int, 11> by_part{};
  int count = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!behind(i)) continue;
    ++count;
    const int nearest = surface.index().nearest(points.row(i)).index;
    if (nearest >= 0) ++by_part[static_cast<int>(body.parts[static_cast<std::size_t>(nearest)])];
  }
  if (count == 0) return "";
  int most = 0;
  for (int p = 1; p < 11; ++p)
    if (by_part[p] > by_part[most]) most = p;
  return std::to_string(count) + " of its " + std::to_string(points.rows()) +
         " vertices inside the body, most near the " + part_name(static_cast<garment::Part>(most));
}

}  // namespace

void resolve_garment_files(GeneratorConfig& config) {
  config.garments.files.clear();
  std::vector<std::string> entries;
  for (const OutfitConfig& o : config.garments.outfits) {
    entries.insert(entries.end(), o.inner.begin(), o.inner.end());
    entries.push_back(o.outer);
  }
  for (const std::string& entry : entries) {
    if (!import::is_garment_file(entry)) continue;
    const import::GarmentFile file = import::read_garment_file(entry);
    import::read_garment_mesh(file, config.garments.fit.edge_length);  // reads, remeshes and checks
    config.garments.files[file.mesh] = content_hash(read_text_file(file.mesh));
    if (file.side_file.empty()) continue;
    config.garments.files[file.side_file] = content_hash(read_text_file(file.side_file));
    const cfg::Node side = cfg::load_file(file.side_file);
    if (const cfg::Node* attributes = side.find("attributes"))
      cfg::read<sim::GarmentAttributes>(*attributes, "attributes");  // names and ranges
  }
}

bool has_imported_garments(const SceneSpec& spec) {
  for (const GarmentSpec& g : spec.garments)
    if (!g.source.empty()) return true;
  return false;
}

void cylindrical_uv(const geometry::TriMesh& mesh, const Eigen::Vector3d& axis, std::vector<float>& uv,
                    std::vector<std::int32_t>& uv_faces) {
  const Eigen::Index n = mesh.vertices.rows();
  std::vector<double> angle(static_cast<std::size_t>(n));
  double radius = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dx = mesh.vertices(i, 0) - axis.x(), dz = mesh.vertices(i, 2) - axis.z();
    angle[static_cast<std::size_t>(i)] = std::atan2(dx, dz);  // 0 at the front (+z)
    radius += std::hypot(dx, dz) / static_cast<double>(n);
  }
  uv.clear();
  uv_faces.clear();
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    double a[3];
    for (int c = 0; c < 3; ++c) a[c] = angle[static_cast<std::size_t>(mesh.faces(f, c))];
    // A face across the seam at the back: its negative angles go once round.
    const double lo = std::min({a[0], a[1], a[2]}), hi = std::max({a[0], a[1], a[2]});
    for (int c = 0; c < 3; ++c) {
      if (hi - lo > M_PI && a[c] < 0) a[c] += 2 * M_PI;
      uv.push_back(static_cast<float>(a[c] * radius));
      uv.push_back(mesh.vertices(mesh.faces(f, c), 1));
      uv_faces.push_back(static_cast<std::int32_t>(3 * f + c));
    }
  }
}

std::vector<data::GarmentData> imported_outfit(const garment::TPoseBody& body, const SceneSpec& spec,
                                               double layer_reach, double edge_length) {
  const Eigen::Vector3d axis(body.joints.at(0).x(), body.joints.at(0).y(), body.joints.at(0).z());
  std::vector<data::GarmentData> out;
  const geometry::Surface body_surface = geometry::Surface::from_mesh(body.mesh, "T-pose body");  // once
  std::vector<geometry::TriMesh> inner;
  for (const GarmentSpec& g : spec.garments) {
    if (g.source.empty())
      throw Error("imported_outfit: garment '" + g.type + "' of scene " + spec.id + " is a template, not a file");
    const import::GarmentFile file = import::read_garment_file(g.source);
    import::ImportedMesh m = import::read_garment_mesh(file, edge_length);
    const std::string inside = inside_body(m.mesh.vertices, body, body_surface);
    if (!inside.empty())
      throw InputError(file.mesh, "vertices", "a garment outside the body in its T-pose (frame 0)", inside);
    if (g.layer == 1 && !inner.empty()) {
      const geometry::Surface under = geometry::Surface::from_mesh(geometry::concatenate(inner), "inner garments",
                                                                   geometry::Surface::OpenEdges::Ignore);
      Eigen::VectorXf distance;
      under.index().nearest_all(m.mesh.vertices, &distance);
      const auto behind_all = under.behind(m.mesh.vertices);
      Eigen::Index behind = 0, near = 0;
      for (Eigen::Index i = 0; i < m.mesh.vertices.rows(); ++i) {
        if (!(distance(i) <= layer_reach)) continue;
        ++near;
        behind += behind_all(i);
      }
      // Inside rather than around: most of the outer garment's vertices
      // near the inner ones are behind them. (A few behind is the test's
      // noise far from the surface; faces that cross are refused with the
      // scene, SceneSimulation.)
      if (2 * behind > near)
        throw InputError(
            file.mesh, "vertices", "an outer garment that encloses the inner ones",
            std::to_string(behind) + " of its " + std::to_string(near) + " vertices near them inside an inner garment");
    }
    data::GarmentData d;
    d.name = file.name;
    const auto taken = [&](const std::string& name) {
      for (const data::GarmentData& other : out)
        if (other.name == name) return true;
      return false;
    };
    for (int k = 2; taken(d.name); ++k) d.name = file.name + "_" + std::to_string(k);
    d.type = "imported";
    d.layer = g.layer;
    d.attributes = attribute_map(g.attributes);
    for (const auto& [key, value] : file.attributes) {
      if (d.attributes.count(key) == 0) {
        std::string known;
        for (const auto& kv : d.attributes) known += (known.empty() ? "" : ", ") + kv.first;
        throw InputError(file.side_file, "attributes." + key, "one of " + known, "'" + key + "'");
      }
      d.attributes[key] = value;
    }
    d.attributes[kSelfContact] = file.self_contact ? 1.0 : 0.0;  // read back by garment_self_contact
    const geometry::TriMesh& mesh = m.mesh;
    d.rest.assign(mesh.vertices.data(), mesh.vertices.data() + mesh.vertices.size());
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
      for (int c = 0; c < 3; ++c) d.faces.push_back(mesh.faces(f, c));
    if (!m.uv.empty()) {
      d.uv = m.uv;
      d.uv_faces = m.uv_faces;
    } else {
      cylindrical_uv(mesh, axis, d.uv, d.uv_faces);
    }
    d.panel.assign(static_cast<std::size_t>(mesh.faces.rows()), 0);
    if (g.layer == 0) inner.push_back(mesh);
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace layers::generate
