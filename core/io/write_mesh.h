#pragma once

#include <string>

#include "core/mesh/mesh.h"

namespace papernet {

/// The mesh as a binary glTF 2.0 (GLB): one mesh, one triangle primitive with POSITION
/// (float32, with min/max) and uint32 indices, no normals (viewers then shade flat, as folded
/// paper looks). Returns the file's bytes.
/// \throw InvalidInputException when the mesh is empty or has a face index out of range.
std::string write_glb(const Mesh& mesh);

/// The mesh as Wavefront OBJ text (v and f lines, 1-based indices).
std::string write_obj(const Mesh& mesh);

}  // namespace papernet
