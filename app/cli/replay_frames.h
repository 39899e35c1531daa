// `cloudbrush replay SESSION --frames DIR`: one PNG per frame of the session's own time line,
// drawn by the same screens the person saw — the painter's screen (scene, live footprint,
// cursor, HUD, status line, pen menu) and, for a study session, the study runner's screens
// (consent, forms, tutorial panel, task picture and countdown, questionnaire) — headless on EGL
// surfaceless, as fast as the machine draws, for turning a session into a video (README: the
// ffmpeg line).
//
// The replay (app/session/session_replay.h) applies the journal's records to the session as
// `cloudbrush replay` always does, so the volumes are the ones without --frames; the screens are
// only shown it (PaintScreen::showReplay, StudyRunOptions::replay_view): their update step
// changes nothing, and the study runner's state follows the journal's `study.*` markers as their
// time comes. Frames run from the first to the last pen sample (in a study session, also study
// marker); frame k at time t_first + k / fps shows every record before the first such record at
// or after that time. A frame equal to the one before is a hard link to its PNG. Progress goes to
// stderr every two seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/study/protocol.h"
#include "app/study/study_session_record.h"
#include "drivers/core/journal.h"

namespace cb {

class Display;
class PaintScreen;
class Screen;
class StudyRunScreen;
class StudyRunState;
class VolumeRenderer;

class ReplayFrameWriter {
 public:
  ReplayFrameWriter(std::string dir, int width, int height, double fps);
  ~ReplayFrameWriter();
  // Frames span the journal's time line (above). A study session's protocol is read from its
  // `study.info` marker's file; when that file is not here the frames show the painter's screen
  // only, and note() says so. False with *error (EGL, the folder).
  bool open(const JournalReadResult& journal, std::string* error);
  // Before record `index` is applied (index == records.size() at the end): writes every frame
  // whose time has come.
  void beforeRecord(size_t index, PaintSession& session);
  // After record `index` was applied (a pen sample's outcome, else null).
  void afterRecord(size_t index, const SampleOutcome* sample);
  const std::string& error() const { return error_; }
  const std::string& note() const { return note_; }
  long framesWritten() const { return written_; }
  long framesEncoded() const { return encoded_; }  // the rest are hard links
  long framesTotal() const { return total_; }

 private:
  bool timeLineRecord(const JournalRecord& record) const;
  bool makeScreens(PaintSession& session);
  void writeFrame();

  std::string dir_;
  int width_, height_;
  double fps_;
  const JournalReadResult* journal_ = nullptr;
  std::unique_ptr<Display> display_;
  std::unique_ptr<VolumeRenderer> renderer_;
  std::unique_ptr<PaintScreen> paint_;
  std::unique_ptr<StudyRunScreen> study_;
  Screen* screen_ = nullptr;
  // A study session: its facts, protocol and the runner's state as the markers so far make it.
  std::optional<StudySessionInfo> info_;
  std::optional<StudyProtocol> protocol_;
  std::unique_ptr<StudyRunState> state_;
  int64_t state_start_ns_ = 0;  // the first study marker's time (the state machine's start)
  int64_t t_first_ = 0;
  long total_ = 0, written_ = 0, encoded_ = 0;
  ImageRgba8 last_frame_;
  std::string last_path_, error_, note_;
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace cb
