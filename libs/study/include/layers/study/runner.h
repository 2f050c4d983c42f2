// layers/study/runner.h -- the one loop that runs a study's steps: steps
// are data (a name, the steps they come after, the fingerprint of their
// inputs, their outputs, the work); the loop orders them by `after`, skips
// those whose steps.yaml record is current, marks what a failure blocks,
// does dry runs, and prints one line per step:
//
//   [study] <run> <step>: current, skipped
//   [study] <run> <step>: running (<why>)
//   [study] <run> <step>: done in 1.2 s
//   [study] <run> <step>: would run (<why>) | FAILED (<error>) | blocked (<why>)
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "layers/study/records.h"

namespace layers::study {

enum class StepStatus { Ran, Current, WouldRun, Failed, Blocked };

struct StepOutcome {
  std::string study, run, step;  // run is empty for study-wide steps (dataset, report)
  StepStatus status = StepStatus::Ran;
  double seconds = 0;
  std::string message;  // why it ran, or the error
};

// What a step's work is given, and what an unrecorded step reports back.
struct StepWork {
  std::string inputs;                // the inputs' fingerprint (recorded steps)
  const Record* previous = nullptr;  // the step's record before this run (nullptr: none)
  bool current = false;              // unrecorded step: it found its outputs complete
  std::string message;               // unrecorded step: shown after its status
};

struct Step {
  std::string run, name;                 // "<run> <name>" (or "<name>") is its id in `after`
  std::vector<std::string> after;        // steps run first; a failed or blocked one blocks this one
  bool after_failures = false;           // run even when an `after` step failed (a report lists what is missing)
  std::string folder;                    // folder of the steps.yaml record; "" = unrecorded: the work itself
                                         // says whether it found everything current
  std::function<std::string()> inputs;   // recorded steps: the inputs' fingerprint, taken when its turn comes
  std::vector<std::string> outputs;      // relative to folder; the step is current only while they exist
  std::function<std::string()> blocked;  // optional, real runs: "" or why it cannot run
  std::function<bool(std::string& message)> would_run;  // unrecorded steps in a dry run
  std::function<void(StepWork& work)> work;

  std::string id() const { return run.empty() ? name : run + " " + name; }
};

struct RunnerOptions {
  bool force = false;    // rerun recorded steps, current or not
  bool dry_run = false;  // print what would run; run nothing, write nothing
};

class Runner {
 public:
  // Outcomes are appended to `outcomes`; `study` prefixes every line.
  Runner(std::string study, RunnerOptions options, std::vector<StepOutcome>& outcomes);

  // Runs `steps` in list order except that a step waits for its `after`
  // steps (of this call or an earlier one). In a dry run a step is marked
  // to run when an `after` step would run. Error for an unknown `after`
  // or a cycle.
  void run(const std::vector<Step>& steps);
  // Reports a step that cannot run.
  void block(const std::string& run, const std::string& name, const std::string& why);
  // Status of a step run by this runner (Blocked when it never ran).
  StepStatus status(const std::string& id) const;

 private:
  void run_step(const Step& step);
  void run_unrecorded(const Step& step);
  void run_recorded(const Step& step, bool upstream_changed);
  StepOutcome& add(const Step& step, StepStatus status, const std::string& message = "");
  void say(const StepOutcome& o) const;
  Records& records(const std::string& folder);

  std::string study_;
  RunnerOptions options_;
  std::vector<StepOutcome>& outcomes_;
  std::map<std::string, StepStatus> done_;                   // by step id
  std::map<std::string, std::string> blocks_with_;           // by step id: what its failure says to the steps after it
  std::map<std::string, std::unique_ptr<Records>> records_;  // by folder
};

}  // namespace layers::study
