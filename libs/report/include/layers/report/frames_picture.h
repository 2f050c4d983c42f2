// layers/report/frames_picture.h -- ground truth and predictions side by
// side: one row for the dataset's ground truth and one per run (its
// eval-<split>/predictions.h5), one column per chosen frame of one
// sequence. Meshes are seen from the front (mesh_view.h): the body light
// grey (back faces culled), inner garments blue, outer garments orange.
// Each panel's polygons are a data file next to the script.
#pragma once

#include <string>
#include <vector>

#include "layers/report/charts.h"
#include "layers/report/gnuplot.h"
#include "layers/report/run_results.h"

namespace layers::report {

struct PictureOptions {
  // Ground-truth dataset; empty: each run's data.dataset, looked up as
  // written, then relative to the run folder and each of its parents.
  std::string dataset;
  // Sequence to show; empty: the first sequence of the first run's
  // predictions that every run with predictions has.
  std::string sequence;
  int frames = 4;  // columns, spread evenly over the predicted frames
};

// Runs without predictions (or without the sequence) and a ground truth
// that cannot be read are left out of the picture and described in
// `notes`. Throws layers::Error when there is nothing to draw.
Chart frames_picture(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs,
                     const PictureOptions& options, std::vector<std::string>& notes);

// Frames to show: `count` frames spread evenly over [2, n_frames - 1] (the
// predicted frames; frames 0 and 1 are the ground truth a rollout starts
// from), fewer when the sequence is shorter.
std::vector<std::int64_t> picture_frames(std::int64_t n_frames, int count);

}  // namespace layers::report
