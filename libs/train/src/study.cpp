// `layers run`: reading study files, fingerprints, steps.yaml records and
// the order and skipping of a study's steps (see study.h).
#include "layers/train/study.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>

#include "layers/core/atomic_file.h"
#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/core/text_file.h"

namespace fs = std::filesystem;

namespace layers::train {
namespace {

const std::vector<std::string> kStudySteps{"train", "eval", "bench", "report"};
const std::vector<std::string> kRunSteps{"train", "eval", "bench"};

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string join(const std::vector<std::string>& items, const char* sep = ", ") {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : sep) + s;
  return out;
}

// `file` relative to the folder of `base` (unchanged when absolute or empty).
std::string beside(const std::string& base, const std::string& file) {
  if (file.empty() || fs::path(file).is_absolute()) return file;
  return (fs::path(base).parent_path() / file).lexically_normal().string();
}

void check_steps(const std::string& source, const std::string& key, const std::vector<std::string>& steps,
                 const std::vector<std::string>& allowed) {
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (!contains(allowed, steps[i]))
      throw InputError(source, key + "[" + std::to_string(i) + "]", "one of " + join(allowed), "'" + steps[i] + "'");
}

bool valid_run_name(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name == "report") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '+' || c == '.';
  });
}

// Sets tree[a][b] to a string scalar (a path must not go through YAML parsing).
void set_string(cfg::Node& tree, const char* section, const char* key, const std::string& value) {
  cfg::Node& s = tree.child(section);
  if (s.kind != cfg::Node::Kind::Map) {
    s = cfg::Node{};
    s.kind = cfg::Node::Kind::Map;
  }
  cfg::Node& v = s.child(key);
  v = cfg::Node{};
  v.kind = cfg::Node::Kind::Scalar;
  v.scalar = value;
}

std::string now_text() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
  return buf;
}

// ---- steps.yaml ---------------------------------------------------------

struct Record {
  std::string state;  // started, done, failed
  std::string inputs;
  std::vector<std::string> outputs;  // relative to the record's folder
  double seconds = 0;
  std::string finished;

  template <class V>
  void visit(V& v) {
    v("state", state);
    v("inputs", inputs);
    v("outputs", outputs);
    v("seconds", seconds);
    v("finished", finished);
  }
};

// The records of one folder, in file order.
class Records {
 public:
  explicit Records(std::string folder) : folder_(std::move(folder)) {
    const fs::path file = fs::path(folder_) / "steps.yaml";
    if (!fs::exists(file)) return;
    try {
      cfg::Node tree = cfg::parse(read_text_file(file.string()), file.string());
      if (tree.kind != cfg::Node::Kind::Map) return;
      for (const auto& [step, node] : tree.map) entries_.emplace_back(step, cfg::read<Record>(node, step));
    } catch (const std::exception& e) {
      spdlog::warn("{}: ignored (every step of it reruns): {}", file.string(), e.what());
      entries_.clear();
    }
  }

  const Record* find(const std::string& step) const {
    for (const auto& [name, r] : entries_)
      if (name == step) return &r;
    return nullptr;
  }

  void put(const std::string& step, const Record& record) {
    for (auto& [name, r] : entries_)
      if (name == step) {
        r = record;
        save();
        return;
      }
    entries_.emplace_back(step, record);
    save();
  }

  // Done with these inputs, and every output still there.
  bool current(const std::string& step, const std::string& inputs) const {
    const Record* r = find(step);
    if (!r || r->state != "done" || r->inputs != inputs) return false;
    for (const std::string& out : r->outputs)
      if (!fs::exists(fs::path(folder_) / out)) return false;
    return true;
  }

  // Why `step` is not current (for the log line).
  std::string reason(const std::string& step, const std::string& inputs) const {
    const Record* r = find(step);
    if (!r) return "no record";
    if (r->state == "started") return "interrupted before";
    if (r->state == "failed") return "failed before";
    if (r->inputs != inputs) return "inputs changed";
    for (const std::string& out : r->outputs)
      if (!fs::exists(fs::path(folder_) / out)) return out + " missing";
    return "forced";
  }

 private:
  void save() const {
    cfg::Node tree;
    tree.kind = cfg::Node::Kind::Map;
    for (const auto& [name, r] : entries_) tree.map.emplace_back(name, cfg::to_node(r));
    write_text_atomic((fs::path(folder_) / "steps.yaml").string(),
                      "# written by `layers run` (docs/studies.md): the inputs' fingerprint and outputs of each "
                      "step\n" + cfg::to_yaml(tree) + "\n");
  }

