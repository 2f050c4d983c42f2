// report.md's text (see markdown.h).
#include "markdown.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "layers/metrics/registry.h"
#include "layers/report/seeds.h"
#include "layers/report/tables.h"
#include "text.h"

namespace layers::report {
namespace {

const std::vector<metrics::MetricDef>& registry() { return metrics::registered(); }

// A run's value of a metric in a table cell: mean ± std (mm) or the mean
// as a percentage (shares).
std::string cell(const metrics::MetricDef& d, const Stat& s) {
  if (d.unit == metrics::Unit::Millimetre) return mean_pm_std(s.mean, s.std);
  return s.count == 0 ? "-" : percent(s.mean);
}

// The metric headings of a table, its alignment cells, and the ground
// truth's heading (its metrics joined by " / ").
std::string metric_headings() {
  std::string out;
  for (const metrics::MetricDef& d : registry()) out += " " + d.label + " |";
  return out;
}
std::string metric_alignment() {
  std::string out;
  for (std::size_t k = 0; k < registry().size(); ++k) out += "---:|";
  return out;
}
std::string truth_heading() {
  std::string out;
  for (const metrics::MetricDef& d : registry())
    if (d.truth) out += (out.empty() ? "ground truth " : " / ") + d.label;
  return out;
}
std::string truth_cell(const EvalResults& e) {
  std::string out;
  for (const metrics::MetricDef& d : registry())
    if (d.truth) {
      const double v = e.truth_of(d.key);
      out += (out.empty() ? "" : " / ") + (d.unit != metrics::Unit::Millimetre ? percent(v)
                                           : std::isfinite(v)                  ? fixed(v, 1)
                                                                               : "-");
    }
  return out;
}

void charts_of(std::ostringstream& md, const ChartSection& section, const std::string& dir) {
  if (!section.missing.empty()) md << "*Chart not drawn: " << section.missing << "*\n\n";
  for (const Chart& c : section.charts)
    md << "![" << c.title << "](" << dir << "/" << c.file << ")\n\n" << c.caption << "\n\n";
}

std::string ms(double v) { return std::isfinite(v) && v > 0 ? fixed(v, v < 10 ? 3 : 1) : "-"; }

std::string divergence(const EvalResults& e) {
  if (e.diverged == 0) return "0 of " + std::to_string(e.sequences);
  const std::int64_t step = e.first_divergence_step();
  return std::to_string(e.diverged) + " of " + std::to_string(e.sequences) +
         (step >= 0 ? " (first at step " + std::to_string(step) + ")" : "");
}

// " **⚠ chosen on the test split (test)**": the mark after a run's name when its checkpoint
// was chosen on the test split or on the split it is evaluated on.
std::string selection_mark(const RunResults& r) {
  if (selection_flag(r).empty()) return "";
  const std::string& on = r.eval->selection.chosen_on;
  return on == r.test_split ? " **⚠ chosen on the test split (" + md_cell(on) + ")**"
                            : " **⚠ chosen on " + md_cell(on) + ", the split evaluated**";
}

// `mean ± std` over seeds of a rate, as percentages.
std::string percent_pm(const Stat& s) {
  if (s.count == 0) return "-";
  return percent(s.mean) + (std::isfinite(s.std) ? " ± " + fixed(100.0 * s.std, 2) : "");
}

// A run's name cell with its selection mark.
std::string run_name_cell(const RunResults& r) { return md_cell(r.name) + selection_mark(r); }

// One row of the models table for an experiment repeated over seeds.
void seed_row(std::ostringstream& md, const SeedGroup& g, const std::vector<RunResults>& runs) {
  const EvalResults& first = *runs[g.runs.front()].eval;
  std::string mark;
  for (std::size_t i : g.runs)
    if (mark.empty()) mark = selection_mark(runs[i]);
  md << "| " << md_cell(g.experiment) << " (" << g.runs.size() << " seeds)" << mark << " | " << md_cell(g.model)
     << " | " << first.parameters << " | " << md_cell(g.split) << " (" << g.sequences << ") |";
  for (const metrics::MetricDef& d : registry()) {
    const Stat m = g.over_seeds.get(d.key);
    const double spread = g.over_sequences.get(d.key).mean;
    if (d.unit == metrics::Unit::Millimetre)
      md << " " << mean_pm_std(m.mean, m.std)
         << (std::isfinite(spread) ? " (sequences ± " + fixed(spread, 1) + ")" : std::string()) << " |";
    else
      md << " " << percent_pm(m) << " |";
  }
  md << " " << truth_cell(first) << " | " << g.diverged << " of "
     << g.sequences * static_cast<std::int64_t>(g.runs.size()) << " | " << ms(g.ms_per_frame) << " |  |\n";
}

// Which split chose each run's checkpoint and which it is evaluated on.
void selection_table(std::ostringstream& md, const std::vector<RunResults>& runs) {
  md << "### Selection\n\n"
     << "Which split chose each run's checkpoint (`checkpoint-best.pt`: the epoch with the lowest validation "
        "error; `last`: nothing chosen) and which split its figures are on. A run whose checkpoint was chosen on "
        "the test split, or on the split it is evaluated on, is marked ⚠: its figures are not a held-out "
        "result. \"unknown\": evaluated before evaluations recorded the choice. Validation error: the chosen "
        "epoch's (the run's selection.json), what variants are compared by; the evaluation figures above are not.\n\n"
     << "| run | checkpoint | chosen on | epoch chosen / epochs | by | validation error (mm) | evaluated on | |\n"
     << "|---|---|---|---:|---|---:|---|---|\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    const SelectionRecord& s = r.eval->selection;
    const std::string flag = selection_flag(r);
    md << "| " << md_cell(r.name) << " | " << md_cell(s.checkpoint) << " | " << md_cell(s.chosen_on) << " | "
       << (s.chosen_epoch > 0 ? std::to_string(s.chosen_epoch) : "-") << " / "
       << (s.epochs > 0 ? std::to_string(s.epochs) : "-") << " | " << md_cell(s.metric.empty() ? "-" : s.metric)
       << " | " << (std::isfinite(s.val_error_mm) ? fixed(s.val_error_mm, 2) : "-") << " | " << md_cell(s.evaluated_on)
       << " | " << (flag.empty() ? "" : "⚠ " + md_cell(flag)) << " |\n";
  }
  md << "\n";
}

void models_table(std::ostringstream& md, const std::vector<RunResults>& runs) {
  const std::vector<bool> front = runs_on_front(runs);
  md << "## Models\n\n"
     << "| run | model | parameters | split (sequences) |" << metric_headings() << " " << truth_heading()
     << " | diverged | ms / frame | Pareto front |\n"
     << "|---|---|---:|---|" << metric_alignment() << "---:|---:|---:|:---:|\n";
  std::vector<const RunResults*> missing;
  const std::vector<SeedGroup> groups = seed_groups(runs);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    if (!r.eval) {
      missing.push_back(&r);
      continue;
    }
    if (const int g = seed_group_of(groups, i); g >= 0) {
      if (groups[g].runs.front() == i) seed_row(md, groups[g], runs);
      continue;
    }
    const EvalResults& e = *r.eval;
    md << "| " << run_name_cell(r) << " | " << md_cell(r.model) << " | " << e.parameters << " | " << md_cell(e.split)
       << " (" << e.sequences << ") |";
    for (const metrics::MetricDef& d : registry()) md << " " << cell(d, e.overall.get(d.key)) << " |";
    md << " " << truth_cell(e) << " | " << divergence(e) << " | " << ms(e.ms_per_frame) << " | "
       << (front[i] ? "yes" : "") << " |\n";
  }
  md << "\n";
  for (const metrics::MetricDef& d : registry())
    md << "- **" << d.label << "**: " << d.description << " (docs/metrics.md, " << d.rule << "); "
       << (d.unit == metrics::Unit::Millimetre ? "mean ± std over sequences" : "mean over sequences") << ", "
       << (d.better == metrics::Better::Lower ? "lower" : "higher") << " is better.\n";
  md << "\nThe ground truth's own values are given for reference (the simulator is not perfect either); \"-\": a "
        "value not measured (an evaluation made before the metric existed, or no inner and outer garment). ms / "
        "frame: time in the model per predicted frame during evaluation.\n\n";
  if (!groups.empty())
    md << "An experiment repeated over seeds is one row, \"name (n seeds)\": each value is the mean ± std over "
          "the seeds of the seeds' overall values (sample std); the error's spread over sequences (mean over "
          "the seeds of each seed's std over sequences) follows in brackets; diverged counts all seeds' "
          "sequences. Each seed's row is in `summary.csv`, the rows over seeds in `seeds.csv`.\n\n";
  for (const SeedGroup& g : groups) {
    md << "- `" << g.experiment << "` per seed, error (mm):";
    for (std::size_t k = 0; k < g.runs.size(); ++k)
      md << (k ? "," : "") << " seed " << g.seeds[k] << " "
         << fixed(runs[g.runs[k]].eval->overall.get(metrics::kError).mean, 1);
    md << "\n";
  }
  if (!groups.empty()) md << "\n";
  for (const RunResults* r : missing)
    md << "- `" << r->name << "` is not in the table: it has no readable evaluation (see Notes).\n";
  if (!missing.empty()) md << "\n";
}

