#include "pipelines/frontend/frontend_runner.h"

#include <chrono>
#include <cstdio>
#include <algorithm>
#include <limits>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <stdexcept>

#include "core/util/stage_timer.h"
#include "pipelines/frontend/frame_prefetcher.h"
#include "pipelines/frontend/frame_tracker.h"
#include "pipelines/frontend/lamp_light_field.h"
#include "pipelines/frontend/image_preprocessor.h"
#include "pipelines/frontend/local_bundle_adjuster.h"
#include "pipelines/frontend/segment_joiner.h"
#include "pipelines/frontend/segment_linker.h"
#include "pipelines/frontend/tracking_loss_monitor.h"

namespace hsmap {

namespace {

std::string formatMetres(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f m", value);
  return text;
}

std::string formatScale(double scale, double sigma) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g +- %.2g", scale, sigma);
  return text;
}

std::string segmentName(const SegmentRecord& segment) {
  return "segment " + std::to_string(segment.id) + " (frames " + std::to_string(segment.first_frame) + "-" +
         std::to_string(segment.last_frame) + ")";
}

// The keyframes' grey images, as the tracker saw them (ImagePreprocessor with
// the same lamp light field), decoded again on demand and kept.
class KeyframeImages {
 public:
  KeyframeImages(const Survey& survey, const FrontendOptions& options, const PinholeRadtanCamera& camera,
                 cv::Mat lamp_light_field)
      : survey_(survey), preprocessor_(options, camera.width(), camera.height(), std::move(lamp_light_field)) {}
  // Empty when the frame cannot be decoded (again).
  cv::Mat gray(int frame) {
    const auto it = images_.find(frame);
    if (it != images_.end()) return it->second;
    cv::Mat gray;
    try {
      gray = preprocessor_.process(survey_.rgb.frame(frame), nullptr);
    } catch (const std::exception&) {
    }
    images_[frame] = gray;
    return gray;
  }

