#include "pipelines/georef/georef_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace hsmap {

void GeorefOptions::validate() const {
  auto check = [](const char* name, double value, bool ok, const char* expected) {
    if (!ok || !std::isfinite(value)) {
      throw std::invalid_argument(std::string("GeorefOptions::") + name + ": expected " + expected + ", got " +
                                  std::to_string(value));
    }
  };
  check("max_vision_gap_s", max_vision_gap_s, max_vision_gap_s > 0.0, "a time > 0 s");
  check("ins_correlation_time_s", ins_correlation_time_s, ins_correlation_time_s >= 0.0,
        "a time >= 0 s (0: independent fixes)");
  check("heading_window_s", heading_window_s, heading_window_s > 0.0, "a time > 0 s");
}

}  // namespace hsmap
