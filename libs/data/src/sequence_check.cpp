// In-memory consistency checks of a SequenceData before it is written
// (see check_sequence in sequence.h).
#include <limits>

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

// The index ranges of a body and a garment: one set of rules for the
// writer (check_sequence) and the reader (check_static_indices).
void check_body_indices(const BodyStatic& b, std::int64_t n_vertices, std::int64_t n_joints, const std::string& base,
                        const Checker& check) {
  check.rule(check_index_range(b.faces, 0, n_vertices, 3), base + "/body/faces");
  check.rule(check_index_range(b.skin_index, 0, n_joints, 4), base + "/body/skin_index");
  check.rule(check_joint_parents(b.joint_parents), base + "/body/joint_parents");
}

void check_garment_indices(const GarmentStatic& g, std::int64_t n_vertices, std::int64_t n_uv, const std::string& base,
                           const Checker& check) {
  check.rule(check_index_range(g.faces, 0, n_vertices, 3), base + "/faces");
  check.rule(check_index_range(g.uv_faces, 0, n_uv, 3), base + "/uv_faces");
  check.rule(check_index_range(g.panel, 0, std::numeric_limits<std::int32_t>::max(), 1), base + "/panel");
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
  check_body_indices(seq.body, *dims.get("Vb"), *dims.get("J"), base, check);

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
    check_garment_indices(g, *gdims.get("V"), *gdims.get("U"), gbase, check);
  }
}

void check_static_indices(const SequenceStatic& seq, const std::string& file) {
  const Checker check(file);
  const std::string base = "/seq/" + seq.id;
  check_body_indices(seq.body, seq.body.n_vertices(), seq.body.n_joints(), base, check);
  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const GarmentStatic& g = seq.garments[k];
    check_garment_indices(g, g.n_vertices(), g.n_uv(), base + "/garments/" + std::to_string(k), check);
  }
}

}  // namespace layers::data
