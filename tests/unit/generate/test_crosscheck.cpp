// Tests of the `layers crosscheck` measures and files (generate/crosscheck.h,
// crosscheck_scene.h) on hand-made sequences: a known stretch, vertices
// behind a normal plane at known distances, the table, crosscheck.json,
// and Blender's results read back, including the PC2 that the Python
// writer of scripts/blender/crosscheck_sim.py makes (run with python3,
// without Blender); and our solver simulating a generated scene again.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/manifest.h"
#include "layers/data/pc2.h"
#include "layers/generate/crosscheck.h"
#include "layers/generate/crosscheck_scene.h"
#include "layers/generate/crosscheck_summary.h"
#include "layers/generate/generator.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/resimulate.h"
#include "run_command.h"
#include "temp_dir.h"
#include "test_paths.h"

using namespace layers;
using generate::CrosscheckRun;

namespace {

// A 3x3 vertex patch in the xz-plane at height y (5 cm spacing), faces
// wound so that the normals point up (+y).
void patch(float y, std::vector<float>& xyz, std::vector<std::int32_t>& faces) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) xyz.insert(xyz.end(), {0.05f * (c - 1), y, 0.05f * (r - 1)});
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) {
      const int a = 3 * r + c, b = a + 1, d = a + 3, e = d + 1;
      faces.insert(faces.end(), {a, d, b, b, d, e});
    }
  }
}

// Body: an octahedron of radius 0.5 whose top vertex is (0, 1, 0); an
// inner patch 3 cm above it and an outer patch 5 cm above it; 3 frames,
// all at rest.
data::SequenceData scene() {
  data::SequenceData seq;
  seq.id = "s";
  seq.n_frames = 3;
  const std::vector<float> body = {0.5f, 0.5f, 0, -0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 0, 0, 0.5f, 0.5f, 0, 0.5f, -0.5f};
  seq.body.faces = {2, 4, 0, 2, 1, 4, 2, 5, 1, 2, 0, 5, 3, 0, 4, 3, 4, 1, 3, 1, 5, 3, 5, 0};
  for (int t = 0; t < 3; ++t) seq.body.positions.insert(seq.body.positions.end(), body.begin(), body.end());
  seq.body.skin_index.assign(6 * 4, 0);  // the vertex count comes from the skinning arrays
  seq.body.skin_weight.assign(6 * 4, 0.25f);
  for (int k = 0; k < 2; ++k) {
    data::GarmentData g;
    g.type = k == 0 ? "tshirt" : "jacket";
    g.name = g.type;
    g.layer = k;
    patch(k == 0 ? 1.03f : 1.05f, g.rest, g.faces);
    for (int t = 0; t < 3; ++t) g.positions.insert(g.positions.end(), g.rest.begin(), g.rest.end());
    seq.garments.push_back(std::move(g));
  }
  return seq;
}

CrosscheckRun as_stored(const data::SequenceData& seq, const std::string& label) {
  CrosscheckRun run;
  run.label = label;
  for (const auto& g : seq.garments) run.garments.push_back(g.positions);
  return run;
}

float& coord(CrosscheckRun& run, int garment, int frame, int vertex, int axis) {
  return run.garments[static_cast<std::size_t>(garment)][static_cast<std::size_t>((frame * 9 + vertex) * 3 + axis)];
}

}  // namespace

TEST(Crosscheck, RestingSceneHasNoStretchNoPenetration) {
  const data::SequenceData seq = scene();
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, as_stored(seq, "ours"));
  EXPECT_EQ(c.frames, 2);
  EXPECT_NEAR(c.stretch_p99, 0.0, 1e-6);
  EXPECT_NEAR(c.stretch_max, 0.0, 1e-6);
  EXPECT_EQ(c.h, 0.0);
  EXPECT_EQ(c.l_1cm, 0.0);
  EXPECT_EQ(c.l_all, 0.0);
  EXPECT_EQ(c.nonfinite, 0);
}

TEST(Crosscheck, KnownStretchFromFrameOneOn) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "stretched");
  // Frames 1 and 2: the outer patch 10% wider along x (about its centre).
  for (int t = 1; t < 3; ++t)
    for (int v = 0; v < 9; ++v) coord(run, 1, t, v, 0) *= 1.1f;
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, run);
  EXPECT_NEAR(c.stretch_max, 0.10, 1e-5);
  EXPECT_NEAR(c.gen_stretch_max, 0.10, 1e-5);
  // Edges per patch: 6 along x (10%), 6 along z (0%), 4 diagonals (5%);
  // the p99 over 2 frames x 32 edges is a 10% edge.
  EXPECT_NEAR(c.stretch_p99, 0.10, 1e-5);
}

