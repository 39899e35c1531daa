// `cloudbrush replay SESSION --frames DIR`: one PNG per frame of the session's own time line, as
// fast as the machine renders (EGL surfaceless, offline), for turning a study session into a
// video (README: the ffmpeg line). Frames run along the pen samples' time line (first to last
// sample); a frame at time t shows the lit cloud from the paint view as it was after every record
// before the first sample at or after t, with the stroke being painted drawn over it as the
// painter's live footprint; frames in which nothing changed are hard links to the previous PNG.
// Progress goes to stderr every two seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "app/render/image_io.h"
#include "app/render/render_config.h"
#include "app/session/paint_session.h"
#include "drivers/core/journal.h"

namespace cb {

class ReplayFrameWriter {
 public:
  ReplayFrameWriter(std::string dir, int width, int height, double fps);
  ~ReplayFrameWriter();
  // Frames span the journal's first to last pen sample. False with *error (EGL, the folder).
  bool open(const JournalReadResult& journal, std::string* error);
  // Before record `index` is applied (index == records.size() at the end): writes every frame
  // whose time has come. The first call also takes the render settings from the session.
  void beforeRecord(size_t index, const PaintSession& session);
  const std::string& error() const { return error_; }
  long framesWritten() const { return written_; }
  long framesRendered() const { return rendered_; }
  long framesTotal() const { return total_; }

 private:
  struct Gl;
  void writeFrame(const PaintSession& session);

  std::string dir_;
  int width_, height_;
  double fps_;
  const JournalReadResult* journal_ = nullptr;
  std::unique_ptr<Gl> gl_;
  RenderConfig config_;
  bool configured_ = false;
  int64_t t_first_ = 0;
  long total_ = 0, written_ = 0, rendered_ = 0;
  uint64_t shown_generation_ = UINT64_MAX;
  Camera shown_camera_;
  Light shown_light_;
  ImageRgba8 scene_;  // the last rendered scene, before the live footprint
  bool last_had_ink_ = false;
  std::string last_path_, error_;
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace cb
