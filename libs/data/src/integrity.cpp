// The dataset integrity check shared by the reader and the validator (see
// integrity.h).
#include "integrity.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "h5_io.h"
#include "layers/core/error.h"
#include "layers/data/content_hash.h"
#include "layers/data/stats.h"

namespace layers::data {

namespace fs = std::filesystem;

namespace {

std::string file_name(const std::string& path) { return fs::path(path).filename().string(); }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

constexpr const char* kHowToRecord =
    "record them once with `layers validate --record-hashes <folder>`, or read it unverified with "
    "--allow-unhashed (data.allow_unhashed: true in an experiment)";

}  // namespace

void check_shard_set(const std::string& manifest_path, const DatasetManifest& manifest,
                     const std::vector<std::string>& shard_paths, ProblemSink& sink) {
  std::vector<std::string> present;
  for (const auto& p : shard_paths) present.push_back(file_name(p));
  if (manifest.shards.empty()) {  // written before the list: the count only
    if (manifest.n_shards != static_cast<std::int64_t>(present.size())) {
      sink.report(Problem{manifest_path, "counts.shards",
                          "expected " + std::to_string(manifest.n_shards) + " shard files (as recorded), got " +
                              std::to_string(present.size()) + " in the folder: " + joined(present)});
    }
    return;
  }
  const std::set<std::string> listed(manifest.shards.begin(), manifest.shards.end());
  const std::set<std::string> there(present.begin(), present.end());
  std::vector<std::string> missing, extra;
  for (const auto& n : manifest.shards)
    if (!there.count(n)) missing.push_back(n);
  for (const auto& n : present)
    if (!listed.count(n)) extra.push_back(n);
  if (!missing.empty()) {
    sink.report(Problem{manifest_path, "shards",
                        "expected the listed shard files in " + fs::path(manifest_path).parent_path().string() +
                            ", got " + std::to_string(missing.size()) + " missing: " + joined(missing)});
  }
  if (!extra.empty()) {
    sink.report(Problem{manifest_path, "shards",
                        "expected only the listed shard files, got " + std::to_string(extra.size()) +
                            " more in the folder: " + joined(extra)});
  }
  if (manifest.n_shards != static_cast<std::int64_t>(manifest.shards.size())) {
    sink.report(Problem{manifest_path, "counts.shards",
                        "expected " + std::to_string(manifest.shards.size()) +
                            " (the files listed under shards), got " + std::to_string(manifest.n_shards)});
  }
}

void check_counts(const std::string& manifest_path, const DatasetManifest& manifest, const ShardTotals& found,
                  ProblemSink& sink) {
  const std::tuple<const char*, std::int64_t, std::int64_t, const char*> counts[] = {
      {"counts.sequences", manifest.n_sequences, found.sequences, "sequences"},
      {"counts.frames", manifest.n_frames, found.frames, "frames"},
      {"counts.garments", manifest.n_garments, found.garments, "garments"}};
  for (const auto& [key, recorded, actual, what] : counts) {
    if (recorded != actual) {
      sink.report(Problem{
          manifest_path, key,
          "expected " + std::to_string(actual) + " (the " + what + " in the shards), got " + std::to_string(recorded)});
    }
  }
}

void check_splits(const SplitsSource& source, const std::map<std::string, std::string>& shard_of_id,
                  ProblemSink& sink) {
  // Complete, not only consistent: statistics come from train.
  if (!source.splits.has("train"))
    sink.report(Problem{source.path, "train", "expected a train split (statistics come from it), got none"});
  std::map<std::string, std::string> standard_owner;  // id -> train/val/test split holding it
  for (const auto& name : source.splits.names()) {
    const auto& ids = source.splits.get(name);
    std::set<std::string> in_split;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::string& id = ids[i];
      if (!shard_of_id.count(id)) {
        sink.report(Problem{source.where(name, i), name,
                            "expected ids of sequences in the dataset's shards, got '" + id + "' (in no shard)"});
      }
      if (!in_split.insert(id).second) {
        sink.report(Problem{source.where(name, i), name, "expected each id once, got '" + id + "' twice"});
      }
      if (name == "train" || name == "val" || name == "test") {
        const auto [owner, fresh] = standard_owner.emplace(id, name);
        if (!fresh && owner->second != name) {
          sink.report(Problem{source.where(name, i), name,
                              "expected each sequence in one of train, val and test, got '" + id + "' in both " +
                                  owner->second + " and " + name});
        }
      }
    }
  }
}

