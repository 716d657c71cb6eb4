#include "core/survey/rgb_frame_check.h"

#include <exception>

#include "core/io/image_integrity.h"

namespace hsmap {
namespace {

std::string frameName(const RgbFrameSource& frames, int i) {
  std::string name = "RGB frame " + std::to_string(i);
  if (!frames.isVideo()) {
    name += " (" + frames.framePath(i).string() + ", " + frames.sourcePath().filename().string() + " line " +
            std::to_string(frames.frameLine(i)) + ")";
  } else {
    name += " of " + frames.sourcePath().string();
  }
  return name;
}

// Decodes frame i; the reason it cannot be, if any.
std::optional<std::string> decodeFailure(const RgbFrameSource& frames, int i) {
  try {
    if (frames.frame(i).empty()) return "it decodes to an empty image";
    return std::nullopt;
  } catch (const std::exception& error) {
    return std::string(error.what());
  }
}

constexpr const char* kBridged = "; the front-end will count it as a lost frame and bridge it";

}  // namespace

std::vector<std::string> checkRgbFramesWhole(const RgbFrameSource& frames) {
  std::vector<std::string> warnings;
  const int count = frames.frameCount();
  if (count == 0) return warnings;
  if (frames.isVideo()) {
    for (int i : {0, count - 1}) {
      if (const auto why = decodeFailure(frames, i)) {
        warnings.push_back(frameName(frames, i) + " cannot be decoded: " + *why +
                           (i == count - 1 ? " (a truncated file still reports its header's frame count)" : "") +
                           kBridged);
      }
      if (count == 1) break;
    }
    return warnings;
  }
  bool first_damaged = false;
  for (int i = 0; i < count; ++i) {
    if (const auto why = findImageDamage(frames.framePath(i))) {
      warnings.push_back(frameName(frames, i) + " is damaged: " + *why + kBridged);
      first_damaged = first_damaged || i == 0;
    }
  }
  if (!first_damaged) {
    if (const auto why = decodeFailure(frames, 0)) {
      warnings.push_back(frameName(frames, 0) + " cannot be decoded: " + *why + kBridged);
    }
  }
  return warnings;
}

}  // namespace hsmap
