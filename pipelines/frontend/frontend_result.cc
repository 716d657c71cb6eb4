#include "pipelines/frontend/frontend_result.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace hsmap {

const char* toString(FrameStatus status) {
  switch (status) {
    case FrameStatus::tracking: return "tracking";
    case FrameStatus::initialising: return "initialising";
    case FrameStatus::lost: return "lost";
    case FrameStatus::no_texture: return "no_texture";
    case FrameStatus::undecodable: return "undecodable";
  }
  return "?";
}

FrameStatus parseFrameStatus(const std::string& name) {
  for (FrameStatus s : {FrameStatus::tracking, FrameStatus::initialising, FrameStatus::lost,
                        FrameStatus::no_texture, FrameStatus::undecodable}) {
    if (name == toString(s)) return s;
  }
  throw std::invalid_argument("unknown frame status '" + name +
                              "': expected tracking, initialising, lost, no_texture or undecodable");
}

const char* toString(SegmentLink link) {
  switch (link) {
    case SegmentLink::reference: return "reference";
    case SegmentLink::vision: return "vision";
    case SegmentLink::ins: return "ins";
    case SegmentLink::none: return "none";
  }
  return "?";
}

SegmentLink parseSegmentLink(const std::string& name) {
  for (SegmentLink l : {SegmentLink::reference, SegmentLink::vision, SegmentLink::ins, SegmentLink::none}) {
    if (name == toString(l)) return l;
  }
  throw std::invalid_argument("unknown segment link '" + name + "': expected reference, vision, ins or none");
}

const char* toString(FrontendStep step) {
  switch (step) {
    case FrontendStep::decode: return "decode";
    case FrontendStep::preprocess: return "preprocess";
    case FrontendStep::track: return "track";
    case FrontendStep::detect: return "detect";
    case FrontendStep::pnp: return "pnp";
    case FrontendStep::triangulate: return "triangulate";
    case FrontendStep::ba: return "ba";
    case FrontendStep::count: break;
  }
  return "?";
}

std::span<const FrameObservation> FrontendResult::observationsOfFrame(int frame) const {
  const auto first = std::lower_bound(frame_observations.begin(), frame_observations.end(), frame,
                                      [](const FrameObservation& o, int f) { return o.frame < f; });
  const auto last = std::upper_bound(first, frame_observations.end(), frame,
                                     [](int f, const FrameObservation& o) { return f < o.frame; });
  return {first, last};
}

int FrontendResult::posedFrameCount() const {
  return int(std::count_if(frames.begin(), frames.end(), [](const FrameRecord& f) { return f.posed; }));
}

double FrontendResult::trackingFramesPerSecond() const {
  double ms = 0.0;
  for (FrontendStep step : {FrontendStep::track, FrontendStep::detect, FrontendStep::pnp,
                            FrontendStep::triangulate, FrontendStep::ba}) {
    ms += total_ms[std::size_t(step)];
  }
  return ms > 0.0 ? 1000.0 * double(frames.size()) / ms : 0.0;
}

std::string FrontendResult::summary() const {
  std::ostringstream text;
  char speed[64];
  std::snprintf(speed, sizeof(speed), "%.1f frames/s (tracking alone %.1f)", frames_per_second,
                trackingFramesPerSecond());
  text << "front-end: " << posedFrameCount() << " of " << frames.size() << " frames posed, "
       << map.keyframes().size() << " keyframes, " << map.validLandmarkCount() << " landmarks, "
       << map.observationCount() << " observations, " << frame_observations.size()
       << " frame observations, " << segments.size()
       << (segments.size() == 1 ? " segment, " : " segments, ") << losses.size()
       << (losses.size() == 1 ? " tracking loss" : " tracking losses") << "; " << speed;
  char memory[64];
  std::snprintf(memory, sizeof(memory), ", peak memory %.0f MB", peak_memory_mb);
  text << memory;
  if (!lamp_light_note.empty()) text << "\n  " << lamp_light_note;
  if (!gain_note.empty()) text << "\n  " << gain_note;
  for (const auto& loss : losses) {
    text << "\n  lost frames " << loss.first_frame << "-" << loss.last_frame << ": " << loss.reason;
  }
  for (const auto& segment : segments) {
    text << "\n  segment " << segment.id << " (frames " << segment.first_frame << "-"
         << segment.last_frame << ", " << segment.keyframes << " keyframes): " << segment.note;
  }
  char steps[256];
  std::snprintf(steps, sizeof(steps),
                "\n  time per frame (ms): decode %.1f, preprocess %.1f, track %.1f, detect %.1f, "
                "pnp %.1f, triangulate %.1f, ba %.1f",
                total_ms[0] / std::max<std::size_t>(1, frames.size()),
                total_ms[1] / std::max<std::size_t>(1, frames.size()),
                total_ms[2] / std::max<std::size_t>(1, frames.size()),
                total_ms[3] / std::max<std::size_t>(1, frames.size()),
                total_ms[4] / std::max<std::size_t>(1, frames.size()),
                total_ms[5] / std::max<std::size_t>(1, frames.size()),
                total_ms[6] / std::max<std::size_t>(1, frames.size()));
  text << steps;
  return text.str();
}

}  // namespace hsmap
