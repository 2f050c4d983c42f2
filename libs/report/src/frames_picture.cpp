// Ground truth and predictions side by side (see frames_picture.h).
#include "layers/report/frames_picture.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/report/mesh_view.h"
#include "text.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kBody = 0xdcdcdc, kInner = 0x3b75af, kOuter = 0xe1812c;
constexpr float kLayerBias = 0.03f;  // sort-depth bias per layer (mesh_view.h), metres

// One row of the picture: a label and where its garments come from.
struct Row {
  std::string label;
  std::shared_ptr<data::Dataset> source;
};

std::shared_ptr<data::Dataset> open_dataset(const std::string& path) {
  return std::make_shared<data::Dataset>(data::Dataset::open(path));
}

// The ground-truth dataset: the option, else a run's data.dataset as
// written or relative to the run folder and its parents.
std::shared_ptr<data::Dataset> ground_truth(const std::vector<RunResults>& runs, const PictureOptions& options,
                                            const std::string& sequence, std::vector<std::string>& notes) {
  std::vector<std::string> candidates;
  if (!options.dataset.empty()) {
    candidates.push_back(options.dataset);
  } else {
    for (const RunResults& r : runs) {
      if (r.dataset.empty()) continue;
      candidates.push_back(r.dataset);
      if (fs::path(r.dataset).is_relative())
        for (fs::path dir = fs::absolute(r.dir).lexically_normal(); dir.has_relative_path(); dir = dir.parent_path())
          candidates.push_back((dir / r.dataset).string());
    }
  }
  std::string why = "no run names its dataset (experiment.yaml data.dataset)";
  for (const std::string& c : candidates) {
    if (!fs::exists(c)) {
      why = "dataset " + c + " not found";
      continue;
    }
    try {
      auto ds = open_dataset(c);
      if (ds->contains(sequence)) return ds;
      why = "dataset " + c + " has no sequence " + sequence;
    } catch (const std::exception& e) {
      why = e.what();
    }
  }
  notes.push_back("picture: no ground-truth row (" + why + "; pass --dataset)");
  return nullptr;
}

// Triangles of one row's garments at one frame.
void add_garments(std::vector<ScreenTriangle>& tris, ScreenBounds* bounds, const data::Dataset& ds,
                  const std::string& sequence, std::int64_t frame) {
  const auto statics = ds.statics(sequence);
  const data::Window w = ds.read_frames(sequence, frame, 1);
  for (std::size_t g = 0; g < statics->garments.size(); ++g) {
    const data::GarmentStatic& gs = statics->garments[g];
    add_mesh(tris, w.garments[g].data(), gs.n_vertices(), gs.faces, gs.layer == 0 ? kInner : kOuter, false,
             kLayerBias * static_cast<float>(1 + gs.layer));
    if (bounds) bounds->add(mesh_bounds(w.garments[g].data(), gs.n_vertices()));
  }
}

}  // namespace

std::vector<std::int64_t> picture_frames(std::int64_t n_frames, int count) {
  std::vector<std::int64_t> frames;
  if (n_frames <= 0 || count <= 0) return frames;
  const std::int64_t first = n_frames > 2 ? 2 : 0, last = n_frames - 1;
  for (int k = 0; k < count; ++k) {
    const double t = count == 1 ? 1.0 : static_cast<double>(k) / (count - 1);
    const auto f = static_cast<std::int64_t>(std::lround(first + t * static_cast<double>(last - first)));
    if (frames.empty() || frames.back() != f) frames.push_back(f);
  }
  return frames;
}

