// Paired per-sequence comparisons of the report's rows (see paired.h).
#include "layers/report/paired.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "layers/report/seeds.h"
#include "text.h"

namespace layers::report {
namespace {

// One row of the comparison: an experiment (its seeds pooled) or a single run.
struct Row {
  std::string name, split, dataset;
  std::int64_t horizon = 0;
  bool learned = false;
  std::map<std::string, double> error_by_sequence;   // mean over seeds of the finite errors
  std::vector<std::map<std::string, double>> seeds;  // per seed run: its finite errors by sequence
};

std::vector<Row> rows_of(const std::vector<RunResults>& runs) {
  const std::vector<SeedGroup> groups = seed_groups(runs);
  std::vector<Row> rows;
  std::vector<bool> grouped_done(groups.size(), false);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!runs[i].eval) continue;
    const int g = seed_group_of(groups, i);
    std::vector<std::size_t> members{i};
    Row row;
    // A repeated experiment is named by the experiment even when only one
    // of its seeds is evaluated (seed_groups groups two or more).
    row.name = runs[i].repeated ? runs[i].experiment : runs[i].name;
    if (g >= 0) {
      if (grouped_done[static_cast<std::size_t>(g)]) continue;
      grouped_done[static_cast<std::size_t>(g)] = true;
      members = groups[static_cast<std::size_t>(g)].runs;
      row.name = groups[static_cast<std::size_t>(g)].experiment;
    }
    const EvalResults& first = *runs[members.front()].eval;
    row.split = first.split;
    row.dataset = first.dataset;
    row.horizon = first.horizon;
    row.learned = first.parameters > 0;
    std::map<std::string, std::pair<double, int>> sums;
    for (std::size_t m : members) {
      std::map<std::string, double>& seed = row.seeds.emplace_back();
      for (const SequenceMetrics& s : runs[m].eval->per_sequence)
        if (std::isfinite(s.error_mm)) {
          sums[s.id].first += s.error_mm;
          sums[s.id].second += 1;
          seed[s.id] = s.error_mm;
        }
    }
    for (const auto& [id, sum] : sums) row.error_by_sequence[id] = sum.first / sum.second;
    rows.push_back(std::move(row));
  }
  return rows;
}

// The sample variance over a learned row's seeds of each seed's mean error
// over `ids` (the compared sequences it has); NaN below two seeds.
double seed_variance(const Row& row, const std::vector<std::string>& ids) {
  std::vector<double> means;
  for (const auto& seed : row.seeds) {
    double sum = 0;
    int count = 0;
    for (const std::string& id : ids) {
      const auto it = seed.find(id);
      if (it == seed.end()) continue;
      sum += it->second;
      ++count;
    }
    if (count > 0) means.push_back(sum / count);
  }
  const MeanInterval m = mean_interval(means);
  return m.sd * m.sd;
}

// Satterthwaite's degrees of freedom as the t value is taken at: rounded
// down, at least 1.
double floored_df(double df) { return std::max(1.0, std::floor(df)); }

// The interval with seed-to-seed variance: SE^2 = sd^2 / n + sum over the
// learned sides of s_seed^2 / S, Satterthwaite's degrees of freedom.
void add_seed_interval(const Row& row, const Row& other, const std::vector<std::string>& ids, PairedComparison& c) {
  const MeanInterval& d = c.difference;
  const bool several = (row.learned && row.seeds.size() >= 2) || (other.learned && other.seeds.size() >= 2);
  const bool one = (row.learned && row.seeds.size() < 2) || (other.learned && other.seeds.size() < 2);
  if (!several || one || d.n < 2) return;
  const double n = static_cast<double>(d.n);
  const double v_seq = d.sd * d.sd / n;
  double v = v_seq, denominator = v_seq * v_seq / (n - 1);
  for (const Row* side : {&row, &other}) {
    if (!side->learned) continue;
    const double s = static_cast<double>(side->seeds.size());
    const double v_side = seed_variance(*side, ids) / s;
    if (!std::isfinite(v_side)) return;
    v += v_side;
    denominator += v_side * v_side / (s - 1);
  }
  c.with_seeds = true;
  c.seeds_se = std::sqrt(v);
  // All components zero (identical errors everywhere): the smallest df.
  c.seeds_df = denominator > 0 ? v * v / denominator : 1.0;
  c.seeds_half_width = t_critical_95(static_cast<std::size_t>(floored_df(c.seeds_df))) * c.seeds_se;
}

