#include "core/survey/water_estimate.h"

#include <set>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"

namespace hsmap {

namespace {

void emitNumbers(YAML::Emitter& out, const std::vector<double>& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double v : values) emitNumber(out, v);
  out << YAML::EndSeq;
}

template <class Container>
void emitOptionalNumbers(YAML::Emitter& out, const Container& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const std::optional<double>& v : values) {
    if (v) {
      emitNumber(out, *v);
    } else {
      out << YAML::Null;
    }
  }
  out << YAML::EndSeq;
}

long long lineOf(const YAML::Node& node) { return node.Mark().line >= 0 ? node.Mark().line + 1 : 0; }

[[noreturn]] void fail(const std::filesystem::path& file, const YAML::Node& node, const std::string& key,
                       const std::string& detail) {
  throw InputError(file, "line " + std::to_string(lineOf(node)) + ", key " + key, detail);
}

std::optional<double> optionalNumber(const std::filesystem::path& file, const YAML::Node& node,
                                     const std::string& key, bool null_allowed) {
  if (node.IsNull() && null_allowed) return std::nullopt;
  if (!node.IsScalar()) fail(file, node, key, "expected a number, got " + describeYamlNode(node));
  std::string message;
  const std::optional<double> value = parseFiniteDouble(node.Scalar(), &message);
  if (!value) fail(file, node, key, "expected a finite number" + std::string(null_allowed ? " or null" : "") +
                                        ", got " + describeYamlNode(node));
  return value;
}

std::vector<std::optional<double>> optionalNumbers(const std::filesystem::path& file, const YAML::Node& map,
                                                   const std::string& parent, const std::string& key,
                                                   std::size_t count, bool null_allowed) {
  const YAML::Node node = map[key];
  const std::string dotted = parent + "." + key;
  if (!node) fail(file, map, dotted, "missing required key");
  if (!node.IsSequence() || (count > 0 && node.size() != count)) {
    fail(file, node, dotted,
         "expected a list of " + (count > 0 ? std::to_string(count) + " " : std::string()) + "numbers" +
             (null_allowed ? " or nulls" : "") + ", got " + describeYamlNode(node) +
             (node.IsSequence() ? " of " + std::to_string(node.size()) : std::string()));
  }
  std::vector<std::optional<double>> values;
  for (std::size_t i = 0; i < node.size(); ++i) {
    values.push_back(optionalNumber(file, node[i], dotted + "[" + std::to_string(i) + "]", null_allowed));
  }
  return values;
}

std::vector<double> numbers(const std::filesystem::path& file, const YAML::Node& map, const std::string& parent,
                            const std::string& key, std::size_t count) {
  std::vector<double> values;
  for (const auto& v : optionalNumbers(file, map, parent, key, count, false)) values.push_back(*v);
  return values;
}

void requireKeys(const std::filesystem::path& file, const YAML::Node& map, const std::string& key,
                 const std::set<std::string>& allowed) {
  if (!map.IsMap()) fail(file, map, key, "expected a map, got " + describeYamlNode(map));
  for (const auto& entry : map) {
    const std::string name = entry.first.Scalar();
    if (allowed.count(name) == 0) fail(file, entry.first, key + "." + name, "unknown key");
  }
}

}  // namespace

