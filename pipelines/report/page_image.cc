#include "pipelines/report/page_image.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/util/input_error.h"
#include "pipelines/report/base64_text.h"

namespace hsmap {

namespace {

// The page's image background (report.css: --image-background).
const cv::Vec3f kBackgroundBgr(40, 34, 30);

cv::Mat overBackground(const cv::Mat& bgra) {
  cv::Mat bgr(bgra.size(), CV_8UC3);
  for (int row = 0; row < bgra.rows; ++row) {
    for (int column = 0; column < bgra.cols; ++column) {
      const cv::Vec4b& p = bgra.at<cv::Vec4b>(row, column);
      const float alpha = p[3] / 255.0f;
      cv::Vec3b& out = bgr.at<cv::Vec3b>(row, column);
      for (int c = 0; c < 3; ++c) out[c] = cv::saturate_cast<uchar>(alpha * p[c] + (1 - alpha) * kBackgroundBgr[c]);
    }
  }
  return bgr;
}

}  // namespace

ReportImage encodePageImage(const cv::Mat& image, int max_side, std::string source) {
  if (image.empty() || image.depth() != CV_8U) {
    throw std::invalid_argument("encodePageImage: expected a non-empty 8-bit image for " + source);
  }
  ReportImage page;
  page.source = std::move(source);
  page.full_width = image.cols;
  page.full_height = image.rows;
  cv::Mat shown = image.channels() == 4 ? overBackground(image) : image;
  const int longer = std::max(shown.cols, shown.rows);
  if (longer > max_side) {
    const double factor = double(max_side) / longer;
    cv::Mat smaller;
    cv::resize(shown, smaller,
               cv::Size(std::max(1, int(std::lround(shown.cols * factor))), std::max(1, int(std::lround(shown.rows * factor)))),
               0, 0, cv::INTER_AREA);
    shown = smaller;
  }
  std::vector<uchar> bytes;
  if (!cv::imencode(".jpg", shown, bytes, {cv::IMWRITE_JPEG_QUALITY, kPageImageQuality})) {
    throw std::runtime_error("encodePageImage: JPEG encoding failed for " + page.source);
  }
  page.width = shown.cols;
  page.height = shown.rows;
  page.data_uri = "data:image/jpeg;base64," + base64Encode(std::string_view((const char*)bytes.data(), bytes.size()));
  return page;
}

ReportImage readPageImage(const std::filesystem::path& file, int max_side) {
  const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  if (image.empty() || image.depth() != CV_8U) {
    throw InputError(file, "", "expected an 8-bit PNG or JPEG image that can be decoded");
  }
  return encodePageImage(image, max_side, file.string());
}

}  // namespace hsmap
