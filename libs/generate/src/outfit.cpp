// A scene's outfit from the garment templates, as LAYERS-H5 garment
// arrays (see outfit.h).
#include "layers/generate/outfit.h"

#include "layers/core/error.h"

namespace layers::generate {
namespace {

template <class Matrix, class T>
std::vector<T> flat(const Matrix& m) {
  std::vector<T> out(static_cast<std::size_t>(m.size()));
  Eigen::Map<Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out.data(), m.rows(), m.cols()) =
      m.template cast<T>();
  return out;
}

// Visitors over sim::GarmentAttributes::visit(), so the attribute names
// are listed once (in libs/sim).
struct ToMap {
  std::map<std::string, double>& out;
  void operator()(const char* key, const double& value, const cfg::Opt& = cfg::Opt()) { out[key] = value; }
};
struct FromMap {
  const std::map<std::string, double>& in;
  const std::string& what;
  void operator()(const char* key, double& value, const cfg::Opt& = cfg::Opt()) {
    auto found = in.find(key);
    if (found == in.end()) throw InputError(what, key, "a garment attribute value", "nothing");
    value = found->second;
  }
};

}  // namespace

std::map<std::string, double> attribute_map(const sim::GarmentAttributes& attributes) {
  std::map<std::string, double> out;
  ToMap visitor{out};
  const_cast<sim::GarmentAttributes&>(attributes).visit(visitor);
  return out;
}

sim::GarmentAttributes garment_attributes(const std::map<std::string, double>& values, const std::string& what) {
  sim::GarmentAttributes attributes;
  FromMap visitor{values, what};
  attributes.visit(visitor);
  return attributes;
}

std::vector<data::GarmentData> fit_outfit(const garment::TPoseBody& body, const SceneSpec& spec,
                                          const garment::GarmentParams& params, const garment::MotionRoom* room) {
  std::vector<std::string> inner;
  std::string outer;
  for (const auto& g : spec.garments) (g.layer == 0 ? inner.push_back(g.type) : void(outer = g.type));
  const auto meshes = garment::build_outfit(inner, outer, body, params, spec.seed, room);
  std::vector<data::GarmentData> out;
  for (const auto& m : meshes) {
    const GarmentSpec* g = nullptr;
    for (const auto& candidate : spec.garments)
      if (candidate.type == m.type) g = &candidate;
    if (!g) throw Error("fit_outfit: the templates built a '" + m.type + "' the scene did not ask for");
    data::GarmentData d;
    d.name = m.type;
    d.type = m.type;
    d.layer = m.layer;
    d.attributes = attribute_map(g->attributes);
    d.faces = flat<geometry::Faces, std::int32_t>(m.faces);
    d.rest = flat<geometry::Points, float>(m.vertices);
    d.uv = flat<garment::UVs, float>(m.uv);
    d.uv_faces = flat<geometry::Faces, std::int32_t>(m.uv_faces);
    d.panel.assign(m.panel.data(), m.panel.data() + m.panel.size());
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace layers::generate
