// The cross-check over several scenes: columns.tsv and the summary table
// (see crosscheck_summary.h).
#include "layers/generate/crosscheck_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "layers/core/error.h"
#include "layers/core/interval.h"

namespace layers::generate {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every numeric field of a column, by name: the one list that columns.tsv
// and the summary's rows use.
struct Field {
  const char* name;
  double CrosscheckColumn::*value;
};
const Field kFields[] = {
    {"ms_per_frame", &CrosscheckColumn::ms_per_frame},
    {"stretch_p99", &CrosscheckColumn::stretch_p99},
    {"stretch_max", &CrosscheckColumn::stretch_max},
    {"h", &CrosscheckColumn::h},
    {"l_1cm", &CrosscheckColumn::l_1cm},
    {"l_3cm", &CrosscheckColumn::l_3cm},
    {"l_all", &CrosscheckColumn::l_all},
    {"gen_h", &CrosscheckColumn::gen_h},
    {"gen_l", &CrosscheckColumn::gen_l},
    {"gen_stretch_max", &CrosscheckColumn::gen_stretch_max},
    {"h_crossing", &CrosscheckColumn::h_crossing},
    {"h_crossing_max", &CrosscheckColumn::h_crossing_max},
    {"l_crossing", &CrosscheckColumn::l_crossing},
    {"l_crossing_max", &CrosscheckColumn::l_crossing_max},
};

// The summary's rows: a field, its caption, and whether it is a share.
struct Row {
  const char* field;
  const char* caption;
  bool share;
};
const Row kRows[] = {
    {"ms_per_frame", "ms per frame", false},
    {"stretch_p99", "edge stretch vs rest, p99", true},
    {"stretch_max", "edge stretch vs rest, max", true},
    {"h", "H: garment vertex behind the nearest body vertex's normal plane", true},
    {"l_1cm", "L: outer vertex behind the nearest inner vertex's normal plane, within 1 cm", true},
    {"l_3cm", "the same within 3 cm", true},
    {"l_all", "the same, unlimited", true},
    {"h_crossing", "garment-body crossings, mean over frames", true},
    {"h_crossing_max", "garment-body crossings, worst frame", true},
    {"l_crossing", "layer crossings, mean over frames", true},
    {"l_crossing_max", "layer crossings, worst frame", true},
};

double CrosscheckColumn::*member(const char* name) {
  for (const Field& f : kFields)
    if (std::string(f.name) == name) return f.value;
  throw Error(std::string("crosscheck_summary: no field ") + name);
}

std::string cell(const MeanInterval& m, bool share) {
  if (m.n == 0) return "n/a";
  const double scale = share ? 100.0 : 1.0;
  const int digits = share ? 2 : 0;
  char buf[64];
  if (m.n < 2)
    std::snprintf(buf, sizeof buf, "%.*f%s (n = 1)", digits, scale * m.mean, share ? "%" : "");
  else
    std::snprintf(buf, sizeof buf, "%.*f ± %.*f%s", digits, scale * m.mean, digits, scale * m.half_width,
                  share ? "%" : "");
  return buf;
}

// The value of `field` for the column labelled `label` in each scene (NaN
// where a scene has no such column).
std::vector<double> values(const std::vector<CrosscheckSceneColumns>& scenes, const std::string& label,
                           double CrosscheckColumn::*field) {
  std::vector<double> out;
  for (const auto& s : scenes) {
    double v = kNaN;
    for (const auto& c : s.columns)
      if (c.label == label) v = c.*field;
    out.push_back(v);
  }
  return out;
}

// A markdown table's header: an empty first cell, then `columns`.
std::string header(const std::vector<std::string>& columns, const std::string& prefix = "") {
  std::string out = "| |";
  for (const auto& c : columns) out += " " + prefix + c + " |";
  out += "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) out += "---|";
  return out + "\n";
}

}  // namespace

std::string crosscheck_columns_tsv(const std::vector<CrosscheckColumn>& columns) {
  std::ostringstream out;
  out << "label\tframes\tnonfinite";
  for (const Field& f : kFields) out << '\t' << f.name;
  out << '\n';
  for (const auto& c : columns) {
    out << c.label << '\t' << c.frames << '\t' << c.nonfinite;
    char buf[32];
    for (const Field& f : kFields) {
      std::snprintf(buf, sizeof buf, "%.9g", c.*f.value);
      out << '\t' << buf;
    }
    out << '\n';
  }
  return out.str();
}