PairedComparison compare(const Row& row, const Row& other, const std::string& why) {
  PairedComparison c;
  c.row = row.name;
  c.against = other.name;
  c.why = why;
  c.split = row.split;
  c.row_seeds = row.learned ? row.seeds.size() : 0;
  c.against_seeds = other.learned ? other.seeds.size() : 0;
  std::vector<double> a, b;
  std::vector<std::string> ids;
  for (const auto& [id, e] : row.error_by_sequence) {
    const auto it = other.error_by_sequence.find(id);
    if (it == other.error_by_sequence.end()) continue;
    ids.push_back(id);
    a.push_back(e);
    b.push_back(it->second);
    if (e < it->second)
      ++c.wins;
    else if (e > it->second)
      ++c.losses;
    else
      ++c.ties;
  }
  c.difference = paired_interval(a, b);
  add_seed_interval(row, other, ids, c);
  // The p-value of the interval read, with the degrees of freedom its t
  // value was taken at.
  const MeanInterval& d = c.difference;
  if (c.with_seeds) {
    c.p_value = c.seeds_se > 0 ? t_two_sided_p(d.mean / c.seeds_se, floored_df(c.seeds_df)) : (d.mean == 0 ? 1.0 : 0.0);
  } else if (d.n >= 2) {
    const double se = d.sd / std::sqrt(static_cast<double>(d.n));
    c.p_value = se > 0 ? t_two_sided_p(d.mean / se, static_cast<double>(d.n - 1)) : (d.mean == 0 ? 1.0 : 0.0);
  } else {
    c.p_value = std::numeric_limits<double>::quiet_NaN();
  }
  return c;
}

}  // namespace

std::string PairedComparison::reading() const {
  if (with_seeds) {
    if (seeds_high() < 0) return "lower";
    if (seeds_low() > 0) return "higher";
    return "not separated";
  }
  if (difference.below_zero()) return "lower";
  if (difference.above_zero()) return "higher";
  return "not separated";
}

std::string PairedComparison::holm_reading() const { return holm ? reading() : "not separated"; }

std::vector<PairedComparison> paired_comparisons(const std::vector<RunResults>& runs,
                                                 const std::map<std::string, std::string>& partners,
                                                 std::vector<std::string>* missing) {
  const std::vector<Row> rows = rows_of(runs);
  const auto find = [&](const std::string& name) -> const Row* {
    for (const Row& r : rows)
      if (r.name == name) return &r;
    return nullptr;
  };
  // Paired only on the same scenes and rollouts: same split, dataset and
  // evaluation horizon.
  const auto comparable = [](const Row& a, const Row& b) {
    return a.split == b.split && a.dataset == b.dataset && a.horizon == b.horizon;
  };
  const auto note = [&](const std::string& text) {
    if (missing) missing->push_back(text);
  };
  std::vector<PairedComparison> out;
  for (const auto& [row_name, partner_name] : partners) {
    const Row* row = find(row_name);
    if (row && !row->learned) note(row_name + ": not a learned row, so it is not compared with a partner");
    if (row_name == partner_name) note(row_name + ": its own partner, not compared");
  }
  for (const Row& row : rows) {
    if (!row.learned) continue;
    for (const Row& other : rows)
      if (!other.learned && comparable(row, other)) out.push_back(compare(row, other, "reference"));
    const auto p = partners.find(row.name);
    if (p == partners.end() || p->second == row.name) continue;
    const Row* partner = find(p->second);
    if (partner == nullptr || !comparable(row, *partner)) {
      note(row.name + ": partner " + p->second +
           (partner ? " is evaluated on another split, dataset or horizon" : " is not in the report"));
      continue;
    }
    out.push_back(compare(row, *partner, "partner"));
  }
  // Holm's rule over the report's comparisons, as one family; a comparison
  // it rejects is still read only where its interval excludes 0.
  std::vector<double> p;
  for (const PairedComparison& c : out) p.push_back(c.p_value);
  const std::vector<bool> rejected = holm_rejects(p);
  for (std::size_t i = 0; i < out.size(); ++i) out[i].holm = rejected[i] && out[i].reading() != "not separated";
  return out;
}

std::string paired_csv(const std::vector<PairedComparison>& comparisons) {
  std::ostringstream out;
  out << "row,against,why,split,sequences,mean_diff_mm,low_mm,high_mm,sd_mm,wins,losses,ties,row_seeds,against_"
         "seeds,seeds_low_mm,seeds_high_mm,seeds_se_mm,seeds_df,interval,p_value,reading,holm_reading\n";
  for (const PairedComparison& c : comparisons) {
    out << csv_field(c.row) << ',' << csv_field(c.against) << ',' << c.why << ',' << csv_field(c.split) << ','
        << c.difference.n << ',' << exact(c.difference.mean) << ',' << exact(c.difference.low()) << ','
        << exact(c.difference.high()) << ',' << exact(c.difference.sd) << ',' << c.wins << ',' << c.losses << ','
        << c.ties << ',' << c.row_seeds << ',' << c.against_seeds << ',';
    if (c.with_seeds)
      out << exact(c.seeds_low()) << ',' << exact(c.seeds_high()) << ',' << exact(c.seeds_se) << ','
          << exact(c.seeds_df) << ",sequences+seeds,";
    else
      out << ",,,,sequences,";
    out << exact(c.p_value) << ',' << csv_field(c.reading()) << ',' << csv_field(c.holm_reading()) << '\n';
  }
  return out.str();
}

}  // namespace layers::report
