#include "pipelines/simulate/rgb_radiance_table.h"

#include <algorithm>
#include <cmath>

#include "pipelines/simulate/underwater_optics.h"

namespace hsmap {

RgbRadianceTable::RgbRadianceTable(double turbidity, double max_path_m, double step_m)
    : step_m_(step_m) {
  // 5 nm steps over the sensitivities' support.
  std::vector<double> wavelengths;
  for (double nm = 380.0; nm <= 720.0; nm += 5.0) wavelengths.push_back(nm);
  const int count = static_cast<int>(wavelengths.size());
  Eigen::MatrixXd weight(3, count);  // S_k I d lambda
  Eigen::MatrixXd reflectance(count, kEndmemberCount + 1);
  Eigen::VectorXd attenuation(count);
  for (int i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) {
      weight(k, i) = rgbResponse(k, wavelengths[i]) * lampSpectrum(wavelengths[i]) * 5.0;
    }
    for (int m = 0; m < kEndmemberCount; ++m) {
      reflectance(i, m) = endmemberReflectance(static_cast<Endmember>(m), wavelengths[i]);
    }
    reflectance(i, kEndmemberCount) = 1.0;
    attenuation[i] = waterAttenuationPerM(wavelengths[i], turbidity);
  }
  const int entries = static_cast<int>(std::ceil(max_path_m / step_m)) + 1;
  entries_.resize(entries);
  for (int e = 0; e < entries; ++e) {
    const double path = e * step_m;
    Eigen::MatrixXd transmitted = reflectance;
    for (int i = 0; i < count; ++i) transmitted.row(i) *= std::exp(-attenuation[i] * path);
    entries_[e] = (weight * transmitted).cast<float>();
  }
}

RgbRadianceTable::Entry RgbRadianceTable::at(double path_m) const {
  const double position = std::clamp(path_m / step_m_, 0.0, double(entries_.size() - 1));
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(position), entries_.size() - 2);
  const float w = static_cast<float>(position - double(i));
  return (1.0f - w) * entries_[i] + w * entries_[i + 1];
}

}  // namespace hsmap
