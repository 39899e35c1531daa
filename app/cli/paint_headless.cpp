#include "app/cli/paint_headless.h"

#include <filesystem>
#include <system_error>

#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/scene/camera.h"

namespace cb {

bool renderHeadless(Display& display, VolumeRenderer& renderer, const Volume& volume,
                    const Light& light, const RenderOptions& base, const std::string& out_dir,
                    const std::string& stem, bool collect_stats, HeadlessRenderResult* result,
                    std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    *error = "cannot create the output directory " + out_dir + ": " + ec.message();
    return false;
  }
  // One render into a float target gives both files: the EXR keeps the linear values, the PNG
  // is the same pixels quantised by GL's conversion on readback.
  RenderTarget target;
  if (!target.create(display.width(), display.height(), RenderTarget::Format::kRgba32F, error))
    return false;
  renderer.sync(volume, light);
  RenderOptions options = base;  // render.toml's style, sky, background and ray-cast settings
  options.scale = 1.0f;
  options.moving = false;
  options.region = glm::ivec4(0);
  options.collect_stats = collect_stats;
  options.finish = true;
  renderer.render(Camera::reference(), display.width(), display.height(), target.fbo(), options);
  result->stats = renderer.lastStats();
  const std::string png = (std::filesystem::path(out_dir) / (stem + ".png")).string();
  const std::string exr = (std::filesystem::path(out_dir) / (stem + ".exr")).string();
  try {
    writePng(png, target.readRgba8());
    result->written.push_back(png);
    writeExr(exr, target.readRgbaF());
    result->written.push_back(exr);
  } catch (const ImageIoError& e) {
    *error = e.what();
    return false;
  }
  std::string present_error;
  if (!display.present(&present_error)) {
    *error = present_error;
    return false;
  }
  return true;
}

}  // namespace cb