  std::string folder_;
  std::vector<std::pair<std::string, Record>> entries_;
};

// Lines "key=value" hashed together.
class Fingerprint {
 public:
  Fingerprint& add(const std::string& key, const std::string& value) {
    text_ += key + "=" + value + "\n";
    return *this;
  }
  std::string str() const { return fingerprint_text(text_); }

 private:
  std::string text_;
};

std::string status_word(StepStatus s) {
  switch (s) {
    case StepStatus::Ran: return "done";
    case StepStatus::Current: return "current, skipped";
    case StepStatus::WouldRun: return "would run";
    case StepStatus::Failed: return "FAILED";
    case StepStatus::Blocked: return "blocked";
  }
  return "";
}

// ---- running one study ----------------------------------------------------

class StudyRunner {
 public:
  StudyRunner(const StudyActions& actions, const StudyOptions& options, StudyResult& result)
      : actions_(actions), options_(options), result_(result) {}

  void run_file(const std::string& path, const std::vector<std::string>& sets, bool top) {
    const std::string key = fs::weakly_canonical(path).string();
    if (running_.count(key)) throw InputError(path, "requires", "no cycle of required studies", "a cycle");
    if (finished_.count(key)) return;
    running_.insert(key);
    const StudyConfig study = load_study(path, sets);
    for (const std::string& req : study.requires_) run_file(req, {}, false);
    run(study, top);
    running_.erase(key);
    finished_.insert(key);
  }

 private:
  void say(const std::string& study, const StepOutcome& o) {
    const std::string who = o.run.empty() ? o.step : o.run + " " + o.step;
    std::string line = "[" + study + "] " + who + ": " + status_word(o.status);
    if (o.status == StepStatus::Ran) line += " in " + Progress::format_duration(o.seconds);
    if (!o.message.empty()) line += " (" + o.message + ")";
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  }

  StepOutcome& add(const std::string& study, const std::string& run, const std::string& step, StepStatus status,
                   const std::string& message = "") {
    StepOutcome o;
    o.study = study, o.run = run, o.step = step, o.status = status, o.message = message;
    result_.steps.push_back(o);
    return result_.steps.back();
  }

  // Runs `work` for a step unless it is current; records it in `records`.
  // Returns the outcome's status.
  StepStatus step(const std::string& study, const std::string& run, const std::string& name, Records& records,
                  const std::string& inputs, const std::vector<std::string>& outputs, bool upstream_changed, bool top,
                  const std::function<void(const Record* previous)>& work) {
    const bool force = options_.force && top;
    if (!force && !upstream_changed && records.current(name, inputs)) {
      say(study, add(study, run, name, StepStatus::Current));
      return StepStatus::Current;
    }
    const std::string why = force ? "forced" : upstream_changed ? "inputs change" : records.reason(name, inputs);
    if (options_.dry_run) {
      say(study, add(study, run, name, StepStatus::WouldRun, why));
      return StepStatus::WouldRun;
    }
    std::printf("[%s] %s%s: running (%s)\n", study.c_str(), run.empty() ? "" : (run + " ").c_str(), name.c_str(),
                why.c_str());
    std::fflush(stdout);
    const Record* found = records.find(name);
    const Record previous = found ? *found : Record{};
    Record record;
    record.state = "started";
    record.inputs = inputs;
    records.put(name, record);
    Timer timer;
    try {
      work(found ? &previous : nullptr);
    } catch (const std::exception& e) {
      record.state = "failed";
      record.seconds = timer.seconds();
      record.finished = now_text();
      records.put(name, record);
      StepOutcome& o = add(study, run, name, StepStatus::Failed, e.what());
      o.seconds = record.seconds;
      say(study, o);
      return StepStatus::Failed;
    }
    record.state = "done";
    record.outputs = outputs;
    record.seconds = timer.seconds();
    record.finished = now_text();
    records.put(name, record);
    StepOutcome& o = add(study, run, name, StepStatus::Ran);
    o.seconds = record.seconds;
    say(study, o);
    return StepStatus::Ran;
  }

  void blocked(const std::string& study, const std::string& run, const std::string& name, const std::string& why) {
    say(study, add(study, run, name, StepStatus::Blocked, why));
  }

