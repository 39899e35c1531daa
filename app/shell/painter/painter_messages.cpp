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

}  // namespace cb
