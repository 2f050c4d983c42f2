// tests/unit/report/predictions_fixture.h -- a tiny synthetic dataset and
// run folders whose eval-test/predictions.h5 drift from it by a known
// offset: what the report's picture and viewer read.
#pragma once

#include <string>
#include <vector>

#include "layers/data/dataset_writer.h"
#include "layers/data/shard_writer.h"
#include "report_fixtures.h"
#include "synthetic_sequence.h"
#include "temp_dir.h"

namespace layers::report::testing {

// A dataset with two short sequences and, per run, predictions of both
// (the garments shifted by `offset` after frame 1, as a rollout would drift).
struct PredictionsFixture {
  layers::test::TempDir dir;
  std::string dataset = dir.file("dataset");
  std::vector<data::SequenceData> sequences;

  explicit PredictionsFixture(const std::string& tag = "report-charts") : dir(tag) {
    data::testing::SyntheticSize size;
    size.frames = 8;
    data::DatasetWriter writer(dataset);
    for (int k = 0; k < 2; ++k) {
      sequences.push_back(data::testing::make_sequence("seq-" + std::to_string(k), 7 + k, size));
      writer.add(sequences.back());
    }
    writer.set_split("test", {"seq-0", "seq-1"});
    writer.finish();
  }

  std::string run(const std::string& name, FakeRun r, float offset) {
    r.dataset = dataset;
    const std::string folder = testing::write_run(dir, name, r);
    std::vector<data::SequenceData> predicted = sequences;
    for (data::SequenceData& s : predicted)
      for (data::GarmentData& g : s.garments) {
        const std::size_t per_frame = g.positions.size() / static_cast<std::size_t>(s.n_frames);
        for (std::size_t i = 2 * per_frame; i < g.positions.size(); ++i) g.positions[i] += offset * (i % 3 == 0);
      }
    data::write_shard(folder + "/eval-test/predictions.h5", predicted);
    return folder;
  }
};

}  // namespace layers::report::testing
