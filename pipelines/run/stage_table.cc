#include "pipelines/run/stage_table.h"

#include <algorithm>
#include <map>

#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/run/frontend_stage.h"
#include "pipelines/run/georef_stage.h"
#include "pipelines/run/joint_stage.h"
#include "pipelines/run/products_stage.h"
#include "pipelines/run/radiometry_stage.h"
#include "pipelines/run/refine_stage.h"
#include "pipelines/run/surface_stage.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

using Published = std::vector<std::pair<fs::path, fs::path>>;

// A georef-format folder (georef_outputs.h) at the contract's paths.
Published trajectoryPublished(const fs::path& folder) {
  return {{folder / georef_files::frames, results_paths::trajectory_frames},
          {folder / georef_files::frames_tum, "trajectory/frames.tum"},
          {folder / georef_files::lines, results_paths::trajectory_uhi_lines},
          {folder / georef_files::lines_tum, "trajectory/uhi_lines.tum"},
          {folder / georef_files::pose_sources, "trajectory/pose_sources.csv"},
          {folder / georef_files::calibration, results_paths::calibration_yaml},
          {folder / georef_files::sparse_ply, results_paths::sparse_ply}};
}

std::string surfaceText(const RunOptions& o) {
  if (o.variant == Variant::planar) {
    return std::string("surface: flat\nseabed_depth_m: ") +
           (o.surface.seabed_depth_m ? formatDouble(*o.surface.seabed_depth_m) : "estimated") + "\n";
  }
  return std::string("surface: ") + toString(o.surface.mode) + "\n";
}

const std::vector<StageDefinition>& definitions() {
  static const std::vector<StageDefinition> table = {
      {StageId::frontend, "frontend", {stage_folders::frontend}, {}, {},
       [](const RunOptions&) { return std::string(); },
       [](const StageContext& c, const RunOptions&) { runFrontendStage(c); }},
      {StageId::georef, "georef", {stage_folders::georef}, trajectoryPublished(stage_folders::georef), {},
       // What georef's result depends on: the front-end's map, or the INS
       // alone (planar); not which variant asked (stage_fingerprints.h).
       [](const RunOptions& o) {
         return std::string("georef_from: ") + (o.variant == Variant::planar ? "ins" : "frontend") + "\n";
       },
       [](const StageContext& c, const RunOptions&) { runGeorefStage(c); }},
      {StageId::surface, "surface", {stage_folders::surface},
       {{fs::path(stage_folders::surface) / stage_folders::mesh_ply, results_paths::mesh_ply}},
       {"--surface", "--seabed-depth"}, surfaceText,
       [](const StageContext& c, const RunOptions& o) { runSurfaceStage(c, o.surface); }},
      {StageId::refine, "refine", {stage_folders::refine},
       {{fs::path(stage_folders::refine) / georef_files::lines, results_paths::trajectory_uhi_lines},
        {fs::path(stage_folders::refine) / georef_files::lines_tum, "trajectory/uhi_lines.tum"},
        {fs::path(stage_folders::refine) / georef_files::calibration, results_paths::calibration_yaml}},
       {"--extrinsic-rounds"},
       [](const RunOptions& o) {
         return "extrinsic_rounds: " + std::to_string(o.refine.rounds) + "\nrefine_cast_pixel_m: " +
                formatDouble(o.refine.cast_pixel_m) + "\n";
       },
       [](const StageContext& c, const RunOptions& o) { runRefineStage(c, o.refine); }},
      {StageId::joint, "joint", {stage_folders::joint},
       [] {
         Published published = trajectoryPublished(stage_folders::joint);
         published.push_back({fs::path(stage_folders::joint) / stage_folders::mesh_ply, results_paths::mesh_ply});
         return published;
       }(),
       {"--joint-rounds", "--joint-tie-points"},
       [](const RunOptions& o) {
         const JointStageOptions& j = o.joint;
         return "joint_rounds: " + std::to_string(j.rounds) + "\njoint_tie_points: " + toString(j.tie_points) +
                "\njoint_cast_pixel_m: " + formatDouble(j.cast_pixel_m) + "\njoint_ortho_patch_spacing_m: " +
                formatDouble(j.ortho_patch_spacing_m) + "\njoint_strip_sigma_match_m: " +
                formatDouble(j.strip_sigma_match_m) + "\njoint_strip_sigma_match_along_m: " +
                formatDouble(j.strip_sigma_match_along_m) + "\n" + surfaceText(o);
       },
       [](const StageContext& c, const RunOptions& o) { runJointStage(c, o.joint, o.surface); }},
      {StageId::radiometry, "radiometry", {radiometry_files::folder},
       {{fs::path(radiometry_files::folder) / radiometry_files::calibration, results_paths::calibration_yaml}}, {},
       [](const RunOptions&) {
         // The stage's options are its defaults (radiometric_observations.h, water_estimation.h).
         return std::string("radiometry: cells 0.1 m, 600 lines, at most 1200000 residuals, 50 iterations, backscatter estimated\n");
       },
       [](const StageContext& c, const RunOptions&) { runRadiometryStage(c); }},
      {StageId::products, "products", {"hyperspectral", "map/rgb_ortho.png", "map/rgb_ortho.tif"}, {},
       {"--ortho-pixel", "--no-geotiff", "--point-cell", "--no-points"},
       [](const RunOptions& o) {
         if (o.variant == Variant::stacked) return std::string("stacked\n");
         const ProductsStageOptions& p = o.products;
         return "ortho_pixel_m: " + formatDouble(p.ortho_pixel_m) + "\ngeotiff: " + (p.geotiff ? "true" : "false") +
                "\npoint_cell_m: " + (p.points ? formatDouble(p.point_cell_m) : std::string("none")) + "\n";
       },
       [](const StageContext& c, const RunOptions& o) { runProductsStage(c, o.products); }},
  };
  return table;
}

