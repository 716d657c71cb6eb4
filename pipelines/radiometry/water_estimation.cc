#include "pipelines/radiometry/water_estimation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/lamp_radiance_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/marginal_covariance.h"

namespace hsmap {

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(mid), values.end());
  return values[mid];
}

struct Problem {
  FactorGraph graph;
  Values values;
};

// The graph and its start (see the header's "Start").
Problem buildProblem(const RadiometricObservations& observations, const std::vector<double>& response_dn,
                     const WaterEstimationOptions& options) {
  const int bands = observations.bands;
  Problem problem;
  const double beam0[2] = {0.0, 0.0};
  for (int b = 0; b < bands; ++b) {
    problem.values.insertScalar(C(std::uint64_t(b)), options.initial_attenuation_per_m);
    problem.values.insertScalar(O(std::uint64_t(b)), 0.0);
  }
  problem.values.insertVector(M(0), Eigen::Vector2d::Zero());

  // Observations of one point are contiguous (radiometric_observations.h).
  std::size_t begin = 0;
  while (begin < observations.items.size()) {
    const int point = observations.items[begin].point;
    std::size_t end = begin;
    while (end < observations.items.size() && observations.items[end].point == point) ++end;
    for (int b = 0; b < bands; ++b) {
      std::vector<double> ratios;
      for (std::size_t i = begin; i < end; ++i) {
        const RadiometricObservation& o = observations.items[i];
        const double illumination =
            lampIllumination(o.lamps, o.uhi_range_m, options.initial_attenuation_per_m, beam0);
        ratios.push_back(double(o.dn[std::size_t(b)]) / (response_dn[std::size_t(b)] * illumination));
      }
      const Key rho = R(std::uint64_t(point) * std::uint64_t(bands) + std::uint64_t(b));
      problem.values.insertScalar(rho, std::log(std::max(median(ratios), 1e-4)));
      for (std::size_t i = begin; i < end; ++i) {
        const RadiometricObservation& o = observations.items[i];
        const double sigma =
            options.relative_noise * std::max(double(o.dn[std::size_t(b)]), 0.0) + options.noise_floor_dn;
        problem.graph.emplace<LampRadianceFactor>(
            C(std::uint64_t(b)), O(std::uint64_t(b)), rho, M(0),
            LampRadianceResidual{double(o.dn[std::size_t(b)]), response_dn[std::size_t(b)], o.uhi_range_m, o.lamps},
            NoiseModel::isotropic(1, sigma), RobustLoss::cauchy(options.loss_scale));
      }
    }
    begin = end;
  }
  return problem;
}

std::string bandList(const std::vector<int>& bands, const std::vector<double>& wavelengths_nm) {
  std::ostringstream text;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    if (i == 6 && bands.size() > 8) {
      text << ", ... (" << bands.size() << " bands)";
      break;
    }
    text << (i ? ", " : "") << bands[i];
    if (std::size_t(bands[i]) < wavelengths_nm.size()) text << " (" << std::lround(wavelengths_nm[std::size_t(bands[i])]) << " nm)";
  }
  return text.str();
}

}  // namespace

void WaterEstimationOptions::validate() const {
  auto fail = [](const std::string& field, const std::string& expected) {
    throw std::invalid_argument("radiometry estimation: " + field + " must be " + expected);
  };
  if (!(initial_attenuation_per_m > 0.0) || !std::isfinite(initial_attenuation_per_m)) {
    fail("initial_attenuation_per_m", "a finite value > 0");
  }
  if (!(relative_noise > 0.0) || !std::isfinite(relative_noise)) fail("relative_noise", "a finite value > 0");
  if (!(noise_floor_dn > 0.0) || !std::isfinite(noise_floor_dn)) fail("noise_floor_dn", "a finite value > 0");
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) fail("loss_scale", "a finite value > 0");
  if (!(max_attenuation_sigma_per_m > 0.0)) fail("max_attenuation_sigma_per_m", "> 0");
  if (!(max_beam_sigma > 0.0)) fail("max_beam_sigma", "> 0");
  if (max_iterations <= 0) fail("max_iterations", "> 0");
  if (num_threads < 0) fail("num_threads", ">= 0 (0: every core)");
}

