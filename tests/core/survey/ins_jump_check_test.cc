#include "core/survey/ins_jump_check.h"

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/expect_input_error.h"

namespace hsmap {
namespace {

using testing::expectInputError;

// A track north at 0.5 m/s (1 s fixes, 4.5e-6 degrees of latitude ~ 0.5 m).
InsTable northTrack(int fixes) {
  InsTable ins;
  for (int i = 0; i < fixes; ++i) {
    InsFix fix;
    fix.t = 100.0 + i;
    fix.lat_deg = 43.0 + 4.5e-6 * i;
    fix.lon_deg = 5.0;
    fix.depth_m = 30.0;
    fix.line_number = i + 2;
    ins.fixes.push_back(fix);
  }
  return ins;
}

TEST(InsJumpCheckTest, ASmoothTrackHasNoFinding) {
  EXPECT_TRUE(checkInsJumps(northTrack(20), "ins.csv", 0.5, 0.05).empty());
}

TEST(InsJumpCheckTest, ImpossibleJumpIsAnErrorAtItsLine) {
  InsTable ins = northTrack(5);
  ins.fixes[3].lon_deg = 91.0;
  try {
    checkInsJumps(ins, "ins.csv", 0.5, 0.05);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "line 5");
    EXPECT_EQ(std::string(e.detail()).rfind("the position jumps ", 0), 0u) << e.detail();
  }
  InsTable deep = northTrack(5);
  deep.fixes[2].depth_m = 5000.0;
  expectInputError([&] { checkInsJumps(deep, "ins.csv", 0.5, 0.05); }, "ins.csv",
                   "line 4: the depth jumps 4970.0 m in 1.000 s from the previous fix (4.97e+03 "
                   "m/s); expected a vehicle's track (no underwater vehicle or acoustic fix moves "
                   "more than 1 km at over 50 m/s)");
}

TEST(InsJumpCheckTest, PlausibleJumpsAreWarningsAndLongGapsAreNot) {
  InsTable ins = northTrack(20);
  ins.fixes[5].lat_deg += 1e-4;  // ~11 m off for one fix: out and back
  const auto warnings = checkInsJumps(ins, "ins.csv", 0.5, 0.05);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].rfind("ins.csv:line 7: the position jumps ", 0), 0u) << warnings[0];
  EXPECT_EQ(warnings[1].rfind("ins.csv:line 8: the position jumps ", 0), 0u) << warnings[1];
  // 2 km in an hour's gap is a vehicle's speed: nothing to report.
  InsTable gap = northTrack(3);
  gap.fixes[2].t = gap.fixes[1].t + 3600.0;
  gap.fixes[2].lat_deg += 0.018;
  EXPECT_TRUE(checkInsJumps(gap, "ins.csv", 0.5, 0.05).empty());
}

TEST(InsJumpCheckTest, ManyWarningsAreSummarised) {
  InsTable ins = northTrack(40);
  for (int i = 2; i < 40; i += 4) ins.fixes[static_cast<std::size_t>(i)].depth_m += 10.0;
  const auto warnings = checkInsJumps(ins, "ins.csv", 0.5, 0.05);
  ASSERT_EQ(warnings.size(), 6u);
  EXPECT_EQ(warnings.back(), "ins.csv: 15 more INS jumps like those above");
}

}  // namespace
}  // namespace hsmap
