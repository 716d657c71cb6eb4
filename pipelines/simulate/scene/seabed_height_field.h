#pragma once
// SeabedHeightField: the bare seabed (no rocks) as a height field z_W(north,
// east), a pure function of the SeabedSceneConfig (preset and seed). The
// scene's triangle grid samples it at its vertices; rock placement and tests
// query it directly.
//
// Units and frames: metres in the scene's build frame (seabed_scene_config.h:
// W turned by -heading_deg about the pivot; W itself at heading 0),
// North-East-Down. z() is the seabed's z_W, DOWN, so a higher seabed has a
// smaller z; elevation() is the relief's height above the mean depth, UP:
// z = seabed_depth_m - elevation + the slope's plane (zero at the pivot,
// deepening by tan(slope_deg) per metre towards slope_direction_deg in W).
//
// What each preset contains (elevation, metres):
//   flat        roughness only: fractal noise at 2.5-10 cm wavelengths,
//               +-8 mm at most (peak to peak about 1.1-1.2 cm);
//   low-relief  the roughness plus gentle undulation at 4-5 m wavelengths,
//               about 0.2-0.4 m peak to peak over the default extent;
//   rugged      rougher roughness (+-2 cm) and the undulation, plus
//               - a scarp across the corridor at 36-40% of the north extent,
//                 rising 1.1-1.3 m towards north over about 1 m (about 60
//                 degrees at its steepest, up to 70 on the ledges of its
//                 face), wavy in plan;
//               - a ridge crossing the corridor diagonally at 70-74% of the
//                 north extent, 0.75-0.95 m high on average (+-20% along its
//                 crest), flanks of about 50 degrees;
//               - rocky crests: sinuous ridges up to 0.18 m high and about
//                 0.35 m wide, in patches.
// The features are placed at fractions of the north extent so every extent
// shows them; their sizes are absolute. Relief stays below 1.5 m above the
// surrounding seabed, so a vehicle at 1-3 m altitude can fly over it.
//
// z() is defined for any (north, east), also outside the extent; it is
// continuously differentiable and costs about 0.05 us (flat) to 0.12 us
// (rugged), so a full 26 m x 6 m grid at 2 cm (391k vertices) takes tens of
// milliseconds.

#include <cstdint>

#include "pipelines/simulate/scene/seabed_scene_config.h"

namespace hsmap {

class SeabedHeightField {
 public:
  // Throws std::invalid_argument when config.validate() does.
  explicit SeabedHeightField(const SeabedSceneConfig& config);

  // z_W (down, metres) of the bare seabed at (north, east).
  double z(double north_m, double east_m) const {
    const double relief_z = config_.seabed_depth_m - elevation(north_m, east_m);
    // Skipped rather than added as zero, so that an unsloped seabed keeps its bits.
    if (!has_slope_) return relief_z;
    return relief_z + slope_north_ * (north_m - config_.pivot_north_m) +
           slope_east_ * (east_m - config_.pivot_east_m);
  }
  // Height of the bare seabed above seabed_depth_m (up, metres).
  double elevation(double north_m, double east_m) const;

  const SeabedSceneConfig& config() const { return config_; }

 private:
  double roughness(double north_m, double east_m) const;
  double undulation(double north_m, double east_m) const;
  double scarp(double north_m, double east_m) const;
  double ridge(double north_m, double east_m) const;
  double crests(double north_m, double east_m) const;

  SeabedSceneConfig config_;
  // Independent noise seeds of the layers, drawn from config.seed.
  std::uint64_t roughness_seed_ = 0, fine_seed_ = 0, undulation_seed_ = 0, scarp_seed_ = 0,
                face_seed_ = 0, ridge_seed_ = 0, crest_seed_ = 0, crest_mask_seed_ = 0;
  double roughness_amplitude_m_ = 0.0;
  double undulation_amplitude_m_ = 0.0;
  // Rugged features (unused by the other presets).
  double scarp_north_m_ = 0.0;  // where the scarp crosses east = 0 (middle of the face)
  double scarp_skew_ = 0.0;     // d(scarp north)/d(east)
  double scarp_rise_m_ = 0.0;
  double scarp_width_m_ = 0.0;                // horizontal width of the face
  double ridge_north_m_ = 0.0;                // where the ridge crest crosses east = 0
  double ridge_cos_ = 1.0, ridge_sin_ = 0.0;  // crest direction is (sin, cos) in (north, east)
  double ridge_height_m_ = 0.0;
  double ridge_half_width_m_ = 0.0;
  // The slope's plane in the build frame: d z / d north and d z / d east.
  bool has_slope_ = false;
  double slope_north_ = 0.0, slope_east_ = 0.0;
};

}  // namespace hsmap
