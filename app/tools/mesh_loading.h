// Mesh files (OBJ, PLY, glTF, and whatever else Debian's Assimp reads) → TriangleMesh, with the
// file size checked before parsing and the result checked closed (triangle_mesh.h).
#pragma once

#include <string>

#include "app/tools/triangle_mesh.h"

namespace cb {

constexpr long long kMaxMeshFileBytes = 512LL << 20;

// ToolError: kUnreadableFile, kMeshFileTooLarge, kMeshUnreadable, and validatedClosedMesh's.
TriangleMesh loadClosedMesh(const std::string& path);

}  // namespace cb
