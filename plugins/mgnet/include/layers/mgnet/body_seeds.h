// layers/mgnet/body_seeds.h -- MGNet's body seed points: for each garment
// vertex, the nearest body vertex. Found anew at every step (a k-d tree over
// the body at t, queried with the garment at t), so the seeds follow
// sliding cloth and work for any garment; nothing is bound to a template.
#pragma once

#include <ATen/ATen.h>

namespace layers::mgnet {

// Index [N] (int64, on the device of `points`) of the row of `body` [Vb,3]
// nearest to each row of `points` [N,3]. Searched on detached CPU copies
// (no gradient flows through the choice). A non-finite query point (a
// diverged rollout) gets body vertex 0 instead of failing; a non-finite
// body is a layers::Error.
at::Tensor nearest_body_vertex(const at::Tensor& body, const at::Tensor& points);

}  // namespace layers::mgnet
