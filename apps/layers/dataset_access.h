// apps/layers/dataset_access.h -- how the verbs that read a dataset given
// on the command line open it: with the reader's integrity check, and an
// --allow-unhashed flag for a dataset written before content hashes.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "layers/data/dataset.h"

namespace layers::app {

// Adds --allow-unhashed to `cmd`, bound to `allow`.
void add_allow_unhashed(CLI::App& cmd, bool& allow);
// Opens `path`; with `allow_unhashed`, says on stderr that sequences
// without a recorded hash are read unverified.
data::Dataset open_dataset(const std::string& path, bool allow_unhashed);

}  // namespace layers::app
