// `cloudbrush replay SESSION.cbj`: re-runs a recorded painting session headlessly through the
// PaintSession (app/session/session_replay.h) and reports the resulting volume's checksum;
// optionally writes the volume and a lit render of it from the session's last paint view.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/replay_frames.h"
#include "app/core/config_paths.h"
#include "app/core/parallel_for.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/egl_context.h"
#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/session_replay.h"
#include "app/study/frame_timing_stats.h"
#include "app/study/study_marker_text.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

constexpr const char* kReplayHelp =
    "usage: cloudbrush replay SESSION.cbj [OPTIONS]\n"
    "\n"
    "Re-runs a recorded session journal without a display: raw pen samples go through the\n"
    "calibration, brush, mapping and render settings recorded in the journal, exactly as\n"
    "while painting, whatever the local config (journals from before recorded settings use\n"
    "config/brush.toml and config/mapping.toml). Prints the volume checksum; the same journal\n"
    "gives the same checksum on any thread count. A damaged journal replays its intact part,\n"
    "says where it broke and exits with status 3. For a study session each task's volume at its\n"
    "end is compared with tasks/ID.cbvol beside the journal; a difference exits with status 4.\n"
    "\n"
    "options:\n"
    "  --out-volume FILE   write the resulting volume (.cbvol, see `cloudbrush render`)\n"
    "  --render FILE.png   write a lit render from the session's last paint view\n"
    "  --frames DIR        write one PNG per frame of the session's time line (frame_000000.png,\n"
    "                      ...), drawn by the screens the person saw (the painter's; a study\n"
    "                      session's consent, forms, tutorial, tasks and questionnaire), as\n"
    "                      fast as possible, headless; progress on stderr. A video:\n"
    "                      ffmpeg -framerate 30 -i DIR/frame_%06d.png -c:v libx264 \\\n"
    "                        -pix_fmt yuv420p session.mp4\n"
    "  --fps N             frames per second of journal time for --frames (default 30)\n"
    "  --size WxH          render and frame size (default: --frames the session's screen as\n"
    "                      recorded, --render 1280x720)\n"
    "  --threads N         worker threads (default: CLOUDBRUSH_THREADS or all cores)\n"
    "  --stats             also print the session's frame timing from its Frame records: pen\n"
    "                      sample -> present latency (p50/p95/p99, histogram), frame intervals,\n"
    "                      missed refreshes, by quarter of the session\n"
    "  --help              this text\n";

int fail(const std::string& message, int code = 1) {
  std::fprintf(stderr, "cloudbrush replay: %s\n", message.c_str());
  return code;
}

