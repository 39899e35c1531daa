#include "app/render/light_preview_texture.h"

namespace cb {

void LightPreviewTexture::upload(const LightPreviewGrid& grid) {
  if (grid.divisor == 0) return;
  if (texture_ == 0 || size_ != grid.size) {
    release();
    glCreateTextures(GL_TEXTURE_3D, 1, &texture_);
    glTextureStorage3D(texture_, 1, GL_R8, grid.size.x, grid.size.y, grid.size.z);
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
      glTextureParameteri(texture_, wrap, GL_CLAMP_TO_EDGE);
    size_ = grid.size;
  }
  lo_ = grid.lo;
  divisor_ = grid.divisor;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(texture_, 0, 0, 0, 0, size_.x, size_.y, size_.z, GL_RED, GL_UNSIGNED_BYTE,
                      grid.bytes.data());
}

void LightPreviewTexture::bind(GLuint program, int unit, glm::ivec3 dims) const {
  // Dense coordinate c is fine voxel position c·dims, coarse position c·dims/divisor (coarse
  // voxel j's centre at j + ½), texel position within the box (c·dims/divisor − lo)/size.
  const glm::vec3 size(size_);
  const glm::vec3 scale = glm::vec3(dims) / (float(divisor_) * size);
  const glm::vec3 offset = -glm::vec3(lo_) / size;
  glBindTextureUnit(GLuint(unit), texture_);
  glUniform1i(glGetUniformLocation(program, "u_light_preview"), unit);
  glUniform3f(glGetUniformLocation(program, "u_preview_scale"), scale.x, scale.y, scale.z);
  glUniform3f(glGetUniformLocation(program, "u_preview_offset"), offset.x, offset.y, offset.z);
}

void LightPreviewTexture::release() {
  if (texture_) glDeleteTextures(1, &texture_);
  texture_ = 0;
  size_ = glm::ivec3(0);
}

}  // namespace cb
