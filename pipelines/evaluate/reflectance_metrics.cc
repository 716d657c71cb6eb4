#include "pipelines/evaluate/reflectance_metrics.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include "core/io/envi_reader.h"
#include "core/survey/water_estimate.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/ortho_raster_grid.h"

namespace hsmap {

namespace fs = std::filesystem;

std::string ReflectanceMetrics::summary() const {
  std::ostringstream out;
  auto figure = [](const MetricValue& m) {
    std::ostringstream text;
    if (m.value) {
      text << *m.value;
    } else {
      text << "null (" << m.reason << ")";
    }
    return text.str();
  };
  out << "  reflectance_sam_deg            " << figure(reflectance_sam_deg) << "  (" << blocks << " blocks of "
      << block_pixels << " truth pixels, " << (registered ? "registered" : "as placed") << "; "
      << band_values_left_out << " block-band values left out: NaN in the product, too dark)\n";
  out << "  reflectance_rmse               " << figure(reflectance_rmse) << "\n";
  out << "  reflectance_gain_free_rmse     " << figure(reflectance_gain_free_rmse) << "\n";
  out << "  water_attenuation_rmse_per_m   " << figure(water_attenuation_rmse_per_m) << "\n";
  return out.str();
}

namespace {

// b = A a + t in W's (east, north), fitted to the matches (a = patch centre,
// b = a + displacement); identity with fewer than 3 matches.
void fitSimilarity(const std::vector<OrthoPatchMatch>& matches, Eigen::Matrix2d& A, Eigen::Vector2d& t) {
  A.setIdentity();
  t.setZero();
  if (matches.size() < 3) return;
  Eigen::MatrixXd J(2 * matches.size(), 4);
  Eigen::VectorXd y(2 * matches.size());
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const Eigen::Vector2d a(matches[i].centre_NE.y(), matches[i].centre_NE.x());
    const Eigen::Vector2d b = a + Eigen::Vector2d(matches[i].displacement_NE.y(), matches[i].displacement_NE.x());
    J.row(Eigen::Index(2 * i)) << a.x(), -a.y(), 1.0, 0.0;
    J.row(Eigen::Index(2 * i + 1)) << a.y(), a.x(), 0.0, 1.0;
    y(Eigen::Index(2 * i)) = b.x();
    y(Eigen::Index(2 * i + 1)) = b.y();
  }
  const Eigen::Vector4d x = J.colPivHouseholderQr().solve(y);
  A << x(0), -x(1), x(1), x(0);
  t << x(2), x(3);
}

}  // namespace

