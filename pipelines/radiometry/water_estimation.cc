#include "pipelines/radiometry/water_estimation.h"

#include <algorithm>
#include <array>
#include <optional>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/gaussian_prior_factor.h"
#include "factors/lamp_radiance_factor.h"
#include "factors/second_difference_prior_factor.h"
#include "pipelines/radiometry/pure_water_absorption.h"
#include "solvers/graph_problem.h"
#include <Eigen/Eigenvalues>

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
                     const std::vector<double>& wavelengths_nm, const WaterEstimationOptions& options) {
  const int bands = observations.bands;
  Problem problem;
  const double beam0[2] = {0.0, 0.0};
  std::vector<double> start(std::size_t(bands), 0.0);
  for (int b = 0; b < bands; ++b) {
    const double prior =
        pureWaterAbsorptionPerM(wavelengths_nm[std::size_t(b)]) + options.attenuation_prior_offset_per_m;
    start[std::size_t(b)] = options.initial_attenuation_per_m.value_or(prior);
    problem.values.insertScalar(C(std::uint64_t(b)), start[std::size_t(b)]);
    problem.values.insertScalar(O(std::uint64_t(b)), 0.0);
    problem.graph.emplace<GaussianPriorFactor>(C(std::uint64_t(b)), Eigen::VectorXd::Constant(1, prior),
                                               NoiseModel::isotropic(1, options.attenuation_prior_sigma_per_m));
  }
  for (int b = 1; b + 1 < bands; ++b) {
    // sigma of the second difference: smoothness_per_m per 10 nm, squared with the band spacing.
    const double spacing_nm = 0.5 * std::abs(wavelengths_nm[std::size_t(b + 1)] - wavelengths_nm[std::size_t(b - 1)]);
    const double sigma = options.attenuation_smoothness_per_m * (spacing_nm / 10.0) * (spacing_nm / 10.0);
    if (sigma > 0.0) {
      problem.graph.emplace<SecondDifferencePriorFactor>(C(std::uint64_t(b - 1)), C(std::uint64_t(b)),
                                                         C(std::uint64_t(b + 1)), NoiseModel::isotropic(1, sigma));
    }
  }
  problem.values.insertVector(M(0), Eigen::Vector2d::Zero());
  problem.graph.emplace<GaussianPriorFactor>(M(0), Eigen::VectorXd(Eigen::Vector2d::Zero()),
                                             NoiseModel::isotropic(2, options.beam_prior_sigma));

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
        const double illumination = lampIllumination(o.lamps, o.uhi_range_m, start[std::size_t(b)], beam0);
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

// The covariance of the shared parameters [c_0..c_B-1, o_0..o_B-1, m_1, m_2]
// (Gauss-Newton, whitened residuals reweighted by the robust loss), the
// reflectances eliminated by their Schur complement: each R key is one
// scalar seen by the factors of one point and band, so the reduced system
// is exact and only (2B + 2)² in size. Backscatter held constant: its rows
// and columns are left out (zero covariance). nullopt when the reduced
// information is not positive definite (rank deficient).
std::optional<Eigen::MatrixXd> sharedCovariance(const Problem& problem, int bands, bool backscatter_free,
                                                double loss_scale) {
  const int n = 2 * bands + 2;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  auto indexOf = [&](Key key, int component) -> int {
    switch (key.kind()) {
      case VariableKind::water_attenuation: return int(key.index());
      case VariableKind::backscatter: return bands + int(key.index());
      case VariableKind::lamp_beam: return 2 * bands + component;
      default: return -1;
    }
  };
  std::optional<Key> group;
  double h_rr = 0.0;
  Eigen::Vector4d h_rs = Eigen::Vector4d::Zero();
  std::array<int, 4> group_index{};
  auto closeGroup = [&] {
    if (group && h_rr > 0.0) {
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) H(group_index[std::size_t(i)], group_index[std::size_t(j)]) -= h_rs[i] * h_rs[j] / h_rr;
      }
    }
    h_rr = 0.0;
    h_rs.setZero();
  };
  for (const auto& factor : problem.graph.factors()) {
    const auto& keys = factor->keys();
    const double w = factor->noise().sqrtInformation()(0, 0);
    const auto cost = static_cast<const CeresFactor&>(*factor).createCostFunction();
    std::vector<const double*> parameters;
    for (const Key& key : keys) parameters.push_back(problem.values.data(key));
    const int residuals = cost->num_residuals();
    std::vector<std::vector<double>> jacobian_storage;
    std::vector<double*> jacobians;
    for (int size : cost->parameter_block_sizes()) {
      jacobian_storage.emplace_back(std::size_t(residuals * size), 0.0);
    }
    for (auto& j : jacobian_storage) jacobians.push_back(j.data());
    std::vector<double> residual(static_cast<std::size_t>(residuals), 0.0);
    cost->Evaluate(parameters.data(), residual.data(), jacobians.data());
    if (factor->name() == "LampRadianceFactor") {
      const Key r_key = keys[2];
      if (!group || *group != r_key) {
        closeGroup();
        group = r_key;
        group_index = {indexOf(keys[0], 0), indexOf(keys[1], 0), 2 * bands, 2 * bands + 1};
      }
      // The robust loss's weight at the solution (iteratively reweighted least
      // squares: Cauchy rho'(s) = 1 / (1 + s / scale²)), so that an outlier
      // counts as little as it did in the solve.
      const double whitened = w * residual[0];
      const double robust = std::sqrt(1.0 / (1.0 + whitened * whitened / (loss_scale * loss_scale)));
      const double wr = w * robust;
      const Eigen::Vector4d j_s(wr * jacobians[0][0], wr * jacobians[1][0], wr * jacobians[3][0], wr * jacobians[3][1]);
      const double j_r = wr * jacobians[2][0];
      for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 4; ++k) H(group_index[std::size_t(i)], group_index[std::size_t(k)]) += j_s[i] * j_s[k];
      }
      h_rr += j_r * j_r;
      h_rs += j_r * j_s;
      continue;
    }
    // Priors: rows of J over shared parameters only (diagonal noise).
    const Eigen::MatrixXd& R = factor->noise().sqrtInformation();
    for (int row = 0; row < residuals; ++row) {
      Eigen::VectorXd j_row = Eigen::VectorXd::Zero(n);
      for (std::size_t k = 0; k < keys.size(); ++k) {
        const int size = cost->parameter_block_sizes()[k];
        for (int c = 0; c < size; ++c) {
          const int index = indexOf(keys[k], c);
          if (index >= 0) j_row[index] += R(row, row) * jacobians[k][std::size_t(row * size + c)];
        }
      }
      H += j_row * j_row.transpose();
    }
  }
  closeGroup();
  std::vector<int> free;
  for (int i = 0; i < n; ++i) {
    if (backscatter_free || i < bands || i >= 2 * bands) free.push_back(i);
  }
  Eigen::MatrixXd reduced(free.size(), free.size());
  for (std::size_t i = 0; i < free.size(); ++i) {
    for (std::size_t j = 0; j < free.size(); ++j) reduced(Eigen::Index(i), Eigen::Index(j)) = H(free[i], free[j]);
  }
  // Jacobi scaling before the eigen-decomposition: the blocks differ in units.
  const Eigen::VectorXd scale = reduced.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * reduced * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  const Eigen::VectorXd values = eigen.eigenvalues();
  if (!(values.minCoeff() > 1e-12 * values.maxCoeff())) return std::nullopt;
  const Eigen::MatrixXd inverse_scaled =
      eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  const Eigen::MatrixXd inverse = scale.asDiagonal() * inverse_scaled * scale.asDiagonal();
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < free.size(); ++i) {
    for (std::size_t j = 0; j < free.size(); ++j) covariance(free[i], free[j]) = inverse(Eigen::Index(i), Eigen::Index(j));
  }
  return covariance;
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
  if (initial_attenuation_per_m && (!(*initial_attenuation_per_m > 0.0) || !std::isfinite(*initial_attenuation_per_m))) {
    fail("initial_attenuation_per_m", "a finite value > 0");
  }
  if (!(attenuation_prior_offset_per_m >= 0.0) || !std::isfinite(attenuation_prior_offset_per_m)) {
    fail("attenuation_prior_offset_per_m", "a finite value >= 0");
  }
  if (!(attenuation_prior_sigma_per_m > 0.0) || !std::isfinite(attenuation_prior_sigma_per_m)) {
    fail("attenuation_prior_sigma_per_m", "a finite value > 0");
  }
  if (!(beam_prior_sigma > 0.0) || !std::isfinite(beam_prior_sigma)) fail("beam_prior_sigma", "a finite value > 0");
  if (!(relative_noise > 0.0) || !std::isfinite(relative_noise)) fail("relative_noise", "a finite value > 0");
  if (!(noise_floor_dn > 0.0) || !std::isfinite(noise_floor_dn)) fail("noise_floor_dn", "a finite value > 0");
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) fail("loss_scale", "a finite value > 0");
  if (!(max_attenuation_sigma_per_m > 0.0)) fail("max_attenuation_sigma_per_m", "> 0");
  if (!(attenuation_smoothness_per_m >= 0.0) || !std::isfinite(attenuation_smoothness_per_m)) {
    fail("attenuation_smoothness_per_m", "a finite value >= 0");
  }
  if (!(max_backscatter_sigma_dn > 0.0)) fail("max_backscatter_sigma_dn", "> 0");
  if (!(max_beam_sigma > 0.0)) fail("max_beam_sigma", "> 0");
  if (max_iterations <= 0) fail("max_iterations", "> 0");
  if (num_threads < 0) fail("num_threads", ">= 0 (0: every core)");
}

