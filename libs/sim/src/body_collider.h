// body_collider.h (internal) -- the moving body as a kinematic collider.
//
// Per frame the body goes linearly from its current pose to the next one;
// per substep its vertices are interpolated and hashed into a grid whose
// cell is the contact search radius: 1.5 x thickness (the touching range) +
// the topology's reach (how far a surface point can be from its nearest
// vertex) + how far the body and the cloth moved in the substep (how deep a
// vertex can have got in). A cloth vertex is resolved against the closest point among the faces
// around its nearest body vertex.
//
// Two mechanisms work together:
//  - support: a vertex touching the body at the start of a frame is held,
//    for that frame, at `thickness` from the body's tangent plane at its
//    closest point (found again each substep) by an attachment the elastic
//    solve sees (see projective.h), so the body carries the garment's
//    weight through the global solve. Its target is the vertex projected
//    onto the half-space outside that plane (PD's projection for a contact
//    constraint), so it pushes along the normal only and never pulls; the
//    attachment ends at the next frame when the vertex has lifted off;
//  - projection: after the elastic iterations every vertex found within
//    `thickness` of the surface is pushed out along the body normal, with
//    position-based Coulomb friction relative to the body's own motion
//    (for supported vertices the friction budget is their support force).
//  - edges (optional): garment edges are kept `edge_thickness` from the
//    body's edges (EdgeContact, the body side fixed, outward = the mean
//    normal of an edge's faces), so a ridge of the body (a shoulder, an
//    elbow) cannot poke between the vertices of a coarser garment; the
//    pairs come from the solver's shared candidate list.
// Because the body advances only 1/substeps of a frame per substep and
// contacts are found afresh every substep, fast limbs cannot skip over a
// vertex unless they move more than the search radius in one substep.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cloth_contact.h"
#include "layers/geometry/mesh.h"
#include "layers/sim/cloth.h"
#include "layers/sim/contact_topology.h"
#include "spatial_hash.h"
#include "surface_query.h"

namespace layers::sim::detail {

class BodyCollider {
 public:
  // What the collider remembers about each vertex of one cloth.
  struct Memory {
    std::vector<int> nearest;            // nearest body vertex (-1: none)
    std::vector<int> face;               // body face of the last contact (-1: none)
    std::vector<std::uint8_t> touching;  // within 1.5 x thickness after the last substep
    std::vector<std::uint8_t> wanted;    // supported this frame (see make_supports)
    std::vector<double> support;         // normal support force of the last iteration (N)
    Vec3s point, normal;                 // this substep's contact point and normal (normal zero: none)
    Vec3s target;                        // support target of the current iteration
    void resize(int n);
  };

  // Topology and pose; InputError (naming "body") for bad faces or values.
  void reset(const geometry::TriMesh& body);
  bool empty() const { return topology_.num_faces() == 0; }
  // This substep's sweep (after begin_substep): the pose at its start and
  // at its end, the faces and the unique edges.
  const Vec3s& pose_before() const { return previous_; }
  const Vec3s& pose_now() const { return current_; }
  // The frame's sweep: its start and end poses.
  const Vec3s& frame_start() const { return start_; }
  const Vec3s& frame_end() const { return end_; }
  const ContactTopology& topology() const { return topology_; }
  const geometry::Edges& edges() const { return edges_; }
  int num_vertices() const { return static_cast<int>(start_.size()); }

  // Poses: the frame starts at the current pose and ends at `next` (same
  // vertex count, finite) or, given nothing, stays.
  void set_pose(const geometry::Points& pose);
  void begin_frame(const geometry::Points* next);
  // Interpolates to fraction s in (0, 1] of the frame and rebuilds the grid;
  // `cloth_step` bounds how far any cloth vertex can have moved.
  void begin_substep(double s, double cloth_step, double thickness);
  // Names the frame's sweep (start and end poses): changes whenever either
  // does (the shared candidate list makes its body pairs once per sweep).
  long sweep_revision() const { return sweep_revision_; }
  void end_frame();

  // At the start of a frame: supports the vertices that ended the last
  // frame touching the body.
  void make_supports(const Cloth::State& state, Memory& memory) const;
  // At each substep (after begin_substep): the closest body point and its
  // normal for each supported vertex; the tangent plane there is its
  // contact plane for the substep.
  void locate_supports(const Cloth::State& state, Memory& memory) const;
  // Before each elastic iteration: the targets (each supported vertex moved
  // onto its contact plane at `thickness`) of the vertices with an
  // attachment weight (from the factorised matrix) that it claims; adds
  // weight x target to `rhs`.
  void aim_supports(const Cloth::State& state, Memory& memory, const std::vector<double>& weights, double thickness,
                    Vec3s& rhs, std::vector<std::uint8_t>& claimed) const;
  // After each elastic iteration: records the support forces.
  void record_supports(const Cloth::State& state, Memory& memory, const std::vector<double>& weights,
                       const std::vector<std::uint8_t>& claimed) const;

  // The projection pass (see above); h is the substep. Returns the largest
  // push along the normal it gave a vertex.
  double collide(Cloth::State& state, Memory& memory, double thickness, double mu, double h) const;
  // The edge pass (see above) over `pairs` (a garment edge, a body edge;
  // from the shared candidate list): the pushes are added to `push`.
  // Returns the largest.
  double collide_edges(const Cloth& cloth, Cloth::State& state, double edge_thickness, Vec3s& push,
                       const std::vector<std::array<int, 2>>& pairs);

 private:
  bool nearest_point(const Vec3& p, int& nearest, SurfaceHit& hit) const;

  ContactTopology topology_;
  Vec3s start_, end_;         // frame poses
  Vec3s current_, previous_;  // this substep's pose and the one before
  double radius_ = 0;         // this substep's search radius (= grid cell)
  SpatialHash grid_;
  geometry::Edges edges_;                          // unique edges
  std::vector<int> edge_face_start_, edge_faces_;  // per edge: its faces
  Vec3s edge_normals_;                             // outward direction per edge, at this substep's pose ...
  std::vector<long> edge_normal_stamp_;            // ... for the edges whose stamp is substep_
  long substep_ = 0;                               // counts begin_substep()
  long sweep_revision_ = 0;
};

}  // namespace layers::sim::detail
