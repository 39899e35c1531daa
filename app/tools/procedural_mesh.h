// Generated test models (nothing can be downloaded): a torus whose tube radius is displaced by
// a smooth bump pattern, and an OBJ writer, for the model → cloud tests and `bench tools`.
#pragma once

#include <string>

#include "app/tools/triangle_mesh.h"

namespace cb {

// Torus about the y axis: ring radius `major`, tube radius `minor`·(1 + amplitude·bumps) with
// bumps = sin(5u)·sin(3v) in [-1, 1]. rings × sides quads, 2·rings·sides triangles, closed.
// 192 × 184 gives 70,656 triangles.
TriangleMesh makeDisplacedTorus(float major, float minor, float amplitude, int rings, int sides);
// The tube radius of that torus at ring angle u and tube angle v.
float displacedTorusTubeRadius(float minor, float amplitude, float u, float v);

// Wavefront OBJ (v / f lines, 1-based). Throws std::runtime_error when the file cannot be written.
void writeObj(const std::string& path, const TriangleMesh& mesh);

}  // namespace cb
