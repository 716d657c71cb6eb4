#include "pipelines/simulate/reflectance_ortho.h"

#include <limits>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/io/envi_writer.h"
#include "core/util/progress.h"

namespace hsmap {

std::optional<Eigen::VectorXf> topSurfaceReflectance(const RenderContext& context,
                                                     const Eigen::MatrixXf& endmembers,
                                                     double north_m, double east_m) {
  const double top = context.caster->bounds().min().z() - 1.0;
  const Ray ray{Eigen::Vector3d(north_m, east_m, top), Eigen::Vector3d(0.0, 0.0, 1.0)};
  const RayHit hit = context.caster->intersect(ray);
  if (!hit.hit()) return std::nullopt;
  const Eigen::Vector3d p_W = ray.origin + hit.distance * ray.direction;
  const Abundances a = context.materials->abundances(p_W, context.kindOf(hit.triangle));
  return endmembers * Eigen::Map<const Eigen::Matrix<float, kEndmemberCount, 1>>(a.data());
}

ReflectanceOrthoSummary writeReflectanceOrtho(const std::filesystem::path& hdr_path,
                                              const SwathFootprint& footprint,
                                              const RenderContext& context,
                                              const std::vector<double>& wavelengths_nm,
                                              std::ostream& log) {
  int first_row = 0, first_col = 0;
  const NorthUpGrid grid = footprint.coveredBounds(&first_row, &first_col);
  if (grid.rows == 0) {
    throw std::runtime_error("the UHI saw no seabed: the reflectance footprint is empty");
  }
  const int bands = static_cast<int>(wavelengths_nm.size());
  const Eigen::MatrixXf endmembers = MaterialField::endmemberMatrix(wavelengths_nm);

  EnviHeader header;
  header.samples = grid.cols;
  header.lines = grid.rows;
  header.bands = bands;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.wavelength = wavelengths_nm;
  header.wavelength_units = "Nanometers";
  header.description = "hsmap simulate: true surface reflectance, NaN outside the UHI footprint";
  EnviMapInfo map;
  map.projection = "Arbitrary";
  map.easting = grid.east_min_m;
  map.northing = grid.north_max_m;
  map.pixel_size_x = map.pixel_size_y = grid.pixel_m;
  map.units = "Meters";
  header.map_info = map;
  EnviWriter writer(hdr_path, header);

  ReflectanceOrthoSummary summary;
  summary.rows = grid.rows;
  summary.cols = grid.cols;
  summary.grid = grid;
  constexpr int kRowsPerBatch = 32;
  std::vector<Eigen::MatrixXf> batch(kRowsPerBatch);
  std::vector<std::int64_t> valid(kRowsPerBatch);
  Progress progress("truth reflectance", grid.rows, "rows", log);
  for (int row0 = 0; row0 < grid.rows; row0 += kRowsPerBatch) {
    const int count = std::min(kRowsPerBatch, grid.rows - row0);
    tbb::parallel_for(0, count, [&](int i) {
      const int row = row0 + i;
      Eigen::MatrixXf& line = batch[i];
      line.setConstant(bands, grid.cols, std::numeric_limits<float>::quiet_NaN());
      valid[i] = 0;
      for (int col = 0; col < grid.cols; ++col) {
        if (!footprint.covered(first_row + row, first_col + col)) continue;
        const auto reflectance =
            topSurfaceReflectance(context, endmembers, grid.northOfRow(row), grid.eastOfCol(col));
        if (!reflectance) continue;
        line.col(col) = *reflectance;
        ++valid[i];
      }
    });
    for (int i = 0; i < count; ++i) {
      writer.writeLine(batch[i]);
      summary.valid_pixels += valid[i];
    }
    progress.advance(count);
  }
  writer.finish();
  progress.finish();
  return summary;
}

}  // namespace hsmap
