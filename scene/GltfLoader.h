#pragma once
// glTF 2.0 import (.gltf and .glb, through tinygltf) into Candela's world-space meshes.
//
// What is read: the default scene's node trees (all root nodes when the file has no scene) with
// their matrix or TRS transforms; triangle-list primitives (POSITION as float VEC3, NORMAL when
// present, else flat normals; indices of 8, 16 or 32 bits, or none); the metallic-roughness
// material's base colour (times the base colour texture's mean linear colour), roughness and
// metallic factors. Other primitive modes are skipped with a warning on stderr. Every count,
// index and byte range is checked against the buffers, so a malformed file raises an InputError
// naming it and never crashes. Files that require any glTF extension are rejected (Candela
// decodes none).

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scene/Scene.h"
#include "util/JsonRead.h"

namespace candela {

/// Appends the meshes and materials of the glTF file at `path`, transformed by `transform`
/// (glTF units are metres, Y-up, as in Candela), to `scene`. Each primitive becomes one Mesh with
/// shape General. `where` names the scene-file entry in error messages. Returns the files read:
/// `path`, then the external buffers and images it names (data: URIs are not files).
std::vector<std::string> loadGltf(const std::string& path, const glm::dmat4& transform,
                                  Scene& scene, const json::Where& where);

}  // namespace candela
