#include "core/survey/calibration_yaml.h"

#include <cmath>

#include "core/survey/number_text.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

// Tolerance on |q| - 1 within which a quaternion is normalised; beyond it the
// four numbers are not a rotation (see survey_config.h).
constexpr double kQuaternionNormTolerance = 1e-3;
// A few ulps of 1: the squared norm of a normalised quaternion lies within it.
constexpr double kUnitSquaredNormSlack = 1e-15;

// Physical bounds (survey_config.h): finite is not enough for a focal length.
constexpr int kMaxImageSide = 65536;
constexpr int kMaxLineSamples = 1000000;
constexpr double kMaxFocalPx = 1e6;
constexpr double kMaxDistortion = 1000.0;
constexpr double kMaxOffsetM = 100.0;  // between two sensors of one vehicle

std::vector<double> distortionCoefficients(const StrictYamlMap& camera, std::size_t count,
                                           std::vector<double> default_value) {
  const std::vector<double> k = camera.numbers("distortion", count, std::move(default_value));
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (std::abs(k[i]) > kMaxDistortion) {
      camera.fail("distortion", "expected coefficients in [-1000, 1000], got " +
                                    formatDouble(k[i]) + " at position " + std::to_string(i + 1));
    }
  }
  return k;
}

void requireModel(const StrictYamlMap& camera, const std::string& model) {
  const std::string found = camera.text("model");
  if (found != model) {
    camera.fail("model", "unsupported camera model " + quoteForMessage(found) + "; expected '" + model + "'");
  }
}

}  // namespace

PinholeRadtanParameters readPinholeRadtanCamera(const StrictYamlMap& parent,
                                                const std::string& key) {
  const StrictYamlMap camera =
      parent.map(key, {"model", "width", "height", "fx", "fy", "cx", "cy", "distortion"});
  requireModel(camera, "pinhole-radtan");
  PinholeRadtanParameters parameters;
  parameters.width = camera.positiveIntegerUpTo("width", kMaxImageSide);
  parameters.height = camera.positiveIntegerUpTo("height", kMaxImageSide);
  parameters.fx = camera.positiveNumberUpTo("fx", kMaxFocalPx);
  parameters.fy = camera.positiveNumberUpTo("fy", kMaxFocalPx);
  parameters.cx = camera.numberInRange("cx", -kMaxFocalPx, kMaxFocalPx);
  parameters.cy = camera.numberInRange("cy", -kMaxFocalPx, kMaxFocalPx);
  const std::vector<double> distortion =
      distortionCoefficients(camera, 5, {0, 0, 0, 0, 0});
  for (std::size_t i = 0; i < 5; ++i) parameters.distortion[i] = distortion[i];
  return parameters;
}

PushbroomParameters readPushbroomCamera(const StrictYamlMap& parent, const std::string& key) {
  const StrictYamlMap camera = parent.map(key, {"model", "samples", "f", "cx", "distortion"});
  requireModel(camera, "pushbroom");
  PushbroomParameters parameters;
  parameters.samples = camera.positiveIntegerUpTo("samples", kMaxLineSamples);
  parameters.f = camera.positiveNumberUpTo("f", kMaxFocalPx);
  parameters.cx = camera.numberInRange("cx", -kMaxFocalPx, kMaxFocalPx);
  const std::vector<double> distortion = distortionCoefficients(camera, 2, {0, 0});
  parameters.distortion = {distortion[0], distortion[1]};
  return parameters;
}

RigidTransformConfig readRigidTransform(const StrictYamlMap& map) {
  const std::vector<double> wxyz = map.numbers("rotation_wxyz", 4);
  const std::vector<double> t = map.numbers("translation_m", 3);
  RigidTransformConfig transform;
  transform.rotation = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  const double norm = transform.rotation.norm();
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    map.fail("rotation_wxyz", "expected a unit quaternion [w, x, y, z] (norm within " +
                                  formatDouble(kQuaternionNormTolerance) + " of 1), got norm " +
                                  formatDouble(norm));
  }
  // A quaternion that is already unit to double precision (as hsmap writes
  // them) is kept bit-identical, so that write -> read is an identity;
  // renormalising it could flip its last bits.
  if (std::abs(transform.rotation.squaredNorm() - 1.0) > kUnitSquaredNormSlack) {
    transform.rotation.normalize();
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > kMaxOffsetM) {
      map.fail("translation_m", "expected offsets in [-100, 100] m between sensors of one "
                                "vehicle, got " + formatDouble(t[i]) + " at position " +
                                std::to_string(i + 1));
    }
  }
  transform.translation_m = Eigen::Vector3d(t[0], t[1], t[2]);
  return transform;
}

void emitNumber(YAML::Emitter& out, double value) { out << formatDouble(value); }

void emitPinholeRadtanCamera(YAML::Emitter& out, const PinholeRadtanParameters& camera) {
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << "pinhole-radtan";
  out << YAML::Key << "width" << YAML::Value << camera.width;
  out << YAML::Key << "height" << YAML::Value << camera.height;
  out << YAML::Key << "fx" << YAML::Value;
  emitNumber(out, camera.fx);
  out << YAML::Key << "fy" << YAML::Value;
  emitNumber(out, camera.fy);
  out << YAML::Key << "cx" << YAML::Value;
  emitNumber(out, camera.cx);
  out << YAML::Key << "cy" << YAML::Value;
  emitNumber(out, camera.cy);
  out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double k : camera.distortion) emitNumber(out, k);
  out << YAML::EndSeq << YAML::EndMap;
}

void emitPushbroomCamera(YAML::Emitter& out, const PushbroomParameters& camera) {
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << "pushbroom";
  out << YAML::Key << "samples" << YAML::Value << camera.samples;
  out << YAML::Key << "f" << YAML::Value;
  emitNumber(out, camera.f);
  out << YAML::Key << "cx" << YAML::Value;
  emitNumber(out, camera.cx);
  out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double k : camera.distortion) emitNumber(out, k);
  out << YAML::EndSeq << YAML::EndMap;
}

void emitRigidTransformKeys(YAML::Emitter& out, const RigidTransformConfig& transform) {
  const Eigen::Quaterniond& q = transform.rotation;
  out << YAML::Key << "rotation_wxyz" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double v : {q.w(), q.x(), q.y(), q.z()}) emitNumber(out, v);
  out << YAML::EndSeq;
  out << YAML::Key << "translation_m" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < 3; ++i) emitNumber(out, transform.translation_m[i]);
  out << YAML::EndSeq;
}

}  // namespace hsmap