  bool dataset_step(const StudyConfig& study) {
    const std::string& folder = study.dataset.folder;
    if (options_.dry_run) {
      const bool present = fs::exists(fs::path(folder) / "dataset.yaml") && fs::exists(fs::path(folder) / "splits.yaml");
      say(study.name, add(study.name, "", "dataset", present ? StepStatus::Current : StepStatus::WouldRun,
                          present ? folder + " present" : folder + " missing or incomplete"));
      return true;
    }
    Timer timer;
    try {
      const bool generated = actions_.dataset(study.dataset);
      StepOutcome& o = add(study.name, "", "dataset", generated ? StepStatus::Ran : StepStatus::Current, folder);
      o.seconds = timer.seconds();
      say(study.name, o);
      return true;
    } catch (const std::exception& e) {
      say(study.name, add(study.name, "", "dataset", StepStatus::Failed, e.what()));
      return false;
    }
  }

  // Writes <dir>/experiment.yaml when it differs (reports read it).
  static void save_experiment(const StudyRun& run) {
    const fs::path file = fs::path(run.dir) / "experiment.yaml";
    if (fs::exists(file) && read_text_file(file.string()) == run.config_yaml) return;
    write_text_atomic(file.string(), run.config_yaml);
  }

  // The experiment as fingerprinted: without run.output and data.dataset
  // (locations: the run folder holds the records, the dataset's files are
  // fingerprinted themselves, so a study folder copied with its dataset
  // stays current) and, for training, without the eval section.
  static std::string fingerprinted_text(const StudyRun& run, bool training) {
    cfg::Node tree = cfg::to_node(run.config);
    auto drop = [](cfg::Node& map, const char* key) {
      map.map.erase(std::remove_if(map.map.begin(), map.map.end(), [&](const auto& kv) { return kv.first == key; }),
                    map.map.end());
    };
    if (cfg::Node* r = tree.find("run")) drop(*r, "output");
    if (cfg::Node* d = tree.find("data")) drop(*d, "dataset");
    if (training) drop(tree, "eval");
    return cfg::to_yaml(tree);
  }

  // Steps of one run.
  void run_steps(const StudyConfig& study, const StudyRun& run, const std::string& dataset_fp, bool dataset_changed,
                 bool top) {
    if (!options_.dry_run) {
      fs::create_directories(run.dir);
      save_experiment(run);
    }
    Records records(run.dir);
    // In a dry run nothing is rerun, so what depends on a step that would
    // run is marked by hand; a real run sees the new stamps.
    bool changed = dataset_changed;
    bool checkpoint_ok = true;
    std::string blocked_why;
    if (contains(run.steps, "train")) {
      const std::string inputs = Fingerprint().add("experiment", fingerprinted_text(run, true)).add("dataset", dataset_fp).str();
      const StepStatus s = step(study.name, run.name, "train", records, inputs,
                                {"checkpoint-last.pt", "checkpoint-best.pt"}, dataset_changed, top,
                                [&](const Record* previous) {
                                  const bool resume = previous && previous->state == "started" &&
                                                      previous->inputs == inputs &&
                                                      fs::exists(fs::path(run.dir) / "checkpoint-last.pt");
                                  actions_.train(run, resume);
                                });
      changed = changed || s == StepStatus::WouldRun;
      if (s == StepStatus::Failed) checkpoint_ok = false, blocked_why = "train failed";
    }
    if (checkpoint_ok && !options_.dry_run && !fs::exists(run.checkpoint)) {
      checkpoint_ok = false;
      blocked_why = "no checkpoint " + run.checkpoint +
                    (run.external_checkpoint ? " (run the study that trains it first; see `requires:`)" : "");
    }
    const std::string checkpoint_fp = file_stamp(run.checkpoint);
    auto inputs_with = [&](const std::string& what) {
      return Fingerprint()
          .add("experiment", fingerprinted_text(run, false))
          .add("dataset", dataset_fp)
          .add("checkpoint", run.external_checkpoint ? run.checkpoint : fs::path(run.checkpoint).filename().string())
          .add("checkpoint_stamp", checkpoint_fp)
          .add("step", what)
          .str();
    };
    if (contains(run.steps, "eval")) {
      for (const std::string& split : run.eval_splits) {
        const std::string name = "eval-" + split;
        if (!checkpoint_ok) {
          blocked(study.name, run.name, name, blocked_why);
          continue;
        }
        std::vector<std::string> outputs{name + "/metrics.json", name + "/sequences.csv"};
        if (run.config.eval.save_predictions) outputs.push_back(name + "/predictions.h5");
        step(study.name, run.name, name, records, inputs_with(name), outputs, changed, top,
             [&](const Record*) { actions_.eval(run, split); });
      }
    }
    if (contains(run.steps, "bench")) {
      if (!checkpoint_ok) {
        blocked(study.name, run.name, "bench", blocked_why);
      } else {
        const StudyBench& b = study.bench;
        const std::string opts = std::to_string(b.levels) + "/" + std::to_string(b.min_time) + "/" +
                                 std::to_string(b.train) + "/" + std::to_string(b.far_body);
        step(study.name, run.name, "bench", records, inputs_with("bench " + opts), {"bench.json"}, changed, top,
             [&](const Record*) { actions_.bench(run, b); });
      }
    }
  }

