#pragma once
// Settings of the visibility graph cut (surface_cut.h). The energy is
// Labatut et al. 2009's: every visibility ray c -> p adds, with weight
// w = visibility_weight * weight(p), a cost w to every facet it crosses
// (cutting there would put matter in front of a point that was seen), a
// cost w to label "outside" the cell just beyond p (the point is on the
// surface of matter behind it), and pins the camera's cell outside.

#include <string>

namespace hsmap {

struct SurfaceCutOptions {
  // alpha_vis of Labatut et al. 2009 (eq. 3): the cost of one ray's
  // evidence. Only ratios with the other weights matter.
  double visibility_weight = 1.0;
  // Labatut's soft visibility: a crossed facet at distance d in front of
  // the point costs w (1 - exp(-d^2 / 2 sigma^2)) instead of w, so noise
  // of about sigma near the surface is not carved away. In metres; 0 turns
  // it off (points exactly on their surface).
  double noise_sigma = 0.0;
  // Cost per square metre of surface (a small area term on every facet
  // between two bounded cells, both directions): prefers the smaller surface where visibility
  // leaves the cut undecided. On a noisy synthetic seabed (2 mm noise,
  // 6 cm spacing, tests/pipelines/surface) 1 removes nearly all the small
  // folds and pockets of the surface (93 of 5738 triangles facing down
  // without it, 10 with it) while a ray still outweighs any facet. 0 turns
  // it off.
  double area_weight = 1.0;
  // Tie-breaking prior, tiny next to visibility_weight: a cell no ray ever
  // crossed is matter (the seabed under its surface is never seen), except
  // an unbounded cell outside the convex hull whose hull facet faces some
  // camera, which is free space. Cost per cell for going against the prior.
  double prior_weight = 1e-3;
  // Stop one ray's walk after this many cells (a guard against a walk that
  // does not end in degenerate geometry); such rays are counted in the
  // report and their partial evidence kept.
  int max_cells_per_ray = 1000000;

  // Empty when the options are usable, otherwise what is wrong.
  std::string validate() const;
};

}  // namespace hsmap