WaterEstimationReport estimateWater(const RadiometricObservations& observations,
                                    const std::vector<double>& response_dn, const std::vector<double>& wavelengths_nm,
                                    const WaterEstimationOptions& options) {
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
  if (int(wavelengths_nm.size()) != bands) {
    throw std::invalid_argument("radiometry estimation: " + std::to_string(wavelengths_nm.size()) +
                                " wavelengths for " + std::to_string(bands) + " bands");
  }

  WaterEstimationReport report;
  report.observations = int(observations.items.size());
  report.points = observations.points;
  Problem problem = buildProblem(observations, response_dn, wavelengths_nm, options);

  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;

  report.backscatter_estimated = options.estimate_backscatter;
  std::optional<Eigen::MatrixXd> covariance;
  for (int attempt = 0; attempt < 2; ++attempt) {
    GraphProblemOptions problem_options;
    // Reflectances within [1e-4, 10]: a point whose views the loss rejects
    // must not run off to an overflowing prediction.
    for (const Key& key : problem.graph.keys()) {
      if (key.kind() == VariableKind::reflectance) {
        problem.values.updateScalar(key, std::clamp(problem.values.scalar(key), std::log(1e-4), std::log(10.0)));
        problem_options.bounds.push_back({key, 0, std::log(1e-4), std::log(10.0)});
      }
    }
    for (int b = 0; b < bands; ++b) {
      // c(λ) >= 0: light is never amplified by the water.
      problem.values.updateScalar(C(std::uint64_t(b)), std::max(0.0, problem.values.scalar(C(std::uint64_t(b)))));
      problem_options.bounds.push_back({C(std::uint64_t(b)), 0, 0.0, 50.0});
    }
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
    covariance = sharedCovariance(problem, bands, report.backscatter_estimated, options.loss_scale);
    report.covariance_computed = covariance.has_value();
    report.covariance_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    bool backscatter_determined = true;
    if (covariance && report.backscatter_estimated) {
      for (int b = 0; b < bands; ++b) {
        const double sigma = std::sqrt(std::max(0.0, (*covariance)(bands + b, bands + b))) * report.residual_scale;
        backscatter_determined = backscatter_determined && sigma <= options.max_backscatter_sigma_dn;
      }
    }
    if ((report.covariance_computed && backscatter_determined) || !report.backscatter_estimated) break;
    report.backscatter_estimated = false;
    report.water.warnings.push_back(
        std::string("radiometry: the survey does not determine the backscatter (") +
        (report.covariance_computed ? "1-sigma above " + std::to_string(options.max_backscatter_sigma_dn) + " DN"
                                    : std::string("the information is rank deficient with it free")) +
        "): held at zero");
  }

  WaterEstimate& water = report.water;
  auto sigmaAt = [&](int index) -> std::optional<double> {
    if (!covariance) return std::nullopt;
    const double variance = (*covariance)(index, index);
    if (!(variance > 0.0)) return std::nullopt;  // held constant
    return std::sqrt(variance) * report.residual_scale;
  };
  for (int b = 0; b < bands; ++b) {
    water.attenuation_per_m.push_back(problem.values.scalar(C(std::uint64_t(b))));
    water.attenuation_sigma_per_m.push_back(sigmaAt(b));
    water.backscatter_dn.push_back(problem.values.scalar(O(std::uint64_t(b))));
    water.backscatter_sigma_dn.push_back(report.backscatter_estimated ? sigmaAt(bands + b) : std::nullopt);
  }
  const Eigen::VectorXd beam = problem.values.vector(M(0));
  water.beam = {beam[0], beam[1]};
  water.beam_sigma = {sigmaAt(2 * bands), sigmaAt(2 * bands + 1)};
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
