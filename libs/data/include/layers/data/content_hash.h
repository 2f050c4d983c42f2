// layers/data/content_hash.h -- the content hash of a sequence: 64-bit
// FNV-1a (layers/core/checksum.h) over everything a sequence holds, in a
// fixed order (frame count, motion, seed, tags, shape, every body, wind and
// garment array and attribute). dataset.yaml lists it per sequence
// (`content_hashes`), and `layers validate` recomputes it from the data it
// reads, so any change or damage of a sequence's content shows.
#pragma once

#include <map>
#include <string>

#include "layers/data/sequence.h"

namespace layers::data {

class Dataset;

// 16 hex digits.
std::string sequence_content_hash(const SequenceData& seq);

// Reads every sequence of the dataset folder `folder` and records its
// content hash in the folder's dataset.yaml (rewritten atomically).
void record_content_hashes(const std::string& folder);

}  // namespace layers::data
