#include "pipelines/simulate/scene/spectral_library.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

namespace {

// Smooth 0 -> 1 step centred on `centre_nm`, `width_nm` wide (a quarter of the
// 10-90% rise).
double rise(double wavelength_nm, double centre_nm, double width_nm) {
  return 1.0 / (1.0 + std::exp(-(wavelength_nm - centre_nm) / width_nm));
}

// Gaussian band of unit height.
double band(double wavelength_nm, double centre_nm, double sigma_nm) {
  const double x = (wavelength_nm - centre_nm) / sigma_nm;
  return std::exp(-0.5 * x * x);
}

double sand(double w) { return 0.17 + 0.27 * rise(w, 470.0, 75.0) + 0.03 * (w - 350.0) / 650.0; }

double sediment(double w) {
  return 0.05 + 0.14 * rise(w, 610.0, 65.0) + 0.008 * band(w, 560.0, 60.0);
}

double rock(double w) { return 0.145 + 0.015 * (w - 350.0) / 650.0 - 0.012 * band(w, 900.0, 80.0); }

double coral(double w) {
  // Orange-red plateau that sags beyond 700 nm, with carotenoid (500 nm) and
  // chlorophyll (675 nm) absorption.
  const double plateau = 0.30 * rise(w, 570.0, 18.0) * (1.0 - 0.35 * rise(w, 700.0, 35.0));
  return 0.03 + plateau - 0.09 * band(w, 675.0, 13.0) - 0.01 * band(w, 500.0, 20.0);
}

double algae(double w) {
  return 0.02 + 0.05 * band(w, 555.0, 30.0) + 0.012 * band(w, 600.0, 25.0) -
         0.012 * band(w, 440.0, 22.0) - 0.015 * band(w, 675.0, 12.0) + 0.38 * rise(w, 715.0, 11.0);
}

}  // namespace

const char* endmemberName(Endmember endmember) {
  switch (endmember) {
    case Endmember::sand: return "sand";
    case Endmember::sediment: return "sediment";
    case Endmember::rock: return "rock";
    case Endmember::coral: return "coral";
    case Endmember::algae: return "algae";
  }
  return "unknown";
}

double endmemberReflectance(Endmember endmember, double wavelength_nm) {
  if (!(wavelength_nm >= kSpectralLibraryMinNm && wavelength_nm <= kSpectralLibraryMaxNm)) {
    std::ostringstream message;
    message << "endmemberReflectance: wavelength must be in [" << kSpectralLibraryMinNm << ", "
            << kSpectralLibraryMaxNm << "] nm, got " << wavelength_nm;
    throw std::invalid_argument(message.str());
  }
  switch (endmember) {
    case Endmember::sand: return sand(wavelength_nm);
    case Endmember::sediment: return sediment(wavelength_nm);
    case Endmember::rock: return rock(wavelength_nm);
    case Endmember::coral: return coral(wavelength_nm);
    case Endmember::algae: return algae(wavelength_nm);
  }
  throw std::invalid_argument("endmemberReflectance: unknown endmember");
}

}  // namespace hsmap
