#include "core/graph/key.h"

namespace hsmap {

char symbolOf(VariableKind kind) {
  switch (kind) {
    case VariableKind::keyframe_pose: return 'x';
    case VariableKind::landmark: return 'l';
    case VariableKind::spline_control_point: return 's';
    case VariableKind::extrinsic: return 'e';
    case VariableKind::time_offset: return 'd';
    case VariableKind::intrinsics: return 'k';
    case VariableKind::water_attenuation: return 'c';
    case VariableKind::backscatter: return 'o';
    case VariableKind::lamp_beam: return 'm';
    case VariableKind::reflectance: return 'r';
  }
  return '?';
}

std::string Key::toString() const { return symbolOf(kind_) + std::to_string(index_); }

}  // namespace hsmap
