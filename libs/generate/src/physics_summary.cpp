// The spread of `layers validate --physics`'s measures over sequences and
// the crossing target's counts (see physics_summary.h).
#include "layers/generate/physics_summary.h"

#include <cmath>
#include <cstdio>

#include "layers/core/error.h"
#include "layers/generate/quantile.h"

namespace layers::generate {

Spread spread_of(const std::vector<double>& values) {
  std::vector<double> kept;
  for (const double v : values)
    if (!std::isnan(v)) kept.push_back(v);
  Spread s;
  s.count = static_cast<int>(kept.size());
  if (kept.empty()) return s;
  s.min = quantile(kept, 0.0);
  s.p10 = quantile(kept, 0.1);
  s.median = quantile(kept, 0.5);
  s.p90 = quantile(kept, 0.9);
  s.max = quantile(kept, 1.0);
  return s;
}

void PhysicsSummary::add_frame(const sim::FrameMeasures& frame) {
  // NaN compares false: an unmeasurable frame is not within.
  const bool h = frame.h_crossing <= target_, l = frame.l_crossing <= target_;
  ++frames_;
  h_within_ += h;
  l_within_ += l;
  both_within_ += h && l;
  current_within_ = current_within_ && h && l;
}

void PhysicsSummary::end_sequence(const std::vector<std::pair<std::string, double>>& columns) {
  if (sequences_ == 0) {
    for (const auto& c : columns) names_.push_back(c.first);
    values_.resize(names_.size());
  }
  if (columns.size() != names_.size())
    throw Error("PhysicsSummary: " + std::to_string(columns.size()) + " columns, expected " +
                std::to_string(names_.size()));
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i].first != names_[i])
      throw Error("PhysicsSummary: column " + std::to_string(i) + " is '" + columns[i].first + "', expected '" +
                  names_[i] + "'");
  }
  for (std::size_t i = 0; i < columns.size(); ++i) values_[i].push_back(columns[i].second);
  ++sequences_;
  sequences_within_ += current_within_;
  current_within_ = true;
}

Spread PhysicsSummary::spread(const std::string& column) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == column) return spread_of(values_[i]);
  throw Error("PhysicsSummary: no column '" + column + "'");
}

std::string PhysicsSummary::text() const {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "spread over %d sequences:\n  %-14s %9s %9s %9s %9s %9s\n", sequences_, "measure",
                "min", "p10", "median", "p90", "max");
  out += line;
  for (const std::string& name : names_) {
    const Spread s = spread(name);
    std::snprintf(line, sizeof(line), "  %-14s %8.3f%% %8.3f%% %8.3f%% %8.3f%% %8.3f%%  (%d measured)\n", name.c_str(),
                  100 * s.min, 100 * s.p10, 100 * s.median, 100 * s.p90, 100 * s.max, s.count);
    out += line;
  }
  const auto pct = [&](std::int64_t n) { return frames_ > 0 ? 100.0 * static_cast<double>(n) / frames_ : 0.0; };
  std::snprintf(line, sizeof(line),
                "crossing target %.2f%%: frames with H-crossing within it %lld of %lld (%.1f%%), L-crossing %lld "
                "(%.1f%%), both %lld (%.1f%%); sequences with both within it in every frame: %d of %d\n",
                100 * target_, static_cast<long long>(h_within_), static_cast<long long>(frames_), pct(h_within_),
                static_cast<long long>(l_within_), pct(l_within_), static_cast<long long>(both_within_),
                pct(both_within_), sequences_within_, sequences_);
  out += line;
  return out;
}

}  // namespace layers::generate
