// The streaming reader: index, shard handle pool, statics LRU cache and
// hyperslab window reads (see dataset.h).
#include "layers/data/dataset.h"
#include "layers/data/value_bounds.h"

#include <filesystem>
#include <list>
#include <set>
#include <unordered_map>

#include "dataset_files.h"
#include "h5_io.h"
#include "integrity.h"
#include "layers/core/error.h"
#include "sequence_io.h"
#include "splits_source.h"

namespace layers::data {

namespace fs = std::filesystem;

struct Dataset::Impl {
  std::string path;
  ReaderOptions options;
  DatasetManifest manifest;
  Splits splits;
  std::vector<std::string> order;
  std::unordered_map<std::string, SequenceInfo> index;
  H5::FileAccPropList fapl;
  ShardTotals totals;
  std::map<std::string, std::string> shard_of_id;
  std::map<std::string, std::map<std::string, std::string>> shard_hashes;  // the shards' own records
  RecordedHashes recorded;  // what each sequence is verified against on its first read
  std::set<std::string> verified;

  // Open shard files, most recently used first.
  std::list<std::pair<std::string, H5::H5File>> files;

  struct Entry {
    std::string id;
    std::shared_ptr<const SequenceStatic> data;
    std::size_t bytes;
  };
  std::list<Entry> lru;  // most recently used first
  std::unordered_map<std::string, std::list<Entry>::iterator> lru_index;
  std::size_t cached_bytes = 0, hits = 0, misses = 0;

  ~Impl() {
    h5::Lock lock;
    files.clear();
    fapl.close();
  }

  const SequenceInfo& info(const std::string& id) const {
    const auto it = index.find(id);
    if (it == index.end()) {
      throw InputError(path, "sequence id", "one of the " + std::to_string(index.size()) + " sequences of the dataset",
                       "'" + id + "'");
    }
    return it->second;
  }

  const H5::H5File& file(const std::string& shard) {
    for (auto it = files.begin(); it != files.end(); ++it) {
      if (it->first == shard) {
        files.splice(files.begin(), files, it);
        return files.front().second;
      }
    }
    files.emplace_front(shard, h5::open_read(shard, fapl));
    while (files.size() > std::max<std::size_t>(options.max_open_files, 1)) files.pop_back();
    return files.front().second;
  }

  H5::Group group(const SequenceInfo& info) {
    const H5::H5File& f = file(info.shard);
    return h5::guard(info.shard, "/seq/" + info.id, [&] { return f.openGroup("/seq/" + info.id); });
  }

  void add_shard(const std::string& shard) {
    const H5::H5File& f = file(shard);
    for (auto& info : index_shard(shard, f)) {
      const auto existing = index.find(info.id);
      if (existing != index.end()) {
        throw InputError(shard, "/seq/" + info.id, "sequence ids unique across shards",
                         "a duplicate of the sequence in " + existing->second.shard);
      }
      order.push_back(info.id);
      totals.add(info);
      shard_of_id[info.id] = shard;
      index.emplace(info.id, std::move(info));
    }
    auto own = h5::guard(shard, "/", [&] { return shard_content_hashes(shard, f); });
    if (!own.empty()) shard_hashes[shard] = std::move(own);
  }

  // Everything of one sequence as stored (no verification).
  SequenceData read_whole(const SequenceInfo& info) {
    SequenceStatic statics = read_static(info.shard, group(info), info);
    Window window;
    frames(info, 0, info.n_frames, window);
    SequenceData seq;
    seq.id = info.id;
    seq.n_frames = info.n_frames;
    seq.motion = info.motion;
    seq.seed = info.seed;
    seq.tags = info.tags;
    seq.shape = info.shape;
    static_cast<BodyStatic&>(seq.body) = std::move(statics.body);
    static_cast<BodyFrames&>(seq.body) = std::move(window.body);
    seq.wind = std::move(window.wind);
    for (std::size_t k = 0; k < statics.garments.size(); ++k) {
      GarmentData g;
      static_cast<GarmentStatic&>(g) = std::move(statics.garments[k]);
      g.positions = std::move(window.garments[k]);
      seq.garments.push_back(std::move(g));
    }
    return seq;
  }