std::map<std::string, std::string> shard_content_hashes(const std::string& path, const H5::H5File& file) {
  h5::Lock lock;
  const H5::Group root = file.openGroup("/");
  std::map<std::string, std::string> out;
  const h5::AttrKind kind = h5::attr_kind(root, kContentHashesAttr);
  if (kind == h5::AttrKind::Missing) return out;
  const std::string where = std::string("/ attribute ") + kContentHashesAttr;
  if (kind != h5::AttrKind::String)
    throw InputError(path, where, "strings '<sequence id> <16 hex digits>'", h5::attr_kind_text(kind));
  for (const std::string& entry : h5::attr_strings(root, kContentHashesAttr)) {
    const std::size_t space = entry.find(' ');
    const std::string hash = space == std::string::npos ? "" : entry.substr(space + 1);
    if (space == 0 || hash.size() != 16 || hash.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw InputError(path, where, "strings '<sequence id> <16 hex digits>'", "'" + entry.substr(0, 80) + "'");
    out[entry.substr(0, space)] = hash;
  }
  return out;
}

void write_shard_content_hashes(H5::H5File& file, const std::map<std::string, std::string>& hashes) {
  h5::Lock lock;
  H5::Group root = file.openGroup("/");
  std::vector<std::string> entries;
  for (const auto& [id, hash] : hashes) entries.push_back(id + " " + hash);
  if (!entries.empty()) h5::set_attr(root, kContentHashesAttr, entries);
}

void check_recorded_hashes(const RecordedHashes& recorded, const std::map<std::string, std::string>& shard_of_id,
                           const std::map<std::string, std::map<std::string, std::string>>& shard_hashes,
                           bool allow_unhashed, ProblemSink& sink) {
  if (recorded.hashes.empty()) {
    if (!allow_unhashed && !shard_of_id.empty())
      sink.report(Problem{recorded.where, recorded.key,
                          "expected a content hash per sequence, got none (written before content hashes: " +
                              std::string(kHowToRecord) + ")"});
    return;
  }
  for (const auto& [id, shard] : shard_of_id) {
    if (!recorded.hashes.count(id) && !allow_unhashed)
      sink.report(Problem{recorded.where, recorded.key,
                          "expected a content hash for sequence '" + id + "' (in " + file_name(shard) + "), got none"});
  }
  for (const auto& [id, hash] : recorded.hashes) {
    if (!shard_of_id.count(id))
      sink.report(Problem{recorded.where, recorded.key + "." + id,
                          "expected sequence '" + id +
                              "' in a shard, got it in none (a shard or the sequence is "
                              "missing)"});
  }
  // The shards' own records: each sequence where it was written, with the
  // content it was written with.
  for (const auto& [shard, own] : shard_hashes) {
    for (const auto& [id, hash] : own) {
      const auto at = shard_of_id.find(id);
      const auto listed = recorded.hashes.find(id);
      if (at == shard_of_id.end() || at->second != shard) {
        sink.report(Problem{shard, "/seq/" + id,
                            "expected the sequence written in this shard, got it " +
                                (at == shard_of_id.end() ? std::string("in no shard")
                                                         : "in " + file_name(at->second) + " (moved or swapped)")});
      } else if (listed != recorded.hashes.end() && listed->second != hash) {
        sink.report(Problem{shard, "/seq/" + id,
                            "expected content hash " + listed->second + " (" + file_name(recorded.where) + "), got " +
                                hash + " recorded in the shard (the shard was replaced or edited)"});
      }
    }
  }
  for (const auto& [id, shard] : shard_of_id) {
    const auto own = shard_hashes.find(shard);
    if (own != shard_hashes.end() && !own->second.count(id))
      sink.report(Problem{shard, "/seq/" + id,
                          "expected only the sequences written in this shard, got this one too (renamed, moved or "
                          "added)"});
  }
}

void check_content(const RecordedHashes& recorded, const SequenceData& seq, ProblemSink& sink) {
  const auto it = recorded.hashes.find(seq.id);
  if (it == recorded.hashes.end()) return;  // unhashed reading was allowed (check_recorded_hashes)
  const std::string now = sequence_content_hash(seq);
  const auto shard = recorded.from_shard.find(seq.id);
  if (now != it->second && shard != recorded.from_shard.end())
    sink.report(Problem{shard->second, std::string("/ attribute ") + kContentHashesAttr + "." + seq.id,
                        "expected " + it->second + ", got " + now + " (the sequence changed since it was written)"});
  else if (now != it->second)
    sink.report(Problem{recorded.where, recorded.key + "." + seq.id,
                        "expected " + it->second + ", got " + now + " (the sequence changed since it was written)"});
}

void check_stats_hash(const std::string& folder, const DatasetManifest& manifest, bool allow_unhashed,
                      ProblemSink& sink) {
  const std::string stats = (fs::path(folder) / "stats.h5").string();
  const std::string manifest_path = (fs::path(folder) / "dataset.yaml").string();
  if (!fs::exists(stats)) return;  // whoever needs it says so
  if (manifest.stats_hash.empty()) {
    if (!allow_unhashed)
      sink.report(Problem{manifest_path, "stats_hash",
                          "expected the content hash of stats.h5, got none (" + std::string(kHowToRecord) + ")"});
    return;
  }
  const std::string now = stats_content_hash(read_stats(stats));
  if (now != manifest.stats_hash)
    sink.report(Problem{stats, "",
                        "expected content hash " + manifest.stats_hash + " (dataset.yaml stats_hash), got " + now +
                            " (the statistics changed since they were written; remove the file and run `layers "
                            "stats` on the folder to compute them again)"});
}

}  // namespace layers::data
