#pragma once
// The push-broom UHI camera of the simulator's presets (survey.yaml's
// uhi.camera: 1920 samples, f 1500 px, cx 962, distortion [0.015, -0.002]),
// for tests that need a realistic line camera.
#include "core/geometry/camera_parameters.h"

namespace hsmap::testing {

inline PushbroomParameters presetUhiCamera() {
  PushbroomParameters camera;
  camera.samples = 1920;
  camera.f = 1500.0;
  camera.cx = 962.0;
  camera.distortion = {0.015, -0.002};
  return camera;
}

}  // namespace hsmap::testing
