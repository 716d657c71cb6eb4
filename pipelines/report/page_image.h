#pragma once
// An image made ready for the report page: shrunk (never enlarged) so that
// its longer side is at most `max_side` pixels, by area averaging, with any
// transparency (where a product has no data) laid over the page's dark
// background, and encoded as a JPEG data: URI. JPEG, not PNG: ortho-images
// are photographs of the seabed, and at quality 88 they are several times
// smaller for no difference visible on the page.

#include <opencv2/core.hpp>
#include <string>

#include "pipelines/report/report_data.h"

namespace hsmap {

inline constexpr int kPageImageQuality = 88;

// `image`: 8-bit grey, BGR or BGRA (OpenCV's order). `source` names what it shows.
ReportImage encodePageImage(const cv::Mat& image, int max_side, std::string source);

// The image file `file` (PNG, JPEG) read and encoded as above.
// InputError naming the file when it cannot be read as an image.
ReportImage readPageImage(const std::filesystem::path& file, int max_side);

}  // namespace hsmap
