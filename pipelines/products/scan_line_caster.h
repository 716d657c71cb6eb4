#pragma once
// ScanLineCaster: where every pixel of a UHI scan line looked on the surface.
// For scan line pose T_W_U (RUN/trajectory/uhi_lines.csv) and the push-broom
// camera (pushbroom_camera.h), pixel s's ray leaves the line's optical centre
// t_W_U along R_W_U * unproject(s) (y_U = 0: the centre of the instantaneous
// field of view) and is cast onto the surface mesh (MeshRayCaster, Embree).
//
// Per pixel: the first hit p_W, the hit triangle, the range (metres from the optical centre)
// and the incidence angle (degrees between the ray and the hit triangle's
// face normal: 0 looking straight at the surface, 90 grazing). A pixel with
// no hit in [min_range_m, max_range_m] is a miss; a pixel whose ray does not
// exist (beyond the fold of the distortion, PushbroomCamera::unproject) is
// counted apart as `no_ray` and never cast.
//
// Threads: castLine() uses Embree's batch intersect (ray streams; a line's
// pixels are the coherent batch it is tuned for) and is sequential;
// castLines() runs lines in parallel with TBB. Const and thread-safe.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"

namespace hsmap {

struct ScanLineCastOptions {
  // Hits nearer than this are ignored (housing, bubbles; > 0 so a pose on
  // the mesh does not hit itself). Metres, >= 0.
  double min_range_m = 0.05;
  // Farther hits are ignored: beyond a few tens of metres nothing is lit
  // underwater. Metres, > min_range_m (infinity allowed).
  double max_range_m = 50.0;

  // std::invalid_argument naming the field.
  void validate() const;
};

// The hits of one scan line, one entry per sample (pixel).
struct ScanLineHits {
  std::int64_t line = -1;                // cube line index
  std::vector<Eigen::Vector3d> p_W;      // NaN for a miss
  std::vector<float> range_m;            // NaN for a miss
  std::vector<float> incidence_deg;      // NaN for a miss
  std::vector<int> triangle;             // the hit triangle (mesh index); -1 for a miss
  int hits = 0;
  int misses = 0;                        // rays cast that hit nothing
  int no_ray = 0;                        // pixels without a ray

  bool hit(int sample) const { return range_m[std::size_t(sample)] == range_m[std::size_t(sample)]; }
};

class ScanLineCaster {
 public:
  // Keeps references to `camera` and `mesh` (they must outlive the caster).
  ScanLineCaster(const PushbroomCamera& camera, const MeshRayCaster& mesh,
                 const ScanLineCastOptions& options = {});

  int samples() const { return camera_.samples(); }
  // Samples with a ray (all but those beyond the distortion's fold).
  int samplesWithRay() const { return samples_with_ray_; }

  // Casts the line `line` seen from T_W_U into `out` (resized; reusing `out`
  // across calls avoids allocations).
  void castLine(std::int64_t line, const SE3d& T_W_U, ScanLineHits& out) const;

  // out[i] = castLine(lines[i], T_W_U[i]); parallel over lines (TBB).
  void castLines(std::span<const std::int64_t> lines, std::span<const SE3d> T_W_U,
                 std::vector<ScanLineHits>& out) const;

 private:
  const PushbroomCamera& camera_;
  const MeshRayCaster& mesh_;
  ScanLineCastOptions options_;
  std::vector<Eigen::Vector3d> rays_U_;  // unit; NaN where the pixel has no ray
  int samples_with_ray_ = 0;
};

}  // namespace hsmap