std::vector<CrosscheckColumn> parse_crosscheck_columns(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::string line;
  std::vector<CrosscheckColumn> out;
  const std::size_t expected = 3 + sizeof(kFields) / sizeof(kFields[0]);
  if (!std::getline(in, line) || line.rfind("label\t", 0) != 0)
    throw InputError(file, "header", "label, frames, nonfinite and the measures, tab-separated", "'" + line + "'");
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string c; std::getline(fields, c, '\t');) cells.push_back(c);
    if (cells.size() != expected)
      throw InputError(file, "line " + std::to_string(n), std::to_string(expected) + " tab-separated fields",
                       std::to_string(cells.size()));
    CrosscheckColumn c;
    c.label = cells[0];
    try {
      std::size_t used = 0;
      c.frames = std::stoll(cells[1], &used);
      if (used != cells[1].size()) throw std::invalid_argument(cells[1]);
      c.nonfinite = std::stoll(cells[2], &used);
      if (used != cells[2].size()) throw std::invalid_argument(cells[2]);
      for (std::size_t i = 0; i + 3 < expected; ++i) {
        const std::string& v = cells[i + 3];
        if (v == "nan" || v == "-nan") {
          c.*kFields[i].value = kNaN;
          continue;
        }
        c.*kFields[i].value = std::stod(v, &used);
        if (used != v.size()) throw std::invalid_argument(v);
      }
    } catch (const std::exception&) {
      throw InputError(file, "line " + std::to_string(n), "numbers after the label", "'" + line + "'");
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::string crosscheck_summary(const std::vector<CrosscheckSceneColumns>& scenes) {
  std::vector<std::string> labels;
  for (const auto& s : scenes)
    for (const auto& c : s.columns)
      if (std::find(labels.begin(), labels.end(), c.label) == labels.end()) labels.push_back(c.label);
  std::string out = "Cross-check over " + std::to_string(scenes.size()) +
                    " scenes: mean over scenes ± the 95% interval (Student t, sample standard deviation).\n\n" +
                    header(labels);
  for (const Row& r : kRows) {
    out += std::string("| ") + r.caption + " |";
    for (const auto& l : labels) out += " " + cell(mean_interval(values(scenes, l, member(r.field))), r.share) + " |";
    out += "\n";
  }

  // Paired, per scene: our stored ground truth minus each Blender column,
  // and our time (simulated again) over each Blender column's.
  const std::string ours = kOursStored, again = kOursAgain;
  std::vector<std::string> blender;
  for (const auto& l : labels)
    if (l != ours && l != again) blender.push_back(l);
  if (blender.empty()) return out;
  out += "\nPaired over scenes: " + ours +
         " minus each other column (mean difference ± 95% interval; * where "
         "the interval excludes 0).\n\n" +
         header(blender, "minus ");
  for (const Row& r : kRows) {
    if (std::string(r.field) == "ms_per_frame") continue;
    out += std::string("| ") + r.caption + " |";
    for (const auto& b : blender) {
      const MeanInterval d = paired_interval(values(scenes, ours, member(r.field)), values(scenes, b, member(r.field)));
      out += " " + cell(d, r.share) + (d.above_zero() || d.below_zero() ? " *" : "") + " |";
    }
    out += "\n";
  }
  out += "| time: " + again + " / the column's, per scene |";
  for (const auto& b : blender) {
    const auto a = values(scenes, again, &CrosscheckColumn::ms_per_frame);
    const auto c = values(scenes, b, &CrosscheckColumn::ms_per_frame);
    std::vector<double> ratio;
    for (std::size_t i = 0; i < a.size(); ++i) ratio.push_back(c[i] > 0 ? a[i] / c[i] : kNaN);
    const MeanInterval m = mean_interval(ratio);
    char buf[64];
    if (m.n >= 2)
      std::snprintf(buf, sizeof buf, "%.2f ± %.2f", m.mean, m.half_width);
    else if (m.n == 1)
      std::snprintf(buf, sizeof buf, "%.2f (n = 1)", m.mean);
    else
      std::snprintf(buf, sizeof buf, "n/a");
    out += std::string(" ") + buf + " |";
  }
  out += "\n\nScenes:\n\n";
  for (const auto& s : scenes) out += "- " + s.title + "\n";
  return out;
}

}  // namespace layers::generate
