#include "core/graph/values.h"

#include <algorithm>
#include <stdexcept>

namespace hsmap {

const char* toString(ValueType type) {
  switch (type) {
    case ValueType::pose3: return "pose3";
    case ValueType::point3: return "point3";
    case ValueType::scalar: return "scalar";
    case ValueType::vector: return "vector";
  }
  return "?";
}

namespace {
std::vector<double> poseBlock(const Eigen::Quaterniond& q_in, const Eigen::Vector3d& t) {
  if (!q_in.coeffs().allFinite() || !t.allFinite() || q_in.norm() < 1e-12) {
    throw std::invalid_argument("Values: a pose needs a finite, non-zero quaternion and a finite translation");
  }
  const Eigen::Quaterniond q = q_in.normalized();
  return {q.x(), q.y(), q.z(), q.w(), t.x(), t.y(), t.z()};
}
}  // namespace

void Values::insert(Key key, ValueType type, std::vector<double> data) {
  if (entries_.count(key) != 0) {
    throw std::invalid_argument("Values: key " + key.toString() + " is already present");
  }
  entries_.emplace(key, Entry{type, std::move(data)});
}

void Values::insertPose(Key key, const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  insert(key, ValueType::pose3, poseBlock(q, t));
}
void Values::insertPoint(Key key, const Eigen::Vector3d& p) {
  insert(key, ValueType::point3, {p.x(), p.y(), p.z()});
}
void Values::insertScalar(Key key, double value) { insert(key, ValueType::scalar, {value}); }
void Values::insertVector(Key key, const Eigen::VectorXd& value) {
  if (value.size() == 0) throw std::invalid_argument("Values: vector " + key.toString() + " is empty");
  insert(key, ValueType::vector, std::vector<double>(value.data(), value.data() + value.size()));
}

void Values::updatePose(Key key, const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  // Copy into the existing block: its address must not change (solvers hold it).
  const std::vector<double> block = poseBlock(q, t);
  std::copy(block.begin(), block.end(), entry(key, ValueType::pose3).data.begin());
}
void Values::updatePoint(Key key, const Eigen::Vector3d& p) {
  Eigen::Map<Eigen::Vector3d>(entry(key, ValueType::point3).data.data()) = p;
}
void Values::updateScalar(Key key, double value) { entry(key, ValueType::scalar).data[0] = value; }
void Values::updateVector(Key key, const Eigen::VectorXd& value) {
  Entry& e = entry(key, ValueType::vector);
  if (static_cast<Eigen::Index>(e.data.size()) != value.size()) {
    throw std::invalid_argument("Values: vector " + key.toString() + " has size " +
                                std::to_string(e.data.size()) + ", not " + std::to_string(value.size()));
  }
  std::copy(value.data(), value.data() + value.size(), e.data.begin());
}

Eigen::Quaterniond Values::poseRotation(Key key) const {
  return Eigen::Map<const Eigen::Quaterniond>(entry(key, ValueType::pose3).data.data());
}
Eigen::Vector3d Values::poseTranslation(Key key) const {
  return Eigen::Map<const Eigen::Vector3d>(entry(key, ValueType::pose3).data.data() + 4);
}
Eigen::Vector3d Values::point(Key key) const {
  return Eigen::Map<const Eigen::Vector3d>(entry(key, ValueType::point3).data.data());
}
double Values::scalar(Key key) const { return entry(key, ValueType::scalar).data[0]; }
Eigen::VectorXd Values::vector(Key key) const {
  const Entry& e = entry(key, ValueType::vector);
  return Eigen::Map<const Eigen::VectorXd>(e.data.data(), static_cast<Eigen::Index>(e.data.size()));
}

ValueType Values::type(Key key) const { return anyEntry(key).type; }
int Values::size(Key key) const { return static_cast<int>(anyEntry(key).data.size()); }
int Values::tangentSize(Key key) const {
  const Entry& e = anyEntry(key);
  return e.type == ValueType::pose3 ? 6 : static_cast<int>(e.data.size());
}

std::vector<Key> Values::keys() const {
  std::vector<Key> result;
  result.reserve(entries_.size());
  for (const auto& [key, e] : entries_) result.push_back(key);
  return result;
}

double* Values::data(Key key) {
  return const_cast<Entry&>(anyEntry(key)).data.data();
}
const double* Values::data(Key key) const { return anyEntry(key).data.data(); }

void Values::erase(Key key) {
  if (entries_.erase(key) == 0) throw std::out_of_range("Values: no variable " + key.toString());
}

const Values::Entry& Values::anyEntry(Key key) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) throw std::out_of_range("Values: no variable " + key.toString());
  return it->second;
}

const Values::Entry& Values::entry(Key key, ValueType expected) const {
  const Entry& e = anyEntry(key);
  if (e.type != expected) {
    throw std::invalid_argument("Values: " + key.toString() + " holds a " + toString(e.type) +
                                ", not a " + toString(expected));
  }
  return e;
}

Values::Entry& Values::entry(Key key, ValueType expected) {
  return const_cast<Entry&>(static_cast<const Values*>(this)->entry(key, expected));
}

}  // namespace hsmap