TEST(Crosscheck, VertexBehindTheInnerPlaneCountsByDistance) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "crossing");
  // Frame 1: the outer centre vertex 0.5 cm under the inner centre vertex
  // (within 1 cm); frame 2: the outer corner vertex 2 cm under the inner
  // corner (within 3 cm, not 1 cm), still above the body.
  coord(run, 1, 1, 4, 1) = 1.025f;
  coord(run, 1, 2, 0, 1) = 1.01f;
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, run);
  EXPECT_NEAR(c.l_1cm, 1.0 / 18, 1e-9);  // 1 of 9 outer vertices x 2 frames
  EXPECT_NEAR(c.l_3cm, 2.0 / 18, 1e-9);
  EXPECT_NEAR(c.l_all, 2.0 / 18, 1e-9);
  EXPECT_EQ(c.h, 0.0);
}

TEST(Crosscheck, TiltedOuterPatchCrossesTheInnerOne) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "tilted");
  // Frame 1 only: the outer patch shifted off the inner grid lines and
  // tilted through the inner patch's plane (y 1.03) along x = 0.025.
  for (int v = 0; v < 9; ++v) {
    coord(run, 1, 1, v, 0) += 0.011f;
    coord(run, 1, 1, v, 2) += 0.007f;
    coord(run, 1, 1, v, 1) = 1.03f + 0.4f * coord(run, 1, 1, v, 0) - 0.01f;
  }
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, run);
  EXPECT_GT(c.l_crossing_max, 0.0);
  EXPECT_NEAR(c.l_crossing, c.l_crossing_max / 2, 1e-12);  // frame 2 rests again
  EXPECT_EQ(c.h_crossing_max, 0.0);
  const generate::CrosscheckColumn rest = generate::measure_crosscheck(seq, as_stored(seq, "ours"));
  EXPECT_EQ(rest.l_crossing_max, 0.0);
}

TEST(Crosscheck, StartIsFrameZeroAndGoesBelowTheTable) {
  data::SequenceData seq = scene();
  seq.garments[1].positions[4 * 3 + 1] = 1.025f;  // frame 0: outer centre under the inner patch
  const sim::FrameMeasures start = generate::measure_start(seq);
  EXPECT_EQ(start.h_penetration, 0.0);
  generate::CrosscheckColumn ours;
  ours.label = "ours";
  const std::string table = generate::crosscheck_table("", {ours}, &start);
  EXPECT_NE(table.find("\nFrame 0 (stored; every column starts from it): H 0.00%,"), std::string::npos) << table;
}

TEST(Crosscheck, GarmentVertexBehindTheBody) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "inside");
  coord(run, 0, 1, 4, 1) = 0.99f;  // inner centre 1 cm under the body's top vertex
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, run);
  EXPECT_NEAR(c.h, 1.0 / 36, 1e-9);  // 1 of 18 garment vertices x 2 frames
  EXPECT_NEAR(c.gen_h, 1.0 / 36, 1e-9);
}

TEST(Crosscheck, NonFiniteFramesAreCountedNotMeasured) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "nan");
  coord(run, 0, 2, 3, 0) = std::nanf("");
  const generate::CrosscheckColumn c = generate::measure_crosscheck(seq, run);
  EXPECT_EQ(c.nonfinite, 1);
  EXPECT_NEAR(c.stretch_max, 0.0, 1e-6);
}

TEST(Crosscheck, RunMustMatchTheSequence) {
  const data::SequenceData seq = scene();
  CrosscheckRun run = as_stored(seq, "short");
  run.garments[1].resize(9 * 3 * 2);
  EXPECT_THROW(generate::measure_crosscheck(seq, run), InputError);
  run.garments.pop_back();
  EXPECT_THROW(generate::measure_crosscheck(seq, run), InputError);
}

TEST(Crosscheck, QuantileIsNearestRank) {
  std::vector<float> v = {5, 1, 4, 2, 3};
  EXPECT_EQ(generate::quantile(v, 0.0), 1.0);
  EXPECT_EQ(generate::quantile(v, 0.5), 3.0);
  EXPECT_EQ(generate::quantile(v, 1.0), 5.0);
  std::vector<float> empty;
  EXPECT_EQ(generate::quantile(empty, 0.99), 0.0);
}

