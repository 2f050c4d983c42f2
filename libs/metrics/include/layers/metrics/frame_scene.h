// layers/metrics/frame_scene.h -- one frame of a scene as the metrics of
// the registry (registry.h) see it: each garment's mesh and layer, the
// ground-truth positions (for errors), the positions one frame earlier
// (for speeds), and the body. What several metrics need is computed once
// per frame, on first use: the body's surface and face tree (shared by the
// prediction's and the ground truth's scene), the L-collision query and
// the body crossings.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "layers/geometry/intersect.h"
#include "layers/geometry/mesh.h"
#include "layers/geometry/penetration.h"
#include "layers/metrics/measures.h"

namespace layers::metrics {

// The body of one frame, its surface and face tree built on first use.
class BodyFrame {
 public:
  explicit BodyFrame(geometry::TriMesh mesh) : mesh_(std::move(mesh)) {}
  const geometry::TriMesh& mesh() const { return mesh_; }
  const geometry::Surface& surface() const;
  const geometry::FaceTree& tree() const;

 private:
  geometry::TriMesh mesh_;
  mutable std::optional<geometry::Surface> surface_;
  mutable std::unique_ptr<geometry::FaceTree> tree_;
};

class FrameScene {
 public:
  // `garments`: each garment's vertices and faces; `layers`: each one's
  // layer (0 inner; any other: outer). `truth`: the ground truth's
  // positions per garment, null when this scene is the ground truth.
  // `previous`: each garment's positions one frame earlier (null: not
  // known). `body`: null when no metric of the frame needs it.
  FrameScene(std::vector<geometry::TriMesh> garments, std::vector<int> layers,
             const std::vector<geometry::Points>* truth, const std::vector<geometry::Points>* previous,
             const BodyFrame* body);

  std::size_t size() const { return garments_.size(); }
  const geometry::TriMesh& garment(std::size_t g) const { return garments_[g]; }
  const std::vector<geometry::TriMesh>& garments() const { return garments_; }
  bool outer(std::size_t g) const { return layers_[g] != 0; }
  bool has_layers() const;  // an inner and an outer garment
  // Error: throws when the scene has none.
  const geometry::Points& truth(std::size_t g) const;
  const geometry::Points& previous(std::size_t g) const;
  const BodyFrame& body() const;

  // The outer garments' vertices against the inner garments as one mesh
  // (both L-collision rules); requires has_layers().
  const LCollisionRates& l_collision() const;
  // Every garment (as one mesh, vertices in order) against the body.
  const geometry::MeshCrossings& body_crossings() const;
  // The outer garments' faces against the inner ones'; requires has_layers().
  const geometry::MeshCrossings& layer_crossings() const;

 private:
  std::vector<geometry::TriMesh> garments_;
  std::vector<int> layers_;
  const std::vector<geometry::Points>* truth_;
  const std::vector<geometry::Points>* previous_;
  const BodyFrame* body_;
  // The outer and the inner garments, split once for the L measures.
  struct Layers {
    std::vector<geometry::TriMesh> outer, inner;
  };
  const Layers& split() const;
  mutable std::optional<Layers> split_;
  mutable std::optional<LCollisionRates> l_collision_;
  mutable std::optional<geometry::MeshCrossings> body_crossings_, layer_crossings_;
};

}  // namespace layers::metrics
