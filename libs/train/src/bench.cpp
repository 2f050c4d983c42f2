// Speed benchmarks of a model on scaled real scenes (see bench.h).
#include "layers/train/bench.h"

#include <ATen/Parallel.h>
#include <benchmark/benchmark.h>
#include <torch/csrc/autograd/grad_mode.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/memory.h"
#include "layers/data/run_layout.h"
#include "layers/geometry/subdivide.h"
#include "layers/train/checkpoint.h"
#include "layers/train/evaluator.h"
#include "layers/train/frame_loss.h"
#include "layers/train/session.h"
#include "layers/train/trainer.h"
#include "layers/train/window_loader.h"
#include "layers/zoo/phase.h"
#include "op_profile.h"

namespace layers::train {
namespace {

// A scene: static data and three frames (t-1, t, t+1) of one sequence.
struct Scene {
  data::SequenceStatic statics;
  data::Window window;
};

// Every garment subdivided once (positions of every frame, rest, UVs).
void subdivide_garments(Scene& s) {
  for (std::size_t k = 0; k < s.statics.garments.size(); ++k) {
    data::GarmentStatic& g = s.statics.garments[k];
    const geometry::Subdivision mesh = geometry::subdivide(g.faces, g.n_vertices());
    const geometry::Subdivision uv = geometry::subdivide(g.uv_faces, g.n_uv());
    s.window.garments[k] = mesh.apply(s.window.garments[k], 3);
    g.rest = mesh.apply(g.rest, 3);
    g.uv = uv.apply(g.uv, 2);
    g.faces = mesh.faces;
    g.uv_faces = uv.faces;
    std::vector<std::int32_t> panel;
    for (std::int32_t p : g.panel) panel.insert(panel.end(), {p, p, p, p});
    g.panel = panel;
  }
}

// Appends a copy of the body 100 m away (same faces and skinning).
void add_far_body(Scene& s) {
  data::BodyStatic& b = s.statics.body;
  const auto nv = static_cast<std::int32_t>(b.n_vertices());
  const std::size_t nf = b.faces.size();
  for (std::size_t i = 0; i < nf; ++i) b.faces.push_back(b.faces[i] + nv);
  b.skin_index.insert(b.skin_index.end(), b.skin_index.begin(), b.skin_index.end());
  b.skin_weight.insert(b.skin_weight.end(), b.skin_weight.begin(), b.skin_weight.end());
  std::vector<float> positions;
  const std::size_t per_frame = static_cast<std::size_t>(nv) * 3;
  for (std::size_t start = 0; start < s.window.body.positions.size(); start += per_frame) {
    const float* frame = s.window.body.positions.data() + start;
    positions.insert(positions.end(), frame, frame + per_frame);
    for (std::size_t i = 0; i < per_frame; ++i) positions.push_back(frame[i] + (i % 3 == 0 ? 100.0f : 0.0f));
  }
  s.window.body.positions = std::move(positions);
}

// One inference step of the scene (rows t-1, t predict t+1).
void infer_step(zoo::Model& model, const FrameTensors& frames) {
  torch::NoGradGuard no_grad;
  zoo::StepOutput out = model.step(step_input(frames, 1, true_states(frames, 1)));
  benchmark::DoNotOptimize(out.garments.front().data_ptr());
}

// One training step of the scene: forward, the experiment's losses,
// backward (gradients cleared after, not applied).
void train_step(zoo::Model& model, const FrameTensors& frames, const LossConfig& loss_config) {
  zoo::StepOutput out = model.step(step_input(frames, 1, true_states(frames, 1)));
  std::vector<at::Tensor> truth;
  for (const at::Tensor& g : frames.garments) truth.push_back(g[2]);
  LossSum loss;
  {
    const zoo::Phase phase("phase:loss");
    loss = frame_loss(model.sequence(), out.garments, truth, frames.body[2], loss_config);
  }
  loss.total.backward();
  const zoo::Phase phase("phase:zero_grad");
  for (at::Tensor p : model.parameters())
    if (p.grad().defined()) p.mutable_grad().zero_();
}

// Collects the timings Google Benchmark measures.
class Collector : public benchmark::BenchmarkReporter {
 public:
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs)
      if (!r.error_occurred) ms[r.run_name.function_name] = r.GetAdjustedRealTime();  // in the run unit (ms)
  }
  std::map<std::string, double> ms;
};

}  // namespace

