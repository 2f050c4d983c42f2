// The cross-check measures and table (see crosscheck.h).
#include "layers/generate/crosscheck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "layers/core/error.h"
#include "layers/generate/stored_measures.h"
#include "layers/geometry/penetration.h"

namespace layers::generate {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The sequence with the run's garment positions, cut to its n_frames.
data::SequenceData with_positions(const data::SequenceData& seq, const CrosscheckRun& run) {
  if (run.garments.size() != seq.garments.size())
    throw InputError(run.label, "garments", std::to_string(seq.garments.size()), std::to_string(run.garments.size()));
  data::SequenceData out = seq;
  for (std::size_t k = 0; k < seq.garments.size(); ++k) {
    const std::size_t need = static_cast<std::size_t>(seq.n_frames * seq.garments[k].n_vertices() * 3);
    if (run.garments[k].size() < need)
      throw InputError(run.label, "garment " + std::to_string(k) + " positions", std::to_string(need) + " floats",
                       std::to_string(run.garments[k].size()));
    out.garments[k].positions.assign(run.garments[k].begin(), run.garments[k].begin() + need);
  }
  return out;
}

// Counts of the vertex-normal L test for one frame.
struct LCounts {
  std::int64_t outer = 0, within_1cm = 0, within_3cm = 0, any = 0;
};

LCounts l_counts(const StoredFrame& f) {
  std::vector<geometry::TriMesh> inner;
  for (const auto& g : f.garments)
    if (!g.outer) inner.push_back(geometry::TriMesh{g.positions, g.faces});
  LCounts c;
  if (inner.empty()) return c;
  const geometry::Surface surface = geometry::Surface::from_mesh(geometry::concatenate(inner), "inner garments");
  for (const auto& g : f.garments) {
    if (!g.outer) continue;
    for (Eigen::Index i = 0; i < g.positions.rows(); ++i) {
      const Eigen::RowVector3f x = g.positions.row(i);
      const geometry::Neighbour h = surface.index().nearest(x);
      ++c.outer;
      if (h.index < 0) continue;
      const float offset = (x - surface.vertices().row(h.index)).dot(surface.normals().row(h.index));
      if (!(offset < 0.0f)) continue;
      ++c.any;
      if (h.distance < 0.03f) ++c.within_3cm;
      if (h.distance < 0.01f) ++c.within_1cm;
    }
  }
  return c;
}

bool finite_frame(const StoredFrame& f) {
  for (const auto& g : f.garments)
    if (sim::count_nonfinite(g.positions) > 0) return false;
  return true;
}

double share(std::int64_t part, std::int64_t whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : kNaN;
}

std::string percent(double v, int digits = 2) {
  if (std::isnan(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f%%", digits, 100.0 * v);
  return buf;
}

std::string number(double v) {
  if (std::isnan(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.0f", v);
  return buf;
}

}  // namespace

CrosscheckColumn measure_crosscheck(const data::SequenceData& seq, const CrosscheckRun& run) {
  const data::SequenceData sim = with_positions(seq, run);
  CrosscheckColumn col;
  col.label = run.label;
  col.ms_per_frame = run.ms_per_frame;
  std::vector<float> stretch;
  std::int64_t h_behind = 0, h_total = 0;
  LCounts l;
  sim::SequenceMeasures generator;
  for_each_stored_frame(sim, [&](std::int64_t t, const StoredFrame& f) {
    if (t == 0) return;
    ++col.frames;
    if (!finite_frame(f)) {
      for (const auto& g : f.garments) col.nonfinite += sim::count_nonfinite(g.positions);
      return;
    }
    const geometry::Surface body = geometry::Surface::from_mesh(f.body, "body");
    for (const auto& g : f.garments) {
      h_behind += body.count_behind(g.positions);
      h_total += g.positions.rows();
      for (Eigen::Index e = 0; e < g.edges.rows(); ++e) {
        const double len = (g.positions.row(g.edges(e, 0)) - g.positions.row(g.edges(e, 1))).norm();
        const double s = g.rest_lengths[e] > 0 ? len / g.rest_lengths[e] - 1.0 : 0.0;
        stretch.push_back(static_cast<float>(std::max(0.0, s)));
      }
    }
    const LCounts c = l_counts(f);
    l.outer += c.outer;
    l.within_1cm += c.within_1cm;
    l.within_3cm += c.within_3cm;
    l.any += c.any;
    generator.add(sim::measure_frame(f.body, f.garments));
  });
  col.stretch_max = stretch.empty() ? 0.0 : *std::max_element(stretch.begin(), stretch.end());
  col.stretch_p99 = quantile(stretch, 0.99);
  col.h = share(h_behind, h_total);
  col.l_1cm = share(l.within_1cm, l.outer);
  col.l_3cm = share(l.within_3cm, l.outer);
  col.l_all = share(l.any, l.outer);
  col.gen_h = generator.frames() > 0 ? generator.mean_h_penetration() : kNaN;
  col.gen_l = generator.frames() > 0 && l.outer > 0 ? generator.mean_l_penetration() : kNaN;
  col.gen_stretch_max = generator.max_stretch();
  col.nonfinite += generator.nonfinite();
  const bool measured = generator.frames() > 0, layered = measured && l.outer > 0;
  col.h_crossing = measured ? generator.mean_h_crossing() : kNaN;
  col.h_crossing_max = measured ? generator.max_h_crossing() : kNaN;
  col.l_crossing = layered ? generator.mean_l_crossing() : kNaN;
  col.l_crossing_max = layered ? generator.max_l_crossing() : kNaN;
  return col;
}

sim::FrameMeasures measure_start(const data::SequenceData& seq) {
  data::SequenceData first = seq;
  first.n_frames = std::min<std::int64_t>(seq.n_frames, 1);
  sim::FrameMeasures out;
  for_each_stored_frame(first,
                        [&](std::int64_t, const StoredFrame& f) { out = sim::measure_frame(f.body, f.garments); });
  return out;
}

std::string crosscheck_table(const std::string& title, const std::vector<CrosscheckColumn>& columns,
                             const sim::FrameMeasures* start) {
  std::string out = title.empty() ? "" : title + "\n\n";
  auto row = [&](const std::string& name, auto cell) {
    out += "| " + name + " |";
    for (const auto& c : columns) out += " " + cell(c) + " |";
    out += "\n";
  };
  row("", [](const CrosscheckColumn& c) { return c.label; });
  out += "|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) out += "---|";
  out += "\n";
  row("ms per frame", [](const CrosscheckColumn& c) { return number(c.ms_per_frame); });
  row("frames measured (1..n-1)", [](const CrosscheckColumn& c) { return std::to_string(c.frames); });
  row("edge stretch vs rest, p99 (max)",
      [](const CrosscheckColumn& c) { return percent(c.stretch_p99, 1) + " (" + percent(c.stretch_max, 1) + ")"; });
  row("H: garment vertex behind the nearest body vertex's normal plane",
      [](const CrosscheckColumn& c) { return percent(c.h); });
  row("L: outer vertex behind the nearest inner vertex's normal plane, within 1 cm of it",
      [](const CrosscheckColumn& c) { return percent(c.l_1cm); });
  row("the same within 3 cm / unlimited",
      [](const CrosscheckColumn& c) { return percent(c.l_3cm) + " / " + percent(c.l_all); });
  row("generator's measures: mean H / mean L / max stretch", [](const CrosscheckColumn& c) {
    return percent(c.gen_h) + " / " + percent(c.gen_l) + " / " + percent(c.gen_stretch_max, 1);
  });
  row("garment-body crossings: share of garment vertices on crossing faces, mean (worst frame)",
      [](const CrosscheckColumn& c) { return percent(c.h_crossing) + " (" + percent(c.h_crossing_max) + ")"; });
  row("layer crossings: share of outer vertices on crossing faces, mean (worst frame)",
      [](const CrosscheckColumn& c) { return percent(c.l_crossing) + " (" + percent(c.l_crossing_max) + ")"; });
  row("non-finite coordinates", [](const CrosscheckColumn& c) { return std::to_string(c.nonfinite); });
  if (start) {
    out += "\nFrame 0 (stored; every column starts from it): H " + percent(start->h_penetration) + ", L (generator) " +
           percent(start->l_penetration) + ", garment-body crossings " + percent(start->h_crossing) +
           ", layer crossings " + percent(start->l_crossing) + ", max stretch " + percent(start->max_stretch, 1) +
           ".\n";
  }
  return out;
}

}  // namespace layers::generate
