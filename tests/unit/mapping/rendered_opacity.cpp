#include "rendered_opacity.h"

#include "app/render/image_io.h"

namespace cb::test {

std::vector<float> renderedOpacity(VolumeRenderer& renderer, RenderTarget& target,
                                   const Volume& volume, const Camera& camera) {
  const int w = target.width(), h = target.height();
  renderer.sync(volume, Light{});
  RenderOptions options;
  options.background = glm::vec4(0.0f);
  renderer.render(camera, w, h, target.fbo(), options);
  const ImageRgba8 image = target.readRgba8();
  std::vector<float> alpha(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      alpha[size_t(y) * size_t(w) + size_t(x)] = image.at(x, y)[3] / 255.0f;
  return alpha;
}

}  // namespace cb::test
