#include "app/shell/painter/painter_messages.h"

namespace cb {

std::string painterMessagesText() {
  const Bilingual all[] = {
      msg::kHowToPaint,      msg::kPressThreeToPaint, msg::kMousePaints,   msg::kPenPaints,
      msg::kHelpKey,         msg::kNoSession,         msg::kSavedAs,       msg::kSaveFailed,
      msg::kCleared,         msg::kQuitAsk,           msg::kForOperator,   msg::kRotating,
      msg::kRotationStopped, msg::kVacuumPlace,       msg::kVacuumCut,     msg::kNothingToUndo,
      msg::kNothingToRedo,   msg::kInkLeftOut,        msg::kInkOnFallback, msg::kStrokeEnded,
      msg::kStatsHistogram,  msg::kStatsTotal,        msg::kStatsMean,     msg::kStatsMax};
  std::string text;
  for (const Bilingual& b : all) text += b.zh;
  return text;
}

std::vector<std::string> firstScreenHint(bool paint_mode, bool tablet) {
  const Bilingual how = paint_mode ? msg::kHowToPaint : msg::kPressThreeToPaint;
  const Bilingual input = tablet ? msg::kPenPaints : msg::kMousePaints;
  return {how.en, how.zh, std::string(input.en) + " · " + msg::kHelpKey.en,
          std::string(input.zh) + " · " + msg::kHelpKey.zh};
}

}  // namespace cb
