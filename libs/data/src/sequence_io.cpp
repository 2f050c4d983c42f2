// Reading and writing the arrays of a sequence group (see sequence_io.h).
#include "sequence_io.h"

#include "dims.h"
#include "h5_io.h"
#include "layers/data/format.h"
#include "sequence_members.h"

#include <type_traits>

namespace layers::data {
namespace {

DimBinder sequence_dims(const SequenceInfo& info) {
  DimBinder dims;
  dims.bind("T", info.n_frames, "index");
  dims.bind("Vb", info.body_vertices, "index");
  dims.bind("Fb", info.body_faces, "index");
  dims.bind("J", info.n_joints, "index");
  return dims;
}

DimBinder garment_dims(const SequenceInfo& info, const GarmentInfo& g) {
  DimBinder dims;
  dims.bind("T", info.n_frames, "index");
  dims.bind("V", g.n_vertices, "index");
  dims.bind("F", g.n_faces, "index");
  dims.bind("U", g.n_uv, "index");
  return dims;
}

h5::Dims to_dims(const std::vector<std::uint64_t>& d) { return h5::Dims(d.begin(), d.end()); }

// Reads arrays of one group (the sequence group or a garment group)
// whose object paths start with `base`.
class GroupReader {
 public:
  GroupReader(const std::string& file, const H5::Group& loc, std::string base, DimBinder dims)
      : file_(file), loc_(loc), base_(std::move(base)), dims_(std::move(dims)) {}

  template <class T>
  std::vector<T> all(const std::string& path) const {
    return h5::read_all<T>(where(path), loc_, path, to_dims(dims_.resolve(array_spec(path))));
  }
  std::vector<std::string> strings(const std::string& path) const {
    return h5::read_strings(where(path), loc_, path, to_dims(dims_.resolve(array_spec(path))));
  }
  // The whole array `spec` into `out` (float, int32 or string).
  template <class T>
  void read(const ArraySpec& spec, std::vector<T>& out) const {
    if constexpr (std::is_same_v<T, std::string>)
      out = strings(spec.path);
    else
      out = all<T>(spec.path);
  }
  std::vector<float> frames(const std::string& path, std::int64_t first, std::int64_t count) const {
    return h5::read_rows<float>(where(path), loc_, path, to_dims(dims_.resolve(array_spec(path))),
                                static_cast<hsize_t>(first), static_cast<hsize_t>(count));
  }