 private:
  const Survey& survey_;
  ImagePreprocessor preprocessor_;
  std::map<int, cv::Mat> images_;
};

// How segments come together before F is chosen: each segment S is in the
// frame G of a group (the first segment of the group), S_G_S; a segment
// joined by vision enters the group of the segment it was joined to.
struct SegmentGroups {
  std::vector<int> group;                  // per segment: its group's first segment
  std::vector<Sim3> S_G_S;
  std::vector<double> relative_sigma;      // of S_G_S's scale (0 for a group's first segment)
  std::vector<SegmentJoin> joins;          // per segment: the join, or the best refused attempt
  std::vector<bool> tried;                 // a vision join was attempted
};

// Joins each segment after the first to an earlier one by vision
// (segment_joiner.h), where their views overlap.
SegmentGroups joinSegmentsByVision(const Survey& survey, const FrameTracker& tracker,
                                   const FrontendOptions& options, const PinholeRadtanCamera& camera,
                                   const cv::Mat& lamp_light_field) {
  const auto& spans = tracker.segments();
  const VisualMap& map = tracker.map();
  SegmentGroups groups;
  const std::size_t n = spans.size();
  groups.group.resize(n);
  groups.S_G_S.assign(n, Sim3());
  groups.relative_sigma.assign(n, 0.0);
  groups.joins.resize(n);
  groups.tried.assign(n, false);
  for (std::size_t s = 0; s < n; ++s) groups.group[s] = int(s);
  if (!options.join_segments_by_vision || n < 2) return groups;

  const double error_scale = options.errorScale(camera.width());
  SegmentJoinOptions join_options;
  join_options.min_inliers = options.join_min_inliers;
  join_options.max_reprojection_px = options.ba_outlier_px * error_scale;
  join_options.pnp.ransac_threshold_px = options.pnp_threshold_px * error_scale;
  join_options.pnp.ransac_iterations = std::max(options.pnp_ransac_iterations, 500);  // many outliers here
  join_options.pnp.pixel_sigma_px = options.pixel_sigma_px * error_scale;
  join_options.pnp.huber_scale = options.huber_scale;
  join_options.pnp.max_iterations = options.refine_max_iterations;
  join_options.pnp.inlier_threshold_px = options.inlier_threshold_px * error_scale;
  join_options.pnp.min_inliers = options.join_min_inliers;
  join_options.pnp.solver_threads = options.solver_threads;
  KeyframeImages images(survey, options, camera, lamp_light_field);
  // (keyframe, segment it is seen from, descriptor) -> view
  std::map<std::tuple<int, int, std::string>, JoinKeyframeView> views;
  auto view = [&](int keyframe_id, const SegmentJoinOptions& o) -> const JoinKeyframeView& {
    const int segment = map.keyframe(keyframe_id).segment;
    const auto key = std::make_tuple(keyframe_id, groups.group[std::size_t(segment)], o.descriptor);
    auto it = views.find(key);
    if (it == views.end()) {
      JoinKeyframeView v = makeJoinView(map, keyframe_id, groups.S_G_S[std::size_t(segment)],
                                        images.gray(map.keyframe(keyframe_id).frame_index));
      describeJoinView(v, o);
      it = views.emplace(key, std::move(v)).first;
    }
    return it->second;
  };
  // Each keyframe pair is tried with SIFT and with ORB (segment_joiner.h):
  // SIFT matches more across a wide baseline over relief, but on a new
  // segment whose own geometry is weak the two descriptors' matched sets
  // give different Sim(3)s, and either may be the one that verifies. Every
  // attempt passes the same verification.
  std::vector<SegmentJoinOptions> descriptor_options(2, join_options);
  descriptor_options[0].descriptor = "sift";
  descriptor_options[1].descriptor = "orb";

  for (std::size_t s = 1; s < n; ++s) {
    if (spans[s].keyframe_ids.empty()) continue;
    const double t_start = map.keyframe(spans[s].keyframe_ids.front()).t;
    // The earlier segments' keyframes nearest in time to this one's start.
    std::vector<int> earlier;
    for (std::size_t e = 0; e < s; ++e) {
      earlier.insert(earlier.end(), spans[e].keyframe_ids.begin(), spans[e].keyframe_ids.end());
    }
    std::stable_sort(earlier.begin(), earlier.end(), [&](int a, int b) {
      return std::abs(map.keyframe(a).t - t_start) < std::abs(map.keyframe(b).t - t_start);
    });
    if (int(earlier.size()) > join_options.earlier_keyframes) earlier.resize(std::size_t(join_options.earlier_keyframes));
    const std::size_t new_count = std::min(spans[s].keyframe_ids.size(), std::size_t(join_options.new_keyframes));
    SegmentJoin best, best_refused;
    std::vector<SegmentJoin> verified;
    for (const SegmentJoinOptions& o : descriptor_options) {
      for (int e : earlier) {
        for (std::size_t j = 0; j < new_count; ++j) {
          SegmentJoin join = joinKeyframePair(view(e, o), view(spans[s].keyframe_ids[j], o), camera, o);
          groups.tried[s] = true;
          if (join.ok) {
            verified.push_back(join);
            if (!best.ok || join.inliers > best.inliers) best = join;
          } else if (best_refused.earlier_keyframe < 0 || join.inliers > best_refused.inliers ||
                     (join.inliers == best_refused.inliers && join.matches > best_refused.matches)) {
            best_refused = std::move(join);
          }
        }
      }
    }
    if (!best.ok) {
      groups.joins[s] = best_refused;
      continue;
    }
    // The best verified pair sets the similarity. The other verified
    // keyframe pairs add their landmark pairs where the accepted similarity
    // agrees (within its RANSAC threshold): ties between more keyframes of both sides,
    // which is what holds the new segment's scale in the adjustment (one
    // keyframe resected on the earlier map fixes its pose, not the
    // segment's scale). Each landmark is paired once.
    const int earlier_segment = best.earlier_segment;
    const int group = groups.group[std::size_t(earlier_segment)];
    const double threshold = join_options.sim3_threshold_fraction * best.altitude;
    std::set<int> paired_earlier, paired_new;
    std::vector<std::pair<int, int>> pairs;
    auto add = [&](const std::pair<int, int>& pair) {
      if (paired_earlier.count(pair.first) || paired_new.count(pair.second)) return;
      const Landmark& e = map.landmark(pair.first);
      const Eigen::Vector3d p_G = groups.S_G_S[std::size_t(e.segment)].apply(e.p_F);
      if ((best.S_G_S.apply(map.landmark(pair.second).p_F) - p_G).norm() > threshold) return;
      paired_earlier.insert(pair.first);
      paired_new.insert(pair.second);
      pairs.push_back(pair);
    };
    for (const auto& pair : best.landmark_pairs) add(pair);
    int tied = 1;
    for (const SegmentJoin& join : verified) {
      if (groups.group[std::size_t(join.earlier_segment)] != group) continue;
      if (join.earlier_keyframe == best.earlier_keyframe && join.new_keyframe == best.new_keyframe) continue;
      const std::size_t before = pairs.size();
      for (const auto& pair : join.landmark_pairs) add(pair);
      tied += pairs.size() > before ? 1 : 0;
    }
    // Then, under the accepted similarity, every overlapping keyframe pair
    // (guided matching, pairsUnderSimilarity): a join at one keyframe pair
    // ties the new segment at one place only. On tiny after 8 black frames
    // the second segment's frames were 12 mm rms from where the first
    // segment's similarity to the truth puts them; tied along both sides
    // (171 landmarks from 7 keyframe pairs instead of 68 from one), 6.7 mm.
    const std::vector<int>& new_ids = spans[s].keyframe_ids;
    for (int e : earlier) {
      if (groups.group[std::size_t(map.keyframe(e).segment)] != group) continue;
      for (int n_id : new_ids) {
        const std::size_t before = pairs.size();
        for (const auto& pair : pairsUnderSimilarity(view(e, descriptor_options[0]), view(n_id, descriptor_options[0]),
                                                     camera, best.S_G_S, threshold, join_options)) {
          add(pair);
        }
        tied += pairs.size() > before ? 1 : 0;
      }
    }
    best.landmark_pairs = std::move(pairs);
    best.pairs_from_keyframe_pairs = tied;
    groups.joins[s] = best;
    groups.group[s] = group;
    groups.S_G_S[s] = best.S_G_S;
    const double relative = best.scale_sigma / best.S_G_S.scale();
    groups.relative_sigma[s] = std::hypot(relative, groups.relative_sigma[std::size_t(earlier_segment)]);
  }
  return groups;
}

std::string joinText(const VisualMap& map, const SegmentJoin& join) {
  std::ostringstream text;
  text << "keyframes at frames " << map.keyframe(join.earlier_keyframe).frame_index << "<->"
       << map.keyframe(join.new_keyframe).frame_index << ", " << join.matches << " " << join.descriptor
       << " matches, " << join.inliers
       << " inliers";
  if (join.ok && join.pairs_from_keyframe_pairs > 1) {
    text << " (" << join.landmark_pairs.size() << " landmarks merged from " << join.pairs_from_keyframe_pairs
         << " verified keyframe pairs)";
  }
  return text.str();
}

// Decides which segments are linked into F and how (S_F_S per segment):
// by vision where a segment's views overlap an earlier one's
// (joinSegmentsByVision), through the INS for each group of joined segments
// otherwise (docs/FRONTEND.md, "Linking segments").
std::vector<SegmentRecord> linkSegments(const Survey& survey, const FrameTracker& tracker,
                                        const FrontendOptions& options, const SegmentGroups& groups,
                                        std::vector<std::string>& warnings) {
  const auto& spans = tracker.segments();
  const VisualMap& map = tracker.map();
  std::vector<SegmentRecord> segments;
  for (const auto& span : spans) {
    SegmentRecord record;
    record.id = span.id;
    record.first_frame = span.first_frame;
    record.last_frame = span.last_frame;
    record.keyframes = int(span.keyframe_ids.size());
    segments.push_back(record);
  }
  if (segments.empty()) return segments;
  const std::size_t n = spans.size();
  std::vector<int> roots;
  for (std::size_t s = 0; s < n; ++s) {
    if (groups.group[s] == int(s)) roots.push_back(int(s));
  }

  // The INS fit of each group (its segments' keyframes in its frame G).
  std::vector<SegmentFit> fits(n);
  const double outlier_threshold_m = std::max(1.0, 4.0 * survey.config.ins.sigma_horizontal_m);
  if (survey.ins.fixes.empty()) {
    for (auto& fit : fits) fit.failure = "the survey has no INS";
  } else if (roots.size() > 1) {
    const InsBodyTrack ins(survey, kSegmentLinkerInsOptions);
    const SE3d T_B_C(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m);
    for (int g : roots) {
      std::vector<double> times;
      std::vector<SE3d> poses;
      for (std::size_t s = 0; s < n; ++s) {
        if (groups.group[s] != g) continue;
        for (int k : spans[s].keyframe_ids) {
          times.push_back(map.keyframe(k).t);
          poses.push_back(groups.S_G_S[s].transformPose(map.keyframe(k).T_F_C));
        }
      }
      fits[std::size_t(g)] = fitSegmentToIns(times, poses, ins, T_B_C, options.min_segment_keyframes,
                                             outlier_threshold_m);
    }
  }
  int reference = -1;
  if (roots.size() == 1) {
    reference = roots[0];
  } else {
    for (int g : roots) {
      if (fits[std::size_t(g)].ok) {
        reference = g;
        break;
      }
    }
  }
  const bool any_fit = reference >= 0;
  if (reference < 0) {
    // Nothing can be linked through the INS: keep the largest group alone.
    int best_keyframes = -1;
    for (int g : roots) {
      int keyframes = 0;
      for (std::size_t s = 0; s < n; ++s) keyframes += groups.group[s] == g ? segments[s].keyframes : 0;
      if (keyframes > best_keyframes) {
        best_keyframes = keyframes;
        reference = g;
      }
    }
  }

  // Each group into F: S_F_G, its relative scale sigma, how, or why not.
  std::map<int, Sim3> S_F_G;
  std::map<int, double> group_sigma;
  std::map<int, std::string> group_note;
  const SegmentFit& reference_fit = fits[std::size_t(reference)];
  S_F_G[reference] = Sim3();
  group_sigma[reference] = 0.0;
  for (int g : roots) {
    if (g == reference) continue;
    const SegmentFit& fit = fits[std::size_t(g)];
    if (!any_fit || !fit.ok) {
      group_note[g] = "not linked: " + fit.failure +
                      (any_fit ? std::string() : "; no segment could be fitted to the INS");
      continue;
    }
    const Sim3 S_F_W = reference_fit.S_W_S.inverse();
    const double own = fit.scale_sigma / fit.S_W_S.scale();
    const double reference_relative = reference_fit.scale_sigma / reference_fit.S_W_S.scale();
    std::ostringstream note;
    note << "linked through the INS (fit rms " << formatMetres(fit.rms_m) << " over " << fit.p_S.size()
         << " keyframes, " << fit.outliers << " left out as outliers beyond " << formatMetres(outlier_threshold_m)
         << "; reference fit rms " << formatMetres(reference_fit.rms_m);
    if (!fit.note.empty()) note << "; " << fit.note;
    if (own > options.max_ins_scale_sigma) {
      // Too weak to carry its own scale: the reference's, rotation and
      // translation from the fit.
      S_F_G[g] = S_F_W * withScale(fit, reference_fit.S_W_S.scale());
      group_sigma[g] = own;
      char text[160];
      std::snprintf(text, sizeof(text),
                    "; its own scale's 1-sigma %.1f %% exceeds %.1f %%, so the reference segment's scale is kept",
                    100.0 * own, 100.0 * options.max_ins_scale_sigma);
      note << text;
    } else {
      S_F_G[g] = S_F_W * fit.S_W_S;
      group_sigma[g] = std::hypot(own, reference_relative);
    }
    group_note[g] = note.str();
  }

  for (std::size_t s = 0; s < n; ++s) {
    SegmentRecord& segment = segments[s];
    const int g = groups.group[s];
    segment.ins_rms_m = (fits[std::size_t(g)].ok && int(s) == g) ? fits[std::size_t(g)].rms_m : 0.0;
    const SegmentJoin& join = groups.joins[s];
    const auto linked = S_F_G.find(g);
    if (linked != S_F_G.end()) {
      segment.linked = true;
      segment.S_F_S = linked->second * groups.S_G_S[s];
      segment.scale_sigma = std::hypot(group_sigma[g], groups.relative_sigma[s]) * segment.S_F_S.scale();
    }
    if (int(s) == reference) {
      segment.reference = true;
      segment.link = SegmentLink::reference;
      segment.note = "reference segment (its frame is F)";
      if (n > 1 && reference_fit.ok) segment.note += "; INS fit rms " + formatMetres(reference_fit.rms_m);
      if (!any_fit && roots.size() > 1) segment.note += "; the others could not be linked through the INS";
      continue;
    }
    if (g != int(s)) {
      segment.joined_to = join.earlier_segment;
      std::ostringstream note;
      note << "joined to segment " << join.earlier_segment << " by vision: " << joinText(map, join) << ", scale "
           << formatScale(segment.S_F_S.scale(), segment.scale_sigma);
      char text[160];
      std::snprintf(text, sizeof(text), " (PnP and Sim(3) poses within %.2f deg and %.1f %% of the altitude, "
                    "reprojection rms %.2f px)", join.rotation_gap_deg, 100.0 * join.position_gap_fraction,
                    join.reprojection_rms_px);
      note << text;
      if (segment.linked) {
        segment.link = SegmentLink::vision;
      } else {
        segment.link = SegmentLink::none;
        note << "; but segment " << g << "'s group is " << group_note[g];
        warnings.push_back(segmentName(segment) + " " + note.str() + "; its frames are reported lost");
      }
      segment.note = note.str();
      continue;
    }
    // A group's first segment, not the reference: the INS.
    std::string vision = "no view overlaps an earlier segment's";
    if (!options.join_segments_by_vision) {
      vision = "vision joins switched off";
    } else if (groups.tried[s] && join.earlier_keyframe >= 0) {
      vision = "vision join refused (best: " + joinText(map, join) + "; " + join.failure + ")";
    }
    if (segment.linked) {
      segment.link = SegmentLink::ins;
      segment.note = group_note[g] + ", scale " + formatScale(segment.S_F_S.scale(), segment.scale_sigma) + "); " + vision;
      warnings.push_back(segmentName(segment) + " " + segment.note);
    } else {
      segment.link = SegmentLink::none;
      segment.note = group_note[g] + "; " + vision;
      warnings.push_back(segmentName(segment) + " " + segment.note + "; its frames are reported lost");
    }
  }
  return segments;
}

// The map of the linked segments (already moved into F by moveIntoF), with
// dense new ids (keyframe_remap, landmark_remap: old id -> new id, -1 when
// dropped).
VisualMap linkedMap(const VisualMap& source, const std::vector<SegmentRecord>& segments,
                    std::vector<int>& keyframe_remap, std::vector<int>& landmark_remap) {
  std::vector<Keyframe> keyframes;
  std::vector<Landmark> landmarks;
  keyframe_remap.assign(source.keyframes().size(), -1);
  landmark_remap.assign(source.landmarks().size(), -1);
  for (const Landmark& l : source.landmarks()) {
    if (!l.valid || l.keyframe_ids.size() < 2) continue;
    const SegmentRecord& segment = segments[std::size_t(l.segment)];
    if (!segment.linked) continue;
    Landmark copy;
    copy.id = int(landmarks.size());
    copy.segment = l.segment;
    copy.p_F = l.p_F;
    landmark_remap[std::size_t(l.id)] = copy.id;
    landmarks.push_back(copy);
  }
  for (const Keyframe& k : source.keyframes()) {
    const SegmentRecord& segment = segments[std::size_t(k.segment)];
    if (!segment.linked) continue;
    Keyframe copy;
    copy.id = int(keyframes.size());
    copy.frame_index = k.frame_index;
    copy.t = k.t;
    copy.segment = k.segment;
    copy.T_F_C = k.T_F_C;
    for (const auto& o : k.observations) {
      const int l = landmark_remap[std::size_t(o.landmark_id)];
      if (l < 0) continue;
      copy.observations.push_back({l, o.pixel});
      landmarks[std::size_t(l)].keyframe_ids.push_back(copy.id);
    }
    keyframe_remap[std::size_t(k.id)] = copy.id;
    keyframes.push_back(std::move(copy));
  }
  VisualMap map;
  map.assign(std::move(keyframes), std::move(landmarks));
  return map;
}

// Moves every linked segment's keyframes and landmarks from its own frame
// into F (S_F_S), in place.
void moveIntoF(VisualMap& map, const std::vector<SegmentRecord>& segments) {
  for (const Keyframe& k : map.keyframes()) {
    const SegmentRecord& segment = segments[std::size_t(k.segment)];
    if (segment.linked) map.keyframe(k.id).T_F_C = segment.S_F_S.transformPose(k.T_F_C);
  }
  for (const Landmark& l : map.landmarks()) {
    const SegmentRecord& segment = segments[std::size_t(l.segment)];
    if (l.valid && segment.linked) map.landmark(l.id).p_F = segment.S_F_S.apply(l.p_F);
  }
}

// Landmark `drop` becomes `keep`: its observations move to `keep` (a
// keyframe that sees both keeps its observation of `keep`), then it is removed.
void mergeLandmark(VisualMap& map, int keep, int drop) {
  const std::vector<int> observers = map.landmark(drop).keyframe_ids;
  for (int k : observers) {
    const auto& observations = map.keyframe(k).observations;
    const auto it = std::find_if(observations.begin(), observations.end(),
                                 [&](const KeyframeObservation& o) { return o.landmark_id == drop; });
    const Eigen::Vector2d pixel = it->pixel;
    map.removeObservation(k, drop);
    map.addObservation(k, keep, pixel);
  }
  map.removeLandmark(drop);
}

// Merges the landmark pairs of every vision join (the new segment's landmark
// into the earlier one) and adjusts each joined segment once with the
// earlier keyframes that see the merged landmarks held fixed: the map in F
// becomes one. merged_into[l]: the landmark l was merged into (-1: none).
void mergeVisionJoins(VisualMap& map, const FrameTracker& tracker, const std::vector<SegmentRecord>& segments,
                      const SegmentGroups& groups, const PinholeRadtanCamera& camera,
                      const FrontendOptions& options, std::vector<int>& merged_into) {
  merged_into.assign(map.landmarks().size(), -1);
  auto resolve = [&](int l) {
    while (merged_into[std::size_t(l)] >= 0) l = merged_into[std::size_t(l)];
    return l;
  };
  LocalBundleAdjustmentOptions ba;
  const double error_scale = options.errorScale(camera.width());
  ba.pixel_sigma_px = options.pixel_sigma_px * error_scale;
  ba.huber_scale = options.huber_scale;
  ba.max_iterations = 2 * options.ba_max_iterations;  // once per join, from a Sim(3) start
  ba.outlier_px = options.ba_outlier_px * error_scale;
  ba.solver_threads = options.solver_threads;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    if (segments[s].link != SegmentLink::vision) continue;
    for (const auto& [earlier, later] : groups.joins[s].landmark_pairs) {
      const int keep = resolve(earlier), drop = resolve(later);
      if (keep == drop || !map.landmark(keep).valid || !map.landmark(drop).valid) continue;
      mergeLandmark(map, keep, drop);
      merged_into[std::size_t(drop)] = keep;
    }
    // Free: the whole new segment (its scale must follow the join, not
    // only its first keyframes); fixed: the earlier segments' keyframes that
    // see its landmarks (the merged ones).
    const std::vector<int>& free = tracker.segments()[s].keyframe_ids;
    std::set<int> fixed;
    for (int k : free) {
      for (const auto& o : map.keyframe(k).observations) {
        for (int other : map.landmark(o.landmark_id).keyframe_ids) {
          if (map.keyframe(other).segment < int(s) && segments[std::size_t(map.keyframe(other).segment)].linked) {
            fixed.insert(other);
          }
        }
      }
    }
    if (fixed.empty()) continue;
    adjustKeyframes(map, free, std::vector<int>(fixed.begin(), fixed.end()), camera, ba);
  }
}

