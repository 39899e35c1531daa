#include "app/cli/replay_frames.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/core/config_paths.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"

namespace cb {

struct ReplayFrameWriter::Gl {
  EglContext ctx;
  std::unique_ptr<VolumeRenderer> renderer;
  std::unique_ptr<RenderTarget> target;
  ~Gl() {
    target.reset();
    renderer.reset();
    destroyGlContext(&ctx);
  }
};

ReplayFrameWriter::ReplayFrameWriter(std::string dir, int width, int height, double fps)
    : dir_(std::move(dir)), width_(width), height_(height), fps_(fps) {}

ReplayFrameWriter::~ReplayFrameWriter() = default;

bool ReplayFrameWriter::open(const JournalReadResult& journal, std::string* error) {
  journal_ = &journal;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) return *error = "--frames " + dir_ + ": " + ec.message(), false;
  int64_t t_last = 0;
  bool first = true;
  // The time line is the pen's: sample times are the device's (kernel) clock, which other
  // records share when painting live but not when the pen itself was a replay.
  for (const JournalRecord& r : journal.records) {
    if (r.type != JournalRecordType::kPenSample) continue;
    if (first) t_first_ = r.t_ns, first = false;
    t_last = std::max(t_last, r.t_ns);
  }
  total_ = first ? 1 : long(std::floor(double(t_last - t_first_) * 1e-9 * fps_)) + 1;
  gl_ = std::make_unique<Gl>();
  if (!createSurfacelessContext(&gl_->ctx, error)) return false;
  gl_->renderer = std::make_unique<VolumeRenderer>();
  gl_->target = std::make_unique<RenderTarget>();
  if (!gl_->renderer->init(error) ||
      !gl_->target->create(width_, height_, RenderTarget::Format::kRgba8, error))
    return false;
  last_progress_ = std::chrono::steady_clock::now();
  return true;
}

void ReplayFrameWriter::beforeRecord(size_t index, const PaintSession& session) {
  if (!gl_ || !error_.empty()) return;
  if (!configured_) {
    // The render settings recorded in the journal, else the local render.toml.
    configured_ = true;
    try {
      if (!session.renderSettings().empty())
        config_ = parseRenderConfigText(session.renderSettings(), "the journal's render.toml");
      else if (const std::string path = configFile("render.toml"); std::filesystem::exists(path))
        config_ = loadRenderConfig(path);
    } catch (const std::exception& e) {
      error_ = e.what();
      return;
    }
  }
  const bool at_end = index >= journal_->records.size();
  if (!at_end && journal_->records[index].type != JournalRecordType::kPenSample) return;
  const int64_t t = at_end ? INT64_MAX : journal_->records[index].t_ns;
  while (written_ < total_ && (at_end || t_first_ + int64_t(double(written_) * 1e9 / fps_) < t)) {
    writeFrame(session);
    if (!error_.empty()) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_progress_ >= std::chrono::seconds(2) || written_ == total_) {
      last_progress_ = now;
      std::fprintf(stderr, "cloudbrush replay: frames %ld/%ld (%.0f%%), %ld rendered\n", written_,
                   total_, 100.0 * double(written_) / double(total_), rendered_);
    }
  }
}

void ReplayFrameWriter::writeFrame(const PaintSession& session) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", written_);
  const std::string path = (std::filesystem::path(dir_) / name).string();
  const Camera& camera = session.camera();
  const Light& light = session.light();
  const bool scene_changed = session.volume().generation() != shown_generation_ ||
                             std::memcmp(&camera, &shown_camera_, sizeof camera) != 0 ||
                             std::memcmp(&light, &shown_light_, sizeof light) != 0 ||
                             last_path_.empty();
  const bool ink = session.engine().inStroke();
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (!scene_changed && !ink && !last_had_ink_) {
    std::filesystem::create_hard_link(last_path_, path, ec);
    if (ec) std::filesystem::copy_file(last_path_, path, ec);
    if (ec) return void(error_ = path + ": " + ec.message());
  } else {
    if (scene_changed) {
      gl_->renderer->sync(session.volume(), light);
      RenderOptions options = config_.options;
      if (const std::optional<RenderStyle> style = parseRenderStyle(session.styleName()))
        options.style = *style;
      options.finish = true;
      gl_->renderer->render(camera, width_, height_, gl_->target->fbo(), options);
      scene_ = gl_->target->readRgba8();
      ++rendered_;
      shown_generation_ = session.volume().generation();
      shown_camera_ = camera;
      shown_light_ = light;
    }
    ImageRgba8 frame = scene_;
    if (ink) {
      // The live footprint over the still scene, as the painter shows it (white ink at 85%,
      // app/render/footprint_overlay.h), scaled from footprint pixels to the frame.
      const Footprint& f = session.engine().footprint();
      for (int y = 0; y < frame.height && f.width > 0; ++y)
        for (int x = 0; x < frame.width; ++x) {
          const float a =
              0.85f *
              std::clamp(f.at(x * f.width / frame.width, y * f.height / frame.height), 0.0f, 1.0f);
          uint8_t* p = frame.at(x, y);
          for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::lround(p[c] + a * (255.0f - p[c])));
        }
    }
    try {
      writePng(path, frame);
    } catch (const ImageIoError& e) {
      return void(error_ = e.what());
    }
  }
  last_had_ink_ = ink;
  last_path_ = path;
  ++written_;
}

}  // namespace cb