 private:
  h5::Where where(const std::string& path) const { return h5::Where{file_, base_ + "/" + path}; }
  const std::string& file_;
  const H5::Group& loc_;
  std::string base_;
  DimBinder dims_;
};

// One array of the schema into `group` under its name (the path's last
// part): per-frame arrays of rank 3 and more chunked by frame, an empty
// optional one left out.
template <class T>
void write_array(H5::Group& group, const ArraySpec& spec, const std::vector<T>& values, const DimBinder& dims) {
  if (spec.optional && values.empty()) return;
  const std::string name = spec.path.substr(spec.path.rfind('/') + 1);
  if constexpr (std::is_same_v<T, std::string>) {
    h5::write_strings(group, name, values);
  } else {
    h5::write(group, name, values, to_dims(dims.resolve(spec)), spec.per_frame() && spec.dims.size() >= 3);
  }
}

std::string garment_path(const SequenceInfo& info, const GarmentInfo& g) {
  return "/seq/" + info.id + "/garments/" + g.group;
}

}  // namespace

SequenceStatic read_static(const std::string& file, const H5::Group& seq, const SequenceInfo& info) {
  h5::Lock lock;
  SequenceStatic out;
  out.id = info.id;
  out.n_frames = info.n_frames;
  const GroupReader body(file, seq, "/seq/" + info.id, sequence_dims(info));
  for (const ArraySpec& spec : body_arrays()) {
    if (spec.per_frame() || (spec.optional && !info.has_tpose_joints)) continue;
    with_body_static(out.body, spec, [&](auto& member) { body.read(spec, member); });
  }
  for (const auto& gi : info.garments) {
    const H5::Group group =
        h5::guard(file, garment_path(info, gi), [&] { return seq.openGroup("garments/" + gi.group); });
    const GroupReader garment(file, group, garment_path(info, gi), garment_dims(info, gi));
    GarmentStatic g;
    g.name = gi.name;
    g.type = gi.type;
    g.layer = gi.layer;
    g.attributes = gi.attributes;
    for (const ArraySpec& spec : garment_arrays()) {
      if (spec.per_frame()) continue;
      with_garment_static(g, spec, [&](auto& member) { garment.read(spec, member); });
    }
    out.garments.push_back(std::move(g));
  }
  check_static_indices(out, file);
  return out;
}

void read_frames(const std::string& file, const H5::Group& seq, const SequenceInfo& info, std::int64_t first,
                 std::int64_t count, Window& window) {
  h5::Lock lock;
  const GroupReader reader(file, seq, "/seq/" + info.id, sequence_dims(info));
  for (const auto* table : {&body_arrays(), &wind_arrays()}) {
    for (const ArraySpec& spec : *table) {
      if (!spec.per_frame()) continue;
      with_frames(window.body, window.wind, spec, [&](auto& member) {
        if constexpr (std::is_same_v<std::decay_t<decltype(member)>, std::vector<float>>)
          member = reader.frames(spec.path, first, count);
      });
    }
  }
  window.garments.clear();
  for (const auto& gi : info.garments) {
    const H5::Group group =
        h5::guard(file, garment_path(info, gi), [&] { return seq.openGroup("garments/" + gi.group); });
    const GroupReader garment(file, group, garment_path(info, gi), garment_dims(info, gi));
    for (const ArraySpec& spec : garment_arrays())
      if (spec.per_frame()) window.garments.push_back(garment.frames(spec.path, first, count));
  }
}

void write_sequence(H5::Group& seqs, const SequenceData& seq) {
  h5::Lock lock;
  const BodyData& b = seq.body;
  DimBinder dims;
  dims.bind("T", seq.n_frames, "n_frames");
  dims.bind("Vb", b.n_vertices(), "body");
  dims.bind("Fb", b.n_faces(), "body");
  dims.bind("J", b.n_joints(), "body");

  H5::Group group = h5::create_group(seqs, seq.id);
  h5::set_attr(group, "n_frames", static_cast<std::int64_t>(seq.n_frames));
  h5::set_attr(group, "motion", seq.motion);
  h5::set_attr(group, "seed", static_cast<std::uint64_t>(seq.seed));
  h5::set_attr(group, "tags", seq.tags);
  for (const auto& [name, value] : seq.shape) h5::set_attr(group, name, value);

  for (const auto& [name, table] : {std::pair{"body", &body_arrays()}, std::pair{"wind", &wind_arrays()}}) {
    H5::Group sub = h5::create_group(group, name);
    for (const ArraySpec& spec : *table)
      with_sequence_array(seq, spec, [&](const auto& member) { write_array(sub, spec, member, dims); });
  }

  H5::Group garments = h5::create_ordered_group(group, "garments");
  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const GarmentData& g = seq.garments[k];
    H5::Group gg = h5::create_group(garments, std::to_string(k));
    h5::set_attr(gg, "name", g.name);
    h5::set_attr(gg, "type", g.type);
    h5::set_attr(gg, "layer", static_cast<std::int64_t>(g.layer));
    for (const auto& [name, value] : g.attributes) h5::set_attr(gg, name, value);
    DimBinder gdims;
    gdims.bind("T", seq.n_frames, "n_frames");
    gdims.bind("V", g.n_vertices(), "garment");
    gdims.bind("F", g.n_faces(), "garment");
    gdims.bind("U", g.n_uv(), "garment");
    for (const ArraySpec& spec : garment_arrays())
      with_garment_array(g, spec, [&](const auto& member) { write_array(gg, spec, member, gdims); });
  }
}

}  // namespace layers::data
