// Self-contact within one garment (see cloth_contact.h).
#include "cloth_contact.h"
#include "contact_response.h"
#include "surface_query.h"

namespace layers::sim::detail {

void SelfContact::collide(const Cloth& cloth, Cloth::State& s, double thickness, double mu, Vec3s& push) {
  const ContactTopology& topology = cloth.topology();
  const double radius = thickness + topology.reach();
  grid_.build(s.x, radius);
  for (int i = 0; i < static_cast<int>(s.x.size()); ++i) {
    const Vec3 p = s.x[i];
    int nearest = -1;
    double best = radius * radius;
    grid_.visit(p, radius, [&](int j) {
      if (j == i) return;
      const double d2 = (s.x[j] - p).squaredNorm();
      if (d2 < best && !cloth.in_two_ring(i, j)) {
        best = d2;
        nearest = j;
      }
    });
    if (nearest < 0) continue;
    SurfaceHit hit;
    if (!closest_around(topology, s.x, nearest, p, hit)) continue;
    // The side p was on at the start of the substep, at the same surface point.
    const double before = side_offset(topology, s.x_start, hit, s.x_start[i]);
    const double side = before > 0 ? 1.0 : before < 0 ? -1.0 : (hit.offset >= 0 ? 1.0 : -1.0);
    Vec3 normal;
    double depth;
    if (!cloth_push(hit, p, side, thickness, normal, depth)) continue;
    resolve_two_way(s.x, s.x_start, s.inv_mass, i, s.x, s.x_start, s.inv_mass,
                    TriangleRef{topology.faces[hit.face], hit.bary}, normal, depth, mu, push, push);
  }
}

}  // namespace layers::sim::detail
