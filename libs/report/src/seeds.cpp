// Experiments repeated over seeds: grouping their runs and the statistics
// over seeds (see seeds.h).
#include "layers/report/seeds.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "layers/metrics/registry.h"
#include "text.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

// Mean and std of the finite values, as the evaluator aggregates
// (metrics::finite_mean_std); count 0 and NaN when none.
Stat stat_of(const std::vector<double>& values) {
  const metrics::MeanStd m = metrics::finite_mean_std(values);
  if (m.count == 0) return Stat{};
  return Stat{m.mean, m.std, static_cast<std::int64_t>(m.count)};
}

// The folder that holds a seed run's seed-<s> folder (its experiment).
std::string experiment_folder(const RunResults& r) {
  const fs::path dir(r.dir);
  const fs::path folder = dir.has_filename() ? dir : dir.parent_path();
  return fs::absolute(folder).lexically_normal().parent_path().string();
}

void summarise(SeedGroup& g, const std::vector<RunResults>& runs) {
  for (const metrics::MetricDef& d : metrics::registered()) {
    std::vector<double> means, spreads;
    for (std::size_t i : g.runs) {
      means.push_back(runs[i].eval->overall.get(d.key).mean);
      spreads.push_back(runs[i].eval->overall.get(d.key).std);
    }
    g.over_seeds.by_key[d.key] = stat_of(means);
    const Stat spread = stat_of(spreads);
    Stat& over_sequences = g.over_sequences.by_key[d.key];
    over_sequences.mean = spread.mean;
    over_sequences.count = spread.count;
  }
  std::vector<double> ms;
  for (std::size_t i : g.runs) {
    const EvalResults& e = *runs[i].eval;
    ms.push_back(e.ms_per_frame);
    g.diverged += e.diverged;
  }
  g.ms_per_frame = stat_of(ms).mean;
  const EvalResults& first = *runs[g.runs.front()].eval;
  g.model = runs[g.runs.front()].model;
  g.split = first.split;
  g.sequences = first.sequences;
}

}  // namespace

std::vector<SeedGroup> seed_groups(const std::vector<RunResults>& runs) {
  std::vector<SeedGroup> groups;
  std::vector<std::string> keys;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    if (!r.repeated || !r.eval) continue;
    // One experiment: the same name and settings (its seeds may sit in the
    // folders of several kept parts), else the same folder.
    const std::string key = r.settings.empty() ? experiment_folder(r) : r.experiment + "\n" + r.settings;
    std::size_t k = 0;
    while (k < keys.size() && keys[k] != key) ++k;
    if (k == keys.size()) {
      keys.push_back(key);
      groups.emplace_back();
      groups.back().experiment = r.experiment;
    }
    groups[k].runs.push_back(i);
    groups[k].seeds.push_back(r.seed);
  }
  std::vector<SeedGroup> several;
  for (SeedGroup& g : groups) {
    if (g.runs.size() < 2) continue;
    summarise(g, runs);
    several.push_back(std::move(g));
  }
  return several;
}

int seed_group_of(const std::vector<SeedGroup>& groups, std::size_t run) {
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t i : groups[g].runs)
      if (i == run) return static_cast<int>(g);
  return -1;
}

std::string seeds_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "experiment,model,split,seeds,seed_list,sequences";
  for (const metrics::MetricDef& d : metrics::registered())
    out << ',' << d.key << ',' << d.key << "_std_seeds," << d.key << "_std_sequences";
  out << ",ms_per_frame,diverged\n";
  for (const SeedGroup& g : seed_groups(runs)) {
    std::string seeds;
    for (std::uint64_t s : g.seeds) seeds += (seeds.empty() ? "" : " ") + std::to_string(s);
    out << csv_field(g.experiment) << ',' << csv_field(g.model) << ',' << csv_field(g.split) << ',' << g.runs.size()
        << ',' << seeds << ',' << g.sequences;
    for (const metrics::MetricDef& d : metrics::registered())
      out << ',' << exact(g.over_seeds.get(d.key).mean) << ',' << exact(g.over_seeds.get(d.key).std) << ','
          << exact(g.over_sequences.get(d.key).mean);
    out << ',' << exact(g.ms_per_frame) << ',' << g.diverged << '\n';
  }
  return out.str();
}

}  // namespace layers::report
