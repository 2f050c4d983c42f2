// Structure checks of shards and sequences (see shard_layout.h).
#include "shard_layout.h"

#include <algorithm>
#include <cctype>

#include "dims.h"
#include "h5_io.h"
#include "layers/core/error.h"
#include "layers/data/format.h"
#include "sequence_rules.h"

namespace layers::data {
namespace {

bool is_index_name(const std::string& name) {
  return !name.empty() && name.size() < 10 &&
         std::all_of(name.begin(), name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// Attribute checks of one object, reporting to the sink.
class AttrReader {
 public:
  AttrReader(const std::string& file, const H5::H5Object& obj, std::string object, ProblemSink& sink)
      : file_(file), obj_(obj), object_(std::move(object)), sink_(sink) {}

  bool expect(const std::string& name, h5::AttrKind want) {
    const h5::AttrKind got = h5::attr_kind(obj_, name);
    const bool numeric_ok = want == h5::AttrKind::Float && got == h5::AttrKind::Integer;
    if (got == want || numeric_ok) return true;
    report(name, std::string("expected ") + h5::attr_kind_text(want) + ", got " + h5::attr_kind_text(got));
    return false;
  }

  void report(const std::string& name, const std::string& message) {
    sink_.report(Problem{file_, object_ + " attribute " + name, message});
  }

  // Numeric attributes other than the reserved ones.
  std::map<std::string, double> numeric_extras(const std::vector<std::string>& reserved) {
    std::map<std::string, double> out;
    for (const auto& name : h5::attr_names(obj_)) {
      if (is_reserved(name, reserved)) continue;
      const auto kind = h5::attr_kind(obj_, name);
      if (kind == h5::AttrKind::Integer || kind == h5::AttrKind::Float) out[name] = h5::attr_double(obj_, name);
    }
    return out;
  }

 private:
  const std::string& file_;
  const H5::H5Object& obj_;
  std::string object_;
  ProblemSink& sink_;
};

// Checks presence, dtype and shape of one array; binds its symbols.
void inspect_array(const std::string& file, const H5::Group& loc, const std::string& base, const std::string& key,
                   const ArraySpec& spec, DimBinder& dims, ProblemSink& sink, std::set<std::string>& well_formed) {
  const std::string object = base + "/" + key;
  const std::string expected = std::string(dtype_name(spec.dtype)) + " " + spec.shape_text();
  if (!h5::is_dataset(loc, spec.path)) {
    if (spec.optional && !h5::exists(loc, spec.path)) return;
    sink.report(Problem{file, object, "missing dataset (expected " + expected + ")"});
    return;
  }
  const H5::DataSet ds = loc.openDataSet(spec.path);
  const H5::DataType type = ds.getDataType();
  bool good = true;
  if (!h5::dtype_matches(type, spec.dtype)) {
    sink.report(Problem{file, object,
                        std::string("expected dtype ") + dtype_name(spec.dtype) + ", got " + h5::dtype_text(type)});
    good = false;
  }
  const h5::Dims got = h5::dims_of(ds);
  if (auto mismatch = dims.match(spec, std::vector<std::uint64_t>(got.begin(), got.end()), object)) {
    sink.report(Problem{file, object, *mismatch});
    good = false;
  }
  if (good) well_formed.insert(key);
}

std::int64_t dim_or_zero(const DimBinder& dims, const char* symbol) { return dims.get(symbol).value_or(0); }

void inspect_sequence_attrs(const std::string& file, const H5::Group& seq, const std::string& base, SequenceInfo& info,
                            DimBinder& dims, ProblemSink& sink) {
  AttrReader attrs(file, seq, base, sink);
  if (attrs.expect("n_frames", h5::AttrKind::Integer)) {
    info.n_frames = h5::attr_int(seq, "n_frames");
    if (info.n_frames < 1) {
      attrs.report("n_frames", "expected at least 1, got " + std::to_string(info.n_frames));
    } else {
      dims.bind("T", info.n_frames, base + " n_frames attribute");
    }
  }
  if (attrs.expect("motion", h5::AttrKind::String)) info.motion = h5::attr_string(seq, "motion");
  if (attrs.expect("seed", h5::AttrKind::Integer)) info.seed = h5::attr_uint(seq, "seed");
  if (attrs.expect("tags", h5::AttrKind::String)) info.tags = h5::attr_strings(seq, "tags");
  info.shape = attrs.numeric_extras(sequence_reserved_attrs());
}

// Keys and object paths of the garment's arrays are relative to the
// sequence group `base` (key_prefix = "garments/<k>/").
GarmentInfo inspect_garment(const std::string& file, const H5::Group& garment, const std::string& group_name,
                            const std::string& base, const std::string& key_prefix, const DimBinder& seq_dims,
                            ProblemSink& sink, std::set<std::string>& well_formed) {
  GarmentInfo g;
  g.group = group_name;
  AttrReader attrs(file, garment, base + "/" + key_prefix.substr(0, key_prefix.size() - 1), sink);
  if (attrs.expect("name", h5::AttrKind::String)) g.name = h5::attr_string(garment, "name");
  if (attrs.expect("type", h5::AttrKind::String)) {
    g.type = h5::attr_string(garment, "type");
    if (auto problem = check_garment_type(g.type)) attrs.report("type", *problem);
  }
  if (attrs.expect("layer", h5::AttrKind::Integer)) {
    const auto layer = h5::attr_int(garment, "layer");
    g.layer = static_cast<int>(layer);
    if (auto problem = check_garment_layer(layer)) attrs.report("layer", *problem);
  }
  g.attributes = attrs.numeric_extras(garment_reserved_attrs());

  DimBinder dims;
  if (const auto t = seq_dims.get("T")) dims.bind("T", *t, "the sequence's frame count");
  for (const auto& spec : garment_arrays()) {
    inspect_array(file, garment, base, key_prefix + spec.path, spec, dims, sink, well_formed);
  }
  g.n_vertices = dim_or_zero(dims, "V");
  g.n_faces = dim_or_zero(dims, "F");
  g.n_uv = dim_or_zero(dims, "U");
  return g;
}

}  // namespace

void ThrowOnProblem::report(Problem problem) {
  throw InputError::message(problem.file, problem.object, problem.message);
}

void check_root(const std::string& file, const H5::H5File& h5, ProblemSink& sink) {
  h5::Lock lock;
  const H5::Group root = h5.openGroup("/");
  AttrReader attrs(file, root, "/", sink);
  auto expect_string = [&](const char* name, const std::string& value) {
    if (!attrs.expect(name, h5::AttrKind::String)) return;
    const std::string got = h5::attr_string(root, name);
    if (got != value) attrs.report(name, "expected \"" + value + "\", got \"" + got + "\"");
  };
  auto expect_int = [&](const char* name, std::int64_t value) {
    if (!attrs.expect(name, h5::AttrKind::Integer)) return;
    const std::int64_t got = h5::attr_int(root, name);
    if (got != value) attrs.report(name, "expected " + std::to_string(value) + ", got " + std::to_string(got));
  };
  expect_string("format", kFormatName);
  expect_int("format_version", kFormatVersion);
  expect_int("fps", kFps);
  expect_string("units", kUnits);
  expect_string("up", kUp);
}

std::vector<std::string> sequence_ids(const std::string& file, const H5::H5File& h5, ProblemSink& sink) {
  h5::Lock lock;
  const H5::Group root = h5.openGroup("/");
  if (!h5::exists(root, "seq") || root.childObjType("seq") != H5O_TYPE_GROUP) {
    sink.report(Problem{file, "/seq", "missing group (a shard keeps its sequences under /seq)"});
    return {};
  }
  return h5::member_names(h5.openGroup("/seq"));
}

SequenceLayout inspect_sequence(const std::string& file, const H5::Group& seq, const std::string& id,
                                ProblemSink& sink) {
  h5::Lock lock;
  SequenceLayout layout;
  SequenceInfo& info = layout.info;
  info.id = id;
  info.shard = file;
  const std::string base = "/seq/" + id;
  DimBinder dims;
  inspect_sequence_attrs(file, seq, base, info, dims, sink);

  for (const char* group : {"body", "wind"}) {
    const auto& table = std::string(group) == "body" ? body_arrays() : wind_arrays();
    if (!h5::exists(seq, group) || seq.childObjType(group) != H5O_TYPE_GROUP) {
      sink.report(Problem{file, base + "/" + group, "missing group"});
      continue;
    }
    for (const auto& spec : table) inspect_array(file, seq, base, spec.path, spec, dims, sink, layout.well_formed);
  }
  info.body_vertices = dim_or_zero(dims, "Vb");
  info.body_faces = dim_or_zero(dims, "Fb");
  info.n_joints = dim_or_zero(dims, "J");
  info.has_tpose_joints = layout.well_formed.count("body/tpose_joints") > 0;
  if (info.n_frames == 0) info.n_frames = dim_or_zero(dims, "T");

  if (!h5::exists(seq, "garments") || seq.childObjType("garments") != H5O_TYPE_GROUP) {
    sink.report(Problem{file, base + "/garments", "missing group"});
    return layout;
  }
  const H5::Group garments = seq.openGroup("garments");
  std::vector<std::string> names;
  for (const auto& name : h5::member_names(garments)) {
    if (!is_index_name(name) || garments.childObjType(name) != H5O_TYPE_GROUP) {
      sink.report(Problem{file, base + "/garments/" + name,
                          "expected a garment group named by its index (0, 1, ...), got an unexpected member"});
      continue;
    }
    names.push_back(name);
  }
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return std::stol(a) < std::stol(b); });
  for (const auto& name : names) {
    info.garments.push_back(inspect_garment(file, garments.openGroup(name), name, base, "garments/" + name + "/", dims,
                                            sink, layout.well_formed));
  }
  return layout;
}

}  // namespace layers::data
