#include "pipelines/compare/image_data_uri.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <vector>

namespace hsmap {

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t word = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      word = (word << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    }
    for (std::size_t k = 0; k < 4; ++k) {
      text += k <= n ? kDigits[(word >> (18 - 6 * k)) & 63u] : '=';
    }
  }
  return text;
}

std::string imageDataUri(const std::filesystem::path& image, int max_side) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(image, error)) return {};
  cv::Mat pixels = cv::imread(image.string(), cv::IMREAD_UNCHANGED);
  if (pixels.empty()) return {};
  const int longer = std::max(pixels.cols, pixels.rows);
  if (longer > max_side) {
    const double scale = double(max_side) / longer;
    cv::Mat smaller;
    cv::resize(pixels, smaller, cv::Size(), scale, scale, cv::INTER_AREA);
    pixels = smaller;
  }
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", pixels, png)) return {};
  return "data:image/png;base64," +
         base64(std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace hsmap
