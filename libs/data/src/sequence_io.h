// sequence_io.h (private) -- reading and writing the arrays of one
// sequence group, given what the index knows of its sizes. Reads check
// dtype and shape against the sizes in SequenceInfo and read per-frame
// arrays by hyperslab.
#pragma once

#include <H5Cpp.h>

#include <cstdint>
#include <string>

#include "layers/data/sequence.h"

namespace layers::data {

SequenceStatic read_static(const std::string& file, const H5::Group& seq, const SequenceInfo& info);
// Frames [first, first + count) into window.body / wind / garments.
void read_frames(const std::string& file, const H5::Group& seq, const SequenceInfo& info, std::int64_t first,
                 std::int64_t count, Window& window);
// Writes a checked sequence as group `id` under `seqs` (/seq).
void write_sequence(H5::Group& seqs, const SequenceData& seq);

}  // namespace layers::data
