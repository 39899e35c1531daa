// cloudbrush bench strokes: the stroke gallery (app/brush/stroke_gallery.h) painted at the
// product's defaults — the painter's screen and starting paint view, the default canvas and
// 256-grid sky, config/brush.toml (its brush at its size), config/mapping.toml and
// config/render.toml — each stroke alone on an empty sky. Figures: each stroke's mapping time
// and cloud voxels, against the same stroke painted as journals before the brush size replay it
// (size 1, no billows: the baseline). With --sheet FILE.png, a contact sheet: one row per stroke
// (gallery order), one column per render style (render_style.h order), each cell the middle of
// the screen (--crop) of a full-size render, box-filtered down to --cell. Never fails on a
// figure.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/bench/benches.h"
#include "app/brush/brush_config.h"
#include "app/brush/stroke_gallery.h"
#include "app/cli/args.h"
#include "app/core/config_paths.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/render/render_style.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/gallery_painting.h"

namespace cb {
namespace {

const char kHelp[] =
    "usage: cloudbrush bench strokes [--size WxH] [--sheet FILE.png] [--cell WxH] [--crop F]\n"
    "                                [--frames DIR] [--only NAME]\n"
    "  --size WxH      the painter's screen (default 1920x1080)\n"
    "  --sheet FILE    write the contact sheet (strokes x styles) as a PNG\n"
    "  --cell WxH      one cell of the sheet (default 160x90)\n"
    "  --crop F        each cell shows the middle F of the screen's width and height (default "
    "0.6)\n"
    "  --frames DIR    also write every full-size render as DIR/STROKE-STYLE.png\n"
    "  --only NAME     only the gallery stroke NAME (its row of the sheet; the others stay "
    "blank)\n";

long long cloudVoxels(const GalleryCloud& cloud) {
  long long n = 0;
  const VoxelBox& b = cloud.report.dirty;
  for (int z = b.lo.z; z < b.hi.z; ++z)
    for (int y = b.lo.y; y < b.hi.y; ++y)
      for (int x = b.lo.x; x < b.hi.x; ++x) n += cloud.volume.at(x, y, z) > 0.05f;
  return n;
}

// The middle `crop` of `image`, box-filtered into the cell at (cx, cy) of `sheet`.
void blitCell(const ImageRgba8& image, float crop, int cx, int cy, int cw, int ch,
              ImageRgba8* sheet) {
  const float x0 = 0.5f * (1.0f - crop) * float(image.width);
  const float y0 = 0.5f * (1.0f - crop) * float(image.height);
  const float sx = crop * float(image.width) / float(cw),
              sy = crop * float(image.height) / float(ch);
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x) {
      const int ax = int(x0 + float(x) * sx), bx = std::max(ax + 1, int(x0 + float(x + 1) * sx));
      const int ay = int(y0 + float(y) * sy), by = std::max(ay + 1, int(y0 + float(y + 1) * sy));
      unsigned sum[4] = {0, 0, 0, 0}, n = 0;
      for (int v = ay; v < by && v < image.height; ++v)
        for (int u = ax; u < bx && u < image.width; ++u, ++n)
          for (int c = 0; c < 4; ++c) sum[c] += image.pixels[(size_t(v) * image.width + u) * 4 + c];
      uint8_t* out = &sheet->pixels[(size_t(cy * ch + y) * sheet->width + cx * cw + x) * 4];
      for (int c = 0; c < 4; ++c) out[c] = uint8_t(n ? sum[c] / n : 0);
    }
}

// One stroke's cloud in every style at full size, each into its cell of row `row` of `sheet`
// and, with `frames_dir`, as frames_dir/STROKE-STYLE.png.
void renderRow(const GalleryCloud& cloud, const std::string& name, const RenderConfig& render,
               int w, int h, float crop, int row, int cw, int ch, const std::string& frames_dir,
               VolumeRenderer* renderer, RenderTarget* target, ImageRgba8* sheet) {
  renderer->sync(cloud.volume, render.light);
  for (size_t s = 0; s < kAllRenderStyles.size(); ++s) {
    RenderOptions o = render.options;
    o.style = kAllRenderStyles[s];
    o.finish = true;
    renderer->render(cloud.camera, w, h, target->fbo(), o);
    const ImageRgba8 frame = target->readRgba8();
    if (!frames_dir.empty())
      writePng(frames_dir + "/" + name + "-" + renderStyleName(o.style) + ".png", frame);
    blitCell(frame, crop, int(s), row, cw, ch, sheet);
  }
}

bool parseSize(const Args& args, const char* key, int* w, int* h) {
  const auto s = args.get(key);
  return !s || (std::sscanf(s->c_str(), "%dx%d", w, h) == 2 && *w > 0 && *h > 0);
}

}  // namespace

