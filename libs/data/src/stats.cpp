// Normalisation statistics from the train split, and stats.h5 I/O (see
// stats.h).
#include "layers/data/stats.h"

#include <cmath>
#include <filesystem>

#include "dataset_files.h"
#include "h5_io.h"
#include "integrity.h"
#include "layers/core/atomic_file.h"
#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/manifest.h"
#include "shard_layout.h"

namespace layers::data {
namespace {

constexpr const char* kStatsFormat = "layers-stats";
constexpr std::int64_t kStatsVersion = 1;
constexpr std::size_t kBlockBytes = 8u << 20;

// Running mean and sum of squared deviations per component, merged batch
// by batch (Chan et al.), in double precision.
class MomentAccumulator {
 public:
  void add(const std::vector<double>& xyz) {
    const std::size_t n = xyz.size() / 3;
    if (n == 0) return;
    for (int c = 0; c < 3; ++c) {
      double mean = 0.0;
      for (std::size_t i = 0; i < n; ++i) mean += xyz[3 * i + c];
      mean /= double(n);
      double m2 = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const double d = xyz[3 * i + c] - mean;
        m2 += d * d;
      }
      const double total = double(count_ + n);
      const double delta = mean - mean_[c];
      mean_[c] += delta * double(n) / total;
      m2_[c] += m2 + delta * delta * double(count_) * double(n) / total;
    }
    count_ += n;
  }

  Moments moments(double floor) const {
    Moments m;
    m.count = static_cast<std::int64_t>(count_);
    for (int c = 0; c < 3; ++c) {
      m.mean[c] = mean_[c];
      m.std[c] = std::max(count_ ? std::sqrt(m2_[c] / double(count_)) : 0.0, floor);
    }
    return m;
  }
  std::uint64_t count() const { return count_; }

 private:
  std::uint64_t count_ = 0;
  double mean_[3] = {0, 0, 0}, m2_[3] = {0, 0, 0};
};

struct Quantities {
  MomentAccumulator position, velocity, acceleration;
};

// Root-relative positions of one mesh, one frame at a time, with the
// previous frame's position and velocity for the differences.
class MeshTrack {
 public:
  MeshTrack(Quantities& into, std::string object) : into_(into), object_(std::move(object)) {}

  void frame(const SequenceInfo& info, std::int64_t t, const float* positions, std::size_t n_vertices,
             const float* root) {
    rel_.resize(n_vertices * 3);
    for (std::size_t i = 0; i < n_vertices * 3; ++i) {
      const float p = positions[i];
      if (!std::isfinite(p)) {
        throw InputError(info.shard, object_, "finite values",
                         "a non-finite value at frame " + std::to_string(t) + ", vertex " + std::to_string(i / 3));
      }
      rel_[i] = double(p) - double(root[i % 3]);
    }
    into_.position.add(rel_);
    if (frames_ >= 1) {
      vel_.resize(rel_.size());
      for (std::size_t i = 0; i < rel_.size(); ++i) vel_[i] = rel_[i] - prev_rel_[i];
      into_.velocity.add(vel_);
      if (frames_ >= 2) {
        acc_.resize(rel_.size());
        for (std::size_t i = 0; i < rel_.size(); ++i) acc_[i] = vel_[i] - prev_vel_[i];
        into_.acceleration.add(acc_);
      }
      prev_vel_.swap(vel_);
    }
    prev_rel_.swap(rel_);
    ++frames_;
  }

 private:
  Quantities& into_;
  std::string object_;
  std::int64_t frames_ = 0;
  std::vector<double> rel_, prev_rel_, vel_, prev_vel_, acc_;
};

void accumulate_sequence(const Dataset& dataset, const SequenceInfo& info, Quantities& garment, Quantities& body) {
  const std::string base = "/seq/" + info.id;
  std::size_t frame_bytes = static_cast<std::size_t>(info.body_vertices) * 12;
  for (const auto& g : info.garments) frame_bytes += static_cast<std::size_t>(g.n_vertices) * 12;
  const std::int64_t block =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(kBlockBytes / std::max<std::size_t>(frame_bytes, 1)));

  MeshTrack body_track(body, base + "/body/positions");
  std::vector<MeshTrack> garment_tracks;
  for (const auto& g : info.garments)
    garment_tracks.emplace_back(garment, base + "/garments/" + g.group + "/positions");

