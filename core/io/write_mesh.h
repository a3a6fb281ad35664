#pragma once

#include <string>

#include "core/mesh/colour.h"
#include "core/mesh/mesh.h"

namespace papernet {

/// The mesh as a binary glTF 2.0 (GLB): one mesh, one triangle primitive with POSITION
/// (float32, with min/max) and uint32 indices, no normals (viewers then shade flat, as folded
/// paper looks), and a white material as paper shows it (not metallic, double-sided; glTF's
/// default material is metallic, which viewers draw dark grey). Returns the file's bytes.
/// \throw InvalidInputException when the mesh is empty or has a face index out of range.
std::string write_glb(const Mesh& mesh);

/// The mesh with its colour (`colour` indexed like mesh.faces, as loading gives it), as GLB:
/// one primitive per material, each corner a vertex of its own (POSITION; TEXCOORD_0 where the
/// material has a texture; COLOR_0, linear RGBA, when the mesh has vertex colours), the
/// materials (base colour, texture, alpha mode; not metallic, double-sided, as paper) and the
/// textures' images as they came (PNG or JPEG, with their samplers). A face's missing texture
/// coordinates are written as (0, 0), its missing colours as white; faces without a material
/// get a white one. Without colour data, write_glb(mesh).
/// \throw InvalidInputException as write_glb(mesh), and when `colour` does not match the mesh.
std::string write_glb(const Mesh& mesh, const MeshColour& colour);

/// The mesh as Wavefront OBJ text (v and f lines, 1-based indices).
std::string write_obj(const Mesh& mesh);

}  // namespace papernet
