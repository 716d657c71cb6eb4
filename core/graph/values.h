#pragma once
// Values: the current estimate of every variable of a factor graph, by key.
//
// Each variable is stored as a flat block of doubles whose address never
// changes while the variable exists, so a solver can hand the blocks to its
// back-end directly and write the optimum back in place. Layouts:
//   pose3   7 doubles [qx qy qz qw tx ty tz]  (Eigen's quaternion memory order,
//           then the translation): the pose T_A_B with p_A = q * p_B + t
//   point3  3 doubles [x y z]
//   scalar  1 double
//   vector  n doubles (e.g. intrinsics)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "core/graph/key.h"

namespace hsmap {

enum class ValueType { pose3, point3, scalar, vector };
const char* toString(ValueType type);

class Values {
 public:
  // Inserting a key twice is an error (std::invalid_argument); use update*().
  void insertPose(Key key, const Eigen::Quaterniond& q, const Eigen::Vector3d& t);
  void insertPoint(Key key, const Eigen::Vector3d& p);
  void insertScalar(Key key, double value);
  void insertVector(Key key, const Eigen::VectorXd& value);

  // Replace an existing value of the same type and size.
  void updatePose(Key key, const Eigen::Quaterniond& q, const Eigen::Vector3d& t);
  void updatePoint(Key key, const Eigen::Vector3d& p);
  void updateScalar(Key key, double value);
  void updateVector(Key key, const Eigen::VectorXd& value);

  // Typed reads; a missing key or a type mismatch is an error naming the key.
  Eigen::Quaterniond poseRotation(Key key) const;
  Eigen::Vector3d poseTranslation(Key key) const;
  Eigen::Vector3d point(Key key) const;
  double scalar(Key key) const;
  Eigen::VectorXd vector(Key key) const;

  bool contains(Key key) const { return entries_.count(key) != 0; }
  ValueType type(Key key) const;
  // Number of stored doubles of the variable (7 for a pose).
  int size(Key key) const;
  // Degrees of freedom of the variable (6 for a pose).
  int tangentSize(Key key) const;
  std::size_t count() const { return entries_.size(); }
  std::vector<Key> keys() const;  // in key order

  // Stable address of the variable's block, for solvers.
  double* data(Key key);
  const double* data(Key key) const;

  void erase(Key key);

 private:
  struct Entry {
    ValueType type;
    std::vector<double> data;
  };
  void insert(Key key, ValueType type, std::vector<double> data);
  Entry& entry(Key key, ValueType expected);
  const Entry& entry(Key key, ValueType expected) const;
  const Entry& anyEntry(Key key) const;

  std::map<Key, Entry> entries_;
};

}  // namespace hsmap
