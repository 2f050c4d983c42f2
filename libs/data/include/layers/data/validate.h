// layers/data/validate.h -- checking a dataset folder or shard file.
//
// validate_dataset reports every problem it finds, not just the first:
// files that cannot be opened (not HDF5, truncated), missing or wrong root
// attributes, missing datasets, wrong dtypes, ranks and shapes,
// inconsistent sizes, non-finite values (streamed frame block by frame
// block), indices out of range, wind outside 0..400 or non-unit
// quaternions, malformed or missing dataset.yaml / splits.yaml, splits
// naming unknown sequences, duplicate ids across shards; then, with the
// reader's own integrity check (the same code, integrity.h), the shard set,
// counts, recorded hashes and every sequence's content hash.
#pragma once

#include <string>
#include <vector>

namespace layers::data {

struct Problem {
  std::string file;               // file path (with :line for YAML files)
  std::string object;             // HDF5 object path or YAML key; may be empty
  std::string message;            // what is wrong: "expected ..., got ..." or free text
  std::string to_string() const;  // "file: object: message"
};

struct ValidateOptions {
  // A dataset without recorded hashes is valid (those it has are checked);
  // how `layers validate --record-hashes` checks a dataset before it
  // records them.
  bool allow_unhashed = false;
};

std::vector<Problem> validate_dataset(const std::string& path, const ValidateOptions& options = {});

}  // namespace layers::data
