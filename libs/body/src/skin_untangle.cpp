// SkinUntangler: Taubin smoothing of the skin around its own crossings (see skin_untangle.h).
#include "layers/body/skin_untangle.h"

#include <algorithm>
#include <string>

#include "layers/core/error.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/normals.h"

namespace layers::body {
namespace {

// Bones whose skin carries no garment and whose parts lie close by design.
bool extremity(const std::string& joint) {
  for (const char* part : {"Hand", "Finger", "Thumb", "Foot", "Toe", "Head"}) {
    if (joint.find(part) != std::string::npos) return true;
  }
  return false;
}

int count(const std::vector<char>& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

bool share_vertex(const geometry::Faces& faces, int a, int b) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (faces(a, i) == faces(b, j)) return true;
    }
  }
  return false;
}

}  // namespace

SkinUntangler::SkinUntangler(const Body& body)
    : faces_(body.rest.faces), adjacency_(geometry::vertex_adjacency(body.rest.faces, body.num_vertices())) {
  const int n = body.num_vertices();
  movable_.assign(static_cast<std::size_t>(n), 1);
  for (int v = 0; v < n && v < body.weights.num_vertices(); ++v) {
    int best = 0;
    for (int k = 1; k < 4; ++k) {
      if (body.weights.weight(v, k) > body.weights.weight(v, best)) best = k;
    }
    movable_[v] = !extremity(body.skeleton.names[body.weights.index(v, best)]);
  }
  movable_face_.assign(static_cast<std::size_t>(faces_.rows()), 1);
  for (Eigen::Index f = 0; f < faces_.rows(); ++f) {
    for (int k = 0; k < 3; ++k) movable_face_[f] = movable_face_[f] && movable_[faces_(f, k)];
  }
}

int SkinUntangler::crossing_faces(const geometry::Points& vertices) const {
  const geometry::TriMesh mesh{vertices, faces_};
  std::vector<char> crossing(movable_face_.size(), 0);
  geometry::visit_crossings(mesh, geometry::FaceTree(mesh), [&](int fa, int fb) {
    if (movable_face_[fa] && movable_face_[fb] && !share_vertex(faces_, fa, fb)) crossing[fa] = 1;
  });
  return count(crossing);
}

SkinUntangleResult SkinUntangler::apply(geometry::Points& vertices, const SkinUntangleOptions& options) const {
  if (vertices.rows() != static_cast<Eigen::Index>(movable_.size())) {
    throw InputError("body", "skin vertices", std::to_string(movable_.size()), std::to_string(vertices.rows()));
  }
  if (options.passes < 0 || options.steps < 0 || !(options.margin >= 0)) {
    throw InputError(
        "body", "skin_untangle", "passes, steps and margin >= 0",
        std::to_string(options.passes) + ", " + std::to_string(options.steps) + ", " + std::to_string(options.margin));
  }
  SkinUntangleResult result;
  if (options.passes == 0) return result;
  geometry::TriMesh mesh{vertices, faces_};
  const std::size_t n = movable_.size();
  std::vector<char> patch(n, 0);
  Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> push(static_cast<Eigen::Index>(n), 3);
  std::vector<int> pushes(n, 0);
  std::vector<std::pair<int, int>> pairs;
  geometry::Points next = vertices, best = vertices;
  int best_pass = 0;
  for (int pass = 0;; ++pass) {
    // The crossing pairs of faces off the hands, feet and head (each pair
    // is visited both ways).
    pairs.clear();
    geometry::visit_crossings(mesh, geometry::FaceTree(mesh), [&](int fa, int fb) {
      if (movable_face_[fa] && movable_face_[fb] && !share_vertex(faces_, fa, fb)) pairs.emplace_back(fa, fb);
    });
    std::vector<char> crossing(movable_face_.size(), 0);
    for (const auto& [fa, fb] : pairs) crossing[fa] = 1;
    const int now = count(crossing);
    if (pass == 0) {
      result.crossing_before = result.crossing_after = now;
    } else if (now < result.crossing_after) {  // the best round is kept: a push can make new crossings
      result.crossing_after = now;
      best = mesh.vertices;
      best_pass = pass;
    }
    // Done when nothing crosses, after `passes` rounds, or after three
    // rounds without a better one (the pushes then go round in circles).
    if (now == 0 || pass == options.passes || pass - best_pass >= 3) break;
    const geometry::Points normals = geometry::face_normals(mesh.vertices, faces_);
    push.setZero();
    std::fill(pushes.begin(), pushes.end(), 0);
    // Every vertex of a crossing face that lies behind the other face's
    // plane (inside the skin there) is pushed out along that face's normal,
    // `margin` past it; each sheet takes half of the way.
    for (const auto& [fa, fb] : pairs) {
      const Eigen::RowVector3f normal = normals.row(fb);
      const Eigen::RowVector3f on = mesh.vertices.row(faces_(fb, 0));
      for (int k = 0; k < 3; ++k) {
        const int v = faces_(fa, k);
        const float depth = -(mesh.vertices.row(v) - on).dot(normal);
        if (depth < 0) continue;
        push.row(v) += 0.5f * (depth + static_cast<float>(options.margin)) * normal;
        ++pushes[v];
      }
    }
    if (std::all_of(pushes.begin(), pushes.end(), [](int k) { return k == 0; })) break;
    std::fill(patch.begin(), patch.end(), 0);
    for (std::size_t v = 0; v < n; ++v) {
      if (pushes[v] == 0) continue;
      mesh.vertices.row(v) += push.row(v) / static_cast<float>(pushes[v]);
      patch[v] = 1;
      for (const int* u = adjacency_.begin(static_cast<int>(v)); u != adjacency_.end(static_cast<int>(v)); ++u) {
        patch[*u] = patch[*u] || movable_[*u];
      }
    }
    // Taubin steps over the pushed vertices and their neighbours, so that a
    // push leaves no spike: each moves towards (lambda > 0), then away from
    // (mu < 0), the mean of its neighbours as they were before the step.
    for (int step = 0; step < 2 * options.steps; ++step) {
      const float factor = static_cast<float>(step % 2 == 0 ? options.lambda : options.mu);
      for (std::size_t v = 0; v < n; ++v) {
        const int degree = adjacency_.degree(static_cast<int>(v));
        if (!patch[v] || degree == 0) continue;
        Eigen::RowVector3f mean = Eigen::RowVector3f::Zero();
        for (const int* u = adjacency_.begin(static_cast<int>(v)); u != adjacency_.end(static_cast<int>(v)); ++u) {
          mean += mesh.vertices.row(*u);
        }
        mean /= static_cast<float>(degree);
        next.row(v) = mesh.vertices.row(v) + factor * (mean - mesh.vertices.row(v));
      }
      for (std::size_t v = 0; v < n; ++v) {
        if (patch[v]) mesh.vertices.row(v) = next.row(v);
      }
    }
  }
  for (Eigen::Index v = 0; v < best.rows(); ++v) result.moved += best.row(v) != vertices.row(v);
  vertices = best;
  return result;
}

}  // namespace layers::body