  // The report's inputs: every file of the runs it reads.
  static std::string report_inputs(const StudyConfig& study, const std::vector<StudyRun>& runs,
                                   const std::string& dataset_fp) {
    Fingerprint f;
    const StudyReport& r = study.report;
    f.add("options", r.title + "|" + r.split + "|" + std::to_string(r.charts) + "|" + std::to_string(r.frames) + "|" +
                         r.sequence);
    f.add("dataset", dataset_fp);
    for (const StudyRun& run : runs) {
      f.add("run", run.dir);
      f.add("experiment.yaml", file_stamp((fs::path(run.dir) / "experiment.yaml").string()));
      f.add("bench.json", file_stamp((fs::path(run.dir) / "bench.json").string()));
      for (const std::string& split : run.eval_splits)
        for (const char* file : {"metrics.json", "predictions.h5"})
          f.add("eval-" + split + "/" + file, file_stamp((fs::path(run.dir) / ("eval-" + split) / file).string()));
    }
    return f.str();
  }

  void run(const StudyConfig& study, bool top) {
    std::printf("[%s] study %s: %zu experiments, steps %s, output %s\n", study.name.c_str(), study.source.c_str(),
                study.experiments.size(), join(study.steps).c_str(), study.output.c_str());
    std::fflush(stdout);
    std::vector<StudyRun> runs = resolve_runs(study);
    if (top && !options_.only.empty()) {
      std::vector<std::string> names;
      for (const StudyRun& r : runs) names.push_back(r.name);
      for (const std::string& o : options_.only)
        if (!contains(names, o)) throw InputError(study.source, "--only " + o, "one of " + join(names), "'" + o + "'");
      runs.erase(std::remove_if(runs.begin(), runs.end(),
                                [&](const StudyRun& r) { return !contains(options_.only, r.name); }),
                 runs.end());
    }
    const bool report = contains(study.steps, "report") && !(top && !options_.only.empty());

    const std::size_t before = result_.steps.size();
    if (!dataset_step(study)) {
      for (const StudyRun& r : runs) blocked(study.name, r.name, "(all steps)", "no dataset");
      if (report) blocked(study.name, "", "report", "no dataset");
      return;
    }
    const bool dataset_changed = options_.dry_run && result_.steps.back().status == StepStatus::WouldRun;
    const std::string dataset_fp = dataset_fingerprint(study.dataset.folder);
    for (const StudyRun& r : runs) run_steps(study, r, dataset_fp, dataset_changed, top);
    const bool any_changed = std::any_of(result_.steps.begin() + static_cast<std::ptrdiff_t>(before),
                                         result_.steps.end(),
                                         [](const StepOutcome& o) { return o.status == StepStatus::WouldRun; });

    if (report) {
      if (!options_.dry_run) fs::create_directories(study.output);
      Records records(study.output);
      const std::string out = (fs::path(study.output) / "report").string();
      const StepStatus s = step(study.name, "", "report", records, report_inputs(study, runs, dataset_fp),
                                {"report/report.md"}, any_changed, top, [&](const Record*) {
                                  std::vector<std::string> dirs;
                                  for (const StudyRun& r : runs) dirs.push_back(r.dir);
                                  actions_.report(study, dirs, out);
                                });
      if (top && (s == StepStatus::Ran || s == StepStatus::Current))
        result_.report = (fs::path(out) / "report.md").string();
    }
  }

  const StudyActions& actions_;
  const StudyOptions& options_;
  StudyResult& result_;
  std::set<std::string> running_, finished_;
};

}  // namespace

// ---- public functions -----------------------------------------------------

std::string fingerprint_text(const std::string& text) { return content_hash(text); }

std::string file_stamp(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "missing";
  const auto time = fs::last_write_time(path, ec);
  if (ec) return "missing";
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count();
  return std::to_string(size) + ":" + std::to_string(ns);
}

std::string dataset_fingerprint(const std::string& folder) {
  if (!fs::is_directory(folder)) return "missing";
  std::vector<std::string> names{"dataset.yaml", "splits.yaml", "stats.h5"};
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("shard-", 0) == 0 && entry.path().extension() == ".h5") names.push_back(name);
  }
  std::sort(names.begin() + 3, names.end());
  std::string text;
  for (const std::string& n : names) text += n + "=" + file_stamp((fs::path(folder) / n).string()) + "\n";
  return fingerprint_text(text);
}

