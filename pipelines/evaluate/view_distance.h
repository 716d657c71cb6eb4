#pragma once
// The view distance h of the frames' view Sim(3) (DATASET.md, "uhi_position_rmse_m";
// view_alignment.h): the median, over the TRUE frames, of the distance from
// the true camera centre along its optical axis (z of C) to the true surface
// truth/scene.ply, i.e. how far ahead of the cameras the seabed they look at
// lies. Each frame is one ray cast (core/raycast, Embree), in one batch.
//
// Frames whose axis misses the surface (looking past its edge) are left out;
// when none meets it, h is missing with the reason. h is in the truth's
// metres.

#include <vector>

#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "pipelines/evaluate/metric_value.h"

namespace hsmap {

struct ViewDistance {
  MetricValue h_m;        // the median distance, or why there is none
  int frames_hit = 0;     // frames whose optical axis meets the surface
  int frames_missed = 0;  // the others
};

ViewDistance medianViewDistance(const std::vector<TimedPose>& frames_true,
                                const MeshRayCaster& true_scene);

}  // namespace hsmap
