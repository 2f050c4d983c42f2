// Stored frames for the validation measures (see stored_measures.h).
#include "layers/generate/stored_measures.h"

#include <string>

#include "layers/core/error.h"
#include "layers/generate/simulate.h"
#include "layers/geometry/topology.h"

namespace layers::generate {

namespace {

geometry::Points frame_points(const std::vector<float>& all, std::int64_t frame, std::int64_t n) {
  return Eigen::Map<const geometry::Points>(all.data() + frame * n * 3, static_cast<Eigen::Index>(n), 3);
}

geometry::Faces faces_of(const std::vector<std::int32_t>& faces) {
  return Eigen::Map<const geometry::Faces>(faces.data(), static_cast<Eigen::Index>(faces.size() / 3), 3);
}

}  // namespace

namespace {

// The frame-independent part: faces, edges, rest lengths, layers.
StoredFrame frame_shape(const data::SequenceData& seq) {
  StoredFrame f;
  f.body.faces = faces_of(seq.body.faces);
  for (const data::GarmentData& g : seq.garments) {
    sim::MeasuredGarment m;
    m.faces = faces_of(g.faces);
    m.edges = geometry::unique_edges(m.faces);
    m.rest_lengths = geometry::edge_lengths(frame_points(g.rest, 0, g.n_vertices()), m.edges);
    m.outer = g.layer == 1;
    m.self_contact = garment_self_contact(g);
    f.garments.push_back(std::move(m));
  }
  return f;
}

void set_positions(const data::SequenceData& seq, std::int64_t t, StoredFrame& f) {
  f.body.vertices = frame_points(seq.body.positions, t, seq.body.n_vertices());
  for (std::size_t k = 0; k < seq.garments.size(); ++k)
    f.garments[k].positions = frame_points(seq.garments[k].positions, t, seq.garments[k].n_vertices());
}

}  // namespace

void for_each_stored_frame(const data::SequenceData& seq,
                           const std::function<void(std::int64_t, const StoredFrame&)>& visit) {
  StoredFrame f = frame_shape(seq);
  for (std::int64_t t = 0; t < seq.n_frames; ++t) {
    set_positions(seq, t, f);
    visit(t, f);
  }
}

StoredFrame stored_frame(const data::SequenceData& seq, std::int64_t frame) {
  if (frame < 0 || frame >= seq.n_frames)
    throw Error("stored_frame: frame " + std::to_string(frame) + " of a sequence of " + std::to_string(seq.n_frames));
  StoredFrame f = frame_shape(seq);
  set_positions(seq, frame, f);
  return f;
}

}  // namespace layers::generate
