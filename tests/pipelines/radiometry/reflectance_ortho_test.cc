#include "pipelines/radiometry/reflectance_ortho.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"
#include "factors/lamp_radiance_factor.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A flat seabed 2 m below a UHI at the origin looking down (T_W_U and T_C_U
// the identity, so C = U = W), two lamps 0.3 m to either side and 0.3 m
// back, a small plate 0.3 m below the port lamp that shades part of the
// line from it. One scan line, each pixel of a one-row "ortho-image" one
// sample of it: the DN written there is the contract's model of a known
// reflectance, c, beam and backscatter, and writeReflectanceOrtho must give
// the reflectance back, NaN where the plate shades the hit, where the ortho
// is empty, where the ancillary layer names no sample and where its range is
// not the hit's (a depth edge).
TEST(ReflectanceOrtho, InvertsTheModelAndLeavesShadowsAndGapsNaN) {
  const testing::TempFolder folder("reflectance-round-trip");
  const int samples = 64, bands = 3;
  const PushbroomParameters parameters{samples, 40.0, 31.5, {0.0, 0.0}};
  const PushbroomCamera camera(parameters);
  std::vector<Eigen::Vector3d> vertices = {{-5, -5, 2}, {5, -5, 2}, {5, 5, 2}, {-5, 5, 2},
                                           {-0.32, -0.28, 0.3}, {-0.28, -0.28, 0.3}, {-0.28, -0.23, 0.3},
                                           {-0.32, -0.23, 0.3}};
  const std::vector<Eigen::Vector3i> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const MeshRayCaster mesh(vertices, triangles);
  LightsConfig lights;
  lights.lamps = {{Eigen::Vector3d(-0.3, -0.3, 0.0), Eigen::Vector3d::UnitZ()},
                  {Eigen::Vector3d(0.3, -0.3, 0.0), Eigen::Vector3d::UnitZ()}};
  const std::vector<double> response = {5000.0, 8000.0, 3000.0};
  WaterEstimate water;
  water.attenuation_per_m = {0.1, 0.25, 0.8};
  water.attenuation_sigma_per_m = {0.01, 0.01, 0.01};
  water.backscatter_dn = {5.0, 3.0, 1.0};
  water.backscatter_sigma_dn = {1.0, 1.0, 1.0};
  water.beam = {-1.0, -1.0 / 6.0};
  const std::vector<LinePose> line_poses = {{0, 0.0, SE3d()}};

  EnviHeader header;
  header.samples = samples;
  header.lines = 1;
  header.bands = bands;
  EnviHeader ancillary_header = header;
  ancillary_header.bands = 4;
  std::vector<float> dn(std::size_t(bands * samples)), ancillary(std::size_t(4 * samples));
  std::vector<double> rho(std::size_t(bands * samples));
  std::vector<bool> shaded(std::size_t(samples), false);
  for (int s = 0; s < samples; ++s) {
    const double x = 2.0 * (s - parameters.cx) / parameters.f;
    const Eigen::Vector3d p(x, 0.0, 2.0);
    std::vector<LampPath> lit;
    for (const LampConfig& lamp : lights.lamps) {
      const Eigen::Vector3d to_lamp = lamp.p_C - p;
      const double r = to_lamp.norm();
      // The plate: where the segment crosses z = 0.3.
      const double t = (2.0 - 0.3) / 2.0;
      const Eigen::Vector3d q = p + t * to_lamp;
      if (q.x() > -0.32 && q.x() < -0.28 && q.y() > -0.28 && q.y() < -0.23) {
        shaded[std::size_t(s)] = true;
        continue;
      }
      LampPath path;
      path.range_m = r;
      path.cos_incidence = -to_lamp.z() / r;              // the normal (0, 0, -1) faces the lamps above
      path.off_axis_rad = std::acos((-to_lamp / r).z());  // the axis is +z (down)
      lit.push_back(path);
    }
    for (int b = 0; b < bands; ++b) {
      const double reflectance = 0.1 + 0.05 * b + 0.003 * s;
      rho[std::size_t(b * samples + s)] = reflectance;
      dn[std::size_t(b * samples + s)] =
          float(response[std::size_t(b)] * reflectance *
                    lampIllumination(lit, p.norm(), water.attenuation_per_m[std::size_t(b)], water.beam.data()) +
                water.backscatter_dn[std::size_t(b)]);
    }
    ancillary[std::size_t(s)] = 0.0f;                 // line
    ancillary[std::size_t(samples + s)] = float(s);  // sample
    ancillary[std::size_t(2 * samples + s)] = float(p.norm());
    ancillary[std::size_t(3 * samples + s)] = 0.0f;
  }
  const int empty = 3, no_sample = 5, depth_edge = 60;
  for (int b = 0; b < bands; ++b) dn[std::size_t(b * samples + empty)] = kNaN;
  ancillary[std::size_t(no_sample)] = kNaN;
  ancillary[std::size_t(samples + no_sample)] = kNaN;
  // A gap-filled pixel blending a near and a far hit: its range is not the recast hit's.
  ancillary[std::size_t(2 * samples + depth_edge)] *= 1.3f;
  {
    EnviWriter ortho(folder / "ortho.hdr", header);
    ortho.writeLine(dn.data());
    ortho.finish();
    EnviWriter anc(folder / "ancillary.hdr", ancillary_header);
    anc.writeLine(ancillary.data());
    anc.finish();
  }
  ReflectanceOptions options;
  options.write_geotiff = false;
  const ReflectanceReport report =
      writeReflectanceOrtho(folder.path(), camera, line_poses, mesh, lights, SE3d(), response, water, options);

  int expected_shaded = 0;
  ASSERT_FALSE(shaded[std::size_t(depth_edge)]);
  for (int s = 0; s < samples; ++s) expected_shaded += shaded[std::size_t(s)] && s != empty && s != no_sample;
  ASSERT_GT(expected_shaded, 0);  // the plate does shade some of the line
  ASSERT_LT(expected_shaded, samples / 2);
  EXPECT_EQ(report.pixels, samples);
  EXPECT_EQ(report.empty, 1);
  EXPECT_EQ(report.undetermined, 2);
  EXPECT_EQ(report.shadowed, expected_shaded);
  EXPECT_EQ(report.valid, samples - 3 - expected_shaded);

  EXPECT_EQ(report.dark_band_values, 0);

  const EnviReader result(folder / "reflectance.hdr");
  std::vector<float> out(std::size_t(bands * samples));
  result.readLine(0, out.data());
  for (int s = 0; s < samples; ++s) {
    for (int b = 0; b < bands; ++b) {
      const float value = out[std::size_t(b * samples + s)];
      if (s == empty || s == no_sample || s == depth_edge || shaded[std::size_t(s)]) {
        EXPECT_TRUE(std::isnan(value)) << "sample " << s << " band " << b;
      } else {
        EXPECT_NEAR(value, rho[std::size_t(b * samples + s)], 1e-4 * rho[std::size_t(b * samples + s)])
            << "sample " << s << " band " << b;
      }
    }
  }
  // Where the lamps' signal is below min_signal_dn every band is too dark
  // to measure: nothing is inverted.
  ReflectanceOptions dark_options = options;
  dark_options.min_signal_dn = 1e9;
  const ReflectanceReport dark =
      writeReflectanceOrtho(folder.path(), camera, line_poses, mesh, lights, SE3d(), response, water, dark_options);
  EXPECT_EQ(dark.valid, 0);
  EXPECT_EQ(dark.undetermined, samples - 1 - expected_shaded);
}

}  // namespace
}  // namespace hsmap
