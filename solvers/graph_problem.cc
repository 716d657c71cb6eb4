#include "solvers/graph_problem.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "factors/ceres_factor.h"
#include "solvers/se3_manifold.h"
#include "solvers/whitened_cost_function.h"

namespace hsmap {

namespace {

// How many offending keys an error message lists before "and N more".
constexpr std::size_t kMaxListed = 5;

std::string describeFactor(const FactorGraph& graph, FactorGraph::FactorIndex index) {
  return "factor #" + std::to_string(index) + " (" + graph.factor(index)->name() + ")";
}

std::string doubles(int n) { return std::to_string(n) + (n == 1 ? " double" : " doubles"); }

[[noreturn]] void fail(const std::string& detail) {
  throw std::invalid_argument("GraphProblem: " + detail);
}

}  // namespace

GraphProblem::GraphProblem(const FactorGraph& graph, Values& values, GraphProblemOptions options)
    : graph_(graph), values_(values), options_(std::move(options)) {
  // Every variable the factors use must have a value.
  const std::vector<Key> missing = graph_.missingKeys(values_);
  if (!missing.empty()) {
    std::ostringstream message;
    message << missing.size() << " variable" << (missing.size() == 1 ? "" : "s")
            << " used by factors " << (missing.size() == 1 ? "has" : "have")
            << " no value in Values: ";
    for (std::size_t i = 0; i < missing.size() && i < kMaxListed; ++i) {
      if (i > 0) message << ", ";
      message << missing[i].toString() << " (used by "
              << describeFactor(graph_, graph_.factorsOf(missing[i]).front()) << ")";
    }
    if (missing.size() > kMaxListed) message << " and " << missing.size() - kMaxListed << " more";
    fail(message.str());
  }
  // A constant key without factors is fine when it has a value (it stays as
  // it is anyway, e.g. "every control point" when some have no measurement);
  // one that names nothing at all is most likely a wrong key.
  for (const Key& key : options_.constant) {
    if (graph_.factorsOf(key).empty() && !values_.contains(key)) {
      fail("constant variable " + key.toString() +
           " is neither used by a factor of the graph nor present in Values");
    }
  }

  se3_manifold_ = std::make_unique<Se3Manifold>();
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_ = std::make_unique<ceres::Problem>(problem_options);

  variables_ = graph_.keys();
  std::size_t total = 0;
  for (const Key& key : variables_) {
    block_offset_[key] = total;
    total += std::size_t(values_.size(key));
  }
  blocks_.resize(total);
  loadValues();
  for (const auto& [key, components] : options_.constant_components) {
    if (graph_.factorsOf(key).empty()) {
      fail("constant components of " + key.toString() + ": the variable is not used by any factor of the graph");
    }
    if (values_.type(key) == ValueType::pose3) {
      fail("constant components of " + key.toString() + ": not supported on poses");
    }
    for (const int index : components) {
      if (index < 0 || index >= values_.size(key)) {
        fail("constant components of " + key.toString() + ": index " + std::to_string(index) +
             " is outside [0, " + std::to_string(values_.size(key)) + ")");
      }
    }
    if (!components.empty() && !isConstant(key)) {
      subset_manifolds_[key] = std::make_unique<ceres::SubsetManifold>(values_.size(key), components);
    }
  }
  for (const Key& key : variables_) {
    const bool is_pose = values_.type(key) == ValueType::pose3;
    const auto subset = subset_manifolds_.find(key);
    ceres::Manifold* manifold = is_pose ? se3_manifold_.get()
                                : subset != subset_manifolds_.end() ? subset->second.get()
                                                                    : nullptr;
    problem_->AddParameterBlock(block(key), values_.size(key), manifold);
    if (isConstant(key)) {
      ++num_constant_variables_;
      problem_->SetParameterBlockConstant(block(key));
    } else {
      num_free_parameters_ += tangentSize(key);
    }
  }

  residual_blocks_.reserve(graph_.size());
  factor_losses_.reserve(graph_.size());
  std::vector<double*> blocks;
  for (FactorGraph::FactorIndex index = 0; index < graph_.size(); ++index) {
    const Factor& factor = *graph_.factor(index);
    const auto* ceres_factor = dynamic_cast<const CeresFactor*>(&factor);
    if (ceres_factor == nullptr) {
      fail(describeFactor(graph_, index) +
           " is not a CeresFactor, so the Ceres solver cannot evaluate it");
    }
    std::unique_ptr<ceres::CostFunction> raw = ceres_factor->createCostFunction();
    if (!raw) fail(describeFactor(graph_, index) + " returned no cost function");
    const std::vector<Key>& keys = factor.keys();
    const std::vector<int32_t>& sizes = raw->parameter_block_sizes();
    if (sizes.size() != keys.size()) {
      fail(describeFactor(graph_, index) + " names " + std::to_string(keys.size()) +
           " variables but its cost function takes " + std::to_string(sizes.size()) +
           " parameter blocks");
    }
    blocks.clear();
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (sizes[k] != values_.size(keys[k])) {
        fail(describeFactor(graph_, index) + " expects a block of " + doubles(sizes[k]) + " for " +
             keys[k].toString() + ", but Values holds a " + toString(values_.type(keys[k])) +
             " of " + doubles(values_.size(keys[k])));
      }
      blocks.push_back(block(keys[k]));
    }
    if (raw->num_residuals() != factor.noise().dimension()) {
      fail(describeFactor(graph_, index) + " returns " + std::to_string(raw->num_residuals()) +
           " residuals but its noise model has dimension " +
           std::to_string(factor.noise().dimension()));
    }

    ceres::LossFunction* loss = nullptr;
    const RobustLoss& robust = factor.robustLoss();
    if (robust.kind != RobustLoss::Kind::none) {
      std::unique_ptr<ceres::LossFunction>& shared =
          losses_[{static_cast<int>(robust.kind), robust.scale}];
      if (!shared) {
        if (robust.kind == RobustLoss::Kind::huber) {
          shared = std::make_unique<ceres::HuberLoss>(robust.scale);
        } else {
          shared = std::make_unique<ceres::CauchyLoss>(robust.scale);
        }
      }
      loss = shared.get();
    }
    auto whitened = std::make_unique<WhitenedCostFunction>(std::move(raw), factor.noise());
    residual_blocks_.push_back(problem_->AddResidualBlock(whitened.release(), loss, blocks));
    factor_losses_.push_back(loss);
  }

