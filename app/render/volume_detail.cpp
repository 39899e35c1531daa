#include "app/render/volume_detail.h"

#include <algorithm>
#include <cmath>

namespace cb {

float volumeDetailScale(const Camera& camera, int height, const std::vector<glm::vec3>& occupied,
                        glm::vec3 world_min, glm::vec3 voxel_size, float floor) {
  const float voxel = std::min({voxel_size.x, voxel_size.y, voxel_size.z});
  if (occupied.empty() || height <= 0 || !(voxel > 0.0f)) return 1.0f;
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  float farthest = 0.0f;
  for (const glm::vec3& p : occupied)
    farthest = std::max(farthest, glm::dot(world_min + p * voxel_size - camera.eye, forward));
  if (!(farthest > 0.0f)) return 1.0f;
  // A world length L at view depth z covers L·height / (2·z·tan(fov/2)) pixels.
  const float half_height = farthest * std::tan(glm::radians(camera.fov_y_deg) * 0.5f);
  const float pixels_per_voxel = voxel * float(height) / (2.0f * half_height);
  const float scale = std::ceil(20.0f / pixels_per_voxel) / 20.0f;
  return std::clamp(scale, floor, 1.0f);
}

float detailCastScale(float requested, bool moving, float detail) {
  if (!moving) return std::clamp(detail, kMinStillDetailScale, 1.0f);
  return std::min(requested, std::clamp(detail, kMinMovingDetailScale, 1.0f));
}

}  // namespace cb
