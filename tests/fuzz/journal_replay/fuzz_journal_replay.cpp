// Fuzz target: replaying a journal past its CRC check ("records that are well-formed
// but nonsensical"). A journal's CRCs only say the bytes arrived as written; a journal written
// by another build, edited, or made up still reaches the replay. The input is read as records
// (no CRC to get past) that go through the same replay a session journal does: a fresh
// PaintSession applies each one (Session, Settings, Device, Calibration, pen samples, UI changes,
// markers, ...), and the study runner restores its state from the `study.*` markers
// (StudyRunState::restore over the bundled protocol, as `study run --resume` does).
//
// Input framing, repeated to the end: type (1 byte, taken modulo the known record types + 1),
// time step (2 bytes LE, in ms), payload length (2 bytes LE), the payload. Sessions whose
// Session record asks for more than a 32³ grid or a 256-pixel screen are skipped (their sizes
// are legal; one input must stay fast), and so are those whose Settings records ask for another
// noise texture or ink volume than the shipped ones: making one is a fixed function of a few
// numbers (not a parser of the input) that takes about 10 s under the fuzzer's coverage
// instrumentation (the noise texture's simplex corners), while the shipped ones are made once per
// process (NoiseTexture::shared, InkVolume::shared).
//
// LLVMFuzzerInitialize replays the empty journal once, so those shared ones, the brush config and
// the protocol are made before libFuzzer starts timing inputs: the first replay took 10 s on a
// quiet 2-core machine and over the per-input timeout (10 s) on a loaded one; later inputs take
// milliseconds.
#include <cstdint>
#include <string>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/mapping/mapping_config.h"
#include "app/session/session_replay.h"
#include "app/study/protocol.h"
#include "app/study/study_run_state.h"
#include "drivers/core/journal.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  cb::JournalReadResult journal;
  journal.version = 1;
  int64_t t = 1'000'000'000;
  size_t i = 0;
  while (i + 5 <= size) {
    cb::JournalRecord record;
    record.type = cb::JournalRecordType(data[i] % (cb::kLastJournalRecordType + 1) + 1);
    t += int64_t(data[i + 1] | (data[i + 2] << 8)) * 1'000'000;
    const size_t n = size_t(data[i + 3] | (data[i + 4] << 8));
    i += 5;
    const size_t take = std::min(n, size - i);
    record.t_ns = t;
    record.payload.assign(data + i, data + i + take);
    i += take;
    if (record.type == cb::JournalRecordType::kSession) {
      cb::PaintSessionSettings s;
      std::string error;
      if (cb::parseSessionSettings(record.text(), &s, &error) &&
          (s.grid > 32 || s.screen_width > 256 || s.screen_height > 256))
        return 0;
    }
    journal.records.push_back(std::move(record));
  }
  static const cb::BrushConfig brush = cb::loadDefaultBrushConfig();
  static const cb::MappingConfig mapping{};
  const cb::RecordedSettings recorded = cb::recordedSettings(journal.records, brush, mapping);
  const cb::NoiseTextureConfig& noise = recorded.mapping.noise;
  if (noise.seed != mapping.noise.seed || noise.size != mapping.noise.size ||
      noise.period_voxels != mapping.noise.period_voxels ||
      noise.octaves != mapping.noise.octaves ||
      recorded.brush.brush3d.ink_volume_size != brush.brush3d.ink_volume_size ||
      recorded.brush.brush3d.ink_seed != brush.brush3d.ink_seed)
    return 0;
  cb::PaintSessionSettings fallback;
  fallback.screen_width = 64;
  fallback.screen_height = 48;
  fallback.grid = 16;
  const cb::SessionReplay replay = cb::replaySession(journal, brush, mapping, fallback);
  if (replay.session) (void)cb::volumeChecksum(replay.session->volume());

  static const cb::StudyProtocol protocol = cb::loadStudyProtocol(cb::defaultStudyProtocolPath());
  std::vector<cb::StudyRunRecord> markers;
  for (const cb::JournalRecord& r : journal.records)
    if (r.type == cb::JournalRecordType::kMarker && r.text().rfind("study.", 0) == 0)
      markers.push_back({r.t_ns, std::string(r.text())});
  cb::StudyRunState state(protocol, 1, markers.empty() ? 0 : markers.front().t_ns);
  std::string error;
  if (state.restore(markers, &error)) (void)state.questionnaireCsv();
  return 0;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  return LLVMFuzzerTestOneInput(nullptr, 0);
}
