// The light preview grid (reduced_light_sweep.h) on the GPU: a 3D R8 texture, filtered
// trilinearly and clamped to its edge, that the ray caster's CB_LIGHT_PREVIEW variant reads for
// the light instead of the brick pool's (volume_pool.glsl, previewTransmittance) while the light
// ball is dragged. Needs a current GL 4.5 context.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "app/render/gl/gl.h"
#include "app/render/reduced_light_sweep.h"

namespace cb {

class LightPreviewTexture {
 public:
  LightPreviewTexture() = default;
  ~LightPreviewTexture() { release(); }
  LightPreviewTexture(const LightPreviewTexture&) = delete;
  LightPreviewTexture& operator=(const LightPreviewTexture&) = delete;

  // Uploads `grid` (the texture is made anew when its size changes).
  void upload(const LightPreviewGrid& grid);
  // Binds the texture to `unit` and sets `program`'s u_light_preview and the mapping from a
  // dense texture coordinate of a volume of `dims` voxels to the grid's texture coordinate
  // (u_preview_scale, u_preview_offset).
  void bind(GLuint program, int unit, glm::ivec3 dims) const;
  bool empty() const { return texture_ == 0; }
  size_t bytes() const { return size_t(size_.x) * size_t(size_.y) * size_t(size_.z); }
  void release();

 private:
  GLuint texture_ = 0;
  glm::ivec3 size_{0}, lo_{0};
  int divisor_ = 0;
};

}  // namespace cb