// The tracker's frame observations of the frames still posed, in the ids of
// the linked map; those of landmarks it no longer has (removed by bundle
// adjustment, left with fewer than two keyframes, or of an unlinked segment)
// are dropped. Filtered in place (the list is the front-end's largest); the
// remap keeps the order of ids, so the list stays sorted.
std::vector<FrameObservation> linkedFrameObservations(std::vector<FrameObservation> observations,
                                                      const std::vector<int>& landmark_remap,
                                                      const std::vector<FrameRecord>& frames) {
  std::vector<bool> posed;
  for (const FrameRecord& f : frames) {
    if (f.index >= int(posed.size())) posed.resize(std::size_t(f.index) + 1, false);
    posed[std::size_t(f.index)] = f.posed;
  }
  std::size_t kept = 0;
  bool reordered = false;
  for (const FrameObservation& o : observations) {
    if (o.frame >= int(posed.size()) || !posed[std::size_t(o.frame)]) continue;
    const int l = landmark_remap[std::size_t(o.landmark)];
    if (l < 0) continue;
    if (kept > 0 && observations[kept - 1].frame == o.frame && observations[kept - 1].landmark >= l) reordered = true;
    observations[kept++] = {o.frame, l, o.u, o.v};
  }
  observations.resize(kept);
  if (reordered) {
    // Merged landmarks (vision joins) took earlier ids: sort each frame's
    // run again (runs stay in frame order) and keep each pair once.
    auto less = [](const FrameObservation& a, const FrameObservation& b) {
      return a.frame < b.frame || (a.frame == b.frame && a.landmark < b.landmark);
    };
    std::sort(observations.begin(), observations.end(), less);
    observations.erase(std::unique(observations.begin(), observations.end(),
                                   [](const FrameObservation& a, const FrameObservation& b) {
                                     return a.frame == b.frame && a.landmark == b.landmark;
                                   }),
                       observations.end());
  }
  return observations;
}

