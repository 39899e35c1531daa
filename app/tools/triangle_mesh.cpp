#include "app/tools/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "app/tools/tool_error.h"

namespace cb {
namespace {

struct PositionHash {
  size_t operator()(const glm::vec3& p) const {
    uint32_t b[3];
    std::memcpy(b, &p, sizeof b);
    return (size_t(b[0]) * 0x9E3779B1u) ^ (size_t(b[1]) * 0x85EBCA77u) ^
           (size_t(b[2]) * 0xC2B2AE3Du);
  }
};

}  // namespace

double enclosedVolume(const TriangleMesh& mesh) {
  double v = 0;
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a(mesh.vertices[t.x]), b(mesh.vertices[t.y]), c(mesh.vertices[t.z]);
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

TriangleMesh validatedClosedMesh(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.triangles.size() > kMaxMeshTriangles)
    throw ToolError(ToolErrorKind::kMeshTooLarge,
                    name + ": " + std::to_string(mesh.triangles.size()) + " triangles, limit " +
                        std::to_string(kMaxMeshTriangles));
  for (const glm::vec3& p : mesh.vertices)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw ToolError(ToolErrorKind::kDegenerateMesh, name + ": a vertex is not finite");
  TriangleMesh out;
  std::unordered_map<glm::vec3, uint32_t, PositionHash> index;
  index.reserve(mesh.vertices.size());
  std::vector<uint32_t> remap(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3 p = mesh.vertices[i] + glm::vec3(0.0f);  // -0 → +0
    auto [it, inserted] = index.emplace(p, uint32_t(out.vertices.size()));
    if (inserted) out.vertices.push_back(p);
    remap[i] = it->second;
  }
  double area = 0;
  for (const glm::uvec3& t : mesh.triangles) {
    if (t.x >= remap.size() || t.y >= remap.size() || t.z >= remap.size())
      throw ToolError(ToolErrorKind::kDegenerateMesh, name + ": a triangle index is out of range");
    const glm::uvec3 w(remap[t.x], remap[t.y], remap[t.z]);
    if (w.x == w.y || w.y == w.z || w.x == w.z) continue;
    const glm::vec3 a = out.vertices[w.x], b = out.vertices[w.y], c = out.vertices[w.z];
    const double ta = 0.5 * glm::length(glm::dvec3(glm::cross(b - a, c - a)));
    if (ta == 0.0) continue;
    area += ta;
    out.triangles.push_back(w);
  }
  if (out.triangles.empty() || area == 0.0)
    throw ToolError(ToolErrorKind::kDegenerateMesh, name + ": no triangle with area");
  // Every undirected edge must be used by exactly two triangles.
  std::vector<uint64_t> edges;
  edges.reserve(out.triangles.size() * 3);
  for (const glm::uvec3& t : out.triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      edges.push_back((uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  size_t bad = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) ++bad;
    i = j;
  }
  if (bad > 0)
    throw ToolError(ToolErrorKind::kOpenMesh,
                    name + ": " + std::to_string(bad) +
                        " edges are not shared by exactly two triangles (the surface has holes "
                        "or non-manifold edges; its inside is undefined)");
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : out.vertices) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = glm::length(glm::dvec3(hi - lo));
  if (std::abs(enclosedVolume(out)) <= 1e-9 * extent * extent * extent)
    throw ToolError(ToolErrorKind::kDegenerateMesh, name + ": the surface encloses no volume");
  return out;
}

}  // namespace cb
