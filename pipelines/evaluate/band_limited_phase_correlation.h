#pragma once
// Phase correlation with a low-pass weight on the normalised cross-power
// spectrum (ortho_metrics.h, registration patches).
//
// Plain phase correlation (cv::phaseCorrelate) whitens the cross-power
// spectrum: every frequency counts as much as any other, so linear filtering
// of both images changes nothing, and frequencies where the two images are
// not the same signal weigh as much as those where they are. Between a
// produced ortho-image (means of push-broom samples spaced ~1-15 mm apart)
// and a point-sampled true reflectance raster with pixel-scale speckle, those
// frequencies are the finest ones: on the simulator's rugged scene, plain
// phase correlation of an ortho-image cast from the TRUE poses onto the TRUE
// surface scatters by ~7 mm per 0.3 m patch, spatially uncorrelated (the
// product's error is ~0 there), which is the metric's noise, not the map's.
//
// Here the whitened cross-power spectrum is multiplied by
//   G(f) = exp(-(f * cutoff_px)^2 / 2),  f in cycles per pixel,
// i.e. the correlation surface is smoothed by a Gaussian of sigma
// cutoff_px / (2 pi) pixels: wavelengths shorter than cutoff_px count less,
// the alignment of the structures both images resolve decides. cutoff_px = 0
// is plain phase correlation.
//
// Why not cv::phaseCorrelate: in OpenCV 4.6, with a window, it returns
// different shifts for the same two images from one call to the next
// (tenths of a pixel); this function is deterministic.
//
// Peak: the integer maximum of the correlation surface, refined by the
// centroid of the 5 x 5 window around it (as cv::phaseCorrelate);
// response = the sum of the surface over that window (the whole surface sums
// to 1: identical images give ~1, unrelated ones ~0; with noise elsewhere
// on the surface it can exceed 1 slightly).
#include <opencv2/core.hpp>

namespace hsmap {

struct PhaseCorrelation {
  cv::Point2d shift;  // produced(x) = truth(x - shift), pixels (x = column, y = row)
  double response = 0.0;
};

// `truth` and `produced`: CV_64F, same size; `window`: CV_64F of that size
// (e.g. cv::createHanningWindow). std::invalid_argument otherwise or for a
// negative or non-finite cutoff.
PhaseCorrelation bandLimitedPhaseCorrelate(const cv::Mat& truth, const cv::Mat& produced,
                                           const cv::Mat& window, double cutoff_px);

}  // namespace hsmap