// Poses again, on the final map, the frames between keyframes of segments
// joined by vision. A frame is posed at tracking time against its segment's
// young map (landmarks triangulated from a two-view start), and keeps that
// pose relative to its keyframe (T_K_C); the join's adjustment then corrects
// the keyframes and the landmarks but not T_K_C. On tiny after 8 black
// frames those frames were 3 mm behind their keyframes along the track,
// 1 % of scale over the segment, while the keyframes were within 0.2 %; posed
// again, 0.3 %. Each frame: every tracked observation of a landmark of the
// final map that reprojects within ba_outlier_px at its pose, refined
// motion-only (frame_pose_estimator.h) with all of them, not the tracker's
// subsample (120 points leave the along-track/pitch pair a few mm loose);
// a frame that does not refine keeps its pose.
void reposeJoinedSegmentFrames(FrontendResult& result, const PinholeRadtanCamera& camera,
                               const FrontendOptions& options) {
  const double error_scale = options.errorScale(camera.width());
  PoseEstimatorOptions pose;
  pose.pixel_sigma_px = options.pixel_sigma_px * error_scale;
  pose.huber_scale = options.huber_scale;
  pose.max_iterations = options.refine_max_iterations;
  pose.solver_threads = options.solver_threads;
  pose.max_refined_points = std::numeric_limits<int>::max();  // every observation: this is the frame's last pose
  const double limit = options.ba_outlier_px * error_scale;
  auto observation = result.frame_observations.begin();
  for (FrameRecord& frame : result.frames) {
    while (observation != result.frame_observations.end() && observation->frame < frame.index) ++observation;
    auto end = observation;
    while (end != result.frame_observations.end() && end->frame == frame.index) ++end;
    if (!frame.posed || frame.keyframe || frame.segment < 0 ||
        result.segments[std::size_t(frame.segment)].link != SegmentLink::vision) {
      continue;
    }
    std::vector<PoseCorrespondence> correspondences;
    const SE3d T_C_F = frame.T_F_C.inverse();
    for (auto o = observation; o != end; ++o) {
      const Landmark& l = result.map.landmark(o->landmark);
      if (!l.valid) continue;
      const Eigen::Vector3d p_C = T_C_F * l.p_F;
      const Eigen::Vector2d pixel(o->u, o->v);
      if (!(p_C.z() > 0.0) || (camera.project(p_C) - pixel).norm() > limit) continue;
      const auto ray = camera.unproject(pixel);
      if (!ray || !(ray->z() > 0.0)) continue;
      correspondences.push_back({l.p_F, ray->head<2>() / ray->z(), pixel});
    }
    if (int(correspondences.size()) < options.join_min_inliers) continue;
    SE3d T_F_C = frame.T_F_C;
    if (refinePoseMotionOnly(correspondences, std::vector<bool>(correspondences.size(), true), camera, pose, T_F_C)) {
      frame.T_F_C = T_F_C;
    }
  }
}

}  // namespace