// The render settings recorded in the journal (any local render.toml is ignored then), else
// the local ones, as before Settings records.
bool renderConfigFor(const PaintSession& session, RenderConfig* config, std::string* error) {
  try {
    if (!session.renderSettings().empty())
      *config = parseRenderConfigText(session.renderSettings(), "the journal's render.toml");
    else if (const std::string path = configFile("render.toml"); std::filesystem::exists(path))
      *config = loadRenderConfig(path);
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  return true;
}

int renderPng(const PaintSession& session, const std::string& path, int width, int height) {
  RenderConfig config;
  std::string config_error;
  if (!renderConfigFor(session, &config, &config_error)) return fail(config_error);
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

// A study session's task end (`study.saved`): the replayed volume there against the one the
// runner saved in the session folder (tasks/ID.cbvol beside the journal), when it is there; one
// line into *task_lines, *task_differs when they differ.
void checkTaskVolume(const JournalRecord& record, const PaintSession& s,
                     const std::filesystem::path& folder, std::vector<std::string>* task_lines,
                     bool* task_differs) {
  if (record.type != JournalRecordType::kMarker || record.text().rfind("study.saved ", 0) != 0)
    return;
  const std::string task = parseStudyMarker(std::string(record.text())).get("task");
  const uint64_t sum = volumeChecksum(s.volume());
  char line[320];
  const std::filesystem::path saved = folder / "tasks" / (task + ".cbvol");
  std::error_code ec;
  if (task.empty() || !std::filesystem::exists(saved, ec)) {
    std::snprintf(line, sizeof line, "task %s: volume checksum %016" PRIx64 " (no %s to compare)",
                  task.c_str(), sum, saved.string().c_str());
  } else {
    uint64_t saved_sum = 0;
    try {
      saved_sum = volumeChecksum(loadVolume(saved.string()));
    } catch (const std::exception& e) {
      task_lines->push_back("task " + task + ": " + e.what());
      *task_differs = true;
      return;
    }
    *task_differs = *task_differs || saved_sum != sum;
    std::snprintf(line, sizeof line, "task %s: volume checksum %016" PRIx64 ", %s %s", task.c_str(),
                  sum, saved_sum == sum ? "identical to" : "DIFFERENT from",
                  saved.string().c_str());
  }
  task_lines->push_back(line);
}

// --frames DIR: the replay's frames as PNGs, width x height at fps, hooked after each record.
// 0, or the exit status after the error was printed.
int openReplayFrames(const std::string& frames_dir, int width, int height, double fps,
                     const JournalReadResult& journal, std::unique_ptr<ReplayFrameWriter>* frames,
                     ReplayHooks* hooks) {
  *frames = std::make_unique<ReplayFrameWriter>(frames_dir, width, height, fps);
  std::string error;
  if (!(*frames)->open(journal, &error)) return fail("--frames: " + error);
  if (!(*frames)->note().empty())
    std::fprintf(stderr, "cloudbrush replay: --frames: %s\n", (*frames)->note().c_str());
  hooks->after_record = [frames](size_t index, const SampleOutcome* sample) {
    (*frames)->afterRecord(index, sample);
  };
  return 0;
}

// --stats: the frame timings the journal recorded.
void printRecordedFrameStats(const JournalReadResult& journal) {
  std::vector<FrameRecord> frames;
  for (const JournalRecord& record : journal.records)
    if (record.type == JournalRecordType::kFrame)
      if (std::optional<FrameRecord> f = decodeFrameRecord(record.t_ns, record.payload))
        frames.push_back(*f);
  std::fputs(formatFrameTimingStats(frameTimingStats(frames), "").c_str(), stdout);
}

}  // namespace

int commandReplay(int argc, char** argv) {
  Args args(argc, argv, {"help", "stats"});
  if (args.has("help")) {
    std::fputs(kReplayHelp, stdout);
    return 0;
  }
  const auto unknown =
      args.unknown({"help", "out-volume", "render", "size", "threads", "frames", "fps", "stats"});
  if (!unknown.empty()) return fail("unknown option " + unknown.front() + " (see --help)", 2);
  if (args.positional().size() != 2)
    return fail("expected one journal file: cloudbrush replay SESSION.cbj (see --help)", 2);
  const std::string journal_path = args.positional()[1];
  const long threads = args.getInt("threads", 0);
  int width = 1280, height = 720;
  const std::string size = args.get("size", "1280x720");
  const bool size_given = args.has("size");
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
  const std::string frames_dir = args.get("frames", "");
  const double fps = args.getDouble("fps", 30.0);
  if (!args.error().empty()) return fail(args.error(), 2);
  if (!(fps > 0.0 && fps <= 240.0)) return fail("--fps: expected a number in (0, 240]", 2);
  std::unique_ptr<ReplayFrameWriter> frames;
  ReplayHooks hooks;
  if (!frames_dir.empty()) {
    int frame_width = width, frame_height = height;
    if (!size_given) {  // the screen the session was painted on
      const PaintSessionSettings recorded =
          recordedSettings(journal.records, BrushConfig{}, mapping).settings;
      frame_width = recorded.screen_width;
      frame_height = recorded.screen_height;
    }
    if (const int status =
            openReplayFrames(frames_dir, frame_width, frame_height, fps, journal, &frames, &hooks))
      return status;
  }
  // A study session's task ends (`study.saved`): the replayed volume there against the one the
  // runner saved in the session folder (tasks/ID.cbvol beside the journal), when it is there.
  std::vector<std::string> task_lines;
  bool task_differs = false;
  const std::filesystem::path folder = std::filesystem::path(journal_path).parent_path();
  hooks.before_record = [&](size_t index, PaintSession& s) {
    if (frames) frames->beforeRecord(index, s);
    if (index >= journal.records.size()) return;
    checkTaskVolume(journal.records[index], s, folder, &task_lines, &task_differs);
  };
  const auto start = std::chrono::steady_clock::now();
  const SessionReplay replay = replaySession(journal, loadDefaultBrushConfig(), mapping, {}, hooks);
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
  if (frames) {
    if (!frames->error().empty()) return fail("--frames: " + frames->error());
    std::printf(
        "frames: %ld PNGs in %s (%ld encoded, the rest links to an equal frame) at %.0f fps\n",
        frames->framesWritten(), frames_dir.c_str(), frames->framesEncoded(), fps);
    frames.reset();  // its GL context goes before the --render one is made
  }
  std::printf("settings: %s\n", replay.recorded_settings
                                    ? "brush and mapping as recorded in the journal"
                                    : "brush and mapping from the local config (none recorded)");
  for (const std::string& line : task_lines) std::printf("%s\n", line.c_str());
  std::printf("volume checksum: %016" PRIx64 "\n", volumeChecksum(session.volume()));
  if (args.has("stats")) printRecordedFrameStats(journal);
  if (task_differs)
    return fail("a task's replayed volume differs from the one saved in " + folder.string(), 4);

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