void paired_table(std::ostringstream& md, const std::vector<PairedComparison>& paired) {
  if (paired.empty()) return;
  const auto cell = [](const std::string& reading) {
    return reading == "lower"    ? std::string("**lower error**")
           : reading == "higher" ? std::string("**higher error**")
                                 : std::string("not separated");
  };
  md << "### Paired comparisons (error per sequence)\n\n"
     << "Each learned row against each reference row (no trained parameters) and against its partner, on the "
        "sequences both evaluated on the same split: per sequence the row's error minus the other's (an "
        "experiment over seeds contributes its mean over seeds per sequence), the mean difference with its 95% "
        "interval over sequences (paired Student t, sample std), and the sequences where the row is lower / "
        "higher. Where a learned side has several seeds, a second interval also counts the seed-to-seed "
        "variance (the variance over seeds of each seed's mean error, over the number of seeds, added to the "
        "squared standard error; Satterthwaite's degrees of freedom): that is the interval read, and the "
        "p-value is its. A difference is read as one only where the interval read excludes 0. The reading "
        "column is unadjusted; the Holm column keeps only what Holm's rule at 5% still separates over all "
        "the "
     << paired.size() << " comparisons of this table. All pairs are in `paired.csv`.\n\n"
     << "| row | against | split (sequences) | difference (mm) [95%, sequences] | [95%, sequences and seeds] "
        "(seeds) | lower / higher | p | reading (unadjusted) | Holm |\n"
     << "|---|---|---|---:|---:|---:|---:|---|---|\n";
  const auto seeds = [](std::size_t s) { return s == 0 ? std::string("-") : std::to_string(s); };
  for (const PairedComparison& c : paired) {
    const MeanInterval& d = c.difference;
    md << "| `" << md_cell(c.row) << "` | `" << md_cell(c.against) << "`" << (c.why == "partner" ? " (partner)" : "")
       << " | " << md_cell(c.split) << " (" << d.n << ") | " << (std::isfinite(d.mean) ? signed_fixed(d.mean, 2) : "-")
       << " [" << (std::isfinite(d.half_width) ? signed_fixed(d.low(), 2) + ", " + signed_fixed(d.high(), 2) : "n/a")
       << "] | "
       << (c.with_seeds ? "[" + signed_fixed(c.seeds_low(), 2) + ", " + signed_fixed(c.seeds_high(), 2) + "]" : "-")
       << " (" << seeds(c.row_seeds) << " / " << seeds(c.against_seeds) << ") | " << c.wins << " / " << c.losses
       << " | "
       << (!std::isfinite(c.p_value) ? std::string("-")
           : c.p_value < 0.001       ? std::string("<0.001")
                                     : fixed(c.p_value, 3))
       << " | " << cell(c.reading()) << " | " << cell(c.holm_reading()) << " |\n";
  }
  md << "\n";
}