  // The sequence's content hash against the recorded one, once per
  // sequence, before any of its values leave the reader.
  void verify(const SequenceData& seq) {
    ThrowOnProblem sink;
    check_content(recorded, seq, sink);
    verified.insert(seq.id);
  }
  void verify(const SequenceInfo& info) {
    if (verified.count(info.id)) return;
    if (!recorded.hashes.count(info.id)) {  // unhashed reading allowed (checked at open)
      verified.insert(info.id);
      return;
    }
    verify(read_whole(info));
  }

  void frames(const SequenceInfo& info, std::int64_t first, std::int64_t count, Window& window) {
    layers::data::read_frames(info.shard, group(info), info, first, count, window);
    check_frame_values(window, first, count, info, info.shard);
  }

  void cache(const std::string& id, std::shared_ptr<const SequenceStatic> data) {
    const std::size_t bytes = data->bytes();
    if (bytes > options.cache_bytes) return;  // larger than the whole cache: not kept
    lru.push_front(Entry{id, std::move(data), bytes});
    lru_index[id] = lru.begin();
    cached_bytes += bytes;
    while (cached_bytes > options.cache_bytes && !lru.empty()) {
      cached_bytes -= lru.back().bytes;
      lru_index.erase(lru.back().id);
      lru.pop_back();
    }
  }
};

Dataset::Dataset(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Dataset::Dataset(Dataset&&) noexcept = default;
Dataset& Dataset::operator=(Dataset&&) noexcept = default;
Dataset::~Dataset() = default;

Dataset Dataset::open(const std::string& path, ReaderOptions options) {
  h5::Lock lock;
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->options = options;
  impl->fapl = h5::bounded_access(options.chunk_cache_bytes);
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    const std::string manifest_path = (fs::path(path) / kManifestFile).string();
    if (!fs::exists(manifest_path)) {
      throw InputError(path, kManifestFile, "a dataset folder with dataset.yaml", "no dataset.yaml");
    }
    impl->manifest = read_manifest(manifest_path);
    const auto shards = list_shards(path);
    if (shards.empty()) throw InputError(path, "", "shard files (shard-NNNNN.h5)", "none");
    // The integrity check (integrity.h): shard set, counts, splits and
    // recorded hashes now; each sequence's content on its first read.
    ThrowOnProblem sink;
    check_shard_set(manifest_path, impl->manifest, shards, sink);
    for (const auto& shard : shards) impl->add_shard(shard);
    check_counts(manifest_path, impl->manifest, impl->totals, sink);
    const std::string splits_path = (fs::path(path) / kSplitsFile).string();
    if (!fs::exists(splits_path))
      throw InputError(splits_path, "", "the dataset's splits (train, val, test, ...)", "no such file");
    const SplitsSource source = read_splits_source(splits_path);
    check_splits(source, impl->shard_of_id, sink);
    impl->splits = source.splits;
    impl->recorded = RecordedHashes{manifest_path, "content_hashes", impl->manifest.content_hashes, {}};
    check_recorded_hashes(impl->recorded, impl->shard_of_id, impl->shard_hashes, options.allow_unhashed, sink);
    // Read unhashed (dataset.yaml lacks hashes): a sequence whose shard
    // records its hash is still verified against it (issue 62 S8).
    for (const auto& [shard, own] : impl->shard_hashes)
      for (const auto& [id, hash] : own)
        if (impl->recorded.hashes.emplace(id, hash).second) impl->recorded.from_shard[id] = shard;
    check_stats_hash(path, impl->manifest, options.allow_unhashed, sink);
  } else {
    impl->manifest.name = fs::path(path).stem().string();
    impl->add_shard(path);
    const auto own = impl->shard_hashes.find(path);
    impl->recorded =
        RecordedHashes{path,
                       std::string("/ attribute ") + kContentHashesAttr,
                       own == impl->shard_hashes.end() ? std::map<std::string, std::string>{} : own->second,
                       {}};
    ThrowOnProblem sink;
    check_recorded_hashes(impl->recorded, impl->shard_of_id, {}, options.allow_unhashed, sink);
  }
  impl->manifest.n_sequences = static_cast<std::int64_t>(impl->order.size());
  return Dataset(std::move(impl));
}

const std::string& Dataset::path() const { return impl_->path; }
const DatasetManifest& Dataset::manifest() const { return impl_->manifest; }
const Splits& Dataset::splits() const { return impl_->splits; }
std::vector<std::string> Dataset::ids() const { return impl_->order; }
bool Dataset::contains(const std::string& id) const { return impl_->index.count(id) > 0; }
const SequenceInfo& Dataset::info(const std::string& id) const { return impl_->info(id); }

std::shared_ptr<const SequenceStatic> Dataset::statics(const std::string& id) const {
  h5::Lock lock;
  Impl& d = *impl_;
  const auto hit = d.lru_index.find(id);
  if (hit != d.lru_index.end()) {
    ++d.hits;
    d.lru.splice(d.lru.begin(), d.lru, hit->second);
    return hit->second->data;
  }
  ++d.misses;
  const SequenceInfo& info = d.info(id);
  d.verify(info);
  auto data = std::make_shared<const SequenceStatic>(read_static(info.shard, d.group(info), info));
  d.cache(id, data);
  return data;
}

Window Dataset::read_frames(const std::string& id, std::int64_t first, std::int64_t count) const {
  h5::Lock lock;
  const SequenceInfo& info = impl_->info(id);
  if (first < 0 || count < 1 || first + count > info.n_frames) {
    throw InputError(
        info.shard, "/seq/" + id,
        "frames within [0," + std::to_string(info.n_frames - 1) + "] (n_frames " + std::to_string(info.n_frames) + ")",
        "frames [" + std::to_string(first) + "," + std::to_string(first + count - 1) + "]");
  }
  Window window;
  window.id = id;
  window.first_frame = window.start = first;
  window.n_frames = count;
  window.horizon = count - 1;
  impl_->verify(info);
  impl_->frames(info, first, count, window);
  return window;
}

Window Dataset::read_window(const std::string& id, std::int64_t start, std::int64_t history,
                            std::int64_t horizon) const {
  h5::Lock lock;
  const SequenceInfo& info = impl_->info(id);
  const std::int64_t first = start - history, last = start + horizon;
  if (history < 0 || horizon < 0 || first < 0 || last > info.n_frames - 1) {
    throw InputError(info.shard, "/seq/" + id + " window",
                     "frames within [0," + std::to_string(info.n_frames - 1) + "] (n_frames " +
                         std::to_string(info.n_frames) + ", history and horizon >= 0)",
                     "frames [" + std::to_string(first) + "," + std::to_string(last) + "] (start " +
                         std::to_string(start) + ", history " + std::to_string(history) + ", horizon " +
                         std::to_string(horizon) + ")");
  }
  Window window;
  window.id = id;
  window.first_frame = first;
  window.n_frames = last - first + 1;
  window.start = start;
  window.history = history;
  window.horizon = horizon;
  impl_->verify(info);
  impl_->frames(info, first, window.n_frames, window);
  return window;
}

SequenceData Dataset::read_sequence(const std::string& id) const {
  h5::Lock lock;
  SequenceData seq = impl_->read_whole(impl_->info(id));
  if (!impl_->verified.count(id)) impl_->verify(seq);
  return seq;
}

const ReaderOptions& Dataset::options() const { return impl_->options; }

void Dataset::verify(const std::vector<std::string>& ids) const {
  h5::Lock lock;
  for (const std::string& id : ids) impl_->verify(impl_->info(id));
}

CacheStats Dataset::cache_stats() const {
  h5::Lock lock;
  return CacheStats{impl_->cached_bytes, impl_->lru.size(), impl_->hits, impl_->misses, impl_->files.size()};
}

}  // namespace layers::data
