// Stored frames for the validation measures (see stored_measures.h).
#include "layers/generate/stored_measures.h"

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

void for_each_stored_frame(const data::SequenceData& seq,
                           const std::function<void(std::int64_t, const StoredFrame&)>& visit) {
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
  for (std::int64_t t = 0; t < seq.n_frames; ++t) {
    f.body.vertices = frame_points(seq.body.positions, t, seq.body.n_vertices());
    for (std::size_t k = 0; k < seq.garments.size(); ++k)
      f.garments[k].positions = frame_points(seq.garments[k].positions, t, seq.garments[k].n_vertices());
    visit(t, f);
  }
}

}  // namespace layers::generate