// One row per trained run: its validation error per epoch at a glance and
// whether the last epoch was still the best (a curve still falling).
void learning_table(std::ostringstream& md, const std::vector<RunResults>& runs) {
  bool any = false;
  for (const RunResults& r : runs) any = any || !r.curve.val_error_mm.empty();
  if (!any) return;
  md << "| run | epochs | windows seen | validation error (mm): first, best (epoch), last | still improving at the "
        "end |\n|---|---:|---:|---|---|\n";
  for (const RunResults& r : runs) {
    const LearningCurve& c = r.curve;
    std::size_t best = c.val_error_mm.size(), first = best;
    for (std::size_t k = 0; k < c.val_error_mm.size(); ++k) {
      if (!std::isfinite(c.val_error_mm[k])) continue;
      if (first == c.val_error_mm.size()) first = k;
      if (best == c.val_error_mm.size() || c.val_error_mm[k] < c.val_error_mm[best]) best = k;
    }
    if (best == c.val_error_mm.size()) continue;  // no validation error recorded
    const std::size_t last = c.val_error_mm.size() - 1;
    const double seen = c.windows_seen.empty() ? kAbsent : c.windows_seen.back();
    md << "| " << md_cell(r.name) << " | " << c.val_error_mm.size() << " | "
       << (std::isfinite(seen) ? std::to_string(static_cast<long long>(seen)) : "-") << " | ";
    if (c.only_best) {
      md << "best " << fixed(c.val_error_mm[best], 2) << " (" << best + 1
         << "); the other epochs' errors were not recorded (selection.json from before the trainer kept them) | - "
            "|\n";
      continue;
    }
    md << fixed(c.val_error_mm[first], 2) << ", " << fixed(c.val_error_mm[best], 2) << " (" << best + 1 << "), "
       << (std::isfinite(c.val_error_mm[last]) ? fixed(c.val_error_mm[last], 2) : "-") << " | "
       << (best == last && last > first ? "yes: the last epoch is the best" : "no") << " |\n";
  }
  for (const ReferenceLevel& level : curve_references(runs, nullptr))
    md << "| " << md_cell(level.name) << " (reference, not trained) | - | - | "
       << (std::isfinite(level.error_mm) ? fixed(level.error_mm, 2) : "-") << " on the same measure | - |\n";
  md << "\n";
}

