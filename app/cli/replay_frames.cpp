#include "app/cli/replay_frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/core/config_paths.h"
#include "app/render/gl/display.h"
#include "app/render/render_config.h"
#include "app/render/volume_renderer.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/study/study_run_screen.h"
#include "app/study/study_run_state.h"

namespace cb {
namespace {

bool isStudyMarker(const JournalRecord& record) {
  if (record.type != JournalRecordType::kMarker) return false;
  const std::string text(record.text());
  return text.rfind("study.", 0) == 0 && text.rfind("study.info ", 0) != 0;
}

bool samePixels(const ImageRgba8& a, const ImageRgba8& b) {
  return a.width == b.width && a.height == b.height && a.pixels == b.pixels;
}

}  // namespace

ReplayFrameWriter::ReplayFrameWriter(std::string dir, int width, int height, double fps)
    : dir_(std::move(dir)), width_(width), height_(height), fps_(fps) {}

ReplayFrameWriter::~ReplayFrameWriter() {
  // The screens and the renderer hold GL objects of the display's context: they go first.
  study_.reset();
  paint_.reset();
  state_.reset();
  renderer_.reset();
  display_.reset();
}

bool ReplayFrameWriter::timeLineRecord(const JournalRecord& record) const {
  // The pen's time line (the device's clock, which the runner's clock follows in a study
  // session; other records of a plain `paint --backend replay` journal are on another clock).
  return record.type == JournalRecordType::kPenSample || (info_ && isStudyMarker(record));
}

bool ReplayFrameWriter::open(const JournalReadResult& journal, std::string* error) {
  journal_ = &journal;
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) return *error = "--frames " + dir_ + ": " + ec.message(), false;
  for (const JournalRecord& r : journal.records) {
    StudySessionInfo info;
    if (r.type == JournalRecordType::kMarker &&
        parseStudyInfoMarker(std::string(r.text()), &info)) {
      info_ = info;
      break;
    }
  }
  if (info_) {
    try {
      protocol_ = loadStudyProtocol(info_->protocol_file);
    } catch (const std::exception& e) {
      note_ = std::string("the study protocol could not be read (") + e.what() +
              "): the frames show the painter's screen only";
      info_.reset();
    }
  }
  int64_t t_last = 0;
  bool first = true;
  for (const JournalRecord& r : journal.records) {
    if (!timeLineRecord(r)) continue;
    if (first) t_first_ = r.t_ns, first = false;
    t_first_ = std::min(t_first_, r.t_ns);
    t_last = std::max(t_last, r.t_ns);
    if (info_ && isStudyMarker(r) && state_start_ns_ == 0) state_start_ns_ = r.t_ns;
  }
  total_ = first ? 1 : long(std::floor(double(t_last - t_first_) * 1e-9 * fps_)) + 1;
  DisplayOptions options;
  options.platform = DisplayPlatform::Surfaceless;
  options.width = width_;
  options.height = height_;
  display_ = openDisplay(options, error);
  if (!display_) return false;
  renderer_ = std::make_unique<VolumeRenderer>();
  if (!renderer_->init(error)) return false;
  last_progress_ = std::chrono::steady_clock::now();
  return true;
}

bool ReplayFrameWriter::makeScreens(PaintSession& session) {
  // The render settings recorded in the journal, else the local render.toml.
  RenderConfig config;
  try {
    if (!session.renderSettings().empty())
      config = parseRenderConfigText(session.renderSettings(), "the journal's render.toml");
    else if (const std::string path = configFile("render.toml"); std::filesystem::exists(path))
      config = loadRenderConfig(path);
  } catch (const std::exception& e) {
    error_ = e.what();
    return false;
  }
  PaintLoopOptions paint;
  paint.render = config.options;
  paint.moving_scale = config.moving_scale;
  paint.orbit_degrees_per_second = 0.0f;
  std::string error;
  if (info_) {
    state_ =
        std::make_unique<StudyRunState>(*protocol_, info_->participant_number, state_start_ns_);
    StudyRunOptions options;
    options.paint = paint;
    options.info = *info_;
    options.replay_view = true;
    study_ = std::make_unique<StudyRunScreen>(*display_, *renderer_, session, nullptr, nullptr,
                                              *state_, options);
    for (const std::string& problem : study_->problems()) error += problem + "; ";
    screen_ = study_.get();
  } else {
    paint_ = std::make_unique<PaintScreen>(*display_, *renderer_, session.volume(), session.light(),
                                           paint);
    paint_->showReplay(&session, &error);
    screen_ = paint_.get();
  }
  if (!error.empty()) error_ = error;
  return error_.empty();
}

void ReplayFrameWriter::beforeRecord(size_t index, PaintSession& session) {
  if (!display_ || !error_.empty()) return;
  const bool at_end = index >= journal_->records.size();
  if (!at_end && !timeLineRecord(journal_->records[index])) return;
  // The screens are made at the first time-line record, once the Settings records are applied.
  if (!screen_ && !makeScreens(session)) return;
  const int64_t t = at_end ? INT64_MAX : journal_->records[index].t_ns;
  while (written_ < total_ && (at_end || t_first_ + int64_t(double(written_) * 1e9 / fps_) < t)) {
    writeFrame();
    if (!error_.empty()) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_progress_ >= std::chrono::seconds(2) || written_ == total_) {
      last_progress_ = now;
      std::fprintf(stderr, "cloudbrush replay: frames %ld/%ld (%.0f%%), %ld encoded\n", written_,
                   total_, 100.0 * double(written_) / double(total_), encoded_);
    }
  }
}

void ReplayFrameWriter::afterRecord(size_t index, const SampleOutcome* sample) {
  if (!screen_ || !error_.empty()) return;
  if (sample) {
    PaintScreen& paint = study_ ? study_->paintScreen() : *paint_;
    paint.replayedSample(*sample);
  }
  const JournalRecord& record = journal_->records[index];
  if (state_ && isStudyMarker(record)) {
    // The runner's state as the journal has it from here on (the same inputs a resumed session
    // applies again, study_run_state.h).
    std::string error;
    if (!state_->restore({StudyRunRecord{record.t_ns, std::string(record.text())}}, &error)) {
      error_ = "the study screens cannot follow the journal at record " + std::to_string(index) +
               ": " + error;
    }
  }
}

void ReplayFrameWriter::writeFrame() {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06ld.png", written_);
  const std::string path = (std::filesystem::path(dir_) / name).string();
  const int64_t t = t_first_ + int64_t(double(written_) * 1e9 / fps_);
  FrameContext frame{*display_, width_, height_, written_, t, written_ ? 1.0 / fps_ : 0.0};
  screen_->update(frame);  // in a replay it changes nothing in the session
  std::string error;
  if (!screen_->draw(frame, &error))
    return void(error_ = "frame " + std::to_string(written_) + ": " + error);
  ImageRgba8 image = readFramebufferRgba8(display_->framebuffer(), width_, height_);
  if (!display_->present(&error)) return void(error_ = error);
  std::error_code ec;
  std::filesystem::remove(path, ec);
  bool linked = false;
  if (!last_path_.empty() && samePixels(image, last_frame_)) {
    std::filesystem::create_hard_link(last_path_, path, ec);
    if (ec) std::filesystem::copy_file(last_path_, path, ec);
    if (ec) return void(error_ = path + ": " + ec.message());
    linked = true;
  }
  if (!linked) {
    try {
      writePng(path, image);
    } catch (const ImageIoError& e) {
      return void(error_ = e.what());
    }
    ++encoded_;
    last_frame_ = std::move(image);
  }
  last_path_ = path;
  ++written_;
}

}  // namespace cb
