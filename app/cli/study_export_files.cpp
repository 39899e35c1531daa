#include "app/cli/study_export_files.h"

#include <cstdio>
#include <exception>
#include <filesystem>

#include "app/cli/study_frame_render.h"
#include "app/study/codebook.h"
#include "app/study/protocol.h"
#include "app/study/render_export.h"
#include "app/study/session_trace.h"
#include "app/study/study_session_record.h"
#include "app/study/volume_export.h"

namespace cb {

int studyFail(const std::string& message, int code) {
  std::fprintf(stderr, "cloudbrush study: %s\n", message.c_str());
  return code;
}

bool parseStudySize(const std::string& text, int* width, int* height) {
  int consumed = 0;
  return std::sscanf(text.c_str(), "%dx%d%n", width, height, &consumed) == 2 &&
         consumed == int(text.size()) && *width >= 1 && *height >= 1 && *width <= 16384 &&
         *height <= 16384;
}

bool AtomicStream::commit(std::string* error, bool announce) {
  out.close();
  if (!out) return *error = file.path() + ": write failed (disk full?)", false;
  if (!file.commit(error)) return false;
  if (announce) std::printf("%s\n", file.path().c_str());
  return true;
}

int exportVolumeAndRender(const Volume& volume, const Camera& camera, const Light* light,
                          const std::string& volume_dir, const std::string& render_dir,
                          const std::string& stem, bool render, int width, int height) {
  try {
    const VolumeExport exported = exportVolume(volume, volume_dir, stem);
    for (const std::string& path : exported.written) std::printf("%s\n", path.c_str());
    if (!exported.note.empty())
      std::fprintf(stderr, "cloudbrush study: %s\n", exported.note.c_str());
    if (!render) return 0;
    ImageRgbaF frame;
    std::string error;
    if (!renderStudyFrame(volume, camera, light, width, height, &frame, &error))
      return studyFail(error);
    for (const std::string& path : exportRender(frame, render_dir, stem))
      std::printf("%s\n", path.c_str());
  } catch (const std::exception& e) {
    return studyFail(e.what());
  }
  return 0;
}

std::string protocolFileOf(const SessionTrace& trace) {
  for (const TraceEvent& e : trace.events) {
    StudySessionInfo info;
    if (e.type == JournalRecordType::kMarker && parseStudyInfoMarker(e.text, &info))
      return std::filesystem::exists(info.protocol_file) ? info.protocol_file : "";
  }
  return "";
}

int writeCodebook(const std::string& protocol_path, const std::string& path) {
  const std::string source = protocol_path.empty() ? defaultStudyProtocolPath() : protocol_path;
  StudyProtocol protocol;
  try {
    protocol = loadStudyProtocol(source);
  } catch (const StudyProtocolError& e) {
    return studyFail(std::string("export: codebook: ") + e.what());
  }
  std::fprintf(stderr, "cloudbrush study: codebook of the protocol %s\n", source.c_str());
  std::string error;
  if (!writeStudyFile(
          path, [&](std::ostream& s) { writeCodebookCsv(s, studyCodebook(protocol)); }, &error))
    return studyFail(error);
  return 0;
}

}  // namespace cb
