// In-memory consistency checks of a SequenceData before it is written
// (see check_sequence in sequence.h).
#include <limits>
#include <type_traits>

#include "dims.h"
#include "layers/core/error.h"
#include "layers/data/format.h"
#include "layers/data/sequence.h"
#include "sequence_members.h"
#include "sequence_rules.h"

namespace layers::data {
namespace {

class Checker {
 public:
  Checker(const std::string& file) : file_(file) {}

  // Sizes of one flat array against its spec; binds its symbols.
  void size(DimBinder& dims, const ArraySpec& spec, std::size_t size, const std::string& object) const {
    std::string message;
    const auto got = dims.infer(spec, size, message);
    if (!got) throw InputError::message(file_, object, message);
    if (auto mismatch = dims.match(spec, *got, object)) throw InputError::message(file_, object, *mismatch);
  }

  void rule(const std::optional<std::string>& problem, const std::string& object) const {
    if (problem) throw InputError::message(file_, object, *problem);
  }

 private:
  const std::string& file_;
};

// Values per row of an array: its second dimension when that is a number
// (faces: 3, skin_index: 4), else 1.
std::size_t row_width(const ArraySpec& spec) {
  if (spec.dims.size() < 2 || spec.dims[1].empty()) return 1;
  for (char c : spec.dims[1])
    if (c < '0' || c > '9') return 1;
  return static_cast<std::size_t>(std::stoul(spec.dims[1]));
}

// The index rules the schema gives the static arrays of a body or of a
// garment (ValueRule::Indices below a dimension, ValueRule::JointParents),
// for the writer (check_sequence) and the reader (check_static_indices).
// `reach(spec, f)` calls f with the spec's member; `dims` holds the
// dimensions the rules name.
template <class Reach>
void check_indices(const std::vector<ArraySpec>& table, Reach&& reach, const DimBinder& dims, const std::string& base,
                   const Checker& check) {
  constexpr std::int64_t kNoMax = std::numeric_limits<std::int32_t>::max();
  for (const ArraySpec& spec : table) {
    if (spec.per_frame() || (spec.values != ValueRule::Indices && spec.values != ValueRule::JointParents)) continue;
    reach(spec, [&](const auto& values) {
      if constexpr (std::is_same_v<std::decay_t<decltype(values)>, std::vector<std::int32_t>>) {
        const std::string object = base + "/" + spec.path;
        if (spec.values == ValueRule::JointParents) return check.rule(check_joint_parents(values), object);
        const std::optional<std::int64_t> bound = spec.below.empty() ? kNoMax : dims.get(spec.below);
        if (!bound && values.empty()) return;
        if (!bound) return check.rule("expected indices below " + spec.below + ", got no " + spec.below, object);
        check.rule(check_index_range(values, 0, *bound, row_width(spec)), object);
      }
    });
  }
}

}  // namespace

void check_sequence(const SequenceData& seq, const std::string& file) {
  const Checker check(file);
  const std::string base = "/seq/" + seq.id;
  check.rule(check_sequence_id(seq.id), base);
  if (seq.n_frames < 1) throw InputError(file, base + " n_frames", "at least 1 frame", std::to_string(seq.n_frames));
  for (const auto& [name, value] : seq.shape) {
    if (name.empty() || is_reserved(name, sequence_reserved_attrs())) {
      throw InputError(file, base + " shape parameter", "a name other than n_frames, motion, seed, tags",
                       "'" + name + "'");
    }
  }

  DimBinder dims;
  dims.bind("T", seq.n_frames, base + " n_frames");
  for (const auto* table : {&body_arrays(), &wind_arrays()}) {
    for (const auto& spec : *table) {
      std::size_t n = 0;
      with_sequence_array(seq, spec, [&](const auto& v) { n = v.size(); });
      if (spec.optional && n == 0) continue;  // absent
      check.size(dims, spec, n, base + "/" + spec.path);
    }
  }
  check_indices(
      body_arrays(), [&](const ArraySpec& spec, auto&& f) { with_body_static(seq.body, spec, f); }, dims, base, check);

  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const GarmentData& g = seq.garments[k];
    const std::string gbase = base + "/garments/" + std::to_string(k);
    check.rule(check_garment_type(g.type), gbase + " type");
    check.rule(check_garment_layer(g.layer), gbase + " layer");
    for (const auto& [name, value] : g.attributes) {
      if (name.empty() || is_reserved(name, garment_reserved_attrs())) {
        throw InputError(file, gbase + " attribute", "a name other than name, type, layer", "'" + name + "'");
      }
    }
    DimBinder gdims;
    gdims.bind("T", seq.n_frames, base + " n_frames");
    for (const auto& spec : garment_arrays()) {
      std::size_t n = 0;
      with_garment_array(g, spec, [&](const auto& v) { n = v.size(); });
      check.size(gdims, spec, n, gbase + "/" + spec.path);
    }
    check_indices(
        garment_arrays(), [&](const ArraySpec& spec, auto&& f) { with_garment_static(g, spec, f); }, gdims, gbase,
        check);
  }
}

void check_static_indices(const SequenceStatic& seq, const std::string& file) {
  const Checker check(file);
  const std::string base = "/seq/" + seq.id;
  // The dimensions a read sequence's rules name, from what was read.
  DimBinder dims;
  dims.bind("Vb", seq.body.n_vertices(), base + "/body");
  dims.bind("J", seq.body.n_joints(), base + "/body");
  check_indices(
      body_arrays(), [&](const ArraySpec& spec, auto&& f) { with_body_static(seq.body, spec, f); }, dims, base, check);
  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const GarmentStatic& g = seq.garments[k];
    DimBinder gdims;
    gdims.bind("V", g.n_vertices(), base + "/garments/" + std::to_string(k));
    gdims.bind("U", g.n_uv(), base + "/garments/" + std::to_string(k));
    check_indices(
        garment_arrays(), [&](const ArraySpec& spec, auto&& f) { with_garment_static(g, spec, f); }, gdims,
        base + "/garments/" + std::to_string(k), check);
  }
}

}  // namespace layers::data
