// Where a step's time goes, by phase and operator (see op_profile.h).
#include "op_profile.h"

#include <torch/csrc/autograd/profiler_legacy.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "layers/core/progress.h"

namespace layers::train {
namespace {

namespace prof = torch::autograd::profiler;

constexpr const char* kPhase = "phase:";

bool is_phase(const std::string& name) { return name.rfind(kPhase, 0) == 0; }
bool is_backward(const std::string& name) { return name.rfind("autograd::engine::evaluate_function", 0) == 0; }

// Sums one thread's events: each pushed range's own time goes to its name
// and to its innermost phase.
void add_thread(const std::vector<prof::LegacyEvent>& events, StepProfile& p) {
  struct Open {
    const prof::LegacyEvent* event;
    std::string name, phase;
    double children_us = 0;
  };
  std::vector<Open> stack;
  for (const prof::LegacyEvent& e : events) {
    if (e.kind() == prof::EventKind::MemoryAlloc) {
      if (e.cpuMemoryUsage() > 0) {
        p.allocated_mb += static_cast<double>(e.cpuMemoryUsage()) / (1024.0 * 1024.0);
        p.allocations += 1;
      }
      continue;
    }
    if (e.kind() == prof::EventKind::PushRange) {
      std::string name = e.name();
      std::string phase = stack.empty() ? "other" : stack.back().phase;
      if (is_phase(name))
        phase = name.substr(std::strlen(kPhase));
      else if (is_backward(name))
        phase = "backward";
      stack.push_back({&e, std::move(name), std::move(phase)});
      continue;
    }
    if (e.kind() != prof::EventKind::PopRange || stack.empty()) continue;
    // The range this pop closes: the innermost open one with its handle
    // (ranges opened inside it and never closed end with it).
    std::size_t at = stack.size();
    while (at > 0 && stack[at - 1].event->handle() != e.handle()) --at;
    if (at == 0) continue;  // a pop of a range opened before profiling
    while (stack.size() > at) stack.pop_back();
    Open open = std::move(stack.back());
    stack.pop_back();
    const double total_us = open.event->cpuElapsedUs(e);
    const double own_ms = std::max(0.0, total_us - open.children_us) / 1000.0;
    if (!stack.empty()) stack.back().children_us += total_us;
    prof::LegacyEvent& flops_of = const_cast<prof::LegacyEvent&>(*open.event);
    const double gflop = static_cast<double>(flops_of.flops()) * 1e-9;
    OpTotals& phase = p.phases[open.phase];
    phase.ms += own_ms;
    OpTotals& op = p.ops[open.name];
    op.ms += own_ms;
    op.calls += 1;
    op.gflop += gflop;
    if (!is_phase(open.name)) {
      phase.calls += 1;
      phase.gflop += gflop;
      OpTotals& in_phase = p.phase_ops[open.phase][open.name];
      in_phase.ms += own_ms;
      in_phase.calls += 1;
      in_phase.gflop += gflop;
    }
  }
}

}  // namespace

StepProfile profile_steps(const std::function<void()>& step, int steps, int warmup) {
  for (int i = 0; i < warmup; ++i) step();
  StepProfile p;
  p.steps = std::max(steps, 1);
  prof::thread_event_lists lists;
  Timer timer;
  {
    const torch::profiler::impl::ProfilerConfig config(torch::profiler::impl::ProfilerState::CPU,
                                                       /*report_input_shapes=*/true, /*profile_memory=*/true,
                                                       /*with_stack=*/false, /*with_flops=*/true);
    prof::TLSLegacyProfilerGuard guard(config, [&](const prof::thread_event_lists& l) { lists = l; });
    for (int i = 0; i < p.steps; ++i) step();
  }
  p.ms = timer.seconds() * 1000.0 / p.steps;
  for (const auto& thread : lists) add_thread(thread, p);
  const double n = p.steps;
  double matmul_gflop = 0, matmul_ms = 0, all_gflop = 0;
  for (auto* totals : {&p.phases, &p.ops})
    for (auto& [name, t] : *totals) t.ms /= n, t.calls /= n, t.gflop /= n;
  for (auto& [phase, ops] : p.phase_ops)
    for (auto& [name, t] : ops) t.ms /= n, t.calls /= n, t.gflop /= n;
  for (const auto& [name, t] : p.ops) {
    all_gflop += t.gflop;
    if (t.gflop > 0 && (name == "aten::mm" || name == "aten::addmm" || name == "aten::bmm" || name == "aten::matmul" ||
                        name == "aten::baddbmm"))
      matmul_gflop += t.gflop, matmul_ms += t.ms;
  }
  p.allocated_mb /= n;
  p.allocations /= n;
  p.matmul_gflops = matmul_ms > 0 ? matmul_gflop / (matmul_ms / 1000.0) : 0;
  p.step_gflops = p.ms > 0 ? all_gflop / (p.ms / 1000.0) : 0;
  return p;
}

double matmul_peak_gflops(std::int64_t n) {
  const at::Tensor a = at::randn({n, n}), b = at::randn({n, n});
  at::Tensor c = at::mm(a, b);  // warm up
  double best = 0;
  for (int rep = 0; rep < 5; ++rep) {
    Timer timer;
    int products = 0;
    while (timer.seconds() < 0.1) c = at::mm(a, b), ++products;
    best = std::max(best, 2.0 * static_cast<double>(n * n * n) * products / timer.seconds() * 1e-9);
  }
  return best;
}

std::vector<std::pair<std::string, double>> phase_list(const StepProfile& p) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [name, t] : p.phases) out.emplace_back(name, t.ms);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

