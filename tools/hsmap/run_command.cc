#include "tools/hsmap/run_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <optional>
#include <ostream>

#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "core/survey/run_record.h"
#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "core/util/stage_timer.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/georef/sequential_georef.h"
#include "pipelines/hyperspectral/hyperspectral_point_cloud.h"
#include "tools/hsmap/joint_stage.h"
#include "tools/hsmap/run_stages.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;

// The stages each variant runs, in order.
const std::vector<std::string>& variantStages(const std::string& variant) {
  static const std::vector<std::string> sequential = {"frontend", "georef", "surface", "products"};
  static const std::vector<std::string> planar = {"georef", "surface", "products"};
  static const std::vector<std::string> stacked = {"products"};
  static const std::vector<std::string> joint = {"frontend", "georef", "surface", "products", "joint"};
  return variant == "planar"    ? planar
         : variant == "stacked" ? stacked
         : variant == "joint"   ? joint
                                : sequential;
}

const std::vector<std::string>& supportedVariants() {
  static const std::vector<std::string> names = {"sequential", "planar", "stacked", "joint"};
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

int indexOf(const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return int(i);
  }
  return -1;
}

// What a stage writes, relative to RUN (removed first under --force).
std::vector<fs::path> stageProducts(const std::string& stage) {
  if (stage == "frontend") return {"frontend"};
  if (stage == "surface") return {results_paths::mesh_ply};
  if (stage == "products") return {"hyperspectral", "map/rgb_ortho.png", "map/rgb_ortho.tif"};
  if (stage == "joint") return {};  // rewrites the trajectory, calibration and products in place
  return {"trajectory", "calibration.yaml", "map/sparse.ply", "georef"};
}

std::string secondsText(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", seconds);
  return text;
}

std::string megabytesText(double mb) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f MiB", mb);
  return text;
}

const std::vector<std::string>& supportedSurfaces() {
  static const std::vector<std::string> names = {"dense", "sparse"};
  return names;
}

}  // namespace

CLI::App* addRunCommand(CLI::App& app, RunOptions& options) {
  CLI::App* command =
      app.add_subcommand("run", "Run the processing stages on a survey into a run folder");
  command->footer(
      "Variants and their stages: sequential = frontend, georef, surface, products; planar = "
      "georef (the INS alone), surface (a flat seabed), products; stacked = products (the scan "
      "lines side by side, no map position); joint = sequential's stages, then joint (one "
      "spline trajectory, T_C_U and the time offset estimated together with cross-modal tie "
      "points; the surface and products rebuilt from it). Each stage writes its files into RUN "
      "under temporary names and moves them into place when complete; run.yaml is written "
      "last. The files are described in "
      "docs/SURVEY_FORMAT.md.\n"
      "Exit status: 0 on success; 2 when the survey is invalid (one line naming the file and "
      "the line or key); 1 on other failures.");
  command->add_option("SURVEY", options.survey, "Survey folder (the folder holding survey.yaml)")
      ->required();
  command->add_option("--out", options.out, "Run folder to write into (created if absent)")
      ->required();
  command->add_option("--variant", options.variant,
                      "Estimation variant: " + joined(supportedVariants()))
      ->default_val(options.variant);
  command->add_option("--until", options.until,
                      "Last stage to run (default: the variant's last)");
  command->add_option("--from", options.from,
                      "First stage to run; earlier stages' files are read from RUN");
  command->add_option("--surface", options.surface,
                      "Surface from: dense (stereo depth maps of the keyframes, fused) or sparse "
                      "(the adjusted landmarks alone)")
      ->default_val(options.surface);
  command->add_option("--ortho-pixel", options.ortho_pixel_m,
                      "Ortho-image pixel size in metres (products stage)")
      ->default_val(options.ortho_pixel_m)
      ->check(CLI::PositiveNumber);
  command->add_flag("!--no-geotiff", options.geotiff,
                    "Skip hyperspectral/ortho.tif (the ENVI ortho-image is always written)");
  command->add_option("--point-cell", options.point_cell_m,
                      "Cell size in metres of hyperspectral/points.ply, the hyperspectral point cloud "
                      "(the hits binned into cubes: mean position and mean spectrum of each)")
      ->default_val(options.point_cell_m);
  command->add_flag("!--no-points", options.points,
                    "Skip hyperspectral/points.ply (one more cast and read of the cube)");
  command->add_option("--extrinsic-rounds", options.extrinsic_rounds,
                      "sequential: rounds of the RGB-UHI extrinsic refinement from the RGB and "
                      "hyperspectral ortho-images, each followed by a new cast (0: keep survey.yaml's "
                      "guess)")
      ->default_val(options.extrinsic_rounds)
      ->check(CLI::Range(0, 10));
  command->add_option("--joint-rounds", options.joint_rounds,
                      "joint: rounds of cross-modal tie points, joint solve and new cast (fewer "
                      "when T_C_U and d stop moving)")
      ->default_val(options.joint_rounds)
      ->check(CLI::Range(1, 10));
  command->add_option("--joint-tie-points", options.joint_tie_points,
                      "joint: tie points of the rounds after the first: 'strip' (each push-broom "
                      "strip matched against its prediction from the RGB frames) or 'ortho' (the "
                      "RGB and hyperspectral ortho-images, as the first round)")
      ->default_val(options.joint_tie_points)
      ->check(CLI::IsMember({"strip", "ortho"}));
  command->add_option("--seabed-depth", options.seabed_depth_m,
                      "planar: the flat seabed's depth (z in W, metres down; default: estimated "
                      "from RGB frame pairs scaled by the INS)");
  command->add_flag("--force", options.force,
                    "Replace the outputs that an earlier run left in RUN");
  return command;
}

