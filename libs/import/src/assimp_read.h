// assimp_read.h (internal) -- the one way this library hands a file to
// assimp: the import runs with assimp's warnings captured (one import at a
// time: assimp's logger is process-wide), and what assimp only warns about
// but silently repairs is refused instead (faces with out-of-range vertex
// indices, which it drops), and a .gltf whose buffers or images are not
// regular files (a FIFO would block assimp) is refused before assimp
// opens it, and so is a file declaring more than its size holds
// (declared_counts.h). InputError naming the file on any failure.
#pragma once

#include <assimp/Importer.hpp>
#include <string>

struct aiScene;

namespace layers::import::detail {

// `importer.ReadFile(path, flags)`; `what` is what the file was expected
// to be, for the message ("a mesh file assimp reads").
const aiScene* read_with_assimp(Assimp::Importer& importer, const std::string& path, unsigned flags,
                                const std::string& what);

}  // namespace layers::import::detail