BenchReport run_bench(const ExperimentConfig& config, const zoo::Registry& registry, const BenchOptions& options) {
  Session s = open_session(config, registry);
  BenchReport report;
  report.model = s.model->name();
  report.parameters = s.model->info().parameters;
  report.threads = config.run.threads;
  // The run's own best or last may not exist yet (the initial weights are
  // timed); a named file must.
  const std::string checkpoint = resolve_checkpoint(config, options.checkpoint);
  const bool own = options.checkpoint == "best" || options.checkpoint == "last";
  if (!own || std::filesystem::exists(checkpoint)) {
    load_checkpoint(checkpoint, *s.model, nullptr);
    report.checkpoint = checkpoint;
  }
  const std::string split = evaluated_split(config, options.split);
  report.sequence = options.sequence;
  if (report.sequence.empty()) {
    report.split = split;
    const std::vector<std::string> ids = select_sequences(s.dataset, split, config.data.subsets);
    if (ids.empty())
      throw InputError(config.data.dataset + "/splits.yaml", split, "a sequence to benchmark on", "none");
    report.sequence = ids.front();
  }
  if (!s.dataset.contains(report.sequence))
    throw InputError(config.data.dataset, "--sequence", "a sequence id of the dataset", report.sequence);
  Scene base{*s.dataset.statics(report.sequence), s.dataset.read_frames(report.sequence, 0, 3)};

  std::vector<std::pair<std::string, BenchRow>> cases;
  std::vector<std::pair<zoo::SequenceStatic, FrameTensors>> scenes;
  Scene scene = base;
  for (int level = 0; level <= options.levels; ++level) {
    if (level > 0) subdivide_garments(scene);
    for (bool far : {false, true}) {
      if (far && !options.far_body) continue;
      Scene c = scene;
      if (far) add_far_body(c);
      c.statics.id = report.sequence + "@bench-" + std::to_string(level) + (far ? "-far" : "");
      zoo::SequenceStatic statics = to_model_static(c.statics, s.selection);
      FrameTensors frames = to_device(to_frame_tensors(c.window, c.statics.garments, s.selection), s.device);
      BenchRow row;
      row.level = level;
      row.far_body = far;
      for (const zoo::GarmentStatic& g : statics.garments) row.garment_vertices += g.rest.size(0);
      row.body_vertices = frames.body.size(1);
      cases.emplace_back("level" + std::to_string(level) + (far ? "_farbody" : ""), row);
      scenes.emplace_back(std::move(statics), std::move(frames));
    }
  }

  const bool trainable = [&] {
    for (const at::Tensor& p : s.model->parameters())
      if (p.requires_grad()) return true;
    return false;
  }();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string name = cases[i].first;
    auto& [statics, frames] = scenes[i];
    zoo::Model& model = *s.model;
    benchmark::RegisterBenchmark((name + "/infer").c_str(),
                                 [&model, &statics = statics, &frames = frames](benchmark::State& st) {
                                   model.train(false);
                                   model.prepare(statics);
                                   // Untimed first step: what a model computes once per
                                   // sequence (DeePSD's heads, caches) is not a frame's cost.
                                   infer_step(model, frames);
                                   for (auto _ : st) infer_step(model, frames);
                                 })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MinTime(options.min_time);
    if (options.train && trainable) {
      benchmark::RegisterBenchmark((name + "/train").c_str(),
                                   [&, &statics = statics, &frames = frames](benchmark::State& st) {
                                     model.train(true);
                                     model.prepare(statics);
                                     train_step(model, frames, config.loss);  // untimed, as above
                                     for (auto _ : st) train_step(model, frames, config.loss);
                                     model.train(false);
                                   })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(options.min_time);
    }
  }
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::ClearRegisteredBenchmarks();

  for (std::size_t i = 0; i < cases.size(); ++i) {
    BenchRow row = cases[i].second;
    row.ms_per_frame = collector.ms[cases[i].first + "/infer"];
    auto t = collector.ms.find(cases[i].first + "/train");
    if (t != collector.ms.end()) row.train_ms_per_frame = t->second;
    // Counters of one more step on this scene.
    s.model->prepare(scenes[i].first);
    {
      torch::NoGradGuard no_grad;
      s.model->step(step_input(scenes[i].second, 1, true_states(scenes[i].second, 1)));
    }
    row.counters = s.model->step_counters();
    report.rows.push_back(row);
  }

  // The model's peak memory, read before the simulator runs in this process.
  report.peak_resident_mib = static_cast<double>(peak_resident_bytes()) / (1024.0 * 1024.0);
  // Our simulator on the same scene at each level (--simulator).
  if (options.simulator)
    for (BenchRow& row : report.rows)
      if (!row.far_body) row.simulator = options.simulator(config.data.dataset, report.sequence, row.level);

  // Where the time goes (--profile): each scene without the far body.
  std::vector<nlohmann::ordered_json> profiles(cases.size());
  double peak = 0;
  if (options.profile) {
    peak = report.matmul_peak_gflops = matmul_peak_gflops();
    for (std::size_t i = 0; i < cases.size(); ++i) {
      if (cases[i].second.far_body) continue;
      zoo::Model& model = *s.model;
      const FrameTensors& frames = scenes[i].second;
      model.train(false);
      model.prepare(scenes[i].first);
      const StepProfile infer = profile_steps([&] { infer_step(model, frames); }, options.profile_steps);
      profiles[i]["infer"] = to_json(infer);
      report.rows[i].infer_phases = phase_list(infer);
      report.rows[i].infer_gflops = infer.step_gflops;
      if (options.train && trainable) {
        model.train(true);
        model.prepare(scenes[i].first);
        const StepProfile train = profile_steps([&] { train_step(model, frames, config.loss); }, options.profile_steps);
        profiles[i]["train"] = to_json(train);
        report.rows[i].train_phases = phase_list(train);
        report.rows[i].train_gflops = train.step_gflops;
        model.train(false);
      }
    }
  }

  report.out = options.out.empty() ? (std::filesystem::path(config.run.output) / data::run_layout::kBench).string()
                                   : options.out;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < report.rows.size(); ++i) {
    const BenchRow& r = report.rows[i];
    rows.push_back({{"level", r.level},
                    {"far_body", r.far_body},
                    {"garment_vertices", r.garment_vertices},
                    {"body_vertices", r.body_vertices},
                    {"counters", r.counters},
                    {"ms_per_frame", r.ms_per_frame},
                    {"train_ms_per_frame", r.train_ms_per_frame}});
    if (r.simulator.garment_vertices > 0)
      rows.back()["simulator"] = {{"garment_vertices", r.simulator.garment_vertices},
                                  {"ms_per_frame", r.simulator.ms_per_frame},
                                  {"model_speedup", r.simulator.ms_per_frame / r.ms_per_frame}};
    if (!profiles[i].is_null()) rows.back()["profile"] = profiles[i];
  }
  nlohmann::ordered_json doc = {
      {"model", report.model},          {"parameters", report.parameters}, {"threads", report.threads},
      {"sequence", report.sequence},    {"split", report.split},           {"checkpoint", report.checkpoint},
      {"dataset", config.data.dataset}, {"experiment", config.source},     {"rows", rows}};
  if (options.profile) doc["matmul_peak_gflops"] = peak;
  doc["peak_resident_mib"] = report.peak_resident_mib;
  std::filesystem::create_directories(std::filesystem::path(report.out).parent_path().empty()
                                          ? std::filesystem::path(".")
                                          : std::filesystem::path(report.out).parent_path());
  write_text_atomic(report.out, doc.dump(2) + "\n");
  return report;
}

}  // namespace layers::train
