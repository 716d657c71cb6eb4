#include "pipelines/frontend/frontend_runner.h"

#include <chrono>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/util/stage_timer.h"
#include "pipelines/frontend/frame_prefetcher.h"
#include "pipelines/frontend/frame_tracker.h"
#include "pipelines/frontend/lamp_light_field.h"
#include "pipelines/frontend/segment_linker.h"
#include "pipelines/frontend/tracking_loss_monitor.h"

namespace hsmap {

namespace {

std::string formatMetres(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f m", value);
  return text;
}

// Decides which segments are linked into F and how (S_F_S per segment).
std::vector<SegmentRecord> linkSegments(const Survey& survey, const FrameTracker& tracker,
                                        const FrontendOptions& options, std::vector<std::string>& warnings) {
  const auto& spans = tracker.segments();
  std::vector<SegmentRecord> segments;
  for (const auto& span : spans) {
    SegmentRecord record;
    record.id = span.id;
    record.first_frame = span.first_frame;
    record.last_frame = span.last_frame;
    record.keyframes = int(span.keyframe_ids.size());
    segments.push_back(record);
  }
  if (segments.size() == 1) {
    segments[0].reference = segments[0].linked = true;
    segments[0].note = "reference segment (its frame is F)";
    return segments;
  }
  if (segments.empty()) return segments;

  std::vector<SegmentFit> fits(spans.size());
  if (survey.ins.fixes.empty()) {
    for (auto& fit : fits) fit.failure = "the survey has no INS";
  } else {
    const InsBodyTrack ins(survey, kSegmentLinkerInsOptions);
    const SE3d T_B_C(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m);
    for (std::size_t s = 0; s < spans.size(); ++s) {
      std::vector<double> times;
      std::vector<SE3d> poses;
      for (int k : spans[s].keyframe_ids) {
        times.push_back(tracker.map().keyframe(k).t);
        poses.push_back(tracker.map().keyframe(k).T_F_C);
      }
      fits[s] = fitSegmentToIns(times, poses, ins, T_B_C, options.min_segment_keyframes);
    }
  }
  int reference = -1;
  for (std::size_t s = 0; s < fits.size(); ++s) {
    if (fits[s].ok) {
      reference = int(s);
      break;
    }
  }
  if (reference < 0) {
    // Nothing can be linked: keep the longest segment alone.
    reference = 0;
    for (std::size_t s = 1; s < segments.size(); ++s) {
      if (segments[s].keyframes > segments[std::size_t(reference)].keyframes) reference = int(s);
    }
    for (std::size_t s = 0; s < segments.size(); ++s) {
      if (int(s) == reference) continue;
      segments[s].note = "not linked: " + fits[s].failure + "; no segment could be fitted to the INS";
      warnings.push_back("segment " + std::to_string(s) + " (frames " +
                         std::to_string(segments[s].first_frame) + "-" +
                         std::to_string(segments[s].last_frame) + ") " + segments[s].note);
    }
    segments[std::size_t(reference)].reference = segments[std::size_t(reference)].linked = true;
    segments[std::size_t(reference)].note = "reference segment (its frame is F); the others could not be linked";
    return segments;
  }
  const Sim3 S_F_W = fits[std::size_t(reference)].S_W_S.inverse();
  for (std::size_t s = 0; s < segments.size(); ++s) {
    SegmentRecord& segment = segments[s];
    segment.ins_rms_m = fits[s].ok ? fits[s].rms_m : 0.0;
    if (int(s) == reference) {
      segment.reference = segment.linked = true;
      segment.note = "reference segment (its frame is F); INS fit rms " + formatMetres(fits[s].rms_m);
      continue;
    }
    if (!fits[s].ok) {
      segment.note = "not linked: " + fits[s].failure;
      warnings.push_back("segment " + std::to_string(s) + " (frames " + std::to_string(segment.first_frame) +
                         "-" + std::to_string(segment.last_frame) + ") " + segment.note +
                         "; its frames are reported lost");
      continue;
    }
    segment.linked = true;
    segment.S_F_S = S_F_W * fits[s].S_W_S;
    std::ostringstream note;
    note << "linked into F through the INS (fit rms " << formatMetres(fits[s].rms_m)
         << ", reference fit rms " << formatMetres(fits[std::size_t(reference)].rms_m) << ", scale "
         << segment.S_F_S.scale() << ")";
    segment.note = note.str();
  }
  return segments;
}

// The map of the linked segments, expressed in F, with dense new ids
// (keyframe_remap, landmark_remap: old id -> new id, -1 when dropped).
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
    copy.p_F = segment.S_F_S.apply(l.p_F);
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
    copy.T_F_C = segment.S_F_S.transformPose(k.T_F_C);
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
  for (const FrameObservation& o : observations) {
    if (o.frame >= int(posed.size()) || !posed[std::size_t(o.frame)]) continue;
    const int l = landmark_remap[std::size_t(o.landmark)];
    if (l < 0) continue;
    observations[kept++] = {o.frame, l, o.u, o.v};
  }
  observations.resize(kept);
  return observations;
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
  {
    LampLightEstimate lamp_light;
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

  // Link segments, then put every frame in F through its keyframe.
  result.segments = linkSegments(survey, tracker, options, result.warnings);
  std::vector<int> keyframe_remap, landmark_remap;
  result.map = linkedMap(tracker.map(), result.segments, keyframe_remap, landmark_remap);
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
    const SE3d T_S_C = tracker.map().keyframe(anchor.keyframe_id).T_F_C * anchor.T_K_C;
    frame.T_F_C = segment.S_F_S.transformPose(T_S_C);
  }
  result.frame_observations =
      linkedFrameObservations(tracker.takeFrameObservations(), landmark_remap, result.frames);
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
