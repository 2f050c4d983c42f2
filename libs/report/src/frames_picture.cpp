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
#include "shown_rows.h"
#include "text.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kBody = 0xdcdcdc, kInner = 0x3b75af, kOuter = 0xe1812c;
constexpr float kLayerBias = 0.03f;  // sort-depth bias per layer (mesh_view.h), metres

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
  const ShownRows shown = shown_rows(runs, options, "picture", notes);
  const std::string& sequence = shown.sequence;
  const std::vector<ShownRow>& rows = shown.rows;
  const std::int64_t n_frames = shown.n_frames;
  const data::Dataset* truth = shown.has_truth ? rows.front().source.get() : nullptr;
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
