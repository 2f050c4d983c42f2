// Paired per-sequence comparisons of the report's rows (see paired.h).
#include "layers/report/paired.h"

#include <cmath>
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
  std::map<std::string, double> error_by_sequence;  // mean over seeds of the finite errors
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
    for (std::size_t m : members)
      for (const SequenceMetrics& s : runs[m].eval->per_sequence)
        if (std::isfinite(s.error_mm)) {
          sums[s.id].first += s.error_mm;
          sums[s.id].second += 1;
        }
    for (const auto& [id, sum] : sums) row.error_by_sequence[id] = sum.first / sum.second;
    rows.push_back(std::move(row));
  }
  return rows;
}

PairedComparison compare(const Row& row, const Row& other, const std::string& why) {
  PairedComparison c;
  c.row = row.name;
  c.against = other.name;
  c.why = why;
  c.split = row.split;
  std::vector<double> a, b;
  for (const auto& [id, e] : row.error_by_sequence) {
    const auto it = other.error_by_sequence.find(id);
    if (it == other.error_by_sequence.end()) continue;
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
  return c;
}

}  // namespace

std::string PairedComparison::reading() const {
  if (difference.below_zero()) return "lower";
  if (difference.above_zero()) return "higher";
  return "not separated";
}

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
  return out;
}

std::string paired_csv(const std::vector<PairedComparison>& comparisons) {
  std::ostringstream out;
  out << "row,against,why,split,sequences,mean_diff_mm,low_mm,high_mm,sd_mm,wins,losses,ties\n";
  for (const PairedComparison& c : comparisons)
    out << csv_field(c.row) << ',' << csv_field(c.against) << ',' << c.why << ',' << csv_field(c.split) << ','
        << c.difference.n << ',' << exact(c.difference.mean) << ',' << exact(c.difference.low()) << ','
        << exact(c.difference.high()) << ',' << exact(c.difference.sd) << ',' << c.wins << ',' << c.losses << ','
        << c.ties << '\n';
  return out.str();
}

}  // namespace layers::report
