// The step loop of `layers run` (see runner.h).
#include "layers/study/runner.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/core/progress.h"

namespace fs = std::filesystem;

namespace layers::study {
namespace {

std::string now_text() {
  std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
  return buf;
}

std::string status_word(StepStatus s) {
  switch (s) {
    case StepStatus::Ran:
      return "done";
    case StepStatus::Current:
      return "current, skipped";
    case StepStatus::WouldRun:
      return "would run";
    case StepStatus::Failed:
      return "FAILED";
    case StepStatus::Blocked:
      return "blocked";
  }
  return "";
}

}  // namespace

Runner::Runner(std::string study, RunnerOptions options, std::vector<StepOutcome>& outcomes)
    : study_(std::move(study)), options_(options), outcomes_(outcomes) {}

void Runner::run(const std::vector<Step>& steps) {
  std::vector<const Step*> pending;
  for (const Step& s : steps) pending.push_back(&s);
  while (!pending.empty()) {
    auto ready = std::find_if(pending.begin(), pending.end(), [&](const Step* s) {
      return std::all_of(s->after.begin(), s->after.end(), [&](const std::string& a) { return done_.count(a) > 0; });
    });
    if (ready == pending.end()) {
      const Step& s = *pending.front();
      for (const std::string& a : s.after)
        if (!done_.count(a) &&
            std::none_of(pending.begin(), pending.end(), [&](const Step* p) { return p->id() == a; }))
          throw Error("study " + study_ + ": step '" + s.id() + "' comes after '" + a + "', which is no step");
      throw Error("study " + study_ + ": the steps' `after` make a cycle (at '" + s.id() + "')");
    }
    const Step& step = **ready;
    pending.erase(ready);
    run_step(step);
  }
}

void Runner::run_step(const Step& step) {
  bool upstream_changed = false;
  for (const std::string& a : step.after) {
    const StepStatus s = done_.at(a);
    if ((s == StepStatus::Failed || s == StepStatus::Blocked) && !step.after_failures) {
      block(step.run, step.name, blocks_with_.at(a));
      return;
    }
    upstream_changed = upstream_changed || s == StepStatus::WouldRun;
  }
  if (!options_.dry_run && step.blocked) {
    const std::string why = step.blocked();
    if (!why.empty()) {
      block(step.run, step.name, why);
      return;
    }
  }
  if (step.folder.empty())
    run_unrecorded(step);
  else
    run_recorded(step, upstream_changed);
}

void Runner::run_unrecorded(const Step& step) {
  if (options_.dry_run) {
    std::string message;
    const bool would = step.would_run(message);
    say(add(step, would ? StepStatus::WouldRun : StepStatus::Current, message));
    return;
  }
  Timer timer;
  StepWork work;
  try {
    step.work(work);
  } catch (const std::exception& e) {
    say(add(step, StepStatus::Failed, e.what()));
    return;
  }
  StepOutcome& o = add(step, work.current ? StepStatus::Current : StepStatus::Ran, work.message);
  o.seconds = timer.seconds();
  say(o);
}

void Runner::run_recorded(const Step& step, bool upstream_changed) {
  Records& records = this->records(step.folder);
  const std::string inputs = step.inputs ? step.inputs() : "";
  if (!options_.force && !upstream_changed && records.current(step.name, inputs)) {
    say(add(step, StepStatus::Current));
    return;
  }
  const std::string why = options_.force     ? "forced"
                          : upstream_changed ? "inputs change"
                                             : records.reason(step.name, inputs);
  if (options_.dry_run) {
    say(add(step, StepStatus::WouldRun, why));
    return;
  }
  std::printf("[%s] %s: running (%s)\n", study_.c_str(), step.id().c_str(), why.c_str());
  std::fflush(stdout);
  const Record* found = records.find(step.name);
  const Record previous = found ? *found : Record{};
  Record record;
  record.state = "started";
  record.inputs = inputs;
  records.put(step.name, record);
  Timer timer;
  StepWork work;
  work.inputs = inputs;
  work.previous = found ? &previous : nullptr;
  try {
    step.work(work);
  } catch (const std::exception& e) {
    record.state = "failed";
    record.seconds = timer.seconds();
    record.finished = now_text();
    records.put(step.name, record);
    StepOutcome& o = add(step, StepStatus::Failed, e.what());
    o.seconds = record.seconds;
    say(o);
    return;
  }
  record.state = "done";
  record.outputs = step.outputs;
  record.seconds = timer.seconds();
  record.finished = now_text();
  records.put(step.name, record);
  StepOutcome& o = add(step, StepStatus::Ran);
  o.seconds = record.seconds;
  say(o);
}

void Runner::block(const std::string& run, const std::string& name, const std::string& why) {
  Step step;
  step.run = run;
  step.name = name;
  say(add(step, StepStatus::Blocked, why));
}

StepStatus Runner::status(const std::string& id) const {
  const auto it = done_.find(id);
  return it == done_.end() ? StepStatus::Blocked : it->second;
}

StepOutcome& Runner::add(const Step& step, StepStatus status, const std::string& message) {
  StepOutcome o;
  o.study = study_, o.run = step.run, o.step = step.name, o.status = status, o.message = message;
  done_[step.id()] = status;
  blocks_with_[step.id()] = status == StepStatus::Failed ? step.name + " failed" : message;
  outcomes_.push_back(o);
  return outcomes_.back();
}

void Runner::say(const StepOutcome& o) const {
  const std::string who = o.run.empty() ? o.step : o.run + " " + o.step;
  std::string line = "[" + study_ + "] " + who + ": " + status_word(o.status);
  if (o.status == StepStatus::Ran) line += " in " + Progress::format_duration(o.seconds);
  if (!o.message.empty()) line += " (" + o.message + ")";
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

Records& Runner::records(const std::string& folder) {
  auto it = records_.find(folder);
  if (it == records_.end()) {
    if (!options_.dry_run) fs::create_directories(folder);
    it = records_.emplace(folder, std::make_unique<Records>(folder)).first;
  }
  return *it->second;
}

}  // namespace layers::study