  for (const VariableBound& bound : options_.bounds) {
    const std::string name = bound.key.toString();
    if (graph_.factorsOf(bound.key).empty()) {
      fail("bound on " + name + ": the variable is not used by any factor of the graph");
    }
    if (values_.type(bound.key) == ValueType::pose3) {
      fail("bound on " + name + ": bounds on poses are not supported (quaternion components " +
           "have no meaning on their own)");
    }
    if (bound.index < 0 || bound.index >= values_.size(bound.key)) {
      fail("bound on " + name + ": index " + std::to_string(bound.index) + " is outside [0, " +
           std::to_string(values_.size(bound.key)) + ")");
    }
    if (!(bound.lower < bound.upper)) {
      std::ostringstream message;
      message << "bound on " << name << "[" << bound.index << "]: lower " << bound.lower
              << " must be below upper " << bound.upper;
      fail(message.str());
    }
    const double current = values_.data(bound.key)[bound.index];
    if (!(current >= bound.lower && current <= bound.upper)) {
      std::ostringstream message;
      message << "bound on " << name << "[" << bound.index << "]: the current value " << current
              << " lies outside [" << bound.lower << ", " << bound.upper << "]";
      fail(message.str());
    }
    problem_->SetParameterLowerBound(block(bound.key), bound.index, bound.lower);
    problem_->SetParameterUpperBound(block(bound.key), bound.index, bound.upper);
  }

  // Greedy independent set of the free landmarks, in key order.
  std::unordered_set<Key> in_group;
  for (const Key& key : variables_) {
    if (key.kind() != VariableKind::landmark || isConstant(key)) continue;
    bool independent = true;
    for (const FactorGraph::FactorIndex index : graph_.factorsOf(key)) {
      for (const Key& other : graph_.factor(index)->keys()) {
        if (other != key && in_group.count(other) != 0) independent = false;
      }
    }
    if (independent) {
      in_group.insert(key);
      eliminated_landmarks_.push_back(key);
    }
  }
}

