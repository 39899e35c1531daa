// cloudbrush render: offline render of a saved volume to PNG or EXR through EGL surfaceless.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/core/config_paths.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

const char kRenderHelp[] =
    "usage: cloudbrush render --volume FILE --out FILE.png|FILE.exr [options]\n"
    "\n"
    "Renders a saved volume (raw float32 + JSON header, see app/volume/volume_file.h) offline\n"
    "with the lit ray caster, headless (EGL surfaceless).\n"
    "\n"
    "  --volume FILE          the volume file (required)\n"
    "  --out FILE             output image, .png (8-bit RGBA) or .exr (float RGBA) (required)\n"
    "  --camera EX,EY,EZ[,TX,TY,TZ[,FOV]]\n"
    "                         eye, target and vertical field of view in degrees; default: the\n"
    "                         reference camera (eye 2.3,1.5,2.3, target 0,-0.05,0, 45°)\n"
    "  --size WxH             image size in pixels (default 1280x720)\n"
    "  --light X,Y,Z          world position of the light ball (default from the config)\n"
    "  --config FILE          renderer defaults (default: render.toml in the config directory,\n"
    "                         see config/render.toml; CLOUDBRUSH_CONFIG_DIR overrides)\n"
    "  --style NAME           thesis|physical|ink|cartoon|sketch (default from the config:\n"
    "                         [style] name, else thesis; see app/render/render_style.h)\n"
    "  --no-skip              disable empty-space skipping (same image, slower)\n"
    "  --stats                print ray-sample statistics (total, mean, max, histogram)\n"
    "  --help                 this text\n";

// Parses "a,b,c,..." into between `min_count` and `max_count` finite numbers.
bool parseNumbers(const std::string& text, size_t min_count, size_t max_count,
                  std::vector<float>* out) {
  out->clear();
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    char* end = nullptr;
    float v = std::strtof(item.c_str(), &end);
    if (item.empty() || *end != 0 || !std::isfinite(v)) return false;
    out->push_back(v);
  }
  return out->size() >= min_count && out->size() <= max_count;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "cloudbrush render: %s\n", message.c_str());
  return 1;
}

}  // namespace

int commandRender(int argc, char** argv) {
  Args args(argc, argv, {"help", "no-skip", "stats"});
  if (args.has("help")) {
    std::printf("%s", kRenderHelp);
    return 0;
  }
  auto unknown = args.unknown(
      {"help", "volume", "out", "camera", "size", "light", "no-skip", "stats", "config", "style"});
  if (!unknown.empty()) return fail("unknown option " + unknown[0] + " (see --help)");
  if (args.positional().size() > 1)
    return fail("unexpected argument '" + args.positional()[1] + "'");
  auto volume_path = args.get("volume");
  auto out_path = args.get("out");
  if (!volume_path || volume_path->empty()) return fail("--volume FILE is required (see --help)");
  if (!out_path || out_path->empty()) return fail("--out FILE.png|FILE.exr is required");
  const std::string& out = *out_path;
  const bool exr = out.size() > 4 &&
                   (out.substr(out.size() - 4) == ".exr" || out.substr(out.size() - 4) == ".EXR");
  const bool png = out.size() > 4 &&
                   (out.substr(out.size() - 4) == ".png" || out.substr(out.size() - 4) == ".PNG");
  if (!exr && !png) return fail("--out '" + out + "': the file must end in .png or .exr");

  int width = 1280, height = 720;
  if (auto size = args.get("size")) {
    char x = 0;
    char extra = 0;
    if (std::sscanf(size->c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' ||
        width < 1 || height < 1 || width > 16384 || height > 16384)
      return fail("--size '" + *size + "': expected WxH with 1 <= W,H <= 16384, e.g. 1280x720");
  }
  Camera camera = Camera::reference();
  if (auto text = args.get("camera")) {
    std::vector<float> v;
    if (!parseNumbers(*text, 3, 7, &v) || v.size() == 4 || v.size() == 5)
      return fail("--camera '" + *text + "': expected EX,EY,EZ[,TX,TY,TZ[,FOV]]");
    camera.eye = {v[0], v[1], v[2]};
    if (v.size() >= 6) camera.target = {v[3], v[4], v[5]};
    if (v.size() == 7) {
      if (v[6] <= 0.0f || v[6] >= 180.0f) return fail("--camera: field of view must be in (0,180)");
      camera.fov_y_deg = v[6];
    }
    if (glm::length(camera.target - camera.eye) < 1e-6f)
      return fail("--camera: eye and target coincide");
  }
  RenderConfig config;
  {
    const std::string config_path = args.get("config", configFile("render.toml"));
    if (args.has("config") || std::filesystem::exists(config_path)) {
      try {
        config = loadRenderConfig(config_path);
      } catch (const std::exception& e) {
        return fail(e.what());
      }
    }
  }
  Light light = config.light;
  if (auto text = args.get("light")) {
    std::vector<float> v;
    if (!parseNumbers(*text, 3, 3, &v)) return fail("--light '" + *text + "': expected X,Y,Z");
    if (glm::length(glm::vec3(v[0], v[1], v[2])) == 0.0f)
      return fail("--light '" + *text + "': the direction must not be 0,0,0");
    light.direction = Light::directionTowards({v[0], v[1], v[2]});
  }

  if (auto text = args.get("style")) {
    auto style = parseRenderStyle(*text);
    if (!style) return fail("--style '" + *text + "': expected one of " + renderStyleNameList());
    config.options.style = *style;
  }

  Volume volume(glm::ivec3(1));
  try {
    volume = loadVolume(*volume_path);
  } catch (const VolumeFileError& e) {
    return fail(e.what());
  }

  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) return fail(error);
  int status = 0;
  {
    VolumeRenderer renderer;
    if (!renderer.init(&error)) return fail(error);
    renderer.sync(volume, light);
    RenderTarget target;
    if (!target.create(width, height,
                       exr ? RenderTarget::Format::kRgba32F : RenderTarget::Format::kRgba8, &error))
      return fail(error);
    RenderOptions options = config.options;
    if (args.has("no-skip")) options.skip_empty_space = false;
    options.collect_stats = args.has("stats");
    options.finish = true;
    renderer.render(camera, width, height, target.fbo(), options);
    try {
      if (exr)
        writeExr(out, target.readRgbaF());
      else
        writePng(out, target.readRgba8());
    } catch (const ImageIoError& e) {
      status = fail(e.what());
    }
    if (status == 0) {
      if (args.has("stats")) std::printf("%s", renderer.lastStats().summary().c_str());
      std::printf("%s\n", out.c_str());
    }
  }
  destroyGlContext(&ctx);
  return status;
}

}  // namespace cb
