// Writing a dataset folder: shards, dataset.yaml, splits.yaml (see
// dataset_writer.h).
#include "layers/data/dataset_writer.h"

#include "layers/data/content_hash.h"

#include <cstdio>
#include <filesystem>
#include <set>

#include "dataset_files.h"
#include "h5_io.h"
#include "layers/core/error.h"
#include "layers/data/manifest.h"
#include "layers/data/shard_writer.h"

namespace layers::data {

namespace fs = std::filesystem;

std::string shard_file_name(std::int64_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "shard-%05lld.h5", static_cast<long long>(index));
  return name;
}

struct DatasetWriter::Impl {
  std::string folder;
  DatasetWriterOptions options;
  std::unique_ptr<ShardWriter> current;
  std::int64_t next_shard = 0, n_shards = 0;
  std::vector<std::string> ids;  // committed, in order
  std::set<std::string> known;   // committed and pending
  std::vector<std::string> pending;
  std::int64_t n_frames = 0, n_garments = 0, pending_frames = 0, pending_garments = 0;
  Splits splits;

  std::string path(const std::string& name) const { return (fs::path(folder) / name).string(); }

  void resume_existing(const std::vector<std::string>& shards) {
    for (const auto& shard : shards) {
      const H5::H5File file = h5::open_read(shard);
      for (const auto& info : index_shard(shard, file)) {
        if (!known.insert(info.id).second) {
          throw InputError(shard, "/seq/" + info.id, "ids unique across shards", "a duplicate id");
        }
        ids.push_back(info.id);
        n_frames += info.n_frames;
        n_garments += static_cast<std::int64_t>(info.garments.size());
      }
      const std::string name = fs::path(shard).filename().string();
      next_shard = std::max<std::int64_t>(next_shard, std::stoll(name.substr(6, name.size() - 9)) + 1);
      ++n_shards;
    }
  }

  void commit_current() {
    if (!current) return;
    if (current->size() == 0) {  // only rejected sequences: nothing to keep
      current.reset();
      return;
    }
    current->commit();
    current.reset();
    ids.insert(ids.end(), pending.begin(), pending.end());
    pending.clear();
    n_frames += pending_frames;
    n_garments += pending_garments;
    pending_frames = pending_garments = 0;
    ++n_shards;
  }
};

DatasetWriter::DatasetWriter(std::string folder, DatasetWriterOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->folder = std::move(folder);
  impl_->options = std::move(options);
  if (impl_->options.sequences_per_shard < 1) {
    throw InputError(impl_->folder, "sequences_per_shard", "at least 1",
                     std::to_string(impl_->options.sequences_per_shard));
  }
  std::error_code ec;
  fs::create_directories(impl_->folder, ec);
  if (!fs::is_directory(impl_->folder)) {
    throw InputError::message(impl_->folder, "", "cannot create the dataset folder: " + ec.message());
  }
  const auto existing = list_shards(impl_->folder);
  if (!existing.empty() && !impl_->options.resume) {
    throw InputError(impl_->folder, "", "an empty dataset folder (or resume)",
                     std::to_string(existing.size()) + " shard files already there");
  }
  if (impl_->options.resume) impl_->resume_existing(existing);
}

DatasetWriter::~DatasetWriter() = default;

bool DatasetWriter::contains(const std::string& id) const { return impl_->known.count(id) > 0; }

void DatasetWriter::add(const SequenceData& seq) {
  Impl& w = *impl_;
  if (w.known.count(seq.id)) {
    throw InputError(w.folder, "/seq/" + seq.id, "a sequence id not yet in the dataset", "a duplicate id");
  }
  if (!w.current) w.current = std::make_unique<ShardWriter>(w.path(shard_file_name(w.next_shard++)));
  w.current->append(seq);
  w.known.insert(seq.id);
  w.pending.push_back(seq.id);
  w.pending_frames += seq.n_frames;
  w.pending_garments += static_cast<std::int64_t>(seq.garments.size());
  if (static_cast<std::int64_t>(w.current->size()) >= w.options.sequences_per_shard) w.commit_current();
}

void DatasetWriter::set_split(const std::string& name, std::vector<std::string> ids) {
  impl_->splits.set(name, std::move(ids));
}

void DatasetWriter::finish() {
  Impl& w = *impl_;
  w.commit_current();
  const std::string splits_path = w.path(kSplitsFile);
  for (const auto& name : w.splits.names()) {
    for (const auto& id : w.splits.get(name)) {
      if (!w.known.count(id)) throw InputError(splits_path, name, "ids of sequences in the dataset", "'" + id + "'");
    }
  }
  DatasetManifest manifest;
  manifest.name = w.options.name;
  manifest.seed = w.options.seed;
  manifest.sequences_per_shard = w.options.sequences_per_shard;
  manifest.n_sequences = static_cast<std::int64_t>(w.ids.size());
  manifest.n_frames = w.n_frames;
  manifest.n_garments = w.n_garments;
  manifest.n_shards = w.n_shards;
  manifest.generator_yaml = w.options.generator_config_yaml;
  // Every dataset has a train split (readers refuse one without it), empty
  // when nothing was put there: statistics come from it.
  if (!w.splits.has("train")) w.splits.set("train", {});
  write_splits(splits_path, w.splits);
  write_manifest(w.path(kManifestFile), manifest);
  record_integrity(w.folder);
}

std::vector<std::string> DatasetWriter::ids() const {
  std::vector<std::string> out = impl_->ids;
  out.insert(out.end(), impl_->pending.begin(), impl_->pending.end());
  return out;
}

}  // namespace layers::data