void emitWaterBlock(YAML::Emitter& out, const WaterEstimate& water) {
  out << YAML::BeginMap;
  out << YAML::Key << "attenuation_per_m" << YAML::Value;
  emitNumbers(out, water.attenuation_per_m);
  out << YAML::Key << "attenuation_sigma_per_m" << YAML::Value;
  emitOptionalNumbers(out, water.attenuation_sigma_per_m);
  out << YAML::Key << "backscatter_dn" << YAML::Value;
  emitNumbers(out, water.backscatter_dn);
  out << YAML::Key << "backscatter_sigma_dn" << YAML::Value;
  emitOptionalNumbers(out, water.backscatter_sigma_dn);
  out << YAML::Key << "beam" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << WaterEstimate::kBeamModel;
  out << YAML::Key << "coefficients" << YAML::Value;
  emitNumbers(out, {water.beam[0], water.beam[1]});
  out << YAML::Key << "coefficients_sigma" << YAML::Value;
  emitOptionalNumbers(out, water.beam_sigma);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

WaterEstimate readWaterBlock(const std::filesystem::path& file, const YAML::Node& node, const std::string& key) {
  requireKeys(file, node, key,
              {"attenuation_per_m", "attenuation_sigma_per_m", "backscatter_dn", "backscatter_sigma_dn", "beam"});
  WaterEstimate water;
  water.attenuation_per_m = numbers(file, node, key, "attenuation_per_m", 0);
  const std::size_t bands = water.attenuation_per_m.size();
  if (bands == 0) fail(file, node["attenuation_per_m"], key + ".attenuation_per_m", "expected at least one band");
  water.attenuation_sigma_per_m = optionalNumbers(file, node, key, "attenuation_sigma_per_m", bands, true);
  water.backscatter_dn = numbers(file, node, key, "backscatter_dn", bands);
  water.backscatter_sigma_dn = optionalNumbers(file, node, key, "backscatter_sigma_dn", bands, true);
  const YAML::Node beam = node["beam"];
  if (!beam) fail(file, node, key + ".beam", "missing required key");
  requireKeys(file, beam, key + ".beam", {"model", "coefficients", "coefficients_sigma"});
  if (!beam["model"] || !beam["model"].IsScalar() || beam["model"].Scalar() != WaterEstimate::kBeamModel) {
    fail(file, beam, key + ".beam.model", std::string("expected '") + WaterEstimate::kBeamModel + "'");
  }
  const std::vector<double> coefficients = numbers(file, beam, key + ".beam", "coefficients", 2);
  const auto sigma = optionalNumbers(file, beam, key + ".beam", "coefficients_sigma", 2, true);
  for (int i = 0; i < 2; ++i) {
    water.beam[std::size_t(i)] = coefficients[std::size_t(i)];
    water.beam_sigma[std::size_t(i)] = sigma[std::size_t(i)];
  }
  return water;
}

void writeWaterEstimate(const std::filesystem::path& file, const WaterEstimate& water) {
  YAML::Emitter out;
  out.SetNullFormat(YAML::LowerNull);
  out << YAML::Comment("hsmap radiometry estimate (format: see docs/RADIOMETRY.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << WaterEstimate::kFormat;
  out << YAML::Key << "water" << YAML::Value;
  emitWaterBlock(out, water);
  out << YAML::Key << "warnings" << YAML::Value << YAML::BeginSeq;
  for (const std::string& warning : water.warnings) out << warning;
  out << YAML::EndSeq;
  out << YAML::EndMap;
  writeTextAtomically(file, std::string(out.c_str()) + "\n");
}

WaterEstimate readWaterEstimate(const std::filesystem::path& file) {
  const YAML::Node root = loadYamlFile(file);
  requireKeys(file, root, "(document)", {"format", "water", "warnings"});
  if (!root["format"] || !root["format"].IsScalar() || root["format"].Scalar() != WaterEstimate::kFormat) {
    fail(file, root, "format", std::string("expected '") + WaterEstimate::kFormat + "'");
  }
  if (!root["water"]) fail(file, root, "water", "missing required key");
  WaterEstimate water = readWaterBlock(file, root["water"], "water");
  const YAML::Node warnings = root["warnings"];
  if (!warnings || !warnings.IsSequence()) fail(file, root, "warnings", "expected a list of texts");
  for (const auto& warning : warnings) {
    if (!warning.IsScalar()) fail(file, warning, "warnings", "expected a text");
    water.warnings.push_back(warning.Scalar());
  }
  return water;
}

}  // namespace hsmap
