// The named errors of the modelling tools. Every check that can fail on outside input (a
// picture, a mesh file) runs before the volume is touched, so a ToolError leaves the cloud as it
// was.
#pragma once

#include <stdexcept>
#include <string>

namespace cb {

enum class ToolErrorKind {
  kUnreadableFile,    // cannot open or read the file
  kNotPng,            // the picture is not a PNG (signature or header)
  kEmptyImage,        // zero width/height, or no shape pixel in the picture
  kImageTooLarge,     // more pixels than kMaxPicturePixels (checked from the header)
  kMeshFileTooLarge,  // more bytes than kMaxMeshFileBytes (checked before parsing)
  kMeshUnreadable,    // Assimp could not parse the file
  kMeshTooLarge,      // more triangles than kMaxMeshTriangles
  kOpenMesh,          // an edge not shared by exactly two triangles
  kDegenerateMesh,    // no triangles, non-finite vertices, zero area or zero volume
  kEmptyVolume,       // morph: a source or target without density
  kMismatchedVolumes  // morph: source and target grids differ
};

const char* toolErrorName(ToolErrorKind kind);

struct ToolError : std::runtime_error {
  ToolError(ToolErrorKind k, const std::string& what)
      : std::runtime_error(std::string(toolErrorName(k)) + ": " + what), kind(k) {}
  ToolErrorKind kind;
};

inline const char* toolErrorName(ToolErrorKind kind) {
  switch (kind) {
    case ToolErrorKind::kUnreadableFile:
      return "unreadable file";
    case ToolErrorKind::kNotPng:
      return "not a PNG";
    case ToolErrorKind::kEmptyImage:
      return "empty image";
    case ToolErrorKind::kImageTooLarge:
      return "image too large";
    case ToolErrorKind::kMeshFileTooLarge:
      return "mesh file too large";
    case ToolErrorKind::kMeshUnreadable:
      return "unreadable mesh";
    case ToolErrorKind::kMeshTooLarge:
      return "mesh too large";
    case ToolErrorKind::kOpenMesh:
      return "open mesh";
    case ToolErrorKind::kDegenerateMesh:
      return "degenerate mesh";
    case ToolErrorKind::kEmptyVolume:
      return "empty volume";
    case ToolErrorKind::kMismatchedVolumes:
      return "mismatched volumes";
  }
  return "tool error";
}

}  // namespace cb
