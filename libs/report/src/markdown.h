// report.md's text (internal to the report library): sections built from
// the loaded runs and the charts that were (or could not be) drawn.
#pragma once

#include <string>
#include <vector>

#include "layers/report/charts.h"
#include "layers/report/paired.h"
#include "layers/report/run_results.h"

namespace layers::report {

// The charts of one section, or why there are none.
struct ChartSection {
  std::vector<Chart> charts;  // file names relative to the charts folder
  std::string missing;        // non-empty: why nothing was drawn
};

struct ReportContent {
  std::string title;
  std::vector<RunResults> runs;
  ChartSection speed, by_step, per_type, frames, learning;
  std::vector<PairedComparison> paired;
  // The viewer (viewer.h): its page relative to report.md and what it
  // shows, or why there is none.
  std::string viewer_page, viewer_caption, viewer_missing;
  std::vector<std::string> problems;
  std::string charts_dir = "charts";  // relative to report.md
};

std::string report_markdown(const ReportContent& content);

}  // namespace layers::report