nlohmann::ordered_json to_json(const StepProfile& p, std::size_t top) {
  using json = nlohmann::ordered_json;
  const auto by_time = [](const std::map<std::string, OpTotals>& m) {
    std::vector<std::pair<std::string, OpTotals>> v(m.begin(), m.end());
    std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second.ms > b.second.ms; });
    return v;
  };
  json phases = json::array(), ops = json::array();
  for (const auto& [name, t] : by_time(p.phases)) {
    json top_in_phase = json::array(), most_called = json::array();
    const auto it = p.phase_ops.find(name);
    if (it != p.phase_ops.end()) {
      for (const auto& [op, o] : by_time(it->second)) {
        if (top_in_phase.size() >= 5) break;
        top_in_phase.push_back({{"op", op}, {"ms", o.ms}, {"calls", o.calls}});
      }
      std::vector<std::pair<std::string, OpTotals>> calls(it->second.begin(), it->second.end());
      std::sort(calls.begin(), calls.end(),
                [](const auto& a, const auto& b) { return a.second.calls > b.second.calls; });
      for (std::size_t k = 0; k < calls.size() && k < 5; ++k)
        most_called.push_back({{"op", calls[k].first}, {"calls", calls[k].second.calls}});
    }
    phases.push_back({{"phase", name},
                      {"ms", t.ms},
                      {"share", p.ms > 0 ? t.ms / p.ms : 0.0},
                      {"ops", t.calls},
                      {"gflop", t.gflop},
                      {"top_ops", top_in_phase},
                      {"most_called", most_called}});
  }
  for (const auto& [name, t] : by_time(p.ops)) {
    if (is_phase(name)) continue;
    if (ops.size() >= top) break;
    ops.push_back({{"op", name}, {"ms", t.ms}, {"calls", t.calls}, {"gflop", t.gflop}});
  }
  double calls = 0, attributed = 0;
  for (const auto& [name, t] : p.ops)
    if (!is_phase(name)) calls += t.calls;
  for (const auto& [name, t] : p.phases) attributed += t.ms;
  // Time in no profiled range (glue between operators outside any phase).
  phases.push_back({{"phase", "(outside ranges)"},
                    {"ms", p.ms - attributed},
                    {"share", p.ms > 0 ? (p.ms - attributed) / p.ms : 0.0},
                    {"ops", 0},
                    {"gflop", 0}});
  return {{"ms", p.ms},
          {"steps", p.steps},
          {"ops", calls},
          {"allocated_mb", p.allocated_mb},
          {"allocations", p.allocations},
          {"matmul_gflops", p.matmul_gflops},
          {"step_gflops", p.step_gflops},
          {"phases", phases},
          {"top_ops", ops}};
}

}  // namespace layers::train
