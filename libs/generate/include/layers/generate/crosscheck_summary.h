// layers/generate/crosscheck_summary.h -- `layers crosscheck` over several
// scenes: each scene's columns saved as columns.tsv beside its table.md
// (read back when a run over many scenes resumes), and one markdown table
// of every measure as a mean over scenes with its 95% interval
// (core/interval.h), then ours against each Blender setup per scene,
// paired.
#pragma once

#include <string>
#include <vector>

#include "layers/generate/crosscheck.h"

namespace layers::generate {

// Tab-separated: a header line of field names, then one line per column.
std::string crosscheck_columns_tsv(const std::vector<CrosscheckColumn>& columns);
// InputError naming `file` when a line or field does not parse.
std::vector<CrosscheckColumn> parse_crosscheck_columns(const std::string& text, const std::string& file);

// One scene's columns with its title.
struct CrosscheckSceneColumns {
  std::string title;
  std::vector<CrosscheckColumn> columns;
};

// Markdown: the columns of every scene matched by label (a scene without
// a column counts as missing there), one row per measure with mean and
// 95% interval over the scenes; then the paired differences of our stored
// ground truth minus each Blender column, and our time simulated again
// over each Blender column's, per scene.
std::string crosscheck_summary(const std::vector<CrosscheckSceneColumns>& scenes);

}  // namespace layers::generate
