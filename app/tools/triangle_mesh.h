// A triangle mesh as the model → cloud tool needs it, and the checks that make its inside
// well defined: a closed (watertight) surface of finite, non-degenerate triangles.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cb {

constexpr size_t kMaxMeshTriangles = 5'000'000;

struct TriangleMesh {
  std::vector<glm::vec3> vertices;
  std::vector<glm::uvec3> triangles;
};

// Welds vertices at identical positions (files repeat a position per normal or texture seam),
// drops triangles that collapse to a line or point, and checks what is left: ToolError
// kDegenerateMesh (no triangles, a non-finite coordinate, zero area or zero enclosed volume),
// kOpenMesh (an edge not shared by exactly two triangles), kMeshTooLarge. `name` goes into the
// message. Returns the welded mesh.
TriangleMesh validatedClosedMesh(const TriangleMesh& mesh, const std::string& name);

// Signed volume enclosed by a closed mesh (divergence theorem); |·| for inside-out meshes.
double enclosedVolume(const TriangleMesh& mesh);

}  // namespace cb