StudyConfig load_study(const std::string& path, const std::vector<std::string>& sets) {
  cfg::Node tree = cfg::load_file(path);
  for (const std::string& s : sets) cfg::apply_set(tree, s);
  StudyConfig study = cfg::read<StudyConfig>(tree);
  study.source = path;
  if (study.name.empty()) study.name = fs::path(path).stem().string();
  if (study.output.empty()) study.output = "runs/" + study.name;
  if (study.dataset.config.empty()) {
    if (!study.dataset.set.empty())
      throw InputError(path, "dataset.set", "no generator overrides without dataset.config",
                       std::to_string(study.dataset.set.size()) + " override(s)");
  } else {
    study.dataset.config = beside(path, study.dataset.config);
    if (!fs::is_regular_file(study.dataset.config))
      throw InputError(path, "dataset.config", "a generator config file (relative to the study file)",
                       "'" + study.dataset.config + "' (no such file)");
  }
  for (std::string& r : study.requires_) {
    r = beside(path, r);
    if (!fs::is_regular_file(r))
      throw InputError(path, "requires", "study files (relative to this one)", "'" + r + "' (no such file)");
  }
  check_steps(path, "steps", study.steps, kStudySteps);
  if (study.experiments.empty()) throw InputError(path, "experiments", "at least one experiment", "none");
  std::set<std::string> names;
  for (std::size_t i = 0; i < study.experiments.size(); ++i) {
    StudyExperiment& e = study.experiments[i];
    const std::string key = "experiments[" + std::to_string(i) + "]";
    if (!valid_run_name(e.name))
      throw InputError(path, key + ".name", "a folder name of letters, digits, _ - + . (not 'report')",
                       "'" + e.name + "'");
    if (!names.insert(e.name).second) throw InputError(path, key + ".name", "a name used once", "'" + e.name + "' again");
    e.file = beside(path, e.file);
    if (!fs::is_regular_file(e.file))
      throw InputError(path, key + ".file", "an experiment config (relative to the study file)",
                       "'" + e.file + "' (no such file)");
    check_steps(path, key + ".steps", e.steps, kRunSteps);
  }
  return study;
}

std::vector<StudyRun> resolve_runs(const StudyConfig& study) {
  std::vector<StudyRun> runs;
  for (const StudyExperiment& e : study.experiments) {
    StudyRun r;
    r.name = e.name;
    r.dir = (fs::path(study.output) / e.name).string();
    cfg::Node tree = cfg::load_file(e.file);
    for (const std::string& s : study.set) cfg::apply_set(tree, s);
    for (const std::string& s : e.set) cfg::apply_set(tree, s);
    set_string(tree, "run", "output", r.dir);
    set_string(tree, "data", "dataset", study.dataset.folder);
    r.config = read_experiment(tree, e.file);
    r.config_yaml = cfg::to_yaml(cfg::to_node(r.config)) + "\n";
    for (const std::string& s : e.steps.empty() ? study.steps : e.steps)
      if (s != "report" && !(s == "train" && !e.checkpoint.empty())) r.steps.push_back(s);
    r.eval_splits = study.eval.splits;
    if (r.eval_splits.empty())
      r.eval_splits.push_back(!r.config.eval.split.empty() ? r.config.eval.split : r.config.data.test_split);
    const std::string file = "checkpoint-" + study.eval.checkpoint + ".pt";
    r.external_checkpoint = !e.checkpoint.empty();
    r.checkpoint = !r.external_checkpoint ? (fs::path(r.dir) / file).string()
                   : fs::is_directory(e.checkpoint) || fs::path(e.checkpoint).extension() != ".pt"
                       ? (fs::path(e.checkpoint) / file).string()
                       : e.checkpoint;
    runs.push_back(std::move(r));
  }
  return runs;
}

bool StudyResult::ok() const { return count(StepStatus::Failed) == 0 && count(StepStatus::Blocked) == 0; }

std::size_t StudyResult::count(StepStatus status) const {
  return static_cast<std::size_t>(
      std::count_if(steps.begin(), steps.end(), [&](const StepOutcome& o) { return o.status == status; }));
}

StudyResult run_study(const std::string& path, const std::vector<std::string>& sets, const StudyActions& actions,
                      const StudyOptions& options) {
  StudyResult result;
  StudyRunner runner(actions, options, result);
  runner.run_file(path, sets, true);
  return result;
}

}  // namespace layers::train
