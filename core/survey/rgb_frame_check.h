#pragma once
// checkRgbFramesWhole: every RGB frame of a survey checked whole, for
// `hsmap inspect`, at the cost of reading each file once.
//
// Loading a survey reads each frame's header only (rgb_frame_source.h), so
// a frame cut short or with changed bytes is found when the front-end
// decodes it, and the run then bridges it as a lost frame. inspect says so
// first, one warning per damaged frame:
//   image list  each file read through (image_integrity.h: the PNG chunks and
//               their CRCs, the JPEG end-of-image marker), and the first frame
//               decoded in full (what a CRC cannot see: a stream that zlib or
//               the JPEG decoder refuses);
//   video       its first and last frames decoded (a truncated file still
//               reports the frame count of its header).
// The warnings name the frame, its file and frames.csv line, and why.

#include <string>
#include <vector>

#include "core/survey/rgb_frame_source.h"

namespace hsmap {

std::vector<std::string> checkRgbFramesWhole(const RgbFrameSource& frames);

}  // namespace hsmap