TEST(Crosscheck, TableHasOneColumnPerRunAndMarksWhatIsMissing) {
  generate::CrosscheckColumn ours, blender;
  ours.label = "ours";
  blender.label = "Blender, merged";
  blender.ms_per_frame = 1234.4;
  blender.l_1cm = 0.0028;
  const std::string table = generate::crosscheck_table("T", {ours, blender});
  EXPECT_EQ(table.rfind("T\n\n|  | ours | Blender, merged |\n|---|---|---|\n", 0), 0u) << table;
  EXPECT_NE(table.find("| ms per frame | n/a | 1234 |"), std::string::npos) << table;
  EXPECT_NE(table.find("within 1 cm of it | 0.00% | 0.28% |"), std::string::npos) << table;
  EXPECT_NE(
      table.find("| layer crossings: share of outer vertices on crossing faces, mean (worst frame) | 0.00% (0.00%) |"),
      std::string::npos)
      << table;
}

TEST(Crosscheck, ManifestNamesMeshesLayersAttributesWindAndGaps) {
  const data::SequenceData seq = scene();
  std::vector<data::GarmentStatic> garments(seq.garments.begin(), seq.garments.end());
  garments[0].attributes = {{"mass", 0.25}};
  garments[1].type = "jacket_hood";
  data::WindData wind;
  wind.rotation = {1, 0, 0, 0, 0.5f, 0.5f, 0.5f, 0.5f, 9, 9, 9, 9};
  wind.strength = {0, 300, 9};
  const generate::CrosscheckGaps gaps{0.005, 0.004, 0.003, true};
  const std::string json = generate::crosscheck_manifest("s_", {"tshirt", "jacket_hood"}, garments, wind, 2, gaps);
  EXPECT_NE(json.find("\"prefix\": \"s_\""), std::string::npos) << json;
  EXPECT_NE(json.find("{\"mesh\": \"tshirt\", \"type\": \"tshirt\", \"layer\": 0, \"self_collision\": false, "
                      "\"attributes\": {\"mass\": 0.25}}"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"layer\": 1, \"self_collision\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"rotation\": [1,0,0,0,0.5,0.5,0.5,0.5], \"strength\": [0,300]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"gaps\": {\"body\": 0.005, \"layer\": 0.004, \"self\": 0.003}"), std::string::npos) << json;
  EXPECT_THROW(generate::crosscheck_manifest("s_", {"one"}, garments, wind, 2, gaps), Error);
}

// A manifest without a generator config gives the solver's defaults.
TEST(Crosscheck, GapsAreTheRecordedSolverConfigsOrTheDefaults) {
  data::DatasetManifest manifest;
  const generate::CrosscheckGaps defaults = generate::crosscheck_gaps(manifest, "dataset.yaml");
  EXPECT_FALSE(defaults.recorded);
  EXPECT_DOUBLE_EQ(defaults.body, sim::SolverConfig().body_thickness);
  manifest.generator_yaml = "sim:\n  body_thickness: 0.007\n  self_thickness: 0.002\n";
  const generate::CrosscheckGaps recorded = generate::crosscheck_gaps(manifest, "dataset.yaml");
  EXPECT_TRUE(recorded.recorded);
  EXPECT_DOUBLE_EQ(recorded.body, 0.007);
  EXPECT_DOUBLE_EQ(recorded.layer, sim::SolverConfig().layer_thickness);
  EXPECT_DOUBLE_EQ(recorded.self, 0.002);
}