Chart frames_picture(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs,
                     const PictureOptions& options, std::vector<std::string>& notes) {
  const std::string name = "frames";
  // The runs' predictions.
  std::vector<Row> predicted;
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    if (r.eval->predictions.empty()) {
      notes.push_back("picture: " + r.name + " has no predictions.h5 (eval.save_predictions off?)");
      continue;
    }
    try {
      predicted.push_back({r.name, open_dataset(r.eval->predictions)});
    } catch (const std::exception& e) {
      notes.push_back("picture: " + r.name + ": cannot read its predictions: " + e.what());
    }
  }
  if (predicted.empty()) throw Error("no run has readable predictions (eval-<split>/predictions.h5)");
  std::string sequence = options.sequence;
  if (sequence.empty()) {
    for (const std::string& id : predicted.front().source->ids()) {
      if (std::all_of(predicted.begin(), predicted.end(), [&](const Row& r) { return r.source->contains(id); })) {
        sequence = id;
        break;
      }
    }
    if (sequence.empty()) sequence = predicted.front().source->ids().front();
  }
  std::vector<Row> rows;
  std::int64_t n_frames = -1;
  for (const Row& r : predicted) {
    if (!r.source->contains(sequence)) {
      notes.push_back("picture: " + r.label + " has no prediction of " + sequence);
      continue;
    }
    const std::int64_t n = r.source->info(sequence).n_frames;
    n_frames = n_frames < 0 ? n : std::min(n_frames, n);
    rows.push_back(r);
  }
  if (rows.empty()) throw Error("no run has a prediction of sequence '" + sequence + "'");
  const std::shared_ptr<data::Dataset> truth = ground_truth(runs, options, sequence, notes);
  if (truth) rows.insert(rows.begin(), Row{"ground truth", truth});
  const std::vector<std::int64_t> frames = picture_frames(n_frames, std::max(1, options.frames));

  // The body (ground truth in every row) once per frame, then each row's garments.
  const data::Dataset& body_source = truth ? *truth : *rows.front().source;
  const auto body_statics = body_source.statics(sequence);
  ScreenBounds bounds;
  std::vector<std::vector<ScreenTriangle>> body(frames.size());
  for (std::size_t c = 0; c < frames.size(); ++c) {
    const data::Window w = body_source.read_frames(sequence, frames[c], 1);
    add_mesh(body[c], w.body.positions.data(), body_statics->body.n_vertices(), body_statics->body.faces, kBody, true);
    bounds.add(mesh_bounds(w.body.positions.data(), body_statics->body.n_vertices()));
  }
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < frames.size(); ++c) {
      std::vector<ScreenTriangle> tris = body[c];
      add_garments(tris, r == 0 ? &bounds : nullptr, *rows[r].source, sequence, frames[c]);
      write_text_atomic(dir + "/" + name + "_" + std::to_string(r) + "_" + std::to_string(c) + ".dat",
                        polygon_data(std::move(tris)));
    }
  }
  if (bounds.empty) throw Error("sequence '" + sequence + "' has no finite vertex in the chosen frames");

  const double pad = 0.03 * std::max(bounds.xmax - bounds.xmin, bounds.ymax - bounds.ymin);
  const double w = bounds.xmax - bounds.xmin + 2 * pad, h = bounds.ymax - bounds.ymin + 2 * pad;
  const int panel_w = 200, label_w = 40, title_h = 64;
  const int panel_h = static_cast<int>(std::clamp(panel_w * h / w, 120.0, 520.0));
  const int width = label_w + panel_w * static_cast<int>(frames.size()) + 10;
  const int height = title_h + panel_h * static_cast<int>(rows.size()) + 10;
  std::ostringstream s;
  s << gp.preamble(name, width, height) << "unset border\nunset tics\nunset key\n"
    << "set style fill solid 1.0 noborder\nset size ratio -1\n"
    << "set xrange [" << exact(bounds.xmin - pad) << ":" << exact(bounds.xmax + pad) << "]\n"
    << "set yrange [" << exact(bounds.ymin - pad) << ":" << exact(bounds.ymax + pad) << "]\n"
    << "set multiplot layout " << rows.size() << "," << frames.size() << " title "
    << gnuplot_string("Sequence " + sequence + ": ground truth and predictions, seen from the front") << " margins "
    << exact(static_cast<double>(label_w) / width) << "," << exact(1.0 - 10.0 / width) << "," << exact(10.0 / height)
    << "," << exact(1.0 - static_cast<double>(title_h) / height) << " spacing 0,0\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < frames.size(); ++c) {
      s << (r == 0 ? "set title " + gnuplot_string("frame " + std::to_string(frames[c])) : "unset title") << "\n"
        << (c == 0 ? "set ylabel " + gnuplot_string(rows[r].label) : "unset ylabel") << "\n"
        << "plot " << gnuplot_string(name + "_" + std::to_string(r) + "_" + std::to_string(c) + ".dat")
        << " using 1:2:3 with filledcurves closed fillcolor rgb variable\n";
    }
  }
  s << "unset multiplot\n";
  gp.plot(dir, name, s.str());

  std::ostringstream frame_list;
  for (std::size_t c = 0; c < frames.size(); ++c) frame_list << (c ? ", " : "") << frames[c];
  return {name + ".png", "Ground truth and predictions",
          "Sequence `" + sequence + "` at frames " + frame_list.str() + ", seen from the front (orthographic). " +
              (truth ? "The top row is the dataset's ground truth; each further row is one run's rollout "
                     : "No ground truth could be read (see the notes); each row is one run's rollout ") +
              "(its eval predictions.h5: started from the ground truth at frames 0 and 1, body and wind ground "
              "truth, garments predicted). Body light grey, inner garments blue, outer garments orange; "
              "faces shaded by how squarely they face the viewer."};
}

}  // namespace layers::report
