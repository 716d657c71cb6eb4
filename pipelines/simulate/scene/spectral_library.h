#pragma once
// The simulator's spectral library: reflectance spectra of the five seabed
// materials ("endmembers") that the material field mixes.
//
// The spectra are smooth analytic curves (sums of logistic steps and Gaussian
// bands), shaped after the published look of each material, not measured:
//   sand      bright (0.25 at 400 nm to 0.46 at 800 nm), slowly rising;
//   sediment  dark and brownish: 0.06 in the blue rising to 0.18 in the NIR;
//   rock      grey and nearly flat (0.145-0.155), a shallow iron dip near 900 nm;
//   coral     low in the blue (0.03 below 500 nm), a steep rise near 570 nm to an
//             orange-red maximum (~0.3 at 620-650 nm), a pigment (chlorophyll
//             of symbionts) absorption band at 675 nm, falling slowly beyond;
//   algae     dark with chlorophyll absorption near 440 and 675 nm, a green
//             bump at 555 nm (0.07) and a red edge above 700 nm (0.4 in the NIR).
// They are distinguishable by shape, not only by brightness: every pair is more
// than 8 degrees apart in spectral angle over 400-800 nm (closest: sand and
// rock, 8.6 degrees; the unmixing and evaluation stages rely on this and the
// tests check it).
//
// Domain and range: defined for wavelengths in [350, 1000] nm (outside it
// std::invalid_argument); values lie strictly inside (0, 1), and the curves
// change by less than 0.01 per nm.

namespace hsmap {

enum class Endmember { sand, sediment, rock, coral, algae };
constexpr int kEndmemberCount = 5;

inline constexpr double kSpectralLibraryMinNm = 350.0;
inline constexpr double kSpectralLibraryMaxNm = 1000.0;

// "sand", "sediment", "rock", "coral", "algae".
const char* endmemberName(Endmember endmember);

// Reflectance (0..1, unitless) of `endmember` at `wavelength_nm`.
double endmemberReflectance(Endmember endmember, double wavelength_nm);

}  // namespace hsmap
