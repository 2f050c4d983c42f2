// Dataset folder listing and shard indexing (see dataset_files.h).
#include "dataset_files.h"

#include <algorithm>
#include <filesystem>

#include "h5_io.h"
#include "shard_layout.h"

namespace layers::data {

std::vector<std::string> list_shards(const std::string& folder) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || name.rfind("shard-", 0) != 0) continue;
    if (name.size() < 9 || name.compare(name.size() - 3, 3, ".h5") != 0) continue;
    out.push_back(entry.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<SequenceInfo> index_shard(const std::string& path, const H5::H5File& file) {
  h5::Lock lock;
  return h5::guard(path, "", [&] {
    ThrowOnProblem sink;
    check_root(path, file, sink);
    std::vector<SequenceInfo> infos;
    for (const auto& id : sequence_ids(path, file, sink)) {
      const H5::Group seq = file.openGroup("/seq/" + id);
      infos.push_back(inspect_sequence(path, seq, id, sink).info);
    }
    return infos;
  });
}

}  // namespace layers::data
