// layers/report/viewer.h -- the report's viewer: a self-contained page
// (<report>/viewer/index.html) that plays the ground truth and each run's
// rollout of one sequence side by side in the browser, offline from disk.
//
// viewer/index.html  the page: play/pause, a frame slider, and a table of
//                    every registered metric (metrics/registry.h) of the
//                    current frame per row, measured by the same code as
//                    the evaluation
// viewer/three.min.js three.js, copied from a package (Debian's libjs-three)
// viewer/scene.js    the scene as `window.LAYERS_SCENE`: meshes' faces,
//                    every frame's positions as base64 float32 (metres, y
//                    up, exactly the stored values), per-frame metrics
//
// The rows and the sequence are the picture's (frames_picture.h
// PictureOptions). The frames are consecutive from the sequence's first,
// as many as fit the byte budget (the whole viewer/ folder under
// ViewerOptions::max_bytes).
// The page exposes `window.layersViewer` (frame count, current frame,
// play, pause, setFrame, positions of a row's mesh as drawn, share of the
// canvas drawn) for tests and scripts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/report/frames_picture.h"
#include "layers/report/run_results.h"

namespace layers::report {

// Where Debian's libjs-three puts the non-module build (r111).
inline constexpr const char* kDebianThree = "/usr/share/javascript/three/three.min.js";

struct ViewerOptions {
  bool enabled = true;
  std::string three = kDebianThree;    // three.min.js to copy into the report
  std::int64_t max_bytes = 9'500'000;  // budget of the viewer/ folder
};

struct Viewer {
  std::string page;                // path of index.html
  std::vector<std::string> files;  // every file written
  std::string sequence;
  std::int64_t frames = 0;  // frames shown (from the sequence's first)
  std::int64_t sequence_frames = 0;
  std::vector<std::string> rows;  // labels, the ground truth first when found
};

// Writes <out_dir>/viewer/. Rows left out are described in `notes`.
// Throws layers::Error when three.js cannot be read, no run has
// predictions, or not even two frames fit the budget.
Viewer write_viewer(const std::vector<RunResults>& runs, const PictureOptions& picture, const ViewerOptions& options,
                    const std::string& out_dir, std::vector<std::string>& notes);

// The page itself (index.html): static, reads three.min.js and scene.js
// beside it.
const std::string& viewer_page();

}  // namespace layers::report
