#include "pipelines/georef/georef_result.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/util/message_text.h"

namespace hsmap {
namespace {

std::string sourceCounts(int vision, int bridged, int ins_only, int held, const char* unit) {
  std::ostringstream out;
  bool first = true;
  auto item = [&](int count, const char* what) {
    if (count == 0) return;
    out << (first ? "" : ", ") << count << " " << what;
    first = false;
  };
  item(vision, "from vision");
  item(bridged, "bridged by the INS across tracking gaps");
  item(ins_only, "from the INS alone");
  item(held, "held at the nearest pose (beyond vision and the INS)");
  if (first) out << "no " << unit;
  return out.str();
}

}  // namespace

int GeorefResult::frameCount(PoseSource source) const {
  return int(std::count_if(frames.begin(), frames.end(),
                           [&](const GeorefFramePose& f) { return f.source == source; }));
}

int GeorefResult::lineCount(PoseSource source) const {
  return int(std::count_if(lines.begin(), lines.end(),
                           [&](const GeorefLinePose& l) { return l.source == source; }));
}

std::string GeorefResult::summary() const {
  std::ostringstream out;
  out << "georef (" << variant << "): " << frames.size() << " frames and " << lines.size()
      << " scan lines posed in W";
  if (!landmarks_W.empty()) out << ", " << landmarks_W.size() << " landmarks";
  out << "\n";
  if (alignment) {
    out << "  INS alignment: " << alignment->inlier_count << " of "
        << alignment->paired_fixes.size() << " fixes within vision agree (threshold "
        << fixedDecimals(alignment->threshold_m, 2) << " m), rms " << fixedDecimals(alignment->rms_m, 3)
        << " m, scale " << alignment->S_W_F.scale() << ", rotation from "
        << alignment->rotation_from << "\n";
  }
  if (bundle) {
    const GeorefBundleReport& b = *bundle;
    out << "  bundle adjustment: " << b.keyframes << " keyframes, " << b.landmarks
        << " landmarks, " << b.reprojection_factors << " reprojections, " << b.position_factors
        << " INS positions";
    if (b.position_correlation_factor > 1.0) {
      out << " (sigmas x " << fixedDecimals(b.position_correlation_factor, 1)
          << ": fixes within the INS's correlation time count as one)";
    }
    out << ", " << b.attitude_factors
        << (b.attitude_measured ? " INS attitudes" : " level, along-track attitude priors");
    out << "; " << b.solves << (b.solves == 1 ? " solve" : " solves") << "\n";
    out << "  " << b.last_solve.toString() << "\n";
    out << "  " << b.removed_observations
        << " observations beyond 3 px after the solve removed from the map\n";
  }
  if (rgb_camera) {
    const PinholeRadtanParameters& c = rgb_camera->camera;
    const auto& s = rgb_camera->sigma;
    out << "  RGB intrinsics estimated (rgb.camera_sigma): fx " << c.fx << ", fy " << c.fy << ", cx " << c.cx
        << ", cy " << c.cy << ", distortion [" << c.distortion[0] << ", " << c.distortion[1] << ", "
        << c.distortion[2] << ", " << c.distortion[3] << ", " << c.distortion[4] << "]";
    if (rgb_camera->sigma_known) {
      out << " (1-sigma " << s[0] << ", " << s[1] << ", " << s[2] << ", " << s[3] << ", [" << s[4] << ", " << s[5]
          << ", " << s[6] << ", " << s[7] << ", " << s[8] << "]; covariance " << fixedDecimals(rgb_camera->covariance_s, 2)
          << " s)";
    }
    out << "\n";
  }
  if (placement) {
    const MapPlacement& p = *placement;
    out << "  map placement (maximum likelihood on " << p.fixes << " INS fixes, "
        << (p.attitude_measured ? "positions and attitude" : "positions, attitude assumed level")
        << "): scale 1-sigma " << fixedDecimals(100.0 * p.scale_sigma, 2) << " % ("
        << fixedDecimals(100.0 * p.scale_sigma_without_attitude, 2) << " % without the attitude, "
        << fixedDecimals(100.0 * p.scale_sigma_without_depth, 2)
        << " % without the depths' precision), rotation 1-sigma "
        << fixedDecimals(p.rotation_sigma_deg[0], 3) << "/" << fixedDecimals(p.rotation_sigma_deg[1], 3)
        << "/" << fixedDecimals(p.rotation_sigma_deg[2], 3) << " deg, position 1-sigma "
        << fixedDecimals(p.position_sigma_m[0], 3) << "/" << fixedDecimals(p.position_sigma_m[1], 3)
        << "/" << fixedDecimals(p.position_sigma_m[2], 3) << " m (N/E/D); correction after the "
        << "adjustment: scale " << fixedDecimals(p.correction_scale, 5) << ", "
        << fixedDecimals(p.correction_rotation_deg, 4) << " deg, "
        << fixedDecimals(p.correction_translation_m, 4) << " m\n";
  }
  if (rejected_fixes.empty()) {
    if (alignment) out << "  INS fixes left out: none\n";
  } else {
    out << "  INS fixes left out (" << rejected_fixes.size() << "):\n";
    for (const RejectedFix& r : rejected_fixes) {
      out << "    ins.csv line " << r.line_number << " (t = " << fixedDecimals(r.t, 3) << " s): "
          << fixedDecimals(r.offset_m, 2) << " m off the track, found by the " << r.stage << "\n";
    }
  }
  if (variant == "sequential") {
    out << "  frames posed by vision: " << repose.keyframes << " keyframes from the adjustment, "
        << repose.pnp << " by PnP on the adjusted landmarks";
    if (repose.from_keyframe > 0) {
      out << ", " << repose.from_keyframe << " carried by their keyframe (PnP failed)";
    }
    out << "\n";
  }
  out << "  frames: "
      << sourceCounts(frameCount(PoseSource::vision), frameCount(PoseSource::ins_bridged),
                      frameCount(PoseSource::ins_only), frameCount(PoseSource::held), "frames")
      << "\n";
  out << "  scan lines (t + " << time_offset_s << " s, through T_C_U): "
      << sourceCounts(lineCount(PoseSource::vision), lineCount(PoseSource::ins_bridged),
                      lineCount(PoseSource::ins_only), lineCount(PoseSource::held), "lines");
  return out.str();
}

}  // namespace hsmap