int runRunCommand(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (indexOf(supportedVariants(), options.variant) < 0) {
    err << "error: unknown variant '" << options.variant << "' for --variant; expected one of "
        << joined(supportedVariants()) << "\n";
    return 1;
  }
  if (indexOf(supportedSurfaces(), options.surface) < 0) {
    err << "error: unknown surface '" << options.surface << "' for --surface; expected one of "
        << joined(supportedSurfaces()) << "\n";
    return 1;
  }
  if (options.points) {
    HyperspectralPointCloudOptions points;
    points.cell_m = options.point_cell_m;
    try {
      points.validate();
    } catch (const std::invalid_argument&) {
      err << "error: --point-cell " << options.point_cell_m << ": expected a cell size between "
          << HyperspectralPointCloudOptions::kMinCellM << " and " << HyperspectralPointCloudOptions::kMaxCellM
          << " m (default " << HyperspectralPointCloudOptions{}.cell_m << "; --no-points skips the point cloud)\n";
      return 1;
    }
  }
  const std::vector<std::string>& stages = variantStages(options.variant);
  const int last = options.until.empty() ? int(stages.size()) - 1 : indexOf(stages, options.until);
  const int first = options.from.empty() ? 0 : indexOf(stages, options.from);
  for (const auto& [flag, name, index] : {std::tuple{"--until", options.until, last},
                                          std::tuple{"--from", options.from, first}}) {
    if (index < 0) {
      err << "error: unknown stage '" << name << "' for " << flag << "; the " << options.variant
          << " variant runs " << joined(stages) << "\n";
      return 1;
    }
  }
  if (first > last) {
    err << "error: --from " << stages[std::size_t(first)] << " comes after --until "
        << stages[std::size_t(last)] << "\n";
    return 1;
  }
  std::error_code error;
  if (fs::exists(options.out, error) && !fs::is_directory(options.out, error)) {
    err << "error: " << options.out.string() << " exists and is not a folder\n";
    return 1;
  }
  // Products an earlier run left: replaced only on purpose.
  std::vector<fs::path> replaced = {results_paths::run_yaml, results_paths::metrics_json};
  for (int s = first; s <= last; ++s) {
    for (const auto& path : stageProducts(stages[std::size_t(s)])) replaced.push_back(path);
  }
  for (const auto& path : replaced) {
    if (!fs::exists(options.out / path, error)) continue;
    if (!options.force) {
      err << "error: " << (options.out / path).string()
          << " exists from an earlier run; pass --force to replace it\n";
      return 1;
    }
  }
  for (const auto& path : replaced) fs::remove_all(options.out / path, error);
  fs::create_directories(options.out);

  RunRecord record;
  record.program_version = HSMAP_VERSION;
  record.variant = options.variant;
  record.survey = fs::absolute(options.survey).lexically_normal();
  record.started_utc = formatUtcTimestamp(std::chrono::system_clock::now());
  record.options["until"] = stages[std::size_t(last)];
  record.options["from"] = stages[std::size_t(first)];
  if (options.variant != "stacked") {
    record.options["surface"] = options.variant == "planar" ? "flat" : options.surface;
  }
  if (options.seabed_depth_m) record.options["seabed_depth_m"] = formatDouble(*options.seabed_depth_m);
  if (indexOf(stages, "products") >= first && indexOf(stages, "products") <= last) {
    record.options["ortho_pixel_m"] = formatDouble(options.ortho_pixel_m);
    record.options["geotiff"] = options.geotiff ? "true" : "false";
    record.options["point_cell_m"] = options.points ? formatDouble(options.point_cell_m) : "none";
    if (options.variant == "sequential") {
      record.options["extrinsic_rounds"] = std::to_string(options.extrinsic_rounds);
    }
  }
  if (indexOf(stages, "joint") >= first && indexOf(stages, "joint") <= last) {
    record.options["joint_rounds"] = std::to_string(options.joint_rounds);
    record.options["joint_tie_points"] = options.joint_tie_points;
  }

  auto finishStage = [&](const std::string& name, double seconds) {
    record.stages.push_back({name, seconds, peakResidentMemoryMb()});
  };
  const auto started = std::chrono::steady_clock::now();
  auto since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  auto stage_start = std::chrono::steady_clock::now();
  const Survey survey = loadSurvey(options.survey);
  finishStage("load", since(stage_start));
  out << "survey '" << survey.config.name << "': " << survey.rgb.frameCount() << " RGB frames, "
      << survey.line_times.size() << " scan lines, " << survey.ins.fixes.size() << " INS fixes ("
      << (survey.ins.has_attitude ? "with" : "without") << " attitude)\n";
  for (const auto& warning : survey.warnings) out << "warning: " << warning << "\n";

  std::optional<FrontendResult> frontend;
  std::optional<GeorefResult> georef;
  for (int s = first; s <= last; ++s) {
    const std::string& stage = stages[std::size_t(s)];
    stage_start = std::chrono::steady_clock::now();
    try {
      if (stage == "frontend") {
        frontend = runFrontendStage(survey, options, out);
      } else if (stage == "georef") {
        if (options.variant != "planar" && !frontend) {
          out << "georef: reading the front-end's files from "
              << (options.out / frontend_files::folder).string() << "\n";
          frontend = readFrontendOutputs(options.out);
        }
        georef = runGeorefStage(survey, frontend, options, out);
      } else if (stage == "surface") {
        if (!georef) {
          err << "error: the surface stage needs the adjusted map of the georef stage in the same "
                 "run; start at --from georef\n";
          return 1;
        }
        runSurfaceStage(survey, *georef, options, out);
      } else if (stage == "products") {
        runProductsStage(survey, options, out);
      } else if (stage == "joint") {
        if (!frontend) {
          out << "joint: reading the front-end's files from "
              << (options.out / frontend_files::folder).string() << "\n";
          frontend = readFrontendOutputs(options.out);
        }
        if (!georef) {
          // The sequential start again, in memory (its files were replaced
          // by an earlier joint stage); deterministic, a few seconds.
          out << "joint: geo-referencing the front-end's map again (in memory, nothing written)\n";
          georef = runSequentialGeoref(survey, *frontend, GeorefOptions{});
          georef->variant = "joint";
        }
        runJointStage(survey, *frontend, *georef, options, out);
      }
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& failure) {
      err << "error: stage " << stage << " failed: " << failure.what() << "\n";
      return 1;
    }
    finishStage(stage, since(stage_start));
  }
  record.total_time_s = since(started);
  record.peak_rss_mb = peakResidentMemoryMb();
  writeRunRecord(options.out / results_paths::run_yaml, record);

  out << "stage times and peak memory (of the process when the stage ended):\n";
  for (const auto& stage : record.stages) {
    char line[128];
    std::snprintf(line, sizeof(line), "  %-10s %10s %10s\n", stage.name.c_str(),
                  secondsText(stage.time_s).c_str(), megabytesText(stage.peak_rss_mb).c_str());
    out << line;
  }
  out << "total " << secondsText(record.total_time_s) << ", peak memory "
      << megabytesText(record.peak_rss_mb) << "; the run is in " << options.out.string()
      << " (run.yaml written)\n";
  return 0;
}

}  // namespace hsmap
