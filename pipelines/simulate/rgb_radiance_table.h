#pragma once
// RgbRadianceTable: the RGB camera's response to each endmember through a
// water path of length L, tabulated in L.
//
// An RGB value is an integral over wavelength of the sensitivity S_k, the lamp
// spectrum I, the reflectance and the attenuation exp(-c L). The reflectance
// is a linear mixture of the endmembers (MaterialField), so
//   RGB_k = sum_l g_l / pi * sum_m a_m * T_km(L_l),
//   T_km(L) = integral S_k(lambda) I(lambda) rho_m(lambda) exp(-c(lambda) L) d lambda
// and T is smooth in L: tabulated every 5 mm and interpolated linearly it is
// exact to far below the 8-bit quantisation, and rendering needs no
// exponential at all. Column kEndmemberCount holds a flat unit reflectance
// (for the exposure).
#include <vector>

#include <Eigen/Core>

#include "pipelines/simulate/scene/spectral_library.h"

namespace hsmap {

class RgbRadianceTable {
 public:
  using Entry = Eigen::Matrix<float, 3, kEndmemberCount + 1>;

  RgbRadianceTable(double turbidity, double max_path_m = 60.0, double step_m = 0.005);

  // T(L), clamped to the tabulated range.
  Entry at(double path_m) const;

 private:
  double step_m_;
  std::vector<Entry, Eigen::aligned_allocator<Entry>> entries_;
};

}  // namespace hsmap