ReflectanceMetrics measureRunReflectance(const fs::path& run_folder, const fs::path& truth_reflectance_hdr,
                                         const std::vector<double>& true_attenuation_per_m,
                                         const GeodeticPoint& origin, const std::vector<OrthoPatchMatch>& matches,
                                         const ReflectanceMetricsOptions& options) {
  ReflectanceMetrics metrics;
  const fs::path produced_hdr = run_folder / "hyperspectral" / "reflectance.hdr";
  const fs::path water_yaml = run_folder / "radiometry" / "water.yaml";
  if (fs::exists(water_yaml)) {
    const WaterEstimate water = readWaterEstimate(water_yaml);
    if (water.attenuation_per_m.size() != true_attenuation_per_m.size()) {
      throw InputError(water_yaml, "key water.attenuation_per_m",
                       "has " + std::to_string(water.attenuation_per_m.size()) + " bands, the truth " +
                           std::to_string(true_attenuation_per_m.size()));
    }
    double sum = 0.0;
    for (std::size_t b = 0; b < true_attenuation_per_m.size(); ++b) {
      const double e = water.attenuation_per_m[b] - true_attenuation_per_m[b];
      sum += e * e;
    }
    metrics.water_attenuation_rmse_per_m = MetricValue::of(std::sqrt(sum / double(true_attenuation_per_m.size())));
  } else {
    metrics.water_attenuation_rmse_per_m = MetricValue::missing("RUN/radiometry/water.yaml not found: no estimate of c");
  }
  const std::string no_product = "RUN/hyperspectral/reflectance.hdr not found: no reflectance product";
  if (!fs::exists(produced_hdr)) {
    metrics.reflectance_sam_deg = metrics.reflectance_rmse = metrics.reflectance_gain_free_rmse =
        MetricValue::missing(no_product);
    return metrics;
  }

  const EnviReader truth(truth_reflectance_hdr);
  const EnviReader produced(produced_hdr);
  const int bands = truth.bands();
  if (produced.bands() != bands) {
    throw InputError(produced_hdr, "", "has " + std::to_string(produced.bands()) + " bands, the truth " +
                                            std::to_string(bands));
  }
  const UtmProjection utm(origin);
  const RasterGrid truth_grid = localRasterGrid(truth.header(), truth_reflectance_hdr);
  const RasterGrid produced_grid = utmRasterGrid(produced.header(), produced_hdr, utm);
  Eigen::Matrix2d A;
  Eigen::Vector2d t;
  fitSimilarity(matches, A, t);
  metrics.registered = matches.size() >= 3;
  const int block = std::max(1, int(std::lround(options.block_m / truth_grid.px)));
  metrics.block_pixels = block;

  std::map<int, Eigen::MatrixXf> cache;  // produced rows (bands x cols)
  Eigen::MatrixXf truth_line;
  // Per valid block: the mean spectra over its pairs, band by band, and which
  // bands the product determined there (a band NaN in every pair is left out).
  std::vector<Eigen::VectorXd> produced_means, truth_means;
  std::vector<Eigen::Array<bool, Eigen::Dynamic, 1>> determined;
  for (int r0 = 0; r0 < truth.lines(); r0 += block) {
    const int rows = std::min(block, truth.lines() - r0);
    const int block_cols = (truth.samples() + block - 1) / block;
    std::vector<Eigen::VectorXd> p_sum(std::size_t(block_cols), Eigen::VectorXd::Zero(bands));
    std::vector<Eigen::VectorXd> t_sum(std::size_t(block_cols), Eigen::VectorXd::Zero(bands));
    std::vector<Eigen::VectorXi> band_pairs(std::size_t(block_cols), Eigen::VectorXi::Zero(bands));
    std::vector<int> pairs(std::size_t(block_cols), 0), truth_valid(std::size_t(block_cols), 0);
    for (int r = r0; r < r0 + rows; ++r) {
      truth.readLine(r, truth_line);
      for (int c = 0; c < truth.samples(); ++c) {
        bool valid = true;
        for (int b = 0; b < bands && valid; ++b) valid = std::isfinite(truth_line(b, c));
        if (!valid) continue;
        const std::size_t k = std::size_t(c / block);
        ++truth_valid[k];
        const Eigen::Vector2d en = A * truth_grid.centre(r, c) + t;
        const Eigen::Vector2d utm_en = utm.nedToUtm(Eigen::Vector3d(en.y(), en.x(), options.reference_down_m));
        const Eigen::Vector2d col_row = produced_grid.pixel(utm_en);
        const int pc = int(std::lround(col_row.x())), pr = int(std::lround(col_row.y()));
        if (pc < 0 || pr < 0 || pc >= produced.samples() || pr >= produced.lines()) continue;
        auto row = cache.find(pr);
        if (row == cache.end()) {
          Eigen::MatrixXf line;
          produced.readLine(pr, line);
          row = cache.emplace(pr, std::move(line)).first;
        }
        // A produced pixel counts when any band is a number (as the ortho
        // metrics' validity); a band NaN there (too dark to measure) is left
        // out of that band's mean.
        bool any = false;
        for (int b = 0; b < bands; ++b) {
          const float v = row->second(b, pc);
          if (!std::isfinite(v)) continue;
          any = true;
          p_sum[k][b] += v;
          t_sum[k][b] += truth_line(b, c);
          ++band_pairs[k][b];
        }
        if (any) ++pairs[k];
      }
    }
    for (int k = 0; k < block_cols; ++k) {
      if (truth_valid[std::size_t(k)] == 0) continue;
      if (double(pairs[std::size_t(k)]) < options.min_valid_fraction * double(block * block)) continue;
      const Eigen::VectorXi& n = band_pairs[std::size_t(k)];
      const Eigen::VectorXd count = n.cast<double>().cwiseMax(1.0);
      produced_means.push_back(p_sum[std::size_t(k)].cwiseQuotient(count));
      truth_means.push_back(t_sum[std::size_t(k)].cwiseQuotient(count));
      determined.push_back((n.array() > 0));
    }
    // Rows above the next block row's reach are no longer needed.
    if (!cache.empty() && cache.size() > 64) cache.erase(cache.begin(), std::next(cache.begin(), std::ptrdiff_t(cache.size() - 32)));
  }
  metrics.blocks = std::int64_t(truth_means.size());
  if (truth_means.empty()) {
    metrics.reflectance_sam_deg = metrics.reflectance_rmse = metrics.reflectance_gain_free_rmse =
        MetricValue::missing("no 2 cm block is valid in both the reflectance product and the truth");
    return metrics;
  }
  double sam = 0.0, squares = 0.0, truth_squares = 0.0;
  std::int64_t sam_blocks = 0, values = 0;
  Eigen::VectorXd pt = Eigen::VectorXd::Zero(bands), pp = Eigen::VectorXd::Zero(bands);
  for (std::size_t i = 0; i < truth_means.size(); ++i) {
    const Eigen::VectorXd mask = determined[i].cast<double>().matrix();
    const Eigen::VectorXd p = produced_means[i].cwiseProduct(mask);
    const Eigen::VectorXd q = truth_means[i].cwiseProduct(mask);
    metrics.band_values_left_out += std::int64_t(bands) - std::int64_t(determined[i].count());
    if (determined[i].count() >= 2 && p.norm() > 0.0 && q.norm() > 0.0) {
      const double chord = (p.normalized() - q.normalized()).norm();
      sam += 2.0 * std::asin(std::min(1.0, 0.5 * chord)) * 180.0 / std::numbers::pi;
      ++sam_blocks;
    }
    squares += (p - q).squaredNorm();
    truth_squares += q.squaredNorm();
    values += determined[i].count();
    pt += p.cwiseProduct(q);
    pp += p.cwiseProduct(p);
  }
  const double n = double(std::max<std::int64_t>(values, 1));
  metrics.reflectance_sam_deg = sam_blocks > 0 ? MetricValue::of(sam / double(sam_blocks))
                                               : MetricValue::missing("no block has two determined bands");
  metrics.reflectance_rmse = MetricValue::of(std::sqrt(squares / n));
  Eigen::VectorXd gain(bands);
  for (int b = 0; b < bands; ++b) gain[b] = pp[b] > 0.0 ? pt[b] / pp[b] : 0.0;
  double gain_free = 0.0;
  for (std::size_t i = 0; i < truth_means.size(); ++i) {
    const Eigen::VectorXd mask = determined[i].cast<double>().matrix();
    gain_free += (produced_means[i].cwiseProduct(gain) - truth_means[i]).cwiseProduct(mask).squaredNorm();
  }
  metrics.reflectance_gain_free_rmse =
      truth_squares > 0.0 ? MetricValue::of(std::sqrt(gain_free / n) / std::sqrt(truth_squares / n))
                          : MetricValue::missing("the true reflectance is zero over every block");
  return metrics;
}

}  // namespace hsmap
