// A study task's own files (`tasks/ID.vdb` and `.cbvol`: volume_export.h; `tasks/ID.exr` and
// `.png`: render_export.h) that could not be written when the task ended (a full disk, an I/O
// error): the task's volume and its rendered end frame are kept in memory and written again on
// each retry (the runner retries every second, as it does its answer files and session.json)
// until it works. The journal holds the strokes either way; these are the files an analyst
// opens without replaying, and `cloudbrush replay` checks the .cbvol against the journal.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/render/image_io.h"
#include "app/volume/volume.h"

namespace cb {

class TaskFileRetry {
 public:
  // `folder`: the session folder; the files go to its tasks/.
  explicit TaskFileRetry(std::string folder) : folder_(std::move(folder)) {}

  // Writes the task's volume files. Appends each file written to *written (relative to the
  // folder: "tasks/ID.cbvol"); a build without OpenVDB sets *note. On failure the volume is
  // kept for retry(), *error says why and false is returned.
  bool writeVolume(const std::string& task, const Volume& volume, std::vector<std::string>* written,
                   std::string* note, std::string* error);
  // The task's volume files as the task goes (so a runner killed mid-task leaves them as of
  // its last write): written as writeVolume does, but nothing is kept when it fails (the task's
  // end writes them again).
  bool writeVolumeSoFar(const std::string& task, const Volume& volume,
                        std::vector<std::string>* written, std::string* note,
                        std::string* error) const {
    return tryVolume(task, volume, written, note, error);
  }
  // Likewise the task's end frame (display-encoded RGBA float) as EXR and PNG.
  bool writeFrame(const std::string& task, const ImageRgbaF& frame,
                  std::vector<std::string>* written, std::string* error);

  // Writes again everything kept; the files written now (relative paths). What still fails
  // stays kept and the first error is in *error ("" when nothing failed).
  std::vector<std::string> retry(std::string* error);

  bool pending() const { return !kept_.empty(); }
  // What is kept, for the operator: "tasks/first.{vdb,cbvol}, tasks/first.{exr,png}".
  std::string pendingText() const;
  // The files kept, relative to the folder, in the order they will be written.
  std::vector<std::string> pendingFiles() const;
  // Memory the kept volumes and frames hold.
  size_t heldBytes() const;

 private:
  struct Kept {
    std::string task;
    std::optional<Volume> volume;
    std::optional<ImageRgbaF> frame;
  };
  Kept& keptFor(const std::string& task);
  bool tryVolume(const std::string& task, const Volume& volume, std::vector<std::string>* written,
                 std::string* note, std::string* error) const;
  bool tryFrame(const std::string& task, const ImageRgbaF& frame, std::vector<std::string>* written,
                std::string* error) const;

  std::string folder_;
  std::vector<Kept> kept_;
};

}  // namespace cb
