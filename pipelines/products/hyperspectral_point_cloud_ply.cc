#include "pipelines/products/hyperspectral_point_cloud_ply.h"

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/util/input_error.h"

namespace hsmap {

namespace {

constexpr int kCountDigits = 12;
constexpr std::size_t kBufferBytes = std::size_t(4) << 20;

std::string bandName(int band) {
  char name[16];
  std::snprintf(name, sizeof(name), "b%03d", band);
  return name;
}

std::string formatNumber(double value, int digits = 17) {
  std::ostringstream text;
  text.precision(digits);
  text << value;
  return text.str();
}

template <typename T>
void append(std::vector<char>& out, const T& value) {
  static_assert(std::endian::native == std::endian::little, "the PLY is little-endian");
  const auto* bytes = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

}  // namespace

HyperspectralPointCloudWriter::HyperspectralPointCloudWriter(const std::filesystem::path& path,
                                                             const std::vector<double>& wavelengths_nm,
                                                             double cell_m, const GeodeticPoint& origin)
    : file_(path), bands_(int(wavelengths_nm.size())) {
  if (wavelengths_nm.empty()) throw std::invalid_argument("hyperspectral point cloud: no wavelengths");
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\n"
         << "comment hsmap hyperspectral point cloud: UHI hits binned into cubes of " << formatNumber(cell_m)
         << " m, mean position and mean spectrum\n"
         << "comment frame W: local north-east-down in metres (x north, y east, z down) at lat "
         << formatNumber(origin.lat_deg) << " lon " << formatNumber(origin.lon_deg) << " depth "
         << formatNumber(origin.depth_m) << "\n";
  for (int b = 0; b < bands_; ++b) {
    header << "comment band " << bandName(b) << " wavelength_nm " << formatNumber(wavelengths_nm[std::size_t(b)])
           << "\n";
  }
  header << "element vertex ";
  const std::string before_count = header.str();
  header << std::string(kCountDigits, '0') << "\n"
         << "property double x\nproperty double y\nproperty double z\nproperty uint hits\n";
  for (int b = 0; b < bands_; ++b) header << "property float " << bandName(b) << "\n";
  header << "end_header\n";
  const std::string text = header.str();
  count_offset_ = std::streamoff(before_count.size());
  header_bytes_ = std::int64_t(text.size());
  file_.stream().write(text.data(), std::streamsize(text.size()));
  buffer_.reserve(kBufferBytes + 64 + std::size_t(bands_) * 4);
}

std::int64_t HyperspectralPointCloudWriter::bytes() const {
  return header_bytes_ + points_ * (28 + 4 * std::int64_t(bands_));
}

void HyperspectralPointCloudWriter::write(const CellPoint& point) {
  append(buffer_, point.p_W.x());
  append(buffer_, point.p_W.y());
  append(buffer_, point.p_W.z());
  append(buffer_, std::uint32_t(point.hits));
  const auto* bytes = reinterpret_cast<const char*>(point.spectrum);
  buffer_.insert(buffer_.end(), bytes, bytes + std::size_t(bands_) * sizeof(float));
  ++points_;
  if (buffer_.size() >= kBufferBytes) flushBuffer();
}

void HyperspectralPointCloudWriter::flushBuffer() {
  file_.stream().write(buffer_.data(), std::streamsize(buffer_.size()));
  buffer_.clear();
  if (!file_.stream()) {
    throw std::runtime_error("cannot write " + file_.partialPath().string() + ": " + std::strerror(errno));
  }
}

void HyperspectralPointCloudWriter::commit() {
  flushBuffer();
  char count[kCountDigits + 1];
  std::snprintf(count, sizeof(count), "%0*lld", kCountDigits, static_cast<long long>(points_));
  std::ofstream& stream = file_.stream();
  stream.seekp(count_offset_);
  stream.write(count, kCountDigits);
  stream.seekp(0, std::ios::end);
  file_.commit();
}

HyperspectralPointCloud readHyperspectralPointCloud(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file");
  HyperspectralPointCloud cloud;
  auto fail = [&](const std::string& what) { throw InputError(path, "header", what); };
  std::string line;
  std::int64_t count = -1;
  std::vector<std::string> properties;
  if (!std::getline(in, line) || line != "ply") fail("expected 'ply' on the first line");
  if (!std::getline(in, line) || line != "format binary_little_endian 1.0") {
    fail("expected 'format binary_little_endian 1.0'");
  }
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, a, b;
    words >> word;
    if (word == "comment") {
      words >> a;
      if (a == "band") {
        double nm = 0.0;
        if (!(words >> a >> b >> nm) || a != bandName(cloud.bands()) || b != "wavelength_nm") {
          fail("bad band comment '" + line + "'");
        }
        cloud.wavelengths_nm.push_back(nm);
      } else if (a == "hsmap") {
        const auto at = line.find("cubes of ");
        if (at != std::string::npos) cloud.cell_m = std::stod(line.substr(at + 9));
      }
    } else if (word == "element") {
      if (!(words >> a >> count) || a != "vertex" || count < 0) fail("bad element line '" + line + "'");
    } else if (word == "property") {
      if (!(words >> a >> b)) fail("bad property line '" + line + "'");
      properties.push_back(a + " " + b);
    } else {
      fail("unexpected line '" + line + "'");
    }
  }
  if (line != "end_header") fail("no end_header");
  if (count < 0) fail("no 'element vertex'");
  std::vector<std::string> expected = {"double x", "double y", "double z", "uint hits"};
  for (int b = 0; b < cloud.bands(); ++b) expected.push_back("float " + bandName(b));
  if (properties != expected) fail("expected the properties x y z (double), hits (uint), b000... (float)");
  const std::size_t bands = std::size_t(cloud.bands());
  const std::size_t record = 28 + 4 * bands;
  std::vector<char> data(record);
  cloud.p_W.resize(std::size_t(count));
  cloud.hits.resize(std::size_t(count));
  cloud.spectra.resize(std::size_t(count) * bands);
  for (std::int64_t i = 0; i < count; ++i) {
    if (!in.read(data.data(), std::streamsize(record))) {
      throw InputError(path, "point " + std::to_string(i), "the file ends before the " + std::to_string(count) +
                                                               " points of its header");
    }
    std::memcpy(cloud.p_W[std::size_t(i)].data(), data.data(), 24);
    std::memcpy(&cloud.hits[std::size_t(i)], data.data() + 24, 4);
    std::memcpy(&cloud.spectra[std::size_t(i) * bands], data.data() + 28, 4 * bands);
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    throw InputError(path, "", "bytes after the " + std::to_string(count) + " points of its header");
  }
  return cloud;
}

}  // namespace hsmap