// Options a variant ignores although a stage it runs reads them.
bool ignoredBy(const std::string& option, Variant variant) {
  if (option == "--surface") return variant == Variant::planar;  // always a flat seabed
  if (option == "--seabed-depth") return variant != Variant::planar;
  if (option == "--ortho-pixel" || option == "--no-geotiff" || option == "--point-cell" || option == "--no-points") {
    return variant == Variant::stacked;  // the scan lines side by side: no grid, no hits
  }
  return false;
}

}  // namespace

const std::vector<StageId>& variantStages(Variant variant) {
  using S = StageId;
  static const std::vector<StageId> sequential = {S::frontend, S::georef, S::surface, S::refine, S::radiometry,
                                                  S::products};
  static const std::vector<StageId> planar = {S::georef, S::surface, S::radiometry, S::products};
  static const std::vector<StageId> stacked = {S::products};
  static const std::vector<StageId> joint = {S::frontend, S::georef, S::surface, S::joint, S::radiometry,
                                             S::products};
  switch (variant) {
    case Variant::planar: return planar;
    case Variant::stacked: return stacked;
    case Variant::joint: return joint;
    case Variant::sequential: break;
  }
  return sequential;
}

const std::vector<StageId>& allStages() {
  static const std::vector<StageId> stages = [] {
    std::vector<StageId> ids;
    for (const StageDefinition& definition : definitions()) ids.push_back(definition.id);
    return ids;
  }();
  return stages;
}

const StageDefinition& stageDefinition(StageId id) {
  for (const StageDefinition& definition : definitions()) {
    if (definition.id == id) return definition;
  }
  throw std::logic_error("stageDefinition: a stage without a definition");
}

int stageIndex(const std::vector<StageId>& stages, const std::string& name) {
  for (std::size_t i = 0; i < stages.size(); ++i) {
    if (name == stageDefinition(stages[i]).name) return int(i);
  }
  return -1;
}

std::string stageList(const std::vector<StageId>& stages) {
  std::string text;
  for (StageId id : stages) text += (text.empty() ? "" : ", ") + std::string(stageDefinition(id).name);
  return text;
}

std::vector<fs::path> publishedContractPaths() {
  std::vector<fs::path> paths;
  for (const StageDefinition& definition : definitions()) {
    for (const auto& [owned, contract] : definition.published) {
      if (std::find(paths.begin(), paths.end(), contract) == paths.end()) paths.push_back(contract);
    }
  }
  return paths;
}

std::string ignoredOptionError(const RunOptions& options) {
  const std::vector<StageId>& stages = variantStages(options.variant);
  for (const std::string& option : options.given) {
    for (const StageDefinition& definition : definitions()) {
      const auto& reads = definition.command_options;
      if (std::find(reads.begin(), reads.end(), option) == reads.end()) continue;
      const bool runs = std::find(stages.begin(), stages.end(), definition.id) != stages.end();
      if (runs && !ignoredBy(option, options.variant)) continue;
      std::string users;
      for (Variant v : {Variant::sequential, Variant::planar, Variant::stacked, Variant::joint}) {
        const auto& s = variantStages(v);
        if (std::find(s.begin(), s.end(), definition.id) != s.end() && !ignoredBy(option, v)) {
          users += (users.empty() ? "" : ", ") + std::string(toString(v));
        }
      }
      return option + " sets the " + definition.name + " stage, which the " + toString(options.variant) +
             " variant " + (runs ? "runs without it" : "does not run") + "; it applies to: " + users;
    }
  }
  return {};
}

}  // namespace hsmap
