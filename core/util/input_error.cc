#include "core/util/input_error.h"

namespace hsmap {
namespace {
std::string render(const std::filesystem::path& file, const std::string& where,
                   const std::string& detail) {
  std::string text = file.string();
  if (!where.empty()) text += ":" + where;
  return text + ": " + detail;
}
}  // namespace

InputError::InputError(std::filesystem::path file, std::string where, std::string detail)
    : std::runtime_error(render(file, where, detail)),
      file_(std::move(file)),
      where_(std::move(where)),
      detail_(std::move(detail)) {}

std::string InputError::atLine(long long line_number) {
  return "line " + std::to_string(line_number);
}

std::string InputError::atKey(const std::string& dotted_key) { return "key " + dotted_key; }

}  // namespace hsmap
