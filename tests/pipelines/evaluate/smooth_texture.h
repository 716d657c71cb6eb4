#pragma once
// A smooth random texture defined in W for the ortho-metric tests: white
// noise on a 2.5 mm lattice blurred by a Gaussian of 1 cm (little energy
// beyond the 5 mm pixels' Nyquist frequency, so that two grids do not alias
// it differently), normalised to mean 0 and standard deviation 1, bilinear
// in between. Broadband, so phase correlation has one clear peak (a sum of
// a few sinusoids would not).
#include <algorithm>
#include <cmath>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace hsmap::testing {

class SmoothTexture {
 public:
  // Covers north [north0, north0 + rows * 2.5 mm) x east [east0, east0 + cols * 2.5 mm).
  SmoothTexture(unsigned seed, double north0, double east0, int rows, int cols)
      : north0_(north0), east0_(east0), rows_(rows), cols_(cols) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    lattice_.create(rows, cols, CV_32F);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) lattice_.at<float>(r, c) = noise(rng);
    }
    cv::GaussianBlur(lattice_, lattice_, cv::Size(0, 0), 4.0);
    cv::Scalar mean, sd;
    cv::meanStdDev(lattice_, mean, sd);
    lattice_ = (lattice_ - mean[0]) / sd[0];
  }

  // At (north, east) in W; clamped to the lattice's edge outside it.
  double operator()(double north, double east) const {
    const double u = (east - east0_) / kCell, v = (north - north0_) / kCell;
    const int c = std::clamp(static_cast<int>(std::floor(u)), 0, cols_ - 2);
    const int r = std::clamp(static_cast<int>(std::floor(v)), 0, rows_ - 2);
    const double fu = u - c, fv = v - r;
    const auto at = [&](int rr, int cc) { return static_cast<double>(lattice_.at<float>(rr, cc)); };
    return (1 - fv) * ((1 - fu) * at(r, c) + fu * at(r, c + 1)) +
           fv * ((1 - fu) * at(r + 1, c) + fu * at(r + 1, c + 1));
  }

 private:
  static constexpr double kCell = 0.0025;
  double north0_, east0_;
  int rows_, cols_;
  cv::Mat lattice_;
};

}  // namespace hsmap::testing
