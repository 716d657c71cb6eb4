#pragma once
// The absorption coefficient of pure water, a_w(λ), in 1/m: the floor of any
// natural water's attenuation c(λ) (dissolved matter and particles only add
// to it). The radiometry stage's prior on c(λ) is centred a little above it
// (water_estimation.h), so that a band the survey does not determine falls
// back on physics rather than wandering.
//
// Values: Smith & Baker (1981), "Optical properties of the clearest natural
// waters (200–800 nm)", Applied Optics 20(2), 177–184, Table 1, every 10 nm
// from 380 to 800 nm, interpolated linearly; held at the end values outside
// that range.

namespace hsmap {

double pureWaterAbsorptionPerM(double wavelength_nm);

}  // namespace hsmap