void pareto_list(std::ostringstream& md, const std::vector<RunResults>& runs) {
  const std::vector<std::size_t> order = runs_front_order(runs);
  md << "**Pareto front of accuracy against speed** (fastest first; a run is on it when no other run is at least "
        "as fast and as accurate while better in one):\n\n";
  if (order.empty()) md << "- none: no run has both a measured speed and an error\n";
  for (std::size_t k = 0; k < order.size(); ++k) {
    const EvalResults& e = *runs[order[k]].eval;
    md << k + 1 << ". `" << runs[order[k]].name << "` (" << runs[order[k]].model << "): " << ms(e.ms_per_frame)
       << " ms/frame, " << fixed(e.overall.get(metrics::kError).mean, 1) << " mm\n";
  }
  md << "\n";
}

void bench_table(std::ostringstream& md, const std::vector<RunResults>& runs) {
  bool any = false;
  for (const RunResults& r : runs) any = any || (r.bench && !r.bench->rows.empty());
  if (!any) return;
  md << "### Speed by scene size (`layers bench`)\n\n"
     << "Inference at batch 1 on one scene of each run's dataset (bench.json's `sequence`: in a study, the "
        "first of the split the run is evaluated on), the garments subdivided (about 4x vertices per level); "
        "\"far body\" adds a copy of the body 100 m away, which should cost nothing when the model "
        "only attends to particles that matter.\n\n"
     << "| run | level | garment vertices | body vertices | far body | ms / frame | train ms / frame | counters |\n"
     << "|---|---:|---:|---:|:---:|---:|---:|---|\n";
  for (const RunResults& r : runs) {
    if (!r.bench) continue;
    for (const BenchPoint& b : r.bench->rows) {
      std::string counters;
      for (const auto& [k, v] : b.counters) counters += (counters.empty() ? "" : ", ") + k + " " + exact(v);
      md << "| " << md_cell(r.name) << " | " << b.level << " | " << b.garment_vertices << " | " << b.body_vertices
         << " | " << (b.far_body ? "yes" : "no") << " | " << ms(b.ms_per_frame) << " | " << ms(b.train_ms_per_frame)
         << " | " << md_cell(counters) << " |\n";
    }
  }
  md << "\n";
}

void divergence_list(std::ostringstream& md, const std::vector<RunResults>& runs) {
  md << "Divergence (a non-finite prediction or a frame error above the bound; rollouts never stop the "
        "evaluation):\n\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    const EvalResults& e = *r.eval;
    md << "- `" << r.name << "`: ";
    const std::int64_t step = e.first_divergence_step();
    if (step < 0) {
      md << "no divergence in " << e.sequences << " sequence" << (e.sequences == 1 ? "" : "s") << " over "
         << e.by_step.size() << " steps";
    } else {
      std::string where;
      for (const SequenceMetrics& s : e.per_sequence)
        if (s.diverged_at - 1 == step) where = s.id + (s.diverge_reason.empty() ? "" : ": " + s.diverge_reason);
      md << e.diverged << " of " << e.sequences << " sequences diverged; first at step " << step << " (frame "
         << step + 1 << ", " << md_cell(where) << ")";
    }
    md << (std::isfinite(e.diverge_mm) ? ", bound " + fixed(e.diverge_mm, 0) + " mm" : std::string()) << "\n";
  }
  md << "\n";
}

