// layers/data/content_hash.h -- the content hash of a sequence: 64-bit
// FNV-1a (layers/core/checksum.h) over everything a sequence holds, in a
// fixed order (frame count, motion, seed, tags, shape, every body, wind and
// garment array and attribute). dataset.yaml lists it per sequence
// (`content_hashes`), each shard in its root attributes, and every reader
// recomputes it when it first reads the sequence (integrity.h), so any
// change or damage of a sequence's content shows.
#pragma once

#include <map>
#include <string>

#include "layers/data/sequence.h"

namespace layers::data {

class Dataset;

// 16 hex digits.
std::string sequence_content_hash(const SequenceData& seq);

// Records in the folder's dataset.yaml (rewritten atomically) what the
// readers verify (integrity.h): the shard file list, the content hash of
// every sequence (read in full; a hash recorded already is verified, not
// replaced) and, when stats.h5 exists, its hash. The writers call it when
// a dataset is complete; `layers validate --record-hashes` calls it to
// migrate a dataset written before.
void record_integrity(const std::string& folder);

}  // namespace layers::data
