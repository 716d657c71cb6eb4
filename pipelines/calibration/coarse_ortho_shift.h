#pragma once
// The coarse step of the ortho-image matching (extrinsic_refinement.h,
// "Method", step 2): where the hyperspectral ortho-image sits relative to the
// RGB one, to a few centimetres, before the lattice's fine search. A guess of
// T_C_U or d a few degrees or tens of milliseconds off shifts the whole
// hyperspectral image by more than the fine search radius (at 1.5 m range,
// 5 degrees is 13 cm), and the lattice then finds nothing but chance peaks.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "pipelines/calibration/extrinsic_refinement_options.h"
#include "pipelines/calibration/ortho_ncc.h"

namespace hsmap {

class CoarseOrthoShift {
 public:
  // Large patches of `rgb` (options.coarse_patch_size_m) every
  // options.coarse_spacing_m, searched in `hyper` within
  // +-options.coarse_search_radius_m on both images resampled to about
  // options.coarse_pixel_m, with the lattice's NCC tests. Both images are on
  // one grid of pixel_m. With fewer than options.coarse_min_matches matches
  // (a swath narrower than the search windows leaves none wholly valid),
  // again with patches, spacing and search radius halved. coarse_pixel_m =
  // 0: no coarse matches (shiftAt always nullopt).
  CoarseOrthoShift(const PreparedImage& rgb, const PreparedImage& hyper, double pixel_m,
                   const ExtrinsicRefinementOptions& options);

  // The shift h - g (fine pixels) of the content at fine grid position g:
  // the per-axis median of the coarse matches within
  // options.coarse_neighbourhood_m, when at least options.coarse_min_matches
  // lie there; nullopt otherwise.
  std::optional<Eigen::Vector2d> shiftAt(const Eigen::Vector2d& g) const;

  std::int64_t patches() const { return patches_; }
  // 1 for the options' sizes, 0.5 when the halved windows were used.
  double scale() const { return scale_; }
  std::int64_t matched() const { return std::int64_t(centres_.size()); }

 private:
  // One lattice of coarse patches at `scale` times the options' sizes,
  // replacing any earlier one.
  void matchLattice(const PreparedImage& rgb_c, const PreparedImage& hyper_c, int factor,
                    double pixel_m, double scale, const ExtrinsicRefinementOptions& options);

  std::vector<Eigen::Vector2d> centres_;  // fine pixels, row-major lattice order
  std::vector<Eigen::Vector2d> shifts_;   // fine pixels
  std::vector<int> cell_of_;              // lattice cell -> index in centres_, -1 none
  int cells_x_ = 0, cells_y_ = 0;
  double origin_x_ = 0.0, origin_y_ = 0.0, cell_px_ = 1.0;  // lattice in fine pixels
  double neighbourhood_px_ = 0.0;
  int min_matches_ = 1;
  std::int64_t patches_ = 0;
  double scale_ = 1.0;
};

}  // namespace hsmap
