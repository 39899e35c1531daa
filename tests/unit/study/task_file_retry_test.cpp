// A task's own files that cannot be written (here: tasks/ is a file, so creating the folder
// fails with a real error from the file system) are kept in memory, named for the operator, and
// written by a later retry once the obstacle is gone; the volume written late is the task's
// volume (checksum), the frame's EXR and PNG appear. The full-disk run of the real runner is
// study_disk_full_test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "app/render/image_io.h"
#include "app/session/session_replay.h"
#include "app/study/study_storage_watch.h"
#include "app/study/task_file_retry.h"
#include "app/study/volume_export.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

namespace fs = std::filesystem;

TEST(TaskFileRetry, KeepsWhatCannotBeWrittenAndWritesItLater) {
  const fs::path folder =
      fs::temp_directory_path() / ("cb_task_retry_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "tasks") << "not a folder";  // the obstacle

  Volume volume(glm::ivec3(16), glm::vec3(-1.0f), glm::vec3(1.0f));
  for (int i = 2; i < 9; ++i) volume.set(i, 5, 7, 0.1f * float(i));
  ImageRgbaF frame;
  frame.width = 8, frame.height = 4;
  frame.pixels.assign(size_t(8 * 4 * 4), 0.5f);

  TaskFileRetry files(folder.string());
  std::vector<std::string> written;
  std::string note, error;
  EXPECT_FALSE(files.writeVolume("first", volume, &written, &note, &error));
  EXPECT_NE(error.find((folder / "tasks").string()), std::string::npos) << error;
  EXPECT_FALSE(files.writeFrame("first", frame, &written, &error));
  EXPECT_TRUE(written.empty());
  ASSERT_TRUE(files.pending());
  const std::string vdb = volumeExportHasVdb() ? "vdb," : "";
  EXPECT_EQ(files.pendingText(), "tasks/first.{" + vdb + "cbvol}, tasks/first.{exr,png}");
  EXPECT_GE(files.heldBytes(), frame.pixels.size() * sizeof(float) + volume.memoryBytes());
  volume.set(3, 3, 3, 1.0f);  // the painter goes on: what is kept is the task's end

  // The banner names what waits.
  StudyStorageWatch watch;
  watch.observe(true, "No space left on device", 1'000'000'000);
  const std::string band =
      watch.operatorText(files.heldBytes(), 3'000'000'000, files.pendingText());
  EXPECT_NE(band.find("waiting to be written: tasks/first.{"), std::string::npos) << band;

  // Still in the way: nothing written, still kept, the error said.
  EXPECT_TRUE(files.retry(&error).empty());
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(files.pending());

  fs::remove(folder / "tasks");
  written = files.retry(&error);
  EXPECT_EQ(error, "");
  EXPECT_FALSE(files.pending());
  EXPECT_EQ(files.heldBytes(), 0u);
  EXPECT_EQ(written.size(), volumeExportHasVdb() ? 4u : 3u);
  for (const std::string& f : written) EXPECT_TRUE(fs::exists(folder / f)) << f;
  volume.set(3, 3, 3, 0.0f);
  EXPECT_EQ(volumeChecksum(loadVolume((folder / "tasks/first.cbvol").string())),
            volumeChecksum(volume));
  const ImageRgba8 png = readPng((folder / "tasks/first.png").string());
  EXPECT_EQ(png.width, 8);
  EXPECT_EQ(png.height, 4);
  EXPECT_TRUE(files.retry(&error).empty()) << "nothing left to write";
  fs::remove_all(folder);
}

}  // namespace
}  // namespace cb
