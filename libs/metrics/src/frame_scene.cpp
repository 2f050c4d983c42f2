// One frame of a scene for the metrics, with its shared intermediate
// results (see frame_scene.h).
#include "layers/metrics/frame_scene.h"

#include "layers/core/error.h"

namespace layers::metrics {

const geometry::Surface& BodyFrame::surface() const {
  if (!surface_) surface_ = geometry::Surface::from_mesh(mesh_, "body");
  return *surface_;
}

const geometry::FaceTree& BodyFrame::tree() const {
  if (!tree_) tree_ = std::make_unique<geometry::FaceTree>(mesh_);
  return *tree_;
}

FrameScene::FrameScene(std::vector<geometry::TriMesh> garments, std::vector<int> layers,
                       const std::vector<geometry::Points>* truth, const std::vector<geometry::Points>* previous,
                       const BodyFrame* body)
    : garments_(std::move(garments)), layers_(std::move(layers)), truth_(truth), previous_(previous), body_(body) {
  if (layers_.size() != garments_.size())
    throw Error("frame scene: " + std::to_string(garments_.size()) + " garments but " + std::to_string(layers_.size()) +
                " layers");
  for (const auto* per_garment : {truth_, previous_})
    if (per_garment && per_garment->size() != garments_.size())
      throw Error("frame scene: " + std::to_string(garments_.size()) + " garments but positions of " +
                  std::to_string(per_garment->size()));
}

bool FrameScene::has_layers() const {
  bool inner = false, outer_found = false;
  for (std::size_t g = 0; g < size(); ++g) (outer(g) ? outer_found : inner) = true;
  return inner && outer_found;
}

const geometry::Points& FrameScene::truth(std::size_t g) const {
  if (!truth_) throw Error("frame scene: a metric needs the ground truth, which this scene is");
  return (*truth_)[g];
}

const geometry::Points& FrameScene::previous(std::size_t g) const {
  if (!previous_) throw Error("frame scene: a metric needs the previous frame, which this scene lacks");
  return (*previous_)[g];
}

const BodyFrame& FrameScene::body() const {
  if (!body_) throw Error("frame scene: a metric needs the body, which this scene lacks");
  return *body_;
}

const FrameScene::Layers& FrameScene::split() const {
  if (!split_) {
    split_.emplace();
    for (std::size_t g = 0; g < size(); ++g) (outer(g) ? split_->outer : split_->inner).push_back(garments_[g]);
  }
  return *split_;
}

const LCollisionRates& FrameScene::l_collision() const {
  // The outer garments' vertices, in order, against the inner ones as one mesh.
  if (!l_collision_)
    l_collision_ =
        l_collision_rates(geometry::concatenate(split().outer).vertices, geometry::concatenate(split().inner));
  return *l_collision_;
}

const geometry::MeshCrossings& FrameScene::body_crossings() const {
  if (!body_crossings_) body_crossings_ = geometry::body_crossings(garments_, body().tree());
  return *body_crossings_;
}

const geometry::MeshCrossings& FrameScene::layer_crossings() const {
  if (!layer_crossings_) layer_crossings_ = geometry::layer_crossings(split().outer, split().inner);
  return *layer_crossings_;
}

}  // namespace layers::metrics
