// garment.cpp -- the garment API: type names and layers, parameter checks,
// building one garment (envelope, recipe, sewing, rest-pose clearance, and
// untangling where that clearance folded a panel onto itself) and
// outfits (bottom, then top, then the outer layer over both).
#include "layers/garment/garment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "layers/core/error.h"
#include "layers/data/format.h"
#include "layers/garment/garment_recipes.h"
#include "layers/garment/garment_untangle.h"
#include "layers/geometry/normals.h"

namespace layers::garment {
namespace {

using garment::Envelope;
using garment::FitContext;
using garment::Pattern;

const char* kConfig = "garment config";

std::string joined(const std::vector<std::string>& names) {
  std::ostringstream s;
  for (std::size_t i = 0; i < names.size(); ++i) s << (i ? ", " : "") << names[i];
  return s.str();
}

void check_range(const std::vector<double>& r, const char* field) {
  if (r.size() != 2 || !(r[0] <= r[1])) {
    std::ostringstream got;
    got << "[";
    for (std::size_t i = 0; i < r.size(); ++i) got << (i ? ", " : "") << r[i];
    got << "]";
    throw InputError(kConfig, field, "a range [lo, hi] with lo <= hi", got.str());
  }
}

std::uint64_t mix(std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t x = seed + 0x9e3779b97f4a7c15ULL * (salt + 1);
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t type_salt(const std::string& type) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : type) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  return h;
}

// Moves vertices closer than `clearance` in front of the surface out
// along the normal of their nearest surface vertex, leaving alone those
// farther than `reach` from it. Returns how many moved.
int push_outside(geometry::Points& v, const geometry::Surface& surface, double clearance,
                 double reach = std::numeric_limits<double>::infinity()) {
  int moved = 0;
  for (int round = 0; round < 8; ++round) {
    int now = 0;
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      const Eigen::RowVector3f x = v.row(i);
      const auto near = surface.index().nearest(x);
      if (near.index < 0 || near.distance > reach) continue;
      const Eigen::RowVector3f n = surface.normals().row(near.index);
      const float offset = (x - surface.vertices().row(near.index)).dot(n);
      if (offset >= clearance) continue;
      v.row(i) = x + (static_cast<float>(clearance) - offset + 1e-4f) * n;
      ++now;
    }
    moved += now;
    if (now == 0) break;
  }
  return moved;
}

}  // namespace

void validate(const GarmentParams& p) {
  check_range(p.layer_clearance, "layer_clearance");
  check_range(p.ease_fitted, "ease_fitted");
  check_range(p.ease_loose, "ease_loose");
  check_range(p.ease_pants, "ease_pants");
  check_range(p.flare, "flare");
  check_range(p.top_length, "top_length");
  check_range(p.jacket_length, "jacket_length");
  check_range(p.skirt_length, "skirt_length");
  check_range(p.dress_length, "dress_length");
  check_range(p.pants_length, "pants_length");
  check_range(p.sleeve_short, "sleeve_short");
  check_range(p.sleeve_long, "sleeve_long");
  check_range(p.belt_width, "belt_width");
  check_range(p.hood_ease, "hood_ease");
  if (!(p.edge_length >= 0.004 && p.edge_length <= 0.1))
    throw InputError(kConfig, "edge_length", "a length in [0.004, 0.1] (m)", std::to_string(p.edge_length));
}

const std::vector<std::string>& garment_types() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const data::GarmentTypeInfo& t : data::garment_type_table())
      if (t.layer != data::kAnyLayer) out.emplace_back(t.name);
    return out;
  }();
  return names;
}

int garment_layer(const std::string& type) {
  const data::GarmentTypeInfo* t = data::find_garment_type(type);
  if (!t || t->layer == data::kAnyLayer)
    throw InputError(kConfig, "type", "one of " + joined(garment_types()), "'" + type + "'");
  return t->layer;
}