int benchStrokes(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) return std::printf("%s", kHelp), 0;
  int w = 1920, h = 1080, cw = 160, ch = 90;
  const float crop = float(args.getDouble("crop", 0.6));
  const std::string sheet_path = args.get("sheet", "");
  const std::string frames_dir = args.get("frames", "");
  const std::string only = args.get("only", "");
  if (!parseSize(args, "size", &w, &h) || !parseSize(args, "cell", &cw, &ch) ||
      !(crop > 0.05f && crop <= 1.0f) || !args.error().empty()) {
    std::fprintf(stderr, "cloudbrush bench strokes: bad arguments %s\n%s", args.error().c_str(),
                 kHelp);
    return 2;
  }
  const BrushConfig brush = loadDefaultBrushConfig();
  const MappingConfig mapping = loadMappingConfig(configFile("mapping.toml"));
  BrushConfig old_brush = brush;  // as journals before the brush size and billows replay
  old_brush.stroke.size = 1.0f;
  old_brush.stroke.billow = 0.0f;
  MappingConfig old_mapping = mapping;
  old_mapping.spheres.billow_amplitude = 0.0f;
  StrokeMapper mapper(mapping), old_mapper(old_mapping);
  mapper.setQuiet(true);
  old_mapper.setQuiet(true);
  const std::vector<GalleryStroke> gallery = strokeGallery(w, h);
  std::printf("bench strokes: %zu strokes at %dx%d, brush %s at size %.2f\n", gallery.size(), w, h,
              brushKindName(brush.default_brush), double(brush.stroke.size));
  BenchReport report("strokes");
  const RenderConfig render = loadRenderConfig(configFile("render.toml"));
  EglContext ctx;
  std::string error;
  const bool sheet = !sheet_path.empty() || !frames_dir.empty();
  if (sheet && !createSurfacelessContext(&ctx, &error)) {
    std::fprintf(stderr, "cloudbrush bench strokes: %s\n", error.c_str());
    return 1;
  }
  ImageRgba8 contact;
  contact.width = cw * int(kAllRenderStyles.size());
  contact.height = ch * int(gallery.size());
  contact.pixels.assign(size_t(contact.width) * contact.height * 4, 255);
  VolumeRenderer renderer;
  RenderTarget target;
  if (sheet &&
      (!renderer.init(&error) || !target.create(w, h, RenderTarget::Format::kRgba8, &error))) {
    std::fprintf(stderr, "cloudbrush bench strokes: %s\n", error.c_str());
    return 1;
  }
  for (size_t i = 0; i < gallery.size(); ++i) {
    const GalleryStroke& g = gallery[i];
    if (!only.empty() && g.name != only) continue;
    const uint32_t index = 100 + uint32_t(i);
    const GalleryCloud now = paintGalleryStroke(g, brush.default_brush, brush, mapper, w, h, index);
    const GalleryCloud before =
        paintGalleryStroke(g, brush.default_brush, old_brush, old_mapper, w, h, index);
    const long long voxels = cloudVoxels(now), old_voxels = cloudVoxels(before);
    std::printf("%-12s mapping %6.1f ms (size 1: %6.1f) | cloud voxels %8lld (size 1: %8lld)\n",
                g.name.c_str(), now.mapping_ms, before.mapping_ms, voxels, old_voxels);
    report.figure(g.name + "_mapping_ms", now.mapping_ms);
    report.figure(g.name + "_voxels", double(voxels));
    report.baseline(g.name + "_mapping_ms", before.mapping_ms);
    report.baseline(g.name + "_voxels", double(old_voxels));
    if (!sheet) continue;
    renderRow(now, g.name, render, w, h, crop, int(i), cw, ch, frames_dir, &renderer, &target,
              &contact);
  }
  if (!sheet_path.empty()) {
    // A palette PNG (at most 256 colours, app/render/image_io.h), small enough for docs/images.
    try {
      writePngPalette(sheet_path, contact);
    } catch (const ImageIoError& e) {
      std::fprintf(stderr, "cloudbrush bench strokes: %s\n", e.what());
      return 1;
    }
    std::printf("wrote %s (%dx%d: rows %zu strokes, columns %zu styles)\n", sheet_path.c_str(),
                contact.width, contact.height, gallery.size(), kAllRenderStyles.size());
  }
  report.print();
  return 0;
}

}  // namespace cb
