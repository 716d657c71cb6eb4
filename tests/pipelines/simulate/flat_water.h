#pragma once
// A level vehicle over a flat seabed kAltitude below its RGB camera, with
// tiny's cameras (the RGB at 160x90) and no sensor noise: the water effects'
// tests render single frames and lines here and compare them with their models.
#include <memory>

#include <opencv2/core.hpp>

#include "pipelines/simulate/rgb_renderer.h"
#include "pipelines/simulate/simulation_config.h"
#include "pipelines/simulate/uhi_renderer.h"

namespace hsmap::testing {

constexpr double kAltitude = 2.0;  // seabed below the RGB camera

// A level vehicle (T_W_B = identity) over a flat seabed, tiny's cameras.
struct FlatWater {
  explicit FlatWater(double turbidity, bool backscatter, const MarineSnowConfig& snow = {}) {
    config = *simulationPreset("tiny");
    config.optics.marine_snow = snow;
    config.optics.turbidity = turbidity;
    config.optics.backscatter.enabled = backscatter;
    config.uhi.read_noise_dn = 0.0;
    config.uhi.electrons_per_dn = 1e12;
    config.rgb.read_noise_dn = 0.0;
    config.rgb.electrons_per_dn = 1e12;
    config.rgb.camera = scaledRgbCamera(160, 90);
    const double z = config.calibration.T_B_C.translation_m.z() + kAltitude;
    scene.vertices = {{-20, -20, z}, {20, -20, z}, {20, 20, z}, {-20, 20, z}};
    scene.triangles = {{0, 2, 1}, {0, 3, 2}};
    scene.triangle_kind = {SurfaceKind::seabed, SurfaceKind::seabed};
    caster = std::make_unique<MeshRayCaster>(scene.vertices, scene.triangles);
    lamps = std::make_unique<LampRig>(config.optics, config.calibration.T_B_C);
    context.scene = &scene;
    context.caster = caster.get();
    context.materials = &materials;
    context.lamps = lamps.get();
    context.turbidity = turbidity;
    context.nominal_altitude_m = kAltitude;
    context.backscatter = config.optics.backscatter;
    context.marine_snow = config.optics.marine_snow;
    context.T_B_C = SE3d(config.calibration.T_B_C.rotation, config.calibration.T_B_C.translation_m);
    context.T_C_U = SE3d(config.calibration.T_C_U.rotation, config.calibration.T_C_U.translation_m);
    wavelengths = uhiBandCentres(config.uhi);
    uhi = std::make_unique<UhiRenderer>(context, config.uhi, wavelengths, 7);
  }
  Eigen::MatrixXf uhiLine() const {
    UhiLineImage line;
    uhi->render(SE3d(), context.T_B_C * context.T_C_U, 0, line);
    return line.dn;
  }
  cv::Mat rgbFrame(std::int64_t frame_index = 0) const {
    const RgbRenderer rgb(context, config.rgb, 7);
    return rgb.render(SE3d(), context.T_B_C, frame_index);
  }

  SimulationConfig config;
  SeabedScene scene;
  std::unique_ptr<MeshRayCaster> caster;
  MaterialField materials{3};
  std::unique_ptr<LampRig> lamps;
  RenderContext context;
  std::vector<double> wavelengths;
  std::unique_ptr<UhiRenderer> uhi;
};

}  // namespace hsmap::testing
