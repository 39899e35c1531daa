// Fuzz target: config/render.toml (outside bytes: edited by hand on kiosks), including the
// lenient [sky], [style.NAME] and [light] time_of_day readers. Any input either loads (bad values
// of the lenient settings become warnings naming FILE:LINE:COL) or throws std::runtime_error; a
// loaded config's values are in their documented ranges.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "app/render/render_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path =
      "/tmp/cb_fuzz_render_config_" + std::to_string(::getpid()) + ".toml";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const cb::RenderConfig c = cb::loadRenderConfig(path);
    const cb::StyleParams& p = c.options.style_params;
    if (p.physical.octaves < 1 || p.physical.octaves > 3) std::abort();
    if (!(p.ink.bleed_sigma >= 0.3f) ||
        cb::inkBleedRadius(p.ink.bleed_sigma) > cb::kMaxInkBleedRadius)
      std::abort();
    if (!(p.cartoon.band_thresholds.x < p.cartoon.band_thresholds.y &&
          p.cartoon.band_thresholds.y < p.cartoon.band_thresholds.z))
      std::abort();
    if (c.options.sky.lic_size < 16 || c.options.sky.lic_size > 4096) std::abort();
    if (c.options.sky.kind == cb::SkyKind::kImage && !c.options.sky.image) std::abort();
    for (const std::string& w : c.warnings)
      if (w.rfind(path + ":", 0) != 0) std::abort();  // every warning names the file
  } catch (const std::runtime_error&) {
  }
  return 0;
}
