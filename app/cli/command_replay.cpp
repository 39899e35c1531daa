// `cloudbrush replay SESSION.cbj`: re-runs a recorded painting session headlessly through the
// PaintSession (app/session/session_replay.h) and reports the resulting volume's checksum; optionally
// writes the volume and a lit render of it from the session's last paint view.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/session_replay.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

constexpr const char* kReplayHelp =
    "usage: cloudbrush replay SESSION.cbj [OPTIONS]\n"
    "\n"
    "Re-runs a recorded session journal without a display: raw pen samples go through the\n"
    "calibration recorded in the journal, the brush (config/brush.toml) and the mapping\n"
    "(config/mapping.toml) exactly as while painting. Prints the volume checksum; the same\n"
    "journal gives the same checksum on any thread count. A damaged journal replays its intact\n"
    "part, says where it broke and exits with status 3.\n"
    "\n"
    "options:\n"
    "  --out-volume FILE   write the resulting volume (.cbvol, see `cloudbrush render`)\n"
    "  --render FILE.png   write a lit render from the session's last paint view\n"
    "  --size WxH          render size (default 1280x720)\n"
    "  --threads N         worker threads (default: CLOUDBRUSH_THREADS or all cores)\n"
    "  --help              this text\n";

int fail(const std::string& message, int code = 1) {
  std::fprintf(stderr, "cloudbrush replay: %s\n", message.c_str());
  return code;
}

int renderPng(const PaintSession& session, const std::string& path, int width, int height) {
  RenderConfig config;
  const std::string config_path = configFile("render.toml");
  if (std::filesystem::exists(config_path)) {
    try {
      config = loadRenderConfig(config_path);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
  }
  EglContext ctx;
  std::string error;
  if (!createSurfacelessContext(&ctx, &error)) return fail(error);
  int status = 0;
  {
    VolumeRenderer renderer;
    RenderTarget target;
    if (!renderer.init(&error) ||
        !target.create(width, height, RenderTarget::Format::kRgba8, &error)) {
      status = fail(error);
    } else {
      renderer.sync(session.volume(), config.light);
      RenderOptions options = config.options;
      options.finish = true;
      renderer.render(session.camera(), width, height, target.fbo(), options);
      try {
        writePng(path, target.readRgba8());
        std::printf("render: %s\n", path.c_str());
      } catch (const ImageIoError& e) {
        status = fail(e.what());
      }
    }
  }
  destroyGlContext(&ctx);
  return status;
}

}  // namespace

int commandReplay(int argc, char** argv) {
  Args args(argc, argv, {"help"});
  if (args.has("help")) {
    std::fputs(kReplayHelp, stdout);
    return 0;
  }
  const auto unknown = args.unknown({"help", "out-volume", "render", "size", "threads"});
  if (!unknown.empty()) return fail("unknown option " + unknown.front() + " (see --help)", 2);
  if (args.positional().size() != 2)
    return fail("expected one journal file: cloudbrush replay SESSION.cbj (see --help)", 2);
  const std::string journal_path = args.positional()[1];
  const long threads = args.getInt("threads", 0);
  int width = 1280, height = 720;
  const std::string size = args.get("size", "1280x720");
  {
    int consumed = 0;
    if (std::sscanf(size.c_str(), "%dx%d%n", &width, &height, &consumed) != 2 ||
        consumed != int(size.size()) || width < 1 || height < 1 || width > 16384 || height > 16384)
      return fail("--size: expected WxH (1..16384 each), got '" + size + "'", 2);
  }
  if (!args.error().empty()) return fail(args.error(), 2);
  if (threads < 0 || threads > 256) return fail("--threads: expected 1..256", 2);
  if (threads > 0) setWorkerThreads(int(threads));
  const std::string render_path = args.get("render", "");
  if (!render_path.empty() &&
      (render_path.size() < 5 || render_path.substr(render_path.size() - 4) != ".png"))
    return fail("--render '" + render_path + "': the file must end in .png", 2);

  if (!std::filesystem::exists(journal_path))
    return fail("journal '" + journal_path + "' does not exist");
  const JournalReadResult journal = readJournal(journal_path);
  if (journal.records.empty() && !journal.error.empty()) return fail(journal.error);

  MappingConfig mapping;
  const std::string mapping_path = configFile("mapping.toml");
  if (std::filesystem::exists(mapping_path)) {
    try {
      mapping = loadMappingConfig(mapping_path);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const SessionReplay replay = replaySession(journal, loadDefaultBrushConfig(), mapping);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const std::string& problem : replay.problems)
    std::fprintf(stderr, "cloudbrush replay: %s: %s\n", journal_path.c_str(), problem.c_str());
  if (!journal.error.empty())
    std::fprintf(stderr,
                 "cloudbrush replay: %s\ncloudbrush replay: replayed the %zu intact records "
                 "before that point\n",
                 journal.error.c_str(), journal.records.size());
  const PaintSession& session = *replay.session;
  const glm::ivec3 dims = session.volume().dims();
  std::printf(
      "replay: %zu records, %zu pen samples, %u strokes mapped into %dx%dx%d in %.0f ms "
      "on %d threads\n",
      replay.records_applied, replay.pen_samples, replay.strokes_mapped, dims.x, dims.y, dims.z, ms,
      workerThreads());
  std::printf("volume checksum: %016" PRIx64 "\n", volumeChecksum(session.volume()));

  if (const std::string out = args.get("out-volume", ""); !out.empty()) {
    try {
      saveVolume(session.volume(), out);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
    std::printf("volume: %s\n", out.c_str());
  }
  if (!render_path.empty())
    if (int status = renderPng(session, render_path, width, height); status != 0) return status;
  return replay.complete() ? 0 : 3;
}

}  // namespace cb
