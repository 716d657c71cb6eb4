#pragma once
// What `hsmap run` is asked to do (docs/RUN.md): the variant, the stages to
// run, and each stage's own options, each with its defaults and validate().
// The command line fills this; the runner (runner.h) checks it and runs.
//
//   variant      stages, in order
//   sequential   frontend, georef, surface, refine, products
//   planar       georef (the INS alone), surface (a flat seabed), products
//   stacked      products (the scan lines side by side, no map position)
//   joint        frontend, georef, surface, joint, products

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "pipelines/surface/surface_meshing.h"

namespace hsmap {

enum class Variant { sequential, planar, stacked, joint };

// "sequential", ...; parseVariant throws std::invalid_argument naming the
// text and the variants for any other.
const char* toString(Variant variant);
Variant parseVariant(const std::string& text);

// Where the joint stage's rounds after the first find their tie points.
enum class JointTiePoints { strip, ortho };
const char* toString(JointTiePoints source);
JointTiePoints parseJointTiePoints(const std::string& text);

// "dense" or "sparse" (the flat seabed is the planar variant's, not a choice).
SurfaceMode parseSurfaceMode(const std::string& text);

struct SurfaceStageOptions {
  SurfaceMode mode = SurfaceMode::dense;  // planar: always flat
  // planar: the flat seabed's z in W (m, down); estimated when absent.
  std::optional<double> seabed_depth_m;
  void validate() const;
};

struct RefineStageOptions {
  // Rounds of the extrinsic refinement from the RGB and hyperspectral
  // ortho-images, each on a new cast (0: keep survey.yaml's guess).
  int rounds = 2;
  static constexpr int kMaxRounds = 10;
  // The casts' pixel (m): the ortho-images matched are at this resolution,
  // whatever the products' pixel.
  double cast_pixel_m = 0.005;
  void validate() const;
};

struct JointStageOptions {
  // Rounds of tie points, joint solve and new surface (fewer when T_C_U, d
  // and the trajectory stop moving).
  int rounds = 3;
  static constexpr int kMaxRounds = 10;
  JointTiePoints tie_points = JointTiePoints::strip;
  // The casts of the rounds that match the ortho-images, as refine's.
  double cast_pixel_m = 0.005;
  // Ortho-image tie points on a lattice twice as dense as the sequential
  // refinement's: T_C_U's translation is seen only through the relief's
  // range differences, so the joint problem needs every confident match it
  // can get. Neighbouring patches then overlap (0.20 m windows every
  // 0.075 m), so their match errors are correlated: each tie point is
  // weighted as if it held only its share of a window (the match sigma
  // inflated by patch size / spacing). Without this the 1-sigma of T_C_U came
  // out 3-4 times too small on low-relief.
  double ortho_patch_spacing_m = 0.075;
  // Tie points matched in the push-broom strip: patches that do not overlap,
  // so no inflation; finer across the track (the sensors' own pixels) than
  // along it (the lines' spacing): 2 mm is three quarters of the strip's
  // pixel on the presets, 5 mm a third of the line spacing. Their residuals
  // after the solve scatter ten times less; the errors all tie points share
  // (the frames' poses, the surface) set their precision, not the matching
  // (docs/JOINT.md, "Weights").
  double strip_sigma_match_m = 0.002;
  double strip_sigma_match_along_m = 0.005;
  void validate() const;
};

struct ProductsStageOptions {
  double ortho_pixel_m = 0.005;  // ortho-image pixel size (m)
  bool geotiff = true;           // also hyperspectral/ortho.tif and map/rgb_ortho.tif
  // hyperspectral/points.ply: the hits binned into cubes of point_cell_m.
  bool points = true;
  double point_cell_m = 0.02;
  void validate() const;
};

struct RunOptions {
  std::filesystem::path survey;
  std::filesystem::path out;
  Variant variant = Variant::sequential;
  std::string from;   // empty: the first stage not up to date (resume)
  std::string until;  // empty: the variant's last stage
  bool force = false;  // redo every stage from `from` (all when empty)
  int threads = 0;     // oneTBB and Ceres threads; 0: every hardware thread
  std::filesystem::path log;  // also write the run's log here (empty: none)

  SurfaceStageOptions surface;
  RefineStageOptions refine;
  JointStageOptions joint;
  ProductsStageOptions products;

  // The command-line options the user gave (e.g. "--extrinsic-rounds"): one
  // that the chosen variant ignores is an error (runner.h).
  std::set<std::string> given;

  // Every stage's options, and threads >= 0. std::invalid_argument naming
  // the option and what was expected.
  void validate() const;
};

}  // namespace hsmap
