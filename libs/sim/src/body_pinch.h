// body_pinch.h (internal) -- where the body pinches the cloth during a
// frame, for the collision pass (collision_pass.h: the body yields there).
// The zones are geometry::pinch_zones_under(), the same zones the measures
// report garment-body crossings in (measures.h; docs/metrics.md "Pinch
// zones"), with the same distance (sim.validation.pinch_distance). The end pose's
// zones carry over as the next frame's start. A body vertex is in a zone
// when every face around it is, at the frame's start and at its end, so
// that the cloth the body is let through ends in the zones the measures
// allow crossings in.
#pragma once

#include <cstdint>
#include <vector>

#include "body_collider.h"
#include "layers/sim/cloth.h"

namespace layers::sim::detail {

class BodyPinch {
 public:
  // The next frame starts from a pose whose zones are not known (a new
  // body, or a pose set without motion).
  void forget() { carried_ = false; }
  // The zones of the frame `body` is about to sweep (after begin_frame;
  // `body_faces` its faces), under the cloths as they stand now.
  const std::vector<std::uint8_t>& update(const BodyCollider& body, const geometry::Faces& body_faces,
                                          const std::vector<Cloth>& cloths, double distance);

 private:
  std::vector<std::uint8_t> start_, end_, frame_;
  bool carried_ = false;
};

}  // namespace layers::sim::detail
