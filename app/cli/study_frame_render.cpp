#include "app/cli/study_frame_render.h"

#include <exception>
#include <filesystem>

#include "app/core/config_paths.h"
#include "app/render/gl/egl_context.h"
#include "app/render/render_config.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"

namespace cb {

bool renderStudyFrame(const Volume& volume, const Camera& camera, const Light* light, int width,
                      int height, ImageRgbaF* frame, std::string* error) {
  RenderConfig config;
  const std::string config_path = configFile("render.toml");
  if (std::filesystem::exists(config_path)) {
    try {
      config = loadRenderConfig(config_path);
    } catch (const std::exception& e) {
      *error = e.what();
      return false;
    }
  }
  EglContext ctx;
  if (!createSurfacelessContext(&ctx, error)) return false;
  bool ok = false;
  {
    VolumeRenderer renderer;
    RenderTarget target;
    if (renderer.init(error) &&
        target.create(width, height, RenderTarget::Format::kRgba32F, error)) {
      renderer.sync(volume, light ? *light : config.light);
      RenderOptions options = config.options;
      options.finish = true;
      renderer.render(camera, width, height, target.fbo(), options);
      *frame = target.readRgbaF();
      ok = true;
    }
  }
  destroyGlContext(&ctx);
  return ok;
}

}  // namespace cb