  for (std::int64_t first = 0; first < info.n_frames; first += block) {
    const std::int64_t count = std::min(block, info.n_frames - first);
    const Window w = dataset.read_frames(info.id, first, count);
    for (std::int64_t f = 0; f < count; ++f) {
      const std::int64_t t = first + f;
      const float* root = w.body.root.data() + 3 * f;
      if (!std::isfinite(root[0]) || !std::isfinite(root[1]) || !std::isfinite(root[2])) {
        throw InputError(info.shard, base + "/body/root", "finite values",
                         "a non-finite value at frame " + std::to_string(t));
      }
      const auto nb = static_cast<std::size_t>(info.body_vertices);
      body_track.frame(info, t, w.body.positions.data() + f * nb * 3, nb, root);
      for (std::size_t k = 0; k < info.garments.size(); ++k) {
        const auto nv = static_cast<std::size_t>(info.garments[k].n_vertices);
        garment_tracks[k].frame(info, t, w.garments[k].data() + f * nv * 3, nv, root);
      }
    }
  }
}

}  // namespace

NormStats compute_stats(const Dataset& dataset, const StatsOptions& options) {
  const std::string splits_file = (std::filesystem::path(dataset.path()) / "splits.yaml").string();
  if (!dataset.splits().has(options.split)) {
    throw InputError(splits_file, options.split, "a split named '" + options.split + "'", "no such split");
  }
  const auto& ids = dataset.splits().get(options.split);
  if (ids.empty()) throw InputError(splits_file, options.split, "at least one sequence", "an empty list");

  Quantities garment, body;
  NormStats stats;
  stats.split = options.split;
  stats.std_floor = options.std_floor;
  for (const auto& id : ids) {
    const SequenceInfo& info = dataset.info(id);
    accumulate_sequence(dataset, info, garment, body);
    ++stats.n_sequences;
    stats.n_frames += info.n_frames;
  }
  const std::pair<const char*, const MomentAccumulator*> all[] = {{"garment velocity", &garment.velocity},
                                                                  {"garment acceleration", &garment.acceleration},
                                                                  {"body velocity", &body.velocity},
                                                                  {"body acceleration", &body.acceleration}};
  for (const auto& [name, acc] : all) {
    if (acc->count() == 0) {
      throw InputError(splits_file, options.split,
                       std::string("data for the ") + name + " (garments and sequences of at least 3 frames)", "none");
    }
  }
  stats.garment_position = garment.position.moments(options.std_floor);
  stats.garment_velocity = garment.velocity.moments(options.std_floor);
  stats.garment_acceleration = garment.acceleration.moments(options.std_floor);
  stats.body_position = body.position.moments(options.std_floor);
  stats.body_velocity = body.velocity.moments(options.std_floor);
  stats.body_acceleration = body.acceleration.moments(options.std_floor);
  return stats;
}

void write_stats(const std::string& path, const NormStats& stats) {
  AtomicPath atomic(path);
  {
    h5::Lock lock;
    h5::guard(path, "", [&] {
      H5::H5File file = h5::create_file(atomic.temp());
      H5::Group root = file.openGroup("/");
      h5::set_attr(root, "format", std::string(kStatsFormat));
      h5::set_attr(root, "format_version", kStatsVersion);
      h5::set_attr(root, "split", stats.split);
      h5::set_attr(root, "n_sequences", stats.n_sequences);
      h5::set_attr(root, "n_frames", stats.n_frames);
      h5::set_attr(root, "std_floor", stats.std_floor);
      for (const char* top : {"garment", "body"}) h5::create_group(root, top);
      for_each_quantity(stats, [&](const char* name, const Moments& m) {
        H5::Group group = h5::create_group(root, name);
        h5::write(group, "mean", std::vector<double>(m.mean.begin(), m.mean.end()), {3});
        h5::write(group, "std", std::vector<double>(m.std.begin(), m.std.end()), {3});
        h5::set_attr(group, "count", m.count);
      });
      file.close();
    });
  }
  atomic.commit();
}