FrontendResult runFrontend(const Survey& survey, const FrontendOptions& options,
                           const FrontendProgress& progress) {
  options.validate();
  const PinholeRadtanCamera camera(survey.config.rgb.camera);
  const int frame_count = survey.rgb.frameCount();
  if (frame_count == 0) throw std::invalid_argument("runFrontend: the survey has no RGB frames");
  if (options.first_frame >= frame_count) {
    throw std::invalid_argument("FrontendOptions.first_frame " + std::to_string(options.first_frame) +
                                " is beyond the survey's " + std::to_string(frame_count) + " frames");
  }
  const int first = options.first_frame;
  const int last = options.last_frame < 0 ? frame_count - 1 : std::min(options.last_frame, frame_count - 1);
  const int total = last - first + 1;

  FrontendResult result;
  const auto start = std::chrono::steady_clock::now();
  FrameTracker tracker(options, camera);
  LampLightEstimate lamp_light;
  {
    if (options.correct_lamp_light) {
      lamp_light = estimateLampLight(survey.rgb, first, last, options, camera.width(), camera.height());
      char seconds[32];
      std::snprintf(seconds, sizeof(seconds), " (%.1f s)", lamp_light.seconds);
      result.lamp_light_note = lamp_light.note + seconds;
    } else {
      result.lamp_light_note = "lamp light not corrected (switched off)";
    }
    FramePrefetcher prefetcher(survey.rgb, options, camera.width(), camera.height(), first, last,
                               lamp_light.field);
    int done = 0;
    while (auto frame = prefetcher.next()) {
      if (!frame->error.empty()) {
        result.warnings.push_back("frame " + std::to_string(frame->index) + " (" +
                                  survey.rgb.framePath(frame->index).string() +
                                  ") could not be decoded: " + frame->error);
      }
      tracker.process(*frame);
      ++done;
      if (progress) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        progress(done, total, s > 0.0 ? done / s : 0.0);
      }
    }
  }
  tracker.finish();
  if (options.compensate_gain) {
    char note[160];
    std::snprintf(note, sizeof(note),
                  "gain steps compensated before tracking: %d frames (largest step %.2f dB)",
                  tracker.gainCompensatedFrames(), tracker.largestGainStepDb());
    result.gain_note = note;
  }
  if (tracker.segments().empty()) {
    std::ostringstream message;
    message << "the front-end never initialised on frames " << first << "-" << last
            << ": no two frames gave a sound start";
    for (const auto& attempt : tracker.initialisationAttempts()) message << "\n  " << attempt;
    if (tracker.initialisationAttempts().empty()) {
      message << "\n  no reference frame had enough texture (see the frames' reasons)";
    }
    throw std::runtime_error(message.str());
  }

  // Link segments (by vision where views overlap, else through the INS),
  // merge the joined landmarks, then put every frame in F through its keyframe.
  const SegmentGroups groups = joinSegmentsByVision(survey, tracker, options, camera, lamp_light.field);
  result.segments = linkSegments(survey, tracker, options, groups, result.warnings);
  moveIntoF(tracker.map(), result.segments);
  std::vector<int> merged_into;
  mergeVisionJoins(tracker.map(), tracker, result.segments, groups, camera, options, merged_into);
  std::vector<int> keyframe_remap, landmark_remap;
  result.map = linkedMap(tracker.map(), result.segments, keyframe_remap, landmark_remap);
  for (std::size_t l = 0; l < merged_into.size(); ++l) {
    int target = int(l);
    while (merged_into[std::size_t(target)] >= 0) target = merged_into[std::size_t(target)];
    if (target != int(l)) landmark_remap[l] = landmark_remap[std::size_t(target)];
  }
  std::map<int, std::string> reasons = tracker.lossReasons();
  result.frames = tracker.records();
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    FrameRecord& frame = result.frames[i];
    const FramePoseAnchor& anchor = tracker.anchors()[i];
    if (frame.keyframe) frame.keyframe_id = keyframe_remap[std::size_t(frame.keyframe_id)];
    if (!frame.posed) continue;
    const SegmentRecord& segment = result.segments[std::size_t(frame.segment)];
    if (!segment.linked || anchor.keyframe_id < 0) {
      frame.posed = false;
      frame.status = FrameStatus::lost;
      frame.keyframe = false;
      frame.keyframe_id = -1;
      reasons.emplace(frame.index, "segment " + std::to_string(segment.id) + " " + segment.note);
      continue;
    }
    // T_K_C is in the segment's units: its translation scales with S_F_S.
    const SE3d T_K_C(anchor.T_K_C.q, segment.S_F_S.scale() * anchor.T_K_C.t);
    frame.T_F_C = result.map.keyframe(keyframe_remap[std::size_t(anchor.keyframe_id)]).T_F_C * T_K_C;
  }
  result.frame_observations =
      linkedFrameObservations(tracker.takeFrameObservations(), landmark_remap, result.frames);
  reposeJoinedSegmentFrames(result, camera, options);
  result.losses = collectLosses(result.frames, reasons);
  for (const auto& frame : result.frames) {
    for (int s = 0; s < kFrontendStepCount; ++s) result.total_ms[std::size_t(s)] += frame.ms[std::size_t(s)];
  }
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.frames_per_second = result.wall_time_s > 0.0 ? total / result.wall_time_s : 0.0;
  result.peak_memory_mb = peakResidentMemoryMb();
  return result;
}

}  // namespace hsmap
