// layers/import/remesh.h -- a user's garment mesh brought to the
// simulator's edge length: isotropic remeshing (CGAL's Polygon Mesh
// Processing, `isotropic_remeshing`) to a target edge length, with the
// open borders (hems, cuffs, the neck) and the UV seams kept as polylines
// (their edges split or collapsed along them, never flipped, their
// vertices left where they are by the smoothing: relaxed along a curved
// border they drifted 3-5 mm inwards), and the UVs carried over: each corner
// of a new face takes the UV the original surface has there, read in the
// UV chart of the original face the new face lies on (so a seam keeps two
// UVs). The shape is the file's: new vertices lie on the original
// surface, and the result is the garment's rest state as fitted.
#pragma once

#include <string>

#include "layers/import/mesh_import.h"

namespace layers::import {

struct RemeshReport {
  int faces_before = 0, faces_after = 0;
  double shortest_before = 0, shortest_after = 0;  // edge lengths (m)
  double mean_before = 0, mean_after = 0;
};

// `mesh` remeshed to edges of about `edge_length` (m) in `iterations`
// rounds. InputError naming `mesh.file` when CGAL cannot take the mesh as
// a surface (a non-manifold vertex or edge) or the target is not positive.
ImportedMesh remesh(const ImportedMesh& mesh, double edge_length, int iterations = 5, RemeshReport* report = nullptr);

// Shortest and mean edge length of a triangle mesh (m).
void edge_lengths(const geometry::TriMesh& mesh, double& shortest, double& mean);

}  // namespace layers::import