GarmentMesh build_garment(const std::string& type, const TPoseBody& body, const GarmentParams& params,
                          std::uint64_t seed, const std::vector<const GarmentMesh*>& under, const MotionRoom* room) {
  const int layer = garment_layer(type);
  validate(params);
  const garment::Landmarks marks = garment::measure(body);
  Envelope env(body);
  for (const GarmentMesh* g : under) env.add_garment(g->mesh(), body);
  const FitContext ctx{env, marks, std::min(0.01, params.edge_length / 2), room};

  garment::Rng rng(mix(seed, type_salt(type)));
  Pattern pattern;
  garment::Style style;
  garment::make_pattern(type, ctx, params, rng, pattern, style);
  const geometry::PointIndex skin(body.mesh.vertices);
  GarmentMesh mesh = garment::sew(pattern, params.edge_length, skin);
  mesh.type = type;
  mesh.layer = layer;
  mesh.style = std::move(style);

  // Rest-pose clearance: out of the skin, then out of what lies underneath.
  const geometry::Surface skin_surface = geometry::Surface::from_mesh(body.mesh, "T-pose body");
  std::vector<geometry::Surface> below;
  for (const GarmentMesh* g : under) below.push_back(geometry::Surface::from_mesh(g->mesh(), g->type));
  const auto push_out = [&] {
    for (int round = 0; round < 3; ++round) {
      int moved = push_outside(mesh.vertices, skin_surface, params.body_clearance);
      for (const auto& s : below) moved += push_outside(mesh.vertices, s, params.layer_gap, params.layer_reach);
      if (moved == 0) break;
    }
  };
  push_out();
  untangle(mesh.vertices, mesh.faces, mesh.boundary, push_out);
  return mesh;
}

GarmentMesh build_garment(const std::string& type, const body::Body& body, const GarmentParams& params,
                          std::uint64_t seed) {
  return build_garment(type, t_pose_body(body), params, seed);
}

std::vector<GarmentMesh> build_outfit(const std::vector<std::string>& inner, const std::string& outer,
                                      const TPoseBody& body, const GarmentParams& params, std::uint64_t seed,
                                      const MotionRoom* room) {
  for (const auto& t : inner)
    if (garment_layer(t) != 0) throw InputError(kConfig, "inner", "inner garment types", "'" + t + "'");
  if (!outer.empty() && garment_layer(outer) != 1)
    throw InputError(kConfig, "outer", "an outer garment type (layer 1 in the garment-type table)", "'" + outer + "'");
  std::vector<std::string> order = inner;
  if (inner.size() == 2) {
    const bool top_first = inner[0] == "tshirt";
    const std::string& bottom = top_first ? inner[1] : inner[0];
    const std::string& top = top_first ? inner[0] : inner[1];
    if (top != "tshirt" || (bottom != "pants" && bottom != "skirt"))
      throw InputError(kConfig, "inner", "one inner type, or tshirt with pants or skirt", "'" + joined(inner) + "'");
    order = {bottom, top};
  } else if (inner.size() != 1) {
    throw InputError(kConfig, "inner", "one inner type, or tshirt with pants or skirt",
                     std::to_string(inner.size()) + " types");
  }
  if (!outer.empty()) order.push_back(outer);
  std::vector<GarmentMesh> out;
  out.reserve(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    std::vector<const GarmentMesh*> under;
    for (const GarmentMesh& g : out) under.push_back(&g);
    out.push_back(build_garment(order[k], body, params, mix(seed, k), under, room));
  }
  return out;
}

ContactCount count_contact(const geometry::Points& vertices, const geometry::Surface& surface, double clearance,
                           double reach) {
  ContactCount c;
  c.min_offset = std::numeric_limits<double>::infinity();
  const Eigen::VectorXf offsets = surface.offsets(vertices);
  Eigen::VectorXf distance;
  surface.index().nearest_all(vertices, &distance);
  for (Eigen::Index i = 0; i < offsets.size(); ++i) {
    if (!std::isfinite(offsets[i]) || distance[i] > reach) continue;
    c.behind += offsets[i] < 0;
    c.too_close += offsets[i] < clearance;
    c.min_offset = std::min(c.min_offset, static_cast<double>(offsets[i]));
  }
  return c;
}

}  // namespace layers::garment
