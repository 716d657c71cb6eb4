#include "core/survey/ins_jump_check.h"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

constexpr double kImpossibleDistanceM = 1000.0;
constexpr double kImpossibleSpeedMps = 50.0;
constexpr double kVehicleSpeedMps = 3.0;
constexpr double kNoiseMultiple = 6.0;
constexpr double kMinAllowanceM = 1.0;
constexpr std::size_t kWarningsListed = 5;

std::string number(double value, const char* format) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string jumpText(const char* what, double metres, double dt) {
  return std::string(what) + " jumps " + number(metres, "%.1f") + " m in " +
         number(dt, "%.3f") + " s from the previous fix (" + number(metres / dt, "%.3g") +
         " m/s)";
}

}  // namespace

std::vector<std::string> checkInsJumps(const InsTable& ins, const std::filesystem::path& file,
                                       double sigma_horizontal_m, double sigma_depth_m) {
  const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
  const double horizontal_allowance = std::max(kMinAllowanceM, kNoiseMultiple * sigma_horizontal_m);
  const double depth_allowance = std::max(kMinAllowanceM, kNoiseMultiple * sigma_depth_m);
  std::vector<std::string> suspicious;
  for (std::size_t i = 1; i < ins.fixes.size(); ++i) {
    const InsFix& a = ins.fixes[i - 1];
    const InsFix& b = ins.fixes[i];
    const double dt = b.t - a.t;  // > 0: the reader checked time order
    double horizontal = 0.0;
    geodesic.Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, horizontal);
    const double vertical = std::abs(b.depth_m - a.depth_m);
    const std::string where = InputError::atLine(b.line_number);
    for (const auto& [what, metres] :
         {std::pair{"the position", horizontal}, std::pair{"the depth", vertical}}) {
      if (metres > kImpossibleDistanceM && metres / dt > kImpossibleSpeedMps) {
        throw InputError(file, where,
                         jumpText(what, metres, dt) +
                             "; expected a vehicle's track (no underwater vehicle or acoustic "
                             "fix moves more than 1 km at over 50 m/s)");
      }
    }
    const bool horizontal_jump = horizontal > kVehicleSpeedMps * dt + horizontal_allowance;
    const bool depth_jump = vertical > kVehicleSpeedMps * dt + depth_allowance;
    if (horizontal_jump || depth_jump) {
      suspicious.push_back(file.string() + ":" + where + ": " +
                           jumpText(horizontal_jump ? "the position" : "the depth",
                                    horizontal_jump ? horizontal : vertical, dt));
    }
  }
  std::vector<std::string> warnings;
  for (std::size_t k = 0; k < std::min(suspicious.size(), kWarningsListed); ++k) {
    warnings.push_back(suspicious[k] +
                       ", more than a vehicle moves; geo-referencing will treat it as an outlier");
  }
  if (suspicious.size() > kWarningsListed) {
    warnings.push_back(file.string() + ": " + std::to_string(suspicious.size() - kWarningsListed) +
                       " more INS jumps like those above");
  }
  return warnings;
}

}  // namespace hsmap
