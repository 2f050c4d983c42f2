// `layers crosscheck`: stored sequences re-simulated by Blender's cloth
// solver from their frame 0 (scripts/blender/crosscheck_sim.py, one run
// per setup) and by ours from the generator config in the dataset.yaml
// (timed), and per scene a markdown table of the same measures on our
// stored ground truth, our run and each Blender result; over several
// scenes, a summary with 95% intervals that resumes where it stopped
// (docs/sim.md "Cross-check against Blender").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "blender_runner.h"
#include "dataset_access.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/data/dataset.h"
#include "layers/generate/crosscheck.h"
#include "layers/generate/crosscheck_scene.h"
#include "layers/generate/crosscheck_summary.h"
#include "output_folder.h"
#include "verbs.h"

namespace layers::app {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> parse_setups(const std::string& text) {
  std::vector<std::string> setups;
  std::istringstream in(text);
  for (std::string s; std::getline(in, s, ',');) {
    if (s != "merged" && s != "separate")
      throw UsageError("--setups: expected a comma-separated list of merged and separate, got '" + text + "'");
    setups.push_back(s);
  }
  if (setups.empty()) throw UsageError("--setups: expected merged, separate or both");
  return setups;
}

// A new work folder: `requested` must not exist yet; "" makes one under
// the temporary folder.
std::string make_work_dir(const std::string& requested) {
  if (requested.empty()) {
    std::string pattern = (fs::temp_directory_path() / "layers-crosscheck-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw Error("cannot create a work folder under " + fs::temp_directory_path().string());
    return pattern;
  }
  std::error_code ec;
  if (fs::exists(requested, ec))
    throw InputError::message(requested, "", "exists; --work must name a new folder (nothing is overwritten)");
  if (!fs::create_directories(requested, ec) || ec)
    throw InputError::message(requested, "", "cannot create the work folder: " + ec.message());
  return requested;
}

std::string title_of(const data::SequenceInfo& info, std::int64_t frames) {
  std::string outfit;
  for (const auto& g : info.garments) outfit += (outfit.empty() ? "" : " + ") + g.type;
  return "Cross-check of " + info.id + " (" + info.motion + "; " + (outfit.empty() ? "no garment" : outfit) + "; " +
         std::to_string(frames) + " frames)";
}

struct Args {
  std::string dataset, blender, setups = "merged,separate", work;
  std::vector<std::string> sequences;
  std::int64_t frames = 0;
  int threads = 1;
  bool allow_unhashed = false;
};

constexpr const char* kColumnsFile = "columns.tsv";
constexpr const char* kScenesFile = "scenes.txt";  // marks a work folder of several scenes

// Frames to compare for one sequence (checked against it).
std::int64_t frames_of(const Args& a, const data::SequenceInfo& info) {
  const std::int64_t frames = a.frames == 0 ? info.n_frames : a.frames;
  if (frames > info.n_frames || frames < 2)
    throw InputError("--frames", info.id, "2.." + std::to_string(info.n_frames), std::to_string(frames));
  if (info.garments.empty()) throw InputError::message(a.dataset, info.id, "has no garment to simulate");
  return frames;
}

// One scene into the new folder `work`: table.md and columns.tsv; returns
// the table and fills `columns`.
std::string run_scene(const Args& a, const std::vector<std::string>& setups, const std::string& blender,
                      const data::Dataset& dataset, const std::string& sequence, const std::string& work,
                      std::vector<generate::CrosscheckColumn>& columns) {
  const data::SequenceInfo& info = dataset.info(sequence);
  const std::int64_t frames = frames_of(a, info);
  const generate::CrosscheckScene scene =
      generate::write_crosscheck_scene(dataset, sequence, frames, (fs::path(work) / "export").string());
  const std::string script = (fs::path(work) / "crosscheck_sim.py").string();
  std::ofstream(script) << kCrosscheckScript;

  data::SequenceData seq = dataset.read_sequence(sequence);
  seq.n_frames = frames;
  std::vector<generate::CrosscheckRun> runs;
  generate::CrosscheckRun ours{generate::kOursStored, std::nan(""), {}};
  for (const auto& g : seq.garments) ours.garments.push_back(g.positions);
  runs.push_back(std::move(ours));
  // Our solver timed on the same scene: simulated again from the
  // generator config the dataset's manifest records, on one thread (a
  // dataset made otherwise has none: our time is n/a then).
  const bool made_here = !dataset.manifest().generator_yaml.empty();
  float drift = 0;  // largest difference from the stored positions
  if (made_here) {
    std::fprintf(stderr, "crosscheck: ours, %lld frames simulated again from the dataset's generator config\n",
                 static_cast<long long>(frames));
    generate::CrosscheckRun again = generate::resimulate_ours(a.dataset, sequence, frames);
    for (std::size_t g = 0; g < again.garments.size() && g < runs[0].garments.size(); ++g) {
      const std::vector<float>& x = again.garments[g];
      const std::vector<float>& y = runs[0].garments[g];
      for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) drift = std::max(drift, std::abs(x[i] - y[i]));
    }
    runs.push_back(std::move(again));
  }
  for (const std::string& setup : setups) {
    const std::string out = (fs::path(work) / setup).string();
    fs::create_directories(out);
    const std::string log = (fs::path(out) / "blender.log").string();
    std::fprintf(stderr, "crosscheck: Blender, %s, %lld frames (log: %s)\n", setup.c_str(),
                 static_cast<long long>(frames), log.c_str());
    const std::string args = "--scene " + shell_quote(scene.manifest) + " --setup " + setup + " --frames " +
                             std::to_string(frames) + " --out " + shell_quote(out);
    const int status = run_blender(blender, a.threads, script, args, log);
    if (status != 0)
      throw Error("Blender (" + setup + ") failed with exit status " + std::to_string(status) + ": " +
                  blender_failure(log) + " (log: " + log + ")");
    runs.push_back(generate::read_crosscheck_run("Blender, " + setup, out, scene, seq));
  }

  columns.clear();
  for (const auto& r : runs) columns.push_back(generate::measure_crosscheck(seq, r));
  const sim::FrameMeasures start = generate::measure_start(seq);
  std::string table = generate::crosscheck_table(title_of(info, frames), columns, &start);
  char drift_text[64];
  std::snprintf(drift_text, sizeof drift_text, "%.3g", 1e3 * drift);
  table += "\nms per frame: Blender's is the wall time of each frame's step (frames 1..n-1, " +
           std::to_string(a.threads) + " Blender thread(s)); " +
           (made_here ? std::string("ours is the CPU time of each frame's step of the same scene simulated again "
                                    "from the generator config in the dataset's dataset.yaml on one thread (frames "
                                    "1..n-1; drape and blend untimed). The frames simulated again differ from the "
                                    "stored ones by at most ") +
                            drift_text + " mm (0: the solver is the one that made the dataset).\n"
                      : std::string("ours is n/a: the dataset's dataset.yaml records no generator config to "
                                    "simulate the scene again from.\n"));
  const generate::CrosscheckGaps gaps = generate::crosscheck_gaps(dataset.manifest(), dataset.path());
  char gap_text[160];
  std::snprintf(gap_text, sizeof gap_text,
                "Gaps handed to Blender (its effective gaps equal these): garment-body %.1f mm, between layers %.1f "
                "mm, within a garment %.1f mm (%s).\n",
                1e3 * gaps.body, 1e3 * gaps.layer, 1e3 * gaps.self,
                gaps.recorded ? "the dataset's generator config" : "the solver's defaults");
  table += gap_text;
  std::ofstream(fs::path(work) / "table.md") << table;
  std::ofstream(fs::path(work) / kColumnsFile) << generate::crosscheck_columns_tsv(columns);
  return table;
}

// The work folder of a run over several scenes: new, or one such run made
// before (it holds scenes.txt naming the same dataset), to resume.
std::string open_multi_work(const std::string& requested, const std::string& dataset) {
  const std::string line = "dataset " + fs::absolute(dataset).lexically_normal().string() + "\n";
  std::error_code ec;
  if (!requested.empty() && fs::exists(requested, ec)) {
    const fs::path marker = fs::path(requested) / kScenesFile;
    std::ifstream in(marker);
    std::string first;
    if (!in || !std::getline(in, first) || first + "\n" != line)
      throw InputError::message(requested, "",
                                "exists and is not a cross-check of several scenes of this dataset (no " +
                                    std::string(kScenesFile) +
                                    " naming it); --work must name a new folder or one "
                                    "to resume (nothing is overwritten)");
    return requested;
  }
  const std::string work = make_work_dir(requested);
  std::ofstream(fs::path(work) / kScenesFile) << line;
  return work;
}

int run(const Args& a) {
  const std::vector<std::string> setups = parse_setups(a.setups);
  if (a.frames < 0 || a.frames == 1) throw UsageError("--frames: expected at least 2 (0 = the whole sequence)");
  const std::string blender = find_blender(a.blender);
  const data::Dataset dataset = open_dataset(a.dataset, a.allow_unhashed);
  std::vector<std::string> sequences;
  for (const std::string& s : a.sequences) {
    if (s == "all") {
      for (const std::string& id : dataset.ids()) sequences.push_back(id);
      continue;
    }
    if (!dataset.contains(s))
      throw InputError::message(a.dataset, s, "no such sequence (`layers info " + a.dataset + "` lists them)");
    sequences.push_back(s);
  }
  for (const std::string& s : sequences) frames_of(a, dataset.info(s));
  if (sequences.empty()) throw InputError::message(a.dataset, "", "holds no sequence");

  if (sequences.size() == 1) {
    const std::string work = make_work_dir(a.work);
    std::fprintf(stderr, "crosscheck: work folder %s\n", work.c_str());
    std::vector<generate::CrosscheckColumn> columns;
    const std::string table = run_scene(a, setups, blender, dataset, sequences[0], work, columns);
    std::fputs(table.c_str(), stdout);
    return kOk;
  }

  // Several scenes: one folder each under the work folder; a scene whose
  // columns.tsv exists is read back (a resumed run), a scene folder
  // without it (an interrupted scene) is moved aside and run again.
  const std::string work = open_multi_work(a.work, a.dataset);
  std::fprintf(stderr, "crosscheck: work folder %s, %zu scenes\n", work.c_str(), sequences.size());
  std::vector<generate::CrosscheckSceneColumns> scenes;
  for (std::size_t i = 0; i < sequences.size(); ++i) {
    const std::string& id = sequences[i];
    const fs::path dir = fs::path(work) / id, tsv = dir / kColumnsFile;
    generate::CrosscheckSceneColumns scene;
    scene.title = title_of(dataset.info(id), frames_of(a, dataset.info(id)));
    if (fs::exists(tsv)) {
      std::fprintf(stderr, "crosscheck: %s (%zu of %zu) read back from %s\n", id.c_str(), i + 1, sequences.size(),
                   tsv.c_str());
      scene.columns = generate::parse_crosscheck_columns(read_text_file(tsv.string()), tsv.string());
      // A scene run with other --frames is not this run's: refused, not averaged in.
      const std::int64_t measured = frames_of(a, dataset.info(id)) - 1;
      for (const generate::CrosscheckColumn& c : scene.columns)
        if (c.frames != measured)
          throw InputError(tsv.string(), c.label + " frames",
                           std::to_string(measured) + " measured frames, as --frames " + std::to_string(measured + 1) +
                               " gives (resume with the --frames the folder was made "
                               "with, or use another --work)",
                           std::to_string(c.frames));
    } else {
      if (fs::exists(dir)) move_aside(dir, "--work");
      fs::create_directories(dir);
      std::fprintf(stderr, "crosscheck: %s (%zu of %zu)\n", id.c_str(), i + 1, sequences.size());
      run_scene(a, setups, blender, dataset, id, dir.string(), scene.columns);
    }
    scenes.push_back(std::move(scene));
  }
  const std::string summary = generate::crosscheck_summary(scenes);
  std::ofstream(fs::path(work) / "summary.md") << summary;
  std::fputs(summary.c_str(), stdout);
  return kOk;
}

}  // namespace