void per_type_table(std::ostringstream& md, const std::vector<RunResults>& runs) {
  md << "| garment type | run | sequences |" << metric_headings() << "\n"
     << "|---|---|---:|" << metric_alignment() << "\n";
  std::vector<std::string> types;
  for (const RunResults& r : runs)
    if (r.eval)
      for (const auto& [type, m] : r.eval->per_type)
        if (std::find(types.begin(), types.end(), type) == types.end()) types.push_back(type);
  std::sort(types.begin(), types.end());
  for (const std::string& type : types)
    for (const RunResults& r : runs) {
      if (!r.eval) continue;
      for (const auto& [t, m] : r.eval->per_type)
        if (t == type) {
          md << "| " << md_cell(type) << " | " << md_cell(r.name) << " | " << m.get(metrics::kError).count << " |";
          for (const metrics::MetricDef& d : registry()) md << " " << cell(d, m.get(d.key)) << " |";
          md << "\n";
        }
    }
  std::string outer;
  for (const metrics::MetricDef& d : registry())
    if (d.scope == metrics::Scope::OuterLayer) outer += (outer.empty() ? "" : ", ") + d.label;
  if (!outer.empty()) md << "\n" << outer << ": measured on the outer garment of a pair (\"-\" for inner garments).";
  md << "\n\n";
}

}  // namespace

std::string report_markdown(const ReportContent& c) {
  std::ostringstream md;
  md << "# " << c.title << "\n\n";
  std::size_t evaluated = 0;
  for (const RunResults& r : c.runs) evaluated += r.eval ? 1 : 0;
  md << "Made by `layers report` from " << c.runs.size() << " run folder" << (c.runs.size() == 1 ? "" : "s") << " ("
     << evaluated << " with an evaluation):";
  for (const RunResults& r : c.runs) md << " `" << r.dir << "`";
  md << ". Errors are real-world millimetres (the paper simulated at 10x scale: its mm are 10x ours); "
        "rates are percentages of vertices.\n\n";
  if (!c.problems.empty())
    md << "> " << c.problems.size() << " missing piece" << (c.problems.size() == 1 ? "" : "s")
       << " -- see [Notes](#notes) at the end.\n\n";

  std::vector<std::string> flagged;
  for (const RunResults& r : c.runs)
    if (!selection_flag(r).empty()) flagged.push_back("`" + r.name + "`");
  if (!flagged.empty()) {
    md << "> **⚠ Selection:** " << flagged.size() << " run" << (flagged.size() == 1 ? "" : "s")
       << " chose the checkpoint on the test split or on the split evaluated:";
    for (const std::string& f : flagged) md << " " << f;
    md << ". Those figures are not held-out results (see [Selection](#selection)).\n\n";
  }

  models_table(md, c.runs);
  paired_table(md, c.paired);
  selection_table(md, c.runs);
  md << "## Accuracy against speed\n\n";
  charts_of(md, c.speed, c.charts_dir);
  pareto_list(md, c.runs);
  bench_table(md, c.runs);

  md << "## Error and collisions along the rollout\n\n";
  divergence_list(md, c.runs);
  charts_of(md, c.by_step, c.charts_dir);

  md << "## Per garment type\n\n";
  per_type_table(md, c.runs);
  charts_of(md, c.per_type, c.charts_dir);

  md << "## Learning curves\n\n";
  charts_of(md, c.learning, c.charts_dir);
  learning_table(md, c.runs);
  md << "## Ground truth and predictions\n\n";
  charts_of(md, c.frames, c.charts_dir);
  if (!c.viewer_page.empty())
    md << "Played in the browser: [" << c.viewer_page << "](" << c.viewer_page << "). " << c.viewer_caption << "\n\n";
  else
    md << "No viewer: " << c.viewer_missing << ".\n\n";

  md << "## Notes\n\n";
  if (c.problems.empty()) md << "Nothing missing.\n";
  for (const std::string& p : c.problems) md << "- " << md_cell(p) << "\n";
  md << "\n## Files\n\n"
     << "- `summary.csv`, `summary.json`: the models table (rates as shares 0..1), Pareto membership; the JSON adds "
        "per-type values, benchmark rows, the front in speed order, these notes and the charts\n"
     << "- `per_type.csv`: one row per run and garment type\n"
     << "- `by_step.csv`: one row per run and rollout step\n"
     << "- `bench.csv`: one row per run and benchmarked scene size\n"
     << "- `seeds.csv`: one row per experiment repeated over seeds (mean, std over seeds, spread over sequences)\n"
     << "- `viewer/`: the viewer, a page that opens offline from disk (`index.html`, three.js, `scene.js` with the "
        "frames)\n"
     << "- `" << c.charts_dir
     << "/`: the PNG charts with their gnuplot scripts (`*.gp`) and data (`*.dat`); "
        "redraw one with `cd "
     << c.charts_dir << " && gnuplot <name>.gp`\n";
  return md.str();
}

}  // namespace layers::report
