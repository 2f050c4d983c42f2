// The LAYERS-H5 schema tables and garment types (see format.h).
#include "layers/data/format.h"

#include <algorithm>

#include "layers/core/error.h"

namespace layers::data {

const char* dtype_name(DType type) {
  switch (type) {
    case DType::Float32:
      return "float32";
    case DType::Float64:
      return "float64";
    case DType::Int32:
      return "int32";
    case DType::String:
      return "string";
  }
  return "?";
}

std::string ArraySpec::shape_text() const {
  std::string out = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) out += (i ? "," : "") + dims[i];
  return out + "]";
}

const std::vector<ArraySpec>& body_arrays() {
  using R = ValueRule;
  static const std::vector<ArraySpec> specs{
      {"body/faces", DType::Int32, {"Fb", "3"}, R::Indices, "Vb"},
      {"body/positions", DType::Float32, {"T", "Vb", "3"}, R::Finite, ""},
      {"body/root", DType::Float32, {"T", "3"}, R::Finite, ""},
      {"body/root_rot", DType::Float32, {"T", "4"}, R::UnitQuaternion, ""},
      {"body/joints", DType::Float32, {"T", "J", "3", "4"}, R::Finite, ""},
      {"body/joint_names", DType::String, {"J"}, R::None, ""},
      {"body/joint_parents", DType::Int32, {"J"}, R::JointParents, ""},
      {"body/skin_index", DType::Int32, {"Vb", "4"}, R::Indices, "J"},
      {"body/skin_weight", DType::Float32, {"Vb", "4"}, R::Finite, ""},
      {"body/tpose_joints", DType::Float32, {"J", "3", "4"}, R::Finite, "", /*optional=*/true},
  };
  return specs;
}

const std::vector<ArraySpec>& wind_arrays() {
  using R = ValueRule;
  static const std::vector<ArraySpec> specs{
      {"wind/rotation", DType::Float32, {"T", "4"}, R::UnitQuaternion, ""},
      {"wind/strength", DType::Float32, {"T"}, R::WindStrength, ""},
  };
  return specs;
}

const std::vector<ArraySpec>& garment_arrays() {
  using R = ValueRule;
  static const std::vector<ArraySpec> specs{
      {"faces", DType::Int32, {"F", "3"}, R::Indices, "V"},
      {"rest", DType::Float32, {"V", "3"}, R::Finite, ""},
      {"uv", DType::Float32, {"U", "2"}, R::Finite, ""},
      {"uv_faces", DType::Int32, {"F", "3"}, R::Indices, "U"},
      {"panel", DType::Int32, {"F"}, R::Indices, ""},
      {"positions", DType::Float32, {"T", "V", "3"}, R::Finite, ""},
  };
  return specs;
}

const ArraySpec& array_spec(const std::string& path) {
  for (const auto* table : {&body_arrays(), &wind_arrays(), &garment_arrays()}) {
    for (const auto& spec : *table) {
      if (spec.path == path) return spec;
    }
  }
  throw Error("layers-h5 schema: unknown array '" + path + "'");
}

const std::vector<GarmentTypeInfo>& garment_type_table() {
  static const std::vector<GarmentTypeInfo> table{
      // name          layer  self-contact  subset
      {"jacket", 1, false, ""},
      {"jacket_hood", 1, true, ""},
      {"dress", 0, true, "L"},
      {"dress_belt", 0, true, ""},
      {"jumpsuit", 0, false, "T"},
      {"tshirt", 0, false, ""},
      {"pants", 0, false, ""},
      {"skirt", 0, true, ""},
      // A user's own mesh (no template): its layer is where its outfit puts it.
      {"imported", kAnyLayer, true, ""}};
  return table;
}

const GarmentTypeInfo* find_garment_type(const std::string& type) {
  for (const GarmentTypeInfo& t : garment_type_table())
    if (type == t.name) return &t;
  return nullptr;
}

const std::vector<std::string>& garment_types() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const GarmentTypeInfo& t : garment_type_table()) out.emplace_back(t.name);
    return out;
  }();
  return names;
}

std::vector<std::string> garment_types_of_layer(int layer) {
  std::vector<std::string> out;
  for (const GarmentTypeInfo& t : garment_type_table())
    if (t.layer == layer) out.emplace_back(t.name);
  return out;
}

bool is_garment_type(const std::string& type) { return find_garment_type(type) != nullptr; }

int garment_type_layer(const std::string& type) {
  const GarmentTypeInfo* t = find_garment_type(type);
  return t ? t->layer : 0;
}

const std::vector<std::string>& sequence_reserved_attrs() {
  static const std::vector<std::string> names{"n_frames", "motion", "seed", "tags"};
  return names;
}

const std::vector<std::string>& garment_reserved_attrs() {
  static const std::vector<std::string> names{"name", "type", "layer"};
  return names;
}

}  // namespace layers::data
