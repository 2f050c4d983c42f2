// dataset_files.h (private) -- names of the files in a dataset folder and
// indexing of shard files (ids, sizes, attributes; no array data).
#pragma once

#include <H5Cpp.h>

#include <string>
#include <vector>

#include "layers/data/sequence.h"

namespace layers::data {

inline constexpr const char* kManifestFile = "dataset.yaml";
inline constexpr const char* kSplitsFile = "splits.yaml";
inline constexpr const char* kStatsFile = "stats.h5";

// shard-*.h5 files of a folder (temporaries excluded), sorted by name.
std::vector<std::string> list_shards(const std::string& folder);
// Checks the root attributes and the structure of every sequence of an
// open shard; throws InputError on the first problem.
std::vector<SequenceInfo> index_shard(const std::string& path, const H5::H5File& file);

}  // namespace layers::data