GraphProblem::~GraphProblem() = default;

int GraphProblem::tangentSize(Key key) const {
  const auto subset = subset_manifolds_.find(key);
  if (subset != subset_manifolds_.end()) return subset->second->TangentSize();
  return values_.tangentSize(key);
}

double* GraphProblem::block(Key key) {
  const auto it = block_offset_.find(key);
  if (it == block_offset_.end()) throw std::out_of_range("GraphProblem: " + key.toString() + " is not a variable");
  return blocks_.data() + it->second;
}

const double* GraphProblem::block(Key key) const { return const_cast<GraphProblem*>(this)->block(key); }

void GraphProblem::loadValues() const {
  for (const auto& [key, offset] : block_offset_) {
    const double* value = values_.data(key);
    std::copy(value, value + values_.size(key), blocks_.begin() + std::ptrdiff_t(offset));
  }
}

void GraphProblem::storeValues() {
  for (const auto& [key, offset] : block_offset_) {
    double* value = values_.data(key);
    std::copy(blocks_.begin() + std::ptrdiff_t(offset), blocks_.begin() + std::ptrdiff_t(offset) + values_.size(key),
              value);
  }
}

std::shared_ptr<ceres::ParameterBlockOrdering> GraphProblem::schurOrdering() const {
  if (eliminated_landmarks_.empty()) return nullptr;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  // The blocks are the problem's; Ceres names them by non-const pointer.
  auto* self = const_cast<GraphProblem*>(this);
  for (const Key& key : variables_) ordering->AddElementToGroup(self->block(key), 1);
  for (const Key& key : eliminated_landmarks_) ordering->AddElementToGroup(self->block(key), 0);
  return ordering;
}

std::vector<FactorEvaluation> GraphProblem::evaluateFactors(int num_threads) const {
  std::vector<FactorEvaluation> evaluations;
  if (residual_blocks_.empty()) return evaluations;
  loadValues();
  // One multi-threaded evaluation of every whitened residual without the
  // loss; the loss is applied here per factor, so outliers can be told apart.
  ceres::Problem::EvaluateOptions evaluate_options;
  evaluate_options.residual_blocks = residual_blocks_;
  evaluate_options.apply_loss_function = false;
  evaluate_options.num_threads = num_threads;
  double total = 0.0;
  std::vector<double> residuals;
  if (!problem_->Evaluate(evaluate_options, &total, &residuals, nullptr, nullptr)) {
    throw std::runtime_error("GraphProblem: a factor failed to evaluate at the current values");
  }
  evaluations.resize(graph_.size());
  std::size_t offset = 0;
  for (FactorGraph::FactorIndex index = 0; index < graph_.size(); ++index) {
    const Factor& factor = *graph_.factor(index);
    const int dimension = factor.residualDimension();
    double squared_norm = 0.0;
    for (int i = 0; i < dimension; ++i) squared_norm += residuals[offset + i] * residuals[offset + i];
    offset += static_cast<std::size_t>(dimension);

    FactorEvaluation& evaluation = evaluations[index];
    evaluation.whitened_norm = std::sqrt(squared_norm);
    const ceres::LossFunction* loss = factor_losses_[index];
    if (loss == nullptr) {
      evaluation.cost = 0.5 * squared_norm;
    } else {
      double rho[3];
      loss->Evaluate(squared_norm, rho);
      evaluation.cost = 0.5 * rho[0];
      evaluation.beyond_loss_scale = evaluation.whitened_norm > factor.robustLoss().scale;
    }
  }
  return evaluations;
}

std::map<std::string, FactorTypeCost> GraphProblem::costByFactorType(int num_threads) const {
  std::map<std::string, FactorTypeCost> costs;
  const std::vector<FactorEvaluation> evaluations = evaluateFactors(num_threads);
  for (FactorGraph::FactorIndex index = 0; index < evaluations.size(); ++index) {
    FactorTypeCost& entry = costs[graph_.factor(index)->name()];
    ++entry.count;
    entry.cost += evaluations[index].cost;
    if (evaluations[index].beyond_loss_scale) ++entry.beyond_loss_scale;
  }
  return costs;
}

}  // namespace hsmap
