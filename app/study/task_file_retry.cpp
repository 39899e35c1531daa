#include "app/study/task_file_retry.h"

#include <algorithm>
#include <exception>
#include <filesystem>

#include "app/study/render_export.h"
#include "app/study/volume_export.h"

namespace cb {
namespace {

std::string relativeToFolder(const std::string& path) {
  return "tasks/" + std::filesystem::path(path).filename().string();
}

}  // namespace

TaskFileRetry::Kept& TaskFileRetry::keptFor(const std::string& task) {
  for (Kept& k : kept_)
    if (k.task == task) return k;
  kept_.push_back(Kept{task, std::nullopt, std::nullopt});
  return kept_.back();
}

bool TaskFileRetry::tryVolume(const std::string& task, const Volume& volume,
                              std::vector<std::string>* written, std::string* note,
                              std::string* error) const {
  try {
    const VolumeExport e = exportVolume(volume, folder_ + "/tasks", task);
    for (const std::string& path : e.written) written->push_back(relativeToFolder(path));
    if (note) *note = e.note;
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

bool TaskFileRetry::tryFrame(const std::string& task, const ImageRgbaF& frame,
                             std::vector<std::string>* written, std::string* error) const {
  try {
    for (const std::string& path : exportRender(frame, folder_ + "/tasks", task))
      written->push_back(relativeToFolder(path));
    return true;
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
}

bool TaskFileRetry::writeVolume(const std::string& task, const Volume& volume,
                                std::vector<std::string>* written, std::string* note,
                                std::string* error) {
  if (tryVolume(task, volume, written, note, error)) return true;
  keptFor(task).volume.emplace(volume);  // a copy: the painter goes on with the next task
  return false;
}

bool TaskFileRetry::writeFrame(const std::string& task, const ImageRgbaF& frame,
                               std::vector<std::string>* written, std::string* error) {
  if (tryFrame(task, frame, written, error)) return true;
  keptFor(task).frame = frame;
  return false;
}

std::vector<std::string> TaskFileRetry::retry(std::string* error) {
  error->clear();
  std::vector<std::string> written;
  for (Kept& k : kept_) {
    std::string failure;
    if (k.volume && tryVolume(k.task, *k.volume, &written, nullptr, &failure)) k.volume.reset();
    if (k.frame && tryFrame(k.task, *k.frame, &written, &failure)) k.frame.reset();
    if (error->empty()) *error = failure;
  }
  kept_.erase(std::remove_if(kept_.begin(), kept_.end(),
                             [](const Kept& k) { return !k.volume && !k.frame; }),
              kept_.end());
  return written;
}

std::vector<std::string> TaskFileRetry::pendingFiles() const {
  std::vector<std::string> files;
  for (const Kept& k : kept_) {
    if (k.volume) {
      if (volumeExportHasVdb()) files.push_back("tasks/" + k.task + ".vdb");
      files.push_back("tasks/" + k.task + ".cbvol");
    }
    if (k.frame) {
      files.push_back("tasks/" + k.task + ".exr");
      files.push_back("tasks/" + k.task + ".png");
    }
  }
  return files;
}

std::string TaskFileRetry::pendingText() const {
  std::string text;
  for (const Kept& k : kept_) {
    const auto add = [&](const std::string& kinds) {
      text += (text.empty() ? "" : ", ") + ("tasks/" + k.task + ".{" + kinds + "}");
    };
    if (k.volume) add(volumeExportHasVdb() ? "vdb,cbvol" : "cbvol");
    if (k.frame) add("exr,png");
  }
  return text;
}

size_t TaskFileRetry::heldBytes() const {
  size_t bytes = 0;
  for (const Kept& k : kept_) {
    if (k.volume) bytes += k.volume->memoryBytes();
    if (k.frame) bytes += k.frame->pixels.size() * sizeof(float);
  }
  return bytes;
}

}  // namespace cb