NormStats read_stats(const std::string& path) {
  h5::Lock lock;
  const H5::H5File file = h5::open_read(path);
  return h5::guard(path, "", [&] {
    const H5::Group root = file.openGroup("/");
    auto require = [&](const H5::H5Object& obj, const std::string& object, const char* name, h5::AttrKind kind) {
      const auto got = h5::attr_kind(obj, name);
      const bool ok = got == kind || (kind == h5::AttrKind::Float && got == h5::AttrKind::Integer);
      if (!ok) throw InputError(path, object + " attribute " + name, h5::attr_kind_text(kind), h5::attr_kind_text(got));
    };
    require(root, "/", "format", h5::AttrKind::String);
    if (h5::attr_string(root, "format") != kStatsFormat) {
      throw InputError(path, "/ attribute format", kStatsFormat, "\"" + h5::attr_string(root, "format") + "\"");
    }
    require(root, "/", "format_version", h5::AttrKind::Integer);
    if (h5::attr_int(root, "format_version") != kStatsVersion) {
      throw InputError(path, "/ attribute format_version", std::to_string(kStatsVersion),
                       std::to_string(h5::attr_int(root, "format_version")));
    }
    NormStats stats;
    require(root, "/", "split", h5::AttrKind::String);
    require(root, "/", "n_sequences", h5::AttrKind::Integer);
    require(root, "/", "n_frames", h5::AttrKind::Integer);
    require(root, "/", "std_floor", h5::AttrKind::Float);
    stats.split = h5::attr_string(root, "split");
    stats.n_sequences = h5::attr_int(root, "n_sequences");
    stats.n_frames = h5::attr_int(root, "n_frames");
    stats.std_floor = h5::attr_double(root, "std_floor");
    for_each_quantity(stats, [&](const char* name, Moments& m) {
      const std::string object = std::string("/") + name;
      if (!h5::exists(root, name))
        throw InputError(path, object, "a group with mean, std and count", "nothing (missing)");
      const H5::Group group = root.openGroup(name);
      const auto mean = h5::read_all<double>(h5::Where{path, object + "/mean"}, group, "mean", {3});
      const auto std = h5::read_all<double>(h5::Where{path, object + "/std"}, group, "std", {3});
      require(group, object, "count", h5::AttrKind::Integer);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(mean[c]) || !std::isfinite(std[c]) || std[c] <= 0.0) {
          throw InputError(path, object, "finite means and positive standard deviations",
                           "mean " + std::to_string(mean[c]) + ", std " + std::to_string(std[c]));
        }
        m.mean[c] = mean[c];
        m.std[c] = std[c];
      }
      m.count = h5::attr_int(group, "count");
    });
    return stats;
  });
}

std::string stats_content_hash(const NormStats& stats) {
  ContentHash h;
  auto text = [&](const std::string& t) {
    const auto n = static_cast<std::uint64_t>(t.size());
    h.add(&n, sizeof n).add(t);
  };
  text(stats.split);
  h.add(&stats.n_sequences, sizeof stats.n_sequences).add(&stats.n_frames, sizeof stats.n_frames);
  h.add(&stats.std_floor, sizeof stats.std_floor);
  for_each_quantity(stats, [&](const char* name, const Moments& m) {
    text(name);
    h.add(m.mean.data(), sizeof m.mean).add(m.std.data(), sizeof m.std).add(&m.count, sizeof m.count);
  });
  return h.hex();
}

NormStats read_stats_verified(const std::string& path, bool allow_unhashed) {
  NormStats stats = read_stats(path);
  const std::filesystem::path file(path), folder = file.parent_path().empty() ? "." : file.parent_path();
  if (file.filename() == kStatsFile && std::filesystem::exists(folder / kManifestFile)) {
    ThrowOnProblem sink;
    check_stats_hash(folder.string(), read_manifest((folder / kManifestFile).string()), allow_unhashed, sink);
  }
  return stats;
}

void write_dataset_stats(const std::string& folder, const NormStats& stats) {
  const std::string manifest_path = (std::filesystem::path(folder) / kManifestFile).string();
  DatasetManifest manifest = read_manifest(manifest_path);
  write_stats((std::filesystem::path(folder) / kStatsFile).string(), stats);
  manifest.stats_hash = stats_content_hash(stats);
  write_manifest(manifest_path, manifest);
}

}  // namespace layers::data
