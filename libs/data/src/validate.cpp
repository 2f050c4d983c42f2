// The dataset validator: structure (shared with the reader's index),
// values streamed block by block, YAML files and cross-shard checks (see
// validate.h).
#include "layers/data/validate.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "dataset_files.h"
#include "h5_io.h"
#include "integrity.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/format.h"
#include "layers/data/manifest.h"
#include "layers/data/splits.h"
#include "layers/data/stats.h"
#include "sequence_rules.h"
#include "shard_layout.h"
#include "splits_source.h"

namespace layers::data {

namespace fs = std::filesystem;

std::string Problem::to_string() const {
  return (file.empty() ? std::string("<input>") : file) + (object.empty() ? "" : ": " + object) + ": " + message;
}

namespace {

constexpr std::size_t kScanBlockBytes = 4u << 20;

Problem problem_from(const InputError& e) {
  std::string message = e.what();
  const std::string prefix =
      (e.file().empty() ? std::string("<input>") : e.file()) + (e.field().empty() ? "" : ": " + e.field()) + ": ";
  if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
  return Problem{e.file(), e.field(), message};
}

std::string index_text(std::uint64_t flat, const h5::Dims& dims) {
  h5::Dims index(dims.size(), 0);
  for (std::size_t i = dims.size(); i-- > 0;) {
    index[i] = dims[i] ? flat % dims[i] : 0;
    flat = dims[i] ? flat / dims[i] : 0;
  }
  return h5::dims_text(index);
}

// The first and the number of offending values of one kind.
struct Offences {
  std::uint64_t count = 0, first = 0;
  double value = 0;
  void add(std::uint64_t flat, double v) {
    if (count++ == 0) {
      first = flat;
      value = v;
    }
  }
};

std::string value_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", v);
  return buffer;
}

// Streams a well-formed float32 array in blocks of rows and reports
// non-finite values and, per rule, non-unit quaternions or strengths
// outside 0..400.
void scan_float_values(const std::string& file, const H5::Group& loc, const std::string& rel, const std::string& object,
                       ValueRule rule, ProblemSink& sink) {
  const H5::DataSet ds = loc.openDataSet(rel);
  const h5::Dims dims = h5::dims_of(ds);
  if (dims.empty()) return;
  std::uint64_t row = 1;
  for (std::size_t i = 1; i < dims.size(); ++i) row *= dims[i];
  if (row == 0 || dims[0] == 0) return;
  const hsize_t rows_per_block = std::max<hsize_t>(1, kScanBlockBytes / (row * sizeof(float)));
  std::vector<float> block;
  Offences non_finite, rule_offences;
  for (hsize_t first = 0; first < dims[0]; first += rows_per_block) {
    const hsize_t count = std::min<hsize_t>(rows_per_block, dims[0] - first);
    block.resize(count * row);
    h5::read_rows_into(ds, dims, first, count, block.data());
    const std::uint64_t base = first * row;
    for (std::uint64_t i = 0; i < block.size(); ++i) {
      const float v = block[i];
      if (!std::isfinite(v)) {
        non_finite.add(base + i, v);
      } else if (rule == ValueRule::WindStrength && (v < 0.0f || v > kMaxWindStrength)) {
        rule_offences.add(base + i, v);
      }
    }
    if (rule == ValueRule::UnitQuaternion) {
      for (std::uint64_t q = 0; q + 4 <= block.size(); q += 4) {
        const double norm = std::sqrt(double(block[q]) * block[q] + double(block[q + 1]) * block[q + 1] +
                                      double(block[q + 2]) * block[q + 2] + double(block[q + 3]) * block[q + 3]);
        if (std::isfinite(norm) && std::abs(norm - 1.0) > kQuaternionTolerance) rule_offences.add(base + q, norm);
      }
    }
  }
  if (non_finite.count) {
    sink.report(Problem{file, object,
                        "expected finite values, got " + std::to_string(non_finite.count) + " non-finite (first " +
                            value_text(non_finite.value) + " at " + index_text(non_finite.first, dims) + ")"});
  }
  if (rule_offences.count) {
    const std::string at = index_text(rule_offences.first, dims);
    if (rule == ValueRule::WindStrength) {
      sink.report(Problem{file, object,
                          "expected strengths in [0,400], got " + std::to_string(rule_offences.count) +
                              " outside (first " + value_text(rule_offences.value) + " at " + at + ")"});
    } else {
      sink.report(
          Problem{file, object,
                  "expected unit quaternions (|q| within 1e-3 of 1), got " + std::to_string(rule_offences.count) +
                      " that are not (first |q| = " + value_text(rule_offences.value) + " at frame " + at + ")"});
    }
  }
}

// A read failure of the array is reported with the array's path.
void scan_floats(const std::string& file, const H5::Group& loc, const std::string& rel, const std::string& object,
                 ValueRule rule, ProblemSink& sink) {
  h5::guard(file, object, [&] { scan_float_values(file, loc, rel, object, rule, sink); });
}

void scan_indices(const std::string& file, const H5::Group& loc, const std::string& rel, const std::string& object,
                  std::int64_t lo, std::int64_t hi, ProblemSink& sink) {
  h5::guard(file, object, [&] {
    const H5::DataSet ds = loc.openDataSet(rel);
    const h5::Dims dims = h5::dims_of(ds);
    const std::vector<std::int32_t> values = h5::read_all<std::int32_t>(h5::Where{file, object}, loc, rel, dims);
    const std::size_t width = dims.size() > 1 ? dims[1] : 1;
    if (auto problem = check_index_range(values, lo, hi, width)) sink.report(Problem{file, object, *problem});
  });
}

// One well-formed array's values, by the rule the schema gives it
// (format.h); `bound` gives the value of a dimension symbol.
template <class Bound>
void check_array(const std::string& file, const H5::Group& loc, const ArraySpec& spec, const std::string& object,
                 const Bound& bound, ProblemSink& sink) {
  constexpr std::int64_t kNoMax = std::numeric_limits<std::int32_t>::max();
  switch (spec.values) {
    case ValueRule::None:
      return;
    case ValueRule::Finite:
    case ValueRule::UnitQuaternion:
    case ValueRule::WindStrength:
      scan_floats(file, loc, spec.path, object, spec.values, sink);
      return;
    case ValueRule::Indices:
      scan_indices(file, loc, spec.path, object, 0, spec.below.empty() ? kNoMax : bound(spec.below), sink);
      return;
    case ValueRule::JointParents: {
      const auto parents =
          h5::read_all<std::int32_t>(h5::Where{file, object}, loc, spec.path, {static_cast<hsize_t>(bound("J"))});
      if (auto problem = check_joint_parents(parents)) sink.report(Problem{file, object, *problem});
      return;
    }
  }
}

// Value checks of the arrays the structure check found well-formed, each
// by its rule in the schema.
void check_values(const std::string& file, const H5::Group& seq, const SequenceLayout& layout, ProblemSink& sink) {
  const SequenceInfo& info = layout.info;
  const std::string base = "/seq/" + info.id;
  auto ok = [&](const std::string& key) { return layout.well_formed.count(key) > 0; };
  auto sequence_bound = [&](const std::string& dim) -> std::int64_t {
    return dim == "Vb" ? info.body_vertices : info.n_joints;  // the symbols the body's rules name
  };
  for (const auto* table : {&body_arrays(), &wind_arrays()})
    for (const ArraySpec& spec : *table)
      if (ok(spec.path)) check_array(file, seq, spec, base + "/" + spec.path, sequence_bound, sink);

  for (const auto& g : info.garments) {
    const std::string key = "garments/" + g.group + "/";
    const H5::Group group = seq.openGroup(key);
    auto garment_bound = [&](const std::string& dim) -> std::int64_t { return dim == "V" ? g.n_vertices : g.n_uv; };
    for (const ArraySpec& spec : garment_arrays())
      if (ok(key + spec.path)) check_array(file, group, spec, base + "/" + key + spec.path, garment_bound, sink);
  }
}

// Returns false when the file cannot be opened at all.
bool validate_shard(const std::string& path, ProblemSink& sink, std::map<std::string, std::string>& seen,
                    ShardTotals& totals) {
  h5::Lock lock;
  H5::H5File file;
  try {
    file = h5::open_read(path, h5::bounded_access(1u << 20));
  } catch (const InputError& e) {
    sink.report(problem_from(e));
    return false;
  }
  try {
    check_root(path, file, sink);
  } catch (const H5::Exception& e) {
    sink.report(Problem{path, "/", h5::damage_text(e)});
  }
  std::vector<std::string> ids;
  try {
    ids = sequence_ids(path, file, sink);
  } catch (const H5::Exception& e) {
    sink.report(Problem{path, "/seq", h5::damage_text(e)});
  }
  for (const auto& id : ids) {
    const std::string object = "/seq/" + id;
    const auto [it, fresh] = seen.emplace(id, path);
    if (!fresh) sink.report(Problem{path, object, "duplicate sequence id: also in " + it->second});
    try {
      const H5::Group seq = file.openGroup(object);
      const SequenceLayout layout = inspect_sequence(path, seq, id, sink);
      totals.add(layout.info);
      check_values(path, seq, layout, sink);
    } catch (const H5::Exception& e) {
      sink.report(Problem{path, object, h5::damage_text(e)});
    } catch (const InputError& e) {
      sink.report(problem_from(e));
    }
  }
  return true;
}

void validate_splits(const std::string& path, const std::map<std::string, std::string>& seen, ProblemSink& sink) {
  try {
    const SplitsSource source = read_splits_source(path);
    check_splits(source, seen, sink);
  } catch (const InputError& e) {
    sink.report(problem_from(e));
  }
}

bool train_split_nonempty(const std::string& splits_path) {
  try {
    const Splits splits = read_splits(splits_path);
    return splits.has("train") && !splits.get("train").empty();
  } catch (const InputError&) {
    return false;  // reported by validate_splits
  }
}

void validate_folder(const std::string& folder, const ValidateOptions& options, ProblemSink& sink) {
  const std::string manifest_path = (fs::path(folder) / kManifestFile).string();
  std::optional<DatasetManifest> manifest;
  if (!fs::exists(manifest_path)) {
    sink.report(Problem{manifest_path, "", "missing (a dataset folder needs dataset.yaml)"});
  } else {
    try {
      manifest = read_manifest(manifest_path);
    } catch (const InputError& e) {
      sink.report(problem_from(e));
    }
  }
  const auto shards = list_shards(folder);
  if (shards.empty()) sink.report(Problem{folder, "", "no shard files (shard-NNNNN.h5)"});
  if (manifest && !shards.empty()) check_shard_set(manifest_path, *manifest, shards, sink);
  std::map<std::string, std::string> seen;
  ShardTotals totals;
  bool all_opened = true;
  for (const auto& shard : shards) all_opened &= validate_shard(shard, sink, seen, totals);

  // (With an unreadable shard the counts would differ for that reason alone.)
  if (manifest && !shards.empty() && all_opened) check_counts(manifest_path, *manifest, totals, sink);
  const std::string splits_path = (fs::path(folder) / kSplitsFile).string();
  if (!fs::exists(splits_path)) {
    sink.report(Problem{splits_path, "", "missing (a dataset folder needs splits.yaml)"});
  } else {
    validate_splits(splits_path, seen, sink);
  }
  const std::string stats_path = (fs::path(folder) / kStatsFile).string();
  if (fs::exists(stats_path)) {
    try {
      read_stats(stats_path);
      if (manifest) check_stats_hash(folder, *manifest, options.allow_unhashed, sink);
    } catch (const InputError& e) {
      sink.report(problem_from(e));
    }
  } else if (train_split_nonempty(splits_path)) {
    sink.report(Problem{stats_path, "",
                        "missing (train, eval and bench need the train split's statistics; `layers generate` "
                        "writes them when the dataset is complete)"});
  }
}

// Every sequence through the reader, which runs the integrity check
// (integrity.h: recorded hashes at open, each sequence's content hash on
// its read) and the physical bounds of value_bounds.h (finite, within 10 m
// of the body root, ...). Run only on a structurally valid dataset, so
// that one damage is not reported twice.
void check_through_reader(const std::string& path, const ValidateOptions& options, ProblemSink& sink) {
  try {
    ReaderOptions reader;
    reader.allow_unhashed = options.allow_unhashed;
    const Dataset dataset = Dataset::open(path, reader);
    for (const std::string& id : dataset.ids()) {
      try {
        dataset.read_sequence(id);
      } catch (const InputError& e) {
        sink.report(problem_from(e));
      }
    }
  } catch (const InputError& e) {
    sink.report(problem_from(e));
  }
}

}  // namespace

std::vector<Problem> validate_dataset(const std::string& path, const ValidateOptions& options) {
  std::vector<Problem> problems;
  CollectProblems sink(problems);
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    validate_folder(path, options, sink);
    if (problems.empty()) check_through_reader(path, options, sink);
  } else if (fs::exists(path, ec)) {
    std::map<std::string, std::string> seen;
    ShardTotals totals;
    validate_shard(path, sink, seen, totals);
    if (problems.empty()) check_through_reader(path, options, sink);
  } else {
    sink.report(Problem{path, "", "does not exist"});
  }
  return problems;
}

}  // namespace layers::data
