#include "pipelines/radiometry/pure_water_absorption.h"

#include <array>
#include <cmath>

namespace hsmap {

namespace {

constexpr double kFirstNm = 380.0;
constexpr double kStepNm = 10.0;
// Smith & Baker (1981), Table 1, a_w in 1/m at 380, 390, ..., 800 nm.
constexpr std::array<double, 43> kAbsorption = {
    0.0220, 0.0191, 0.0171, 0.0162, 0.0153, 0.0144, 0.0145, 0.0145, 0.0156, 0.0156, 0.0176,
    0.0196, 0.0257, 0.0357, 0.0477, 0.0507, 0.0558, 0.0638, 0.0708, 0.0799, 0.108,  0.157,
    0.244,  0.289,  0.309,  0.319,  0.329,  0.349,  0.400,  0.430,  0.450,  0.500,  0.650,
    0.839,  1.169,  1.799,  2.38,   2.47,   2.55,   2.51,   2.36,   2.16,   2.07};

}  // namespace

double pureWaterAbsorptionPerM(double wavelength_nm) {
  const double f = (wavelength_nm - kFirstNm) / kStepNm;
  if (!(f > 0.0)) return kAbsorption.front();
  if (f >= double(kAbsorption.size() - 1)) return kAbsorption.back();
  const std::size_t i = std::size_t(std::floor(f));
  const double t = f - double(i);
  return kAbsorption[i] * (1.0 - t) + kAbsorption[i + 1] * t;
}

}  // namespace hsmap
