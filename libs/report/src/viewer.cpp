// The report's viewer: the scene file and the copied three.js (see
// viewer.h; the page is viewer_page.cpp).
#include "layers/report/viewer.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/data/format.h"
#include "layers/metrics/registry.h"
#include "shown_rows.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string base64(const void* data, std::size_t n) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const unsigned v = (p[i] << 16) | ((i + 1 < n ? p[i + 1] : 0) << 8) | (i + 2 < n ? p[i + 2] : 0);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < n ? k[(v >> 6) & 63] : '=';
    out += i + 2 < n ? k[v & 63] : '=';
  }
  return out;
}
template <typename T>
std::string base64(const std::vector<T>& v) {
  return base64(v.data(), v.size() * sizeof(T));
}

geometry::Points points_at(const std::vector<float>& frames, std::int64_t t, std::int64_t n) {
  return Eigen::Map<const geometry::Points>(frames.data() + t * n * 3, n, 3);
}
geometry::Faces faces_of(const std::vector<std::int32_t>& f) {
  return Eigen::Map<const geometry::Faces>(f.data(), static_cast<Eigen::Index>(f.size() / 3), 3);
}

// Same garments (count, vertices, faces) as the first row.
std::string topology_difference(const data::SequenceStatic& a, const data::SequenceStatic& b) {
  if (a.garments.size() != b.garments.size())
    return std::to_string(b.garments.size()) + " garments, not " + std::to_string(a.garments.size());
  for (std::size_t g = 0; g < a.garments.size(); ++g)
    if (a.garments[g].faces != b.garments[g].faces || a.garments[g].n_vertices() != b.garments[g].n_vertices())
      return "garment " + std::to_string(g) + " has another mesh";
  return "";
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

Viewer write_viewer(const std::vector<RunResults>& runs, const PictureOptions& picture, const ViewerOptions& options,
                    const std::string& out_dir, std::vector<std::string>& notes) {
  if (!options.enabled) throw Error("the viewer was switched off");
  std::string three;
  try {
    three = read_text_file(options.three);
  } catch (const std::exception&) {
    throw Error("three.js not found at " + options.three + " (install Debian's libjs-three, or pass --three)");
  }
  ShownRows shown = shown_rows(runs, picture, "viewer", notes);
  const std::string& seq = shown.sequence;
  const auto statics = shown.rows.front().source->statics(seq);
  for (std::size_t r = 1; r < shown.rows.size();) {
    const std::string diff = topology_difference(*statics, *shown.rows[r].source->statics(seq));
    if (diff.empty()) {
      ++r;
      continue;
    }
    notes.push_back("viewer: " + shown.rows[r].label + " left out: its sequence " + seq + " has " + diff);
    shown.rows.erase(shown.rows.begin() + static_cast<std::ptrdiff_t>(r));
  }

  // Frames that fit the budget, from upper bounds of each part's size in
  // scene.js: base64 is 4/3 of the bytes, a metric value at most 24
  // characters, the rest of the JSON a few kilobytes.
  const std::int64_t body_v = statics->body.n_vertices();
  const std::int64_t n_rows = static_cast<std::int64_t>(shown.rows.size());
  const std::int64_t n_defs = static_cast<std::int64_t>(metrics::registered().size());
  std::int64_t garment_v = 0, fixed = 4096 + 512 * n_defs + 16 * statics->body.n_faces();
  for (const data::GarmentStatic& g : statics->garments) {
    garment_v += g.n_vertices();
    fixed += 16 * g.n_faces();
  }
  const std::int64_t per_frame = 16 * (body_v + garment_v * n_rows) + 24 * n_defs * n_rows;
  const std::int64_t budget = options.max_bytes - static_cast<std::int64_t>(three.size() + viewer_page().size());
  const std::int64_t fit = (budget - fixed) / per_frame;
  const std::int64_t frames = std::min(shown.n_frames, fit);
  if (frames < 2)
    throw Error("not even two frames of sequence " + seq + " fit the viewer's budget of " +
                std::to_string(options.max_bytes) + " bytes");
  if (frames < shown.n_frames)
    notes.push_back("viewer: shows frames 0-" + std::to_string(frames - 1) + " of " + std::to_string(shown.n_frames) +
                    " (the byte budget)");

  std::vector<data::Window> windows;
  for (const ShownRow& row : shown.rows) windows.push_back(row.source->read_frames(seq, 0, frames));
  const data::Window& first = windows.front();

  // Every registered metric of every frame of every row.
  const std::vector<metrics::MetricDef> defs = metrics::registered();
  std::vector<int> layers;
  std::vector<geometry::Faces> garment_faces;
  for (const data::GarmentStatic& g : statics->garments) {
    layers.push_back(g.layer);
    garment_faces.push_back(faces_of(g.faces));
  }
  const geometry::Faces body_faces = faces_of(statics->body.faces);
  auto garment_points = [&](std::size_t r, std::int64_t t) {
    std::vector<geometry::Points> pts;
    for (std::size_t g = 0; g < statics->garments.size(); ++g)
      pts.push_back(points_at(windows[r].garments[g], t, statics->garments[g].n_vertices()));
    return pts;
  };
  std::vector<std::vector<std::vector<double>>> values(
      shown.rows.size(), std::vector<std::vector<double>>(defs.size(), std::vector<double>(frames, NAN)));
  // Each row's garments at the frame before (kept from the last step).
  std::vector<std::vector<geometry::Points>> before;
  for (std::int64_t t = 0; t < frames; ++t) {
    const metrics::BodyFrame body(geometry::TriMesh{points_at(first.body.positions, t, body_v), body_faces});
    std::vector<std::vector<geometry::Points>> now;
    for (std::size_t r = 0; r < shown.rows.size(); ++r) now.push_back(garment_points(r, t));
    const std::vector<geometry::Points>* truth = shown.has_truth ? &now[0] : nullptr;
    for (std::size_t r = 0; r < shown.rows.size(); ++r) {
      const bool is_truth = shown.has_truth && r == 0;
      std::vector<geometry::TriMesh> meshes;
      for (std::size_t g = 0; g < now[r].size(); ++g) meshes.push_back({now[r][g], garment_faces[g]});
      const metrics::FrameScene scene(std::move(meshes), layers, is_truth ? nullptr : truth,
                                      t > 0 ? &before[r] : nullptr, &body);
      for (std::size_t k = 0; k < defs.size(); ++k) {
        if (is_truth && !defs[k].truth) continue;
        try {
          values[r][k][static_cast<std::size_t>(t)] = defs[k].compute(scene).scene;
        } catch (const std::exception&) {
          // Not measurable here (no ground truth for an error, no previous frame): left blank.
        }
      }
    }
    before = std::move(now);
  }

  json scene = {
      {"sequence", seq},
      {"fps", data::kFps},
      {"first_frame", first.first_frame},
      {"frames", frames},
      {"sequence_frames", shown.n_frames},
      {"body",
       {{"vertices", body_v}, {"faces", base64(statics->body.faces)}, {"positions", base64(first.body.positions)}}}};
  json garments = json::array();
  for (const data::GarmentStatic& g : statics->garments)
    garments.push_back({{"name", g.name},
                        {"type", g.type},
                        {"layer", g.layer},
                        {"vertices", g.n_vertices()},
                        {"faces", base64(g.faces)}});
  scene["garments"] = garments;
  json metric_list = json::array();
  for (const metrics::MetricDef& d : defs)
    metric_list.push_back({{"key", d.key},
                           {"label", d.label},
                           {"description", d.description},
                           {"unit", d.unit == metrics::Unit::Millimetre ? "mm" : "share"}});
  scene["metrics"] = metric_list;
  json rows = json::array();
  Viewer viewer;
  for (std::size_t r = 0; r < shown.rows.size(); ++r) {
    json positions = json::array(), row_values = json::object();
    for (const std::vector<float>& g : windows[r].garments) positions.push_back(base64(g));
    for (std::size_t k = 0; k < defs.size(); ++k) {
      json v = json::array();
      for (double x : values[r][k]) v.push_back(number_or_null(x));
      row_values[defs[k].key] = v;
    }
    rows.push_back({{"label", shown.rows[r].label},
                    {"truth", shown.has_truth && r == 0},
                    {"garments", positions},
                    {"values", row_values}});
    viewer.rows.push_back(shown.rows[r].label);
  }
  scene["rows"] = rows;

  const fs::path dir = fs::path(out_dir) / "viewer";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw Error("cannot create " + dir.string() + (ec ? ": " + ec.message() : ""));
  auto write = [&](const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    write_text_atomic(path, text);
    viewer.files.push_back(path);
  };
  write("three.min.js", three);
  write("scene.js", "window.LAYERS_SCENE = " + scene.dump() + ";\n");
  write("index.html", viewer_page());
  viewer.page = viewer.files.back();
  viewer.sequence = seq;
  viewer.frames = frames;
  viewer.sequence_frames = shown.n_frames;
  return viewer;
}

}  // namespace layers::report
