#include "core/survey/ins_fixes_in_world.h"

#include "core/geometry/local_ned_frame.h"
#include "core/geometry/so3.h"
#include "core/survey/survey.h"

namespace hsmap {

std::vector<InsFixInWorld> insFixesInWorld(const Survey& survey) {
  const LocalNedFrame ned(survey.origin);
  std::vector<InsFixInWorld> fixes;
  fixes.reserve(survey.ins.fixes.size());
  for (const InsFix& fix : survey.ins.fixes) {
    InsFixInWorld w;
    w.t = fix.t;
    w.p_W_B = ned.toNed(GeodeticPoint{fix.lat_deg, fix.lon_deg, fix.depth_m});
    if (survey.ins.has_attitude) {
      w.q_W_B = quaternionFromRollPitchHeadingDeg(fix.roll_deg, fix.pitch_deg, fix.heading_deg);
    }
    w.line_number = fix.line_number;
    fixes.push_back(w);
  }
  return fixes;
}

}  // namespace hsmap
