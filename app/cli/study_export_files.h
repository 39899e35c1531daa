// What the study exports share: the error line and exit status, the atomic stream every export
// file is written through, and a volume with its render.
#pragma once

#include <fstream>
#include <string>

#include "app/core/atomic_file.h"

namespace cb {

struct Camera;
struct Light;
class Volume;
struct SessionTrace;

// Prints "cloudbrush study: MESSAGE" on stderr; returns `code` (the exit status).
int studyFail(const std::string& message, int code = 1);

// "WxH" with 1..16384 each.
bool parseStudySize(const std::string& text, int* width, int* height);

// An export file written through a stream: at a temporary beside `path`, renamed over it once
// whole and on the disk (app/core/atomic_file.h).
struct AtomicStream {
  explicit AtomicStream(const std::string& path)
      : file(path), out(file.tempPath(), std::ios::binary) {}
  // Closes, checks and commits; false with *error naming the file. Prints the path when
  // `announce`.
  bool commit(std::string* error, bool announce = true);
  AtomicFileReplacement file;
  std::ofstream out;
};

// Writes `path` with `write(stream)` atomically; false with a message naming the file.
template <typename Write>
bool writeStudyFile(const std::string& path, Write write, std::string* error) {
  AtomicStream file(path);
  if (!file.out) return *error = path + ": cannot create", false;
  write(file.out);
  return file.commit(error);
}

// VOLUME_DIR/STEM.{vdb,cbvol} and, when `render`, RENDER_DIR/STEM.{exr,png} of `volume` seen
// from `camera` at width x height. 0, or the exit status (the error printed).
int exportVolumeAndRender(const Volume& volume, const Camera& camera, const Light* light,
                          const std::string& volume_dir, const std::string& render_dir,
                          const std::string& stem, bool render, int width, int height);

// The protocol file a study session's study.info names (when it is still there), else "".
std::string protocolFileOf(const SessionTrace& trace);

// codebook.csv of `protocol_path` (empty: the bundled protocol) at `path`. 0, or the exit status.
int writeCodebook(const std::string& protocol_path, const std::string& path);

}  // namespace cb
