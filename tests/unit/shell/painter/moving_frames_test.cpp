// The painter's choice of how to draw a frame while the view moves (moving_frames.h): the fixed
// policies, and kFaster's measured choice with its warm-up frame, budget and re-probes (every
// kReprobeFrames and after a rest).
#include <gtest/gtest.h>

#include "app/shell/painter/moving_frames.h"

namespace cb {
namespace {

constexpr double kBudget = 1000.0 / 30.0;

// Draws `frames` moving frames, each the way the chooser says, reprojected ones taking
// `reprojected_ms` and reduced ones `reduced_ms`; returns how many were reprojected.
int drive(MovingPathChooser& chooser, int frames, double reprojected_ms, double reduced_ms) {
  int reprojected = 0;
  for (int i = 0; i < frames; ++i) {
    const bool r = chooser.reprojectNext();
    reprojected += r;
    chooser.measured(r, r ? reprojected_ms : reduced_ms);
  }
  return reprojected;
}

TEST(MovingFrames, TheFixedPoliciesNeverChange) {
  MovingPathChooser reduced(MovingFrames::kReduced, kBudget);
  EXPECT_EQ(drive(reduced, 200, 1.0, 500.0), 0) << "even when reprojection is far faster";
  MovingPathChooser reprojected(MovingFrames::kReprojected, kBudget);
  EXPECT_EQ(drive(reprojected, 200, 500.0, 1.0), 200) << "even when far slower";
}

TEST(MovingFrames, ReprojectionWithinTheBudgetIsKept) {
  MovingPathChooser chooser(MovingFrames::kFaster, kBudget);
  // Reduced frames would be faster still, but reprojection keeps to 30 fps: never probed.
  EXPECT_EQ(drive(chooser, 300, 30.0, 5.0), 300);
  EXPECT_LT(chooser.reducedMs(), 0.0) << "the reduced scale was never drawn";
}

TEST(MovingFrames, OverTheBudgetTheFasterIsDrawnAndTheOtherReprobed) {
  MovingPathChooser chooser(MovingFrames::kFaster, kBudget);
  // The first frame (programs compiled, targets made) is left out: 900 ms does not count.
  EXPECT_TRUE(chooser.reprojectNext());
  chooser.measured(true, 900.0);
  EXPECT_LT(chooser.reprojectedMs(), 0.0);
  // Reprojection at 60 ms is over budget: the reduced scale is tried (its own first frame left
  // out, then one measured) and, at 40 ms, kept.
  EXPECT_TRUE(chooser.reprojectNext());
  chooser.measured(true, 60.0);
  EXPECT_DOUBLE_EQ(chooser.reprojectedMs(), 60.0);
  EXPECT_FALSE(chooser.reprojectNext());
  chooser.measured(false, 40.0);
  EXPECT_FALSE(chooser.reprojectNext());
  chooser.measured(false, 40.0);
  EXPECT_DOUBLE_EQ(chooser.reducedMs(), 40.0);
  // From here reduced frames, with one reprojected probe every kReprobeFrames.
  const int n = 3 * MovingPathChooser::kReprobeFrames;
  const int probes = drive(chooser, n, 60.0, 40.0);
  EXPECT_GE(probes, 2);
  EXPECT_LE(probes, 3);
  // Reprojection gets cheaper (20 ms: within budget) while the reduced frames do not: the next
  // probe shows it, and it is drawn from then on.
  const int after = drive(chooser, MovingPathChooser::kReprobeFrames + 20, 20.0, 40.0);
  EXPECT_GE(after, 20) << "reprojection drawn once its probe showed it the faster";
  EXPECT_TRUE(chooser.reprojectNext());
  // And the reduced frames slowing down (90 ms) in their own median also turns the choice.
  MovingPathChooser slower(MovingFrames::kFaster, kBudget);
  drive(slower, 10, 60.0, 40.0);
  EXPECT_FALSE(slower.reprojectNext());
  drive(slower, 10, 60.0, 90.0);
  EXPECT_TRUE(slower.reprojectNext());
}

TEST(MovingFrames, AMovementAfterARestStartsWithAProbe) {
  MovingPathChooser chooser(MovingFrames::kFaster, kBudget);
  drive(chooser, 10, 60.0, 40.0);  // settled on the reduced scale
  EXPECT_FALSE(chooser.reprojectNext());
  chooser.rested();  // the drag ended; the next one may turn a denser view
  EXPECT_TRUE(chooser.reprojectNext()) << "the first frame of the next movement is a probe";
  chooser.measured(true, 30.0);  // which shows reprojection within budget now
  EXPECT_TRUE(chooser.reprojectNext());
  EXPECT_EQ(drive(chooser, 50, 30.0, 40.0), 50);
}

TEST(MovingFrames, OneSlowFrameDoesNotTurnTheChoice) {
  MovingPathChooser chooser(MovingFrames::kFaster, kBudget);
  drive(chooser, 10, 55.0, 75.0);  // settled on reprojection: over budget, but the faster
  ASSERT_TRUE(chooser.reprojectNext());
  chooser.measured(true, 400.0);  // a frame that also wrote a PNG
  EXPECT_TRUE(chooser.reprojectNext());
  EXPECT_DOUBLE_EQ(chooser.reprojectedMs(), 55.0);
}

}  // namespace
}  // namespace cb
