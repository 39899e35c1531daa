#include "app/tools/mesh_loading.h"

#include <filesystem>
#include <system_error>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

#include "app/tools/tool_error.h"

namespace cb {

TriangleMesh loadClosedMesh(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) throw ToolError(ToolErrorKind::kUnreadableFile, path + ": " + ec.message());
  if ((long long)bytes > kMaxMeshFileBytes)
    throw ToolError(
        ToolErrorKind::kMeshFileTooLarge,
        path + ": " + std::to_string(bytes) + " bytes, limit " + std::to_string(kMaxMeshFileBytes));
  Assimp::Importer importer;
  // Points and lines carry no inside; drop them before triangulating polygons.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode)
    throw ToolError(ToolErrorKind::kMeshUnreadable, path + ": " + importer.GetErrorString());
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    const uint32_t base = uint32_t(mesh.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v)
      mesh.vertices.emplace_back(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      mesh.triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[1],
                                  base + face.mIndices[2]);
    }
  }
  return validatedClosedMesh(mesh, path);
}

}  // namespace cb