// crosscheck_sim.py's blender_distances inverts Blender 3.4.1's 8/9 rule:
// (distance_min + thickness_outer) * 8/9 and 2 * self_distance_min * 8/9
// give our gaps back.
TEST(Crosscheck, PythonMapsOurGapsToBlendersDistances) {
  if (std::system("python3 -c 'import struct' > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  const std::string script = test::source_dir() + "/scripts/blender/crosscheck_sim.py";
  const std::string code =
      "import importlib.util as u; s = u.spec_from_file_location('c', '" + script +
      "'); m = u.module_from_spec(s); s.loader.exec_module(m); g = {'body': 0.005, 'layer': 0.004, 'self': 0.003}; "
      "e = 8.0 / 9; "
      "d = m.blender_distances(g, False); "
      "print('%.6f %.6f %.6f' % ((d['cloth_distance'] + d['body_thickness_outer']) * e, "
      "(d['cloth_distance'] + d['layer_thickness_outer']) * e, 2 * d['self_distance'] * e)); "
      "print('%.6f' % (2 * m.blender_distances(g, True)['self_distance'] * e))";
  const auto r = test::run_command("python3 -c \"" + code + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "0.005000 0.004000 0.003000\n0.004000\n");
}

TEST(Crosscheck, ReadsBlenderResultsAndRefusesWrongSizes) {
  test::TempDir dir;
  const data::SequenceData seq = scene();
  generate::CrosscheckScene sc;
  sc.meshes = {"tshirt", "jacket"};
  sc.frames = 3;
  for (std::size_t k = 0; k < 2; ++k)
    data::write_pc2(dir.file(sc.meshes[k] + ".pc2"), {{9, 0.0f, 1.0f, 3}, seq.garments[k].positions});
  dir.write("timing.txt", "ms_per_frame 812.500\nframes 2\nsetup merged\n");
  const CrosscheckRun run = generate::read_crosscheck_run("Blender", dir.path(), sc, seq);
  EXPECT_EQ(run.ms_per_frame, 812.5);
  ASSERT_EQ(run.garments.size(), 2u);
  EXPECT_EQ(run.garments[1], seq.garments[1].positions);

  sc.frames = 4;  // more frames than Blender wrote
  EXPECT_THROW(generate::read_crosscheck_run("Blender", dir.path(), sc, seq), InputError);
  sc.frames = 3;
  sc.meshes[1] = "missing";
  EXPECT_THROW(generate::read_crosscheck_run("Blender", dir.path(), sc, seq), InputError);
}

// The PC2 written by crosscheck_sim.py's write_pc2 (Python's struct, run
// with python3 outside Blender) reads back with data::read_pc2.
TEST(Crosscheck, PythonPc2WriterRoundTrip) {
  if (std::system("python3 -c 'import struct' > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  test::TempDir dir;
  const std::string script = test::source_dir() + "/scripts/blender/crosscheck_sim.py";
  const std::string out = dir.file("g.pc2");
  const std::string code = "import importlib.util as u; s = u.spec_from_file_location('c', '" + script +
                           "'); m = u.module_from_spec(s); s.loader.exec_module(m); "
                           "m.write_pc2('" +
                           out + "', [[0.5, -1, 2, 3, 4, 5.25], [6, 7, 8, 9, 10, -11.125]], 2)";
  const auto r = test::run_command("python3 -c \"" + code + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const data::Pc2Cache cache = data::read_pc2(out);
  EXPECT_EQ(cache.header.n_points, 2);
  EXPECT_EQ(cache.header.n_samples, 2);
  EXPECT_EQ(cache.header.start_frame, 0.0f);
  EXPECT_EQ(cache.header.sample_rate, 1.0f);
  EXPECT_EQ(cache.positions, (std::vector<float>{0.5f, -1, 2, 3, 4, 5.25f, 6, 7, 8, 9, 10, -11.125f}));
}

TEST(Crosscheck, OursSimulatedAgainEqualsTheStoredFramesAndIsTimed) {
  // One short, coarse scene of configs/data/tiny.yaml made by the
  // generator, then simulated again from the folder's generator.yaml.
  test::TempDir dir;
  cfg::Node tree = cfg::load_file(test::source_dir() + "/configs/data/tiny.yaml");
  for (const char* set :
       {"sequences=1", "frames=3", "drape_frames=2", "body.transition_frames=2", "garments.fit.edge_length=0.1",
        "sim.validation.max_h_penetration=1", "sim.validation.max_l_penetration=1", "sim.validation.max_stretch=100",
        "sim.validation.max_h_crossing_clear=1", "splits.val=0", "splits.test=0"})
    cfg::apply_set(tree, set);
  const auto config = cfg::read<generate::GeneratorConfig>(tree);
  generate::GenerateOptions options;
  options.out = dir.file("ds");
  options.progress = false;
  const generate::GenerateReport report =
      generate::generate_dataset(config, cfg::to_yaml(cfg::to_node(config)), options);
  ASSERT_EQ(report.written, 1);
  const data::Dataset ds = data::Dataset::open(options.out);
  const data::SequenceData stored = ds.read_sequence("seq-000000");
  const CrosscheckRun again = generate::resimulate_ours(options.out, "seq-000000", 3);
  EXPECT_GT(again.ms_per_frame, 0.0);
  ASSERT_EQ(again.garments.size(), stored.garments.size());
  for (std::size_t g = 0; g < stored.garments.size(); ++g) EXPECT_EQ(again.garments[g], stored.garments[g].positions);
  // Not a sequence the generator made, more frames than it recorded, no
  // generator.yaml: one line each.
  const auto message = [&](const std::string& folder, const std::string& id, std::int64_t frames) {
    try {
      generate::resimulate_ours(folder, id, frames);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(options.out, "a", 3).find("seq-NNNNNN"), std::string::npos);
  EXPECT_NE(message(options.out, "seq-000000", 4).find("frames"), std::string::npos);
  EXPECT_NE(message(dir.file("none"), "seq-000000", 3).find("generator.yaml"), std::string::npos);

  // At half the fit's edge length (`layers bench --simulator`'s next
  // level): the same scene with about 4x the garment vertices, timed, no
  // positions kept; an edge length outside the fit's range is one line.
  std::int64_t stored_vertices = 0;
  for (const auto& g : stored.garments) stored_vertices += g.n_vertices();
  generate::ResimulateOptions finer;
  finer.edge_scale = 0.5;
  finer.keep_positions = false;
  const generate::Resimulation fine = generate::resimulate(options.out, "seq-000000", 2, finer);
  EXPECT_GT(fine.garment_vertices, 3 * stored_vertices);
  EXPECT_LT(fine.garment_vertices, 5 * stored_vertices);
  EXPECT_GT(fine.wall_ms_per_frame, 0.0);
  EXPECT_GT(fine.cpu_ms_per_frame, 0.0);
  EXPECT_TRUE(fine.garments.empty());
  generate::ResimulateOptions too_fine;
  too_fine.edge_scale = 0.01;
  try {
    generate::resimulate(options.out, "seq-000000", 2, too_fine);
    ADD_FAILURE() << "an edge length of 1 mm was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("garments.fit.edge_length x 0.01"), std::string::npos) << e.what();
  }
}

// Several scenes: the columns written to columns.tsv read back equal
// (NaN included), and the summary's means, intervals and paired
// differences are the hand-worked ones.
TEST(CrosscheckSummary, ColumnsRoundTripAndPairedIntervals) {
  std::vector<generate::CrosscheckSceneColumns> scenes;
  for (double blender : {0.020, 0.021, 0.022}) {
    generate::CrosscheckColumn ours, other;
    ours.label = generate::kOursStored;
    ours.frames = other.frames = 3;
    other.label = "Blender, merged";
    other.ms_per_frame = 500;
    other.l_crossing = blender;
    ours.stretch_p99 = 0.08;
    other.stretch_p99 = 0.08;
    scenes.push_back({"scene", {ours, other}});
  }
  const std::string tsv = generate::crosscheck_columns_tsv(scenes[1].columns);
  const auto back = generate::parse_crosscheck_columns(tsv, "columns.tsv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].label, "Blender, merged");
  EXPECT_EQ(back[1].frames, 3);
  EXPECT_DOUBLE_EQ(back[1].l_crossing, 0.021);
  EXPECT_TRUE(std::isnan(back[0].ms_per_frame));
  EXPECT_THROW(generate::parse_crosscheck_columns("label\tframes\nx\t1\n", "columns.tsv"), InputError);
  EXPECT_THROW(generate::parse_crosscheck_columns("nonsense", "columns.tsv"), InputError);

  const std::string md = generate::crosscheck_summary(scenes);
  // Blender's mean 2.10%, half-width 4.303 * 0.1% / sqrt(3) = 0.25%.
  EXPECT_NE(md.find("| layer crossings, mean over frames | 0.00 ± 0.00% | 2.10 ± 0.25% |"), std::string::npos) << md;
  EXPECT_NE(md.find("| ms per frame | n/a | 500 ± 0 |"), std::string::npos) << md;
  // Paired: ours minus Blender -2.10 ± 0.25%, the interval below zero (*);
  // equal stretch: 0, no star.
  EXPECT_NE(md.find("| layer crossings, mean over frames | -2.10 ± 0.25% * |"), std::string::npos) << md;
  EXPECT_NE(md.find("| edge stretch vs rest, p99 | 0.00 ± 0.00% |"), std::string::npos) << md;
}
