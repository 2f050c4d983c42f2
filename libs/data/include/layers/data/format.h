// layers/data/format.h -- the LAYERS-H5 format, version 1, as data.
//
// Constants of the root attributes and the schema of every array a
// sequence holds (docs/format.md). The writer, the reader's index and
// the validator all check files against these tables, so the format is
// written down once. Dimension symbols in shapes:
//   T  frames            Vb body vertices    Fb body faces   J joints
//   V  garment vertices  F  garment faces    U  garment UV coordinates
// and digits are fixed sizes. Layout of one shard:
//   /                 attrs format="layers-h5", format_version=1, fps=30, units="m", up="y"
//   /seq/<id>/        attrs n_frames (int), motion (string), seed (uint64),
//                     tags (string array), and one float64 attr per body
//                     shape parameter (any other numeric attribute)
//   /seq/<id>/body/...        body arrays below
//   /seq/<id>/wind/...        wind arrays below
//   /seq/<id>/garments/<k>/   k = 0, 1, ...; attrs name, type, layer (0 inner,
//                     1 outer) and one float64 attr per garment attribute
//                     (mass, tension, ...: any other numeric attribute)
// positions (and joints) are chunked by frame: chunk [1, V, 3].
// Optional arrays (ArraySpec::optional) may be absent; when present they are
// checked like the others. body/tpose_joints is one: the joint transforms
// of the T-pose the garments' rest shapes were made in (same convention as
// body/joints; files written before it existed lack it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace layers::data {

inline constexpr const char* kFormatName = "layers-h5";
inline constexpr std::int64_t kFormatVersion = 1;
inline constexpr std::int64_t kFps = 30;
inline constexpr const char* kUnits = "m";
inline constexpr const char* kUp = "y";
inline constexpr double kMaxWindStrength = 400.0;
// Allowed deviation of a quaternion's norm from 1.
inline constexpr double kQuaternionTolerance = 1e-3;

enum class DType { Float32, Float64, Int32, String };
const char* dtype_name(DType type);

// What the validator checks of an array's values (docs/format.md "What
// readers check"): nothing (strings), finite floats, unit quaternions in
// every row of 4, wind strengths in [0, kMaxWindStrength], indices in
// [0, <dimension `below`>) (no upper bound when `below` is empty), or a
// joint hierarchy (each parent in [-1, J) and not the joint itself).
enum class ValueRule { None, Finite, UnitQuaternion, WindStrength, Indices, JointParents };

// One array of the format: its path relative to its group (the sequence
// group for body/ and wind/, a garment group for garment arrays), its
// element type, its shape in dimension symbols and the rule its values
// follow.
struct ArraySpec {
  std::string path;
  DType dtype;
  std::vector<std::string> dims;
  ValueRule values = ValueRule::None;
  std::string below;      // ValueRule::Indices: the dimension symbol bounding them
  bool optional = false;  // may be absent from a sequence
  bool per_frame() const { return !dims.empty() && dims.front() == "T"; }
  // "[T,Vb,3]"
  std::string shape_text() const;
};

const std::vector<ArraySpec>& body_arrays();     // body/faces, body/positions, ..., body/tpose_joints (optional)
const std::vector<ArraySpec>& wind_arrays();     // wind/rotation, wind/strength
const std::vector<ArraySpec>& garment_arrays();  // faces, rest, uv, uv_faces, panel, positions
// Looks an array up by path in the three tables; throws layers::Error if unknown.
const ArraySpec& array_spec(const std::string& path);

// The garment types (docs/format.md "Garment types and layers"): one
// table, read by the format's checks, the garment builder (one recipe per
// entry, libs/garment/src/garment_recipes.cpp; a test checks both name the
// same types), the generator and the scene spec. Adding a type is one
// entry here plus its recipe. The type `imported` (a user's own mesh,
// libs/import) has no recipe and either layer (kAnyLayer).
inline constexpr int kAnyLayer = -1;
struct GarmentTypeInfo {
  const char* name;
  int layer;           // 0 inner, 1 outer, kAnyLayer: where the outfit puts it
  bool self_contact;   // simulated with self-contact (it can fold onto itself: skirts, hoods)
  const char* subset;  // the paper's subset of a scene with this inner garment alone ("T", "L"), or ""
};
const std::vector<GarmentTypeInfo>& garment_type_table();
// nullptr for an unknown type.
const GarmentTypeInfo* find_garment_type(const std::string& type);
// The names, in the table's order; those of one layer (not `imported`).
const std::vector<std::string>& garment_types();
std::vector<std::string> garment_types_of_layer(int layer);
bool is_garment_type(const std::string& type);
// 1 for outer types (jacket, jacket_hood), 0 for inner ones (and unknown),
// kAnyLayer for `imported`.
int garment_type_layer(const std::string& type);

// Attribute names with a fixed meaning (never taken as shape parameters or
// garment attribute values).
const std::vector<std::string>& sequence_reserved_attrs();  // n_frames, motion, seed, tags
const std::vector<std::string>& garment_reserved_attrs();   // name, type, layer

}  // namespace layers::data