VerbRun register_crosscheck(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand(
      "crosscheck", "Re-simulate a stored sequence with Blender's cloth from its frame 0 and compare the measures");
  auto args = std::make_shared<Args>();
  cmd->add_option("dataset", args->dataset, "dataset folder or shard .h5 file")->required();
  add_allow_unhashed(*cmd, args->allow_unhashed);
  cmd->add_option("sequences", args->sequences,
                  "sequence ids, or all; with several, a summary with 95% intervals over them")
      ->required();
  cmd->add_option("--blender", args->blender, "Blender executable (default: $LAYERS_BLENDER, else blender on PATH)");
  cmd->add_option("--setups", args->setups, "merged (all layers one cloth, self-collision), separate, or both")
      ->capture_default_str();
  cmd->add_option("--frames", args->frames, "frames 0..N-1 to simulate and compare (0 = the whole sequence)")
      ->capture_default_str();
  cmd->add_option("--work", args->work,
                  "new folder for the export, Blender's results and table.md (default: a new "
                  "folder under the temporary directory); with several sequences, one folder per scene "
                  "and summary.md, and a folder of such a run resumes it");
  cmd->add_option("--blender-threads", args->threads, "threads Blender may use")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  return [args]() { return run(*args); };
}

}  // namespace layers::app
