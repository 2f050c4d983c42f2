// Reading and writing the arrays of a sequence group (see sequence_io.h).
#include "sequence_io.h"

#include "dims.h"
#include "h5_io.h"
#include "layers/data/format.h"

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
  out.body.faces = body.all<std::int32_t>("body/faces");
  out.body.joint_names = body.strings("body/joint_names");
  out.body.joint_parents = body.all<std::int32_t>("body/joint_parents");
  out.body.skin_index = body.all<std::int32_t>("body/skin_index");
  out.body.skin_weight = body.all<float>("body/skin_weight");
  if (info.has_tpose_joints) out.body.tpose_joints = body.all<float>("body/tpose_joints");
  for (const auto& gi : info.garments) {
    const H5::Group group =
        h5::guard(file, garment_path(info, gi), [&] { return seq.openGroup("garments/" + gi.group); });
    const GroupReader garment(file, group, garment_path(info, gi), garment_dims(info, gi));
    GarmentStatic g;
    g.name = gi.name;
    g.type = gi.type;
    g.layer = gi.layer;
    g.attributes = gi.attributes;
    g.faces = garment.all<std::int32_t>("faces");
    g.rest = garment.all<float>("rest");
    g.uv = garment.all<float>("uv");
    g.uv_faces = garment.all<std::int32_t>("uv_faces");
    g.panel = garment.all<std::int32_t>("panel");
    out.garments.push_back(std::move(g));
  }
  check_static_indices(out, file);
  return out;
}

void read_frames(const std::string& file, const H5::Group& seq, const SequenceInfo& info, std::int64_t first,
                 std::int64_t count, Window& window) {
  h5::Lock lock;
  const GroupReader reader(file, seq, "/seq/" + info.id, sequence_dims(info));
  window.body.positions = reader.frames("body/positions", first, count);
  window.body.root = reader.frames("body/root", first, count);
  window.body.root_rot = reader.frames("body/root_rot", first, count);
  window.body.joints = reader.frames("body/joints", first, count);
  window.wind.rotation = reader.frames("wind/rotation", first, count);
  window.wind.strength = reader.frames("wind/strength", first, count);
  window.garments.clear();
  for (const auto& gi : info.garments) {
    const H5::Group group =
        h5::guard(file, garment_path(info, gi), [&] { return seq.openGroup("garments/" + gi.group); });
    const GroupReader garment(file, group, garment_path(info, gi), garment_dims(info, gi));
    window.garments.push_back(garment.frames("positions", first, count));
  }
}

void write_sequence(H5::Group& seqs, const SequenceData& seq) {
  h5::Lock lock;
  const auto T = static_cast<hsize_t>(seq.n_frames);
  const BodyData& b = seq.body;
  const auto Vb = static_cast<hsize_t>(b.n_vertices());
  const auto J = static_cast<hsize_t>(b.n_joints());

  H5::Group group = h5::create_group(seqs, seq.id);
  h5::set_attr(group, "n_frames", static_cast<std::int64_t>(seq.n_frames));
  h5::set_attr(group, "motion", seq.motion);
  h5::set_attr(group, "seed", static_cast<std::uint64_t>(seq.seed));
  h5::set_attr(group, "tags", seq.tags);
  for (const auto& [name, value] : seq.shape) h5::set_attr(group, name, value);

  H5::Group body = h5::create_group(group, "body");
  h5::write(body, "faces", b.faces, {static_cast<hsize_t>(b.n_faces()), 3});
  h5::write(body, "positions", b.positions, {T, Vb, 3}, true);
  h5::write(body, "root", b.root, {T, 3});
  h5::write(body, "root_rot", b.root_rot, {T, 4});
  h5::write(body, "joints", b.joints, {T, J, 3, 4}, true);
  h5::write_strings(body, "joint_names", b.joint_names);
  h5::write(body, "joint_parents", b.joint_parents, {J});
  h5::write(body, "skin_index", b.skin_index, {Vb, 4});
  h5::write(body, "skin_weight", b.skin_weight, {Vb, 4});
  if (!b.tpose_joints.empty()) h5::write(body, "tpose_joints", b.tpose_joints, {J, 3, 4});

  H5::Group wind = h5::create_group(group, "wind");
  h5::write(wind, "rotation", seq.wind.rotation, {T, 4});
  h5::write(wind, "strength", seq.wind.strength, {T});

  H5::Group garments = h5::create_ordered_group(group, "garments");
  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const GarmentData& g = seq.garments[k];
    const auto V = static_cast<hsize_t>(g.n_vertices());
    const auto F = static_cast<hsize_t>(g.n_faces());
    H5::Group gg = h5::create_group(garments, std::to_string(k));
    h5::set_attr(gg, "name", g.name);
    h5::set_attr(gg, "type", g.type);
    h5::set_attr(gg, "layer", static_cast<std::int64_t>(g.layer));
    for (const auto& [name, value] : g.attributes) h5::set_attr(gg, name, value);
    h5::write(gg, "faces", g.faces, {F, 3});
    h5::write(gg, "rest", g.rest, {V, 3});
    h5::write(gg, "uv", g.uv, {static_cast<hsize_t>(g.n_uv()), 2});
    h5::write(gg, "uv_faces", g.uv_faces, {F, 3});
    h5::write(gg, "panel", g.panel, {F});
    h5::write(gg, "positions", g.positions, {T, V, 3}, true);
  }
}

}  // namespace layers::data
