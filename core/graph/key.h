#pragma once
// Key: the typed name of one variable of the factor graph.
//
// As in GTSAM, a key reads like the maths: X(3) is keyframe pose 3, L(17) is
// landmark 17, S(5) is control point 5 of the SE(3) spline, E(0) the RGB–UHI
// extrinsic T_C_U, D(0) the UHI time offset d, K(0) a set of intrinsics. The
// kind is part of the key, so X(3) and L(3) are different variables.

#include <compare>
#include <cstdint>
#include <functional>
#include <string>

namespace hsmap {

enum class VariableKind : std::uint8_t {
  keyframe_pose,         // 'x': T_W_C of a keyframe (SE(3))
  landmark,              // 'l': p_W of a 3D point
  spline_control_point,  // 's': control pose of the SE(3) B-spline
  extrinsic,             // 'e': a sensor-to-sensor pose such as T_C_U
  time_offset,           // 'd': a clock offset in seconds
  intrinsics,            // 'k': camera intrinsic parameters
  water_attenuation,     // 'c': the water's attenuation c(lambda) of one band, 1/m
  backscatter,           // 'o': the additive backscatter of one band, DN
  lamp_beam,             // 'm': the lamps' beam-shape coefficients
  reflectance,           // 'r': log reflectance of one seabed point in one band
};

// The one-letter symbol of a kind, as printed in keys ("x3").
char symbolOf(VariableKind kind);

class Key {
 public:
  constexpr Key(VariableKind kind, std::uint64_t index) : kind_(kind), index_(index) {}

  constexpr VariableKind kind() const { return kind_; }
  constexpr std::uint64_t index() const { return index_; }
  std::string toString() const;  // "x3", "l17", "e0"

  friend constexpr auto operator<=>(const Key&, const Key&) = default;

 private:
  VariableKind kind_;
  std::uint64_t index_;
};

constexpr Key X(std::uint64_t i) { return {VariableKind::keyframe_pose, i}; }
constexpr Key L(std::uint64_t i) { return {VariableKind::landmark, i}; }
constexpr Key S(std::uint64_t i) { return {VariableKind::spline_control_point, i}; }
constexpr Key E(std::uint64_t i = 0) { return {VariableKind::extrinsic, i}; }
constexpr Key D(std::uint64_t i = 0) { return {VariableKind::time_offset, i}; }
constexpr Key K(std::uint64_t i = 0) { return {VariableKind::intrinsics, i}; }
constexpr Key C(std::uint64_t band) { return {VariableKind::water_attenuation, band}; }
constexpr Key O(std::uint64_t band) { return {VariableKind::backscatter, band}; }
constexpr Key M(std::uint64_t i = 0) { return {VariableKind::lamp_beam, i}; }
constexpr Key R(std::uint64_t i) { return {VariableKind::reflectance, i}; }

}  // namespace hsmap

template <>
struct std::hash<hsmap::Key> {
  std::size_t operator()(const hsmap::Key& key) const noexcept {
    return std::hash<std::uint64_t>{}((key.index() << 3) ^ static_cast<std::uint64_t>(key.kind()));
  }
};
