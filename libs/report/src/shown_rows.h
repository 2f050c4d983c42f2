// Which rows the report's picture and viewer show (internal): the runs
// with readable predictions of one sequence, and the dataset's ground
// truth above them when it can be found. One choice for both, so the
// still picture and the viewer always show the same scene.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "layers/data/dataset.h"
#include "layers/report/frames_picture.h"
#include "layers/report/run_results.h"

namespace layers::report {

struct ShownRow {
  std::string label;                      // "ground truth" or the run's name
  std::shared_ptr<data::Dataset> source;  // the dataset or the run's predictions.h5
};

struct ShownRows {
  std::string sequence;
  std::vector<ShownRow> rows;  // the ground truth first when has_truth
  bool has_truth = false;
  std::int64_t n_frames = 0;  // frames every row has
};

// Runs without predictions or without the sequence, and a ground truth
// that cannot be found, are left out and described in `notes` (prefixed
// with `what`). Throws layers::Error when no run has predictions of the
// sequence.
ShownRows shown_rows(const std::vector<RunResults>& runs, const PictureOptions& options, const std::string& what,
                     std::vector<std::string>& notes);

}  // namespace layers::report
