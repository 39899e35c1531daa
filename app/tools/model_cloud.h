// Model → cloud: a closed mesh is voxelised (inside by ray parity along x through voxel
// centres), the depth of every inside voxel below the surface comes from an exact distance
// transform, and the density rises from 0 at a noise-eroded surface to the peak `falloff`
// voxels deeper (the thesis's simplex noise on sphere surfaces, §6.5). Placed like a picture:
// the model's bounding-box centre on the anchor (tool_view.h), its largest side
// `size_fraction` of the view's height at the anchor's depth, model axes kept (y up).
//
// Why not the seed's tetrahedron sampling (002 §3.1.2): it needs a 3D curve skeleton (Cornea et
// al.), and a tetrahedron from a face to its nearest skeleton point leaves the model wherever the
// face cannot see that point (any non-convex part), so the cloud would not stay inside the model.
// Parity voxelisation is exact inside at voxel resolution, costs O(triangles + voxels), and the
// distance transform gives the same "dense inside, thin at the edge" profile the seed builds
// with its apex-weighted CDF (Eq. 3.1–3.2).
#pragma once

#include <cstdint>
#include <string>

#include "app/tools/tool_view.h"
#include "app/tools/triangle_mesh.h"
#include "app/volume/volume.h"

namespace cb {

struct ModelCloudParams {
  uint32_t seed = 1;
  float peak_density = 1.0f;
  float falloff_voxels = 4.0f;        // depth over which the density rises to the peak
  float noise_erosion_voxels = 3.0f;  // the surface is eroded by up to this much
  float noise_frequency = 12.0f;      // noise cycles per world unit
};

// The world transform of a mesh placed from the view: world = anchor + (p − centre)·scale.
struct ModelPlacement {
  glm::vec3 centre{0};  // model space, bounding-box centre
  glm::vec3 anchor{0};  // world
  float scale = 1;
  glm::vec3 toWorld(glm::vec3 p) const { return anchor + (p - centre) * scale; }
};
ModelPlacement placeModel(const TriangleMesh& mesh, const ToolView& view, const Volume& volume);

// Where the cloud of `mesh` placed from `view` can write, in `volume`'s voxel grid and not
// clipped to it: the placed mesh's voxel bounding box plus one voxel all round. meshToCloud
// writes only inside it (noise only erodes); the session grows the sky to hold it first
// (tool_view.h placementReach). `mesh` as validatedClosedMesh passes it.
VoxelBox modelReach(const TriangleMesh& mesh, const ToolView& view, const Volume& volume);

// Loads, checks (loadClosedMesh: ToolError before the volume is touched) and writes the cloud.
VoxelBox modelToCloud(const std::string& mesh_path, const ToolView& view,
                      const ModelCloudParams& params, Volume* volume);
// The same for a mesh in memory (checked with validatedClosedMesh).
VoxelBox meshToCloud(const TriangleMesh& mesh, const ToolView& view, const ModelCloudParams& params,
                     Volume* volume);

}  // namespace cb