WaterEstimationReport estimateWater(const RadiometricObservations& observations,
                                    const std::vector<double>& response_dn, const WaterEstimationOptions& options) {
  options.validate();
  const int bands = observations.bands;
  if (int(response_dn.size()) != bands) {
    throw std::invalid_argument("radiometry estimation: the lamp response has " + std::to_string(response_dn.size()) +
                                " bands, the observations " + std::to_string(bands));
  }
  for (double k : response_dn) {
    if (!(k > 0.0) || !std::isfinite(k)) throw std::invalid_argument("radiometry estimation: a lamp response <= 0");
  }
  if (observations.items.empty()) throw std::invalid_argument("radiometry estimation: no observation");

  WaterEstimationReport report;
  report.observations = int(observations.items.size());
  report.points = observations.points;
  Problem problem = buildProblem(observations, response_dn, options);

  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;
  solver.function_tolerance = 1e-8;

  std::vector<Key> shared;
  for (int b = 0; b < bands; ++b) shared.push_back(C(std::uint64_t(b)));
  for (int b = 0; b < bands; ++b) shared.push_back(O(std::uint64_t(b)));
  shared.push_back(M(0));

  report.backscatter_estimated = options.estimate_backscatter;
  std::map<Key, Eigen::MatrixXd> covariance;
  for (int attempt = 0; attempt < 2; ++attempt) {
    GraphProblemOptions problem_options;
    if (!report.backscatter_estimated) {
      for (int b = 0; b < bands; ++b) {
        problem.values.updateScalar(O(std::uint64_t(b)), 0.0);
        problem_options.constant.insert(O(std::uint64_t(b)));
      }
    }
    GraphProblem graph_problem(problem.graph, problem.values, problem_options);
    report.solve = solve(graph_problem, solver);
    const int dof = report.solve.num_residuals - report.solve.num_free_parameters;
    report.residual_scale = dof > 0 ? std::sqrt(2.0 * report.solve.final_cost / dof) : 1.0;
    const auto start = std::chrono::steady_clock::now();
    try {
      CovarianceOptions covariance_options;
      covariance_options.num_threads = options.num_threads;
      covariance = marginalCovariances(graph_problem, shared, covariance_options);
      report.covariance_computed = true;
    } catch (const CovarianceRankDeficient&) {
      covariance.clear();
    }
    report.covariance_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (report.covariance_computed || !report.backscatter_estimated) break;
    report.backscatter_estimated = false;
    report.water.warnings.push_back(
        "radiometry: the survey does not determine the backscatter (the covariance is rank deficient with it "
        "free): held at zero");
  }

  WaterEstimate& water = report.water;
  const double scale2 = report.residual_scale * report.residual_scale;
  auto sigmaOf = [&](Key key, int index) -> std::optional<double> {
    if (!report.covariance_computed) return std::nullopt;
    const Eigen::MatrixXd& cov = covariance.at(key);
    if (cov.rows() <= index) return std::nullopt;
    const double variance = cov(index, index);
    if (variance <= 0.0) return std::nullopt;  // held constant
    return std::sqrt(variance * scale2);
  };
  for (int b = 0; b < bands; ++b) {
    water.attenuation_per_m.push_back(problem.values.scalar(C(std::uint64_t(b))));
    water.attenuation_sigma_per_m.push_back(sigmaOf(C(std::uint64_t(b)), 0));
    water.backscatter_dn.push_back(problem.values.scalar(O(std::uint64_t(b))));
    water.backscatter_sigma_dn.push_back(report.backscatter_estimated ? sigmaOf(O(std::uint64_t(b)), 0)
                                                                       : std::nullopt);
  }
  const Eigen::VectorXd beam = problem.values.vector(M(0));
  water.beam = {beam[0], beam[1]};
  water.beam_sigma = {sigmaOf(M(0), 0), sigmaOf(M(0), 1)};
  std::vector<int> weak;
  for (int b = 0; b < bands; ++b) {
    const auto& sigma = water.attenuation_sigma_per_m[std::size_t(b)];
    if (report.covariance_computed && (!sigma || *sigma > options.max_attenuation_sigma_per_m)) weak.push_back(b);
  }
  if (!weak.empty()) {
    std::ostringstream text;
    text << "radiometry: the survey does not determine c(λ) to " << options.max_attenuation_sigma_per_m
         << " /m (1-sigma) at " << weak.size() << " of " << bands << " bands: " << bandList(weak, {})
         << "; the range to each seabed point varies too little (a constant altitude over a flat seabed, no "
            "overlapping lanes)";
    water.warnings.push_back(text.str());
  }
  if (report.covariance_computed && (!water.beam_sigma[0] || *water.beam_sigma[0] > options.max_beam_sigma ||
                                     !water.beam_sigma[1] || *water.beam_sigma[1] > options.max_beam_sigma)) {
    water.warnings.push_back("radiometry: the survey does not determine the lamps' beam shape to " +
                             std::to_string(options.max_beam_sigma) +
                             " (1-sigma of its coefficients): the seabed points are seen from too narrow a "
                             "range of angles off the lamps' axes");
  }
  if (!report.covariance_computed) {
    water.warnings.push_back(
        "radiometry: the survey does not determine c(λ) and the beam together (the covariance is rank "
        "deficient): no 1-sigma");
  }
  return report;
}

std::string WaterEstimationReport::summary(const std::vector<double>& wavelengths_nm) const {
  std::ostringstream text;
  text << "radiometry: " << solve.toString() << "\n";
  text << "radiometry: " << observations << " observations of " << points
       << " seabed points; residual scale " << residual_scale << " (sigmas); covariance "
       << (covariance_computed ? "computed" : "rank deficient") << " in " << covariance_seconds << " s\n";
  text << std::setprecision(4);
  text << "radiometry: band  nm  c (1/m)  sigma  backscatter (DN)\n";
  for (int b = 0; b < water.bands(); ++b) {
    text << "radiometry:   " << b << "  " << (std::size_t(b) < wavelengths_nm.size() ? wavelengths_nm[std::size_t(b)] : 0.0)
         << "  " << water.attenuation_per_m[std::size_t(b)] << "  ";
    if (water.attenuation_sigma_per_m[std::size_t(b)]) {
      text << *water.attenuation_sigma_per_m[std::size_t(b)];
    } else {
      text << "-";
    }
    text << "  " << water.backscatter_dn[std::size_t(b)] << "\n";
  }
  text << "radiometry: beam B(θ) = exp(" << water.beam[0] << " θ² + " << water.beam[1] << " θ⁴)";
  if (water.beam_sigma[0] && water.beam_sigma[1]) {
    text << ", 1-sigma " << *water.beam_sigma[0] << ", " << *water.beam_sigma[1];
  }
  text << "\n";
  for (const std::string& warning : water.warnings) text << "warning: " << warning << "\n";
  return text.str();
}

}  // namespace hsmap
