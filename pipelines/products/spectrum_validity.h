#pragma once
// Which samples of one scan line have a usable spectrum, the rule shared by
// every product cast from the cube (ortho-image, point cloud): a sample is
// NON-FINITE if any of its bands is NaN or infinite, else IGNORED if any band
// equals the cube header's `data ignore value`. Such samples are counted and
// left out, never painted or averaged as numbers.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/io/envi_reader.h"

namespace hsmap {

// `pixel_major`: one line as EnviReader::readLinePixelMajor gives it, samples
// x bands (each sample's spectrum contiguous), decoded from a cube of data
// type `stored` (an integer type holds no NaN or infinity, so its values
// are not scanned for them: with no ignore value either, nothing is read).
// Writes one flag per sample into non_finite and ignored (1 = yes).
void markInvalidSamples(const float* pixel_major, int bands, int samples, EnviDataType stored,
                        std::optional<float> ignore, std::uint8_t* non_finite, std::uint8_t* ignored);

// The inputs every product cast from the cube needs to agree on: one
// wavelength per band and the UHI camera's samples equal to the cube's.
// std::invalid_argument starting with `who` otherwise.
void requireCubeMatches(const std::string& who, const EnviReader& cube,
                        const std::vector<double>& wavelengths_nm, const PushbroomCamera& camera);

}  // namespace hsmap
