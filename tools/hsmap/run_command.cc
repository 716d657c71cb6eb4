#include "tools/hsmap/run_command.h"

#include <CLI/CLI.hpp>
#include <ostream>
#include <stdexcept>

#include "pipelines/run/runner.h"

namespace hsmap {

CLI::App* addRunCommand(CLI::App& app, RunCommandLine& line) {
  RunOptions& options = line.options;
  CLI::App* command = app.add_subcommand("run", "Run the processing stages on a survey into a run folder");
  line.command = command;
  command->footer(
      "Variants and their stages: sequential = frontend, georef, surface, refine (T_C_U from the RGB and "
      "hyperspectral ortho-images), products; planar = georef (the INS alone), surface (a flat seabed), "
      "products; stacked = products (the scan lines side by side, no map position); joint = frontend, "
      "georef, surface, joint (one spline trajectory, T_C_U and the time offset estimated together with "
      "cross-modal tie points, the surface meshed again), products.\n"
      "On an existing run folder, stages that are up to date (same options, same survey files) are "
      "skipped and said so; a changed option redoes its stage and the ones after. The files are "
      "described in docs/RUN.md and docs/SURVEY_FORMAT.md.\n"
      "Exit status: 0 on success; 2 when the survey is invalid (one line naming the file and the line or "
      "key); 1 on other failures.");
  command->add_option("SURVEY", options.survey, "Survey folder (the folder holding survey.yaml)")->required();
  command->add_option("--out", options.out, "Run folder to write into (created if absent)")->required();
  command->add_option("--variant", line.variant, "Estimation variant: sequential, planar, stacked, joint")
      ->default_val(line.variant);
  command->add_option("--until", options.until, "Last stage to run (default: the variant's last)");
  command->add_option("--from", options.from,
                      "Stage to start at: it and the stages after it are redone from the files of the "
                      "stages before it in RUN (default: the first stage not up to date)");
  command->add_flag("--force", options.force, "Redo every stage (from --from when given), replacing what RUN holds");
  command->add_option("--threads", options.threads,
                      "Threads for the solvers (Ceres) and the parallel loops (oneTBB); 0: every hardware "
                      "thread. With 1, runs repeat bit for bit")
      ->default_val(options.threads);
  command->add_option("--log", options.log, "Also append the run's log to this file");
  command->add_option("--surface", line.surface,
                      "sequential, joint: surface from dense (stereo depth maps of the keyframes, fused) or "
                      "sparse (the adjusted landmarks alone)")
      ->default_val(line.surface);
  command->add_option("--seabed-depth", line.seabed_depth_m,
                      "planar: the flat seabed's depth (z in W, metres down; default: estimated from RGB "
                      "frame pairs scaled by the INS)");
  command->add_option("--extrinsic-rounds", options.refine.rounds,
                      "sequential (refine stage): rounds of the RGB-UHI extrinsic refinement from the RGB and "
                      "hyperspectral ortho-images, each on a new cast (0: keep survey.yaml's guess)")
      ->default_val(options.refine.rounds);
  command->add_option("--joint-rounds", options.joint.rounds,
                      "joint: rounds of cross-modal tie points, joint solve and new surface (fewer when T_C_U, "
                      "d and the trajectory stop moving)")
      ->default_val(options.joint.rounds);
  command->add_option("--joint-tie-points", line.joint_tie_points,
                      "joint: tie points of the rounds after the first: 'strip' (each push-broom strip matched "
                      "against its prediction from the RGB frames) or 'ortho' (the RGB and hyperspectral "
                      "ortho-images, as the first round)")
      ->default_val(line.joint_tie_points);
  command->add_option("--ortho-pixel", options.products.ortho_pixel_m, "Ortho-image pixel size in metres (products)")
      ->default_val(options.products.ortho_pixel_m);
  command->add_flag("!--no-geotiff", options.products.geotiff,
                    "Skip hyperspectral/ortho.tif and map/rgb_ortho.tif (the ENVI ortho-image is always written)");
  command->add_option("--point-cell", options.products.point_cell_m,
                      "Cell size in metres of hyperspectral/points.ply, the hyperspectral point cloud (the hits "
                      "binned into cubes: mean position and mean spectrum of each)")
      ->default_val(options.products.point_cell_m);
  command->add_flag("!--no-points", options.products.points,
                    "Skip hyperspectral/points.ply (one more cast and read of the cube)");
  return command;
}

int runRunCommand(RunCommandLine& line, std::ostream& out, std::ostream& err) {
  RunOptions& options = line.options;
  try {
    options.variant = parseVariant(line.variant);
    options.surface.mode = parseSurfaceMode(line.surface);
    options.joint.tie_points = parseJointTiePoints(line.joint_tie_points);
  } catch (const std::invalid_argument& failure) {
    err << "error: " << failure.what() << "\n";
    return 1;
  }
  // The options given on the command line, so that one the variant ignores
  // is an error rather than silently dropped.
  for (const CLI::Option* option : line.command->get_options()) {
    if (option->count() == 0) continue;
    for (const std::string& name : option->get_lnames()) options.given.insert("--" + name);
    for (const std::string& name : option->get_fnames()) {
      if (!name.empty() && name[0] == '!') options.given.insert(name.substr(1));
    }
  }
  if (line.command->count("--seabed-depth") > 0) options.surface.seabed_depth_m = line.seabed_depth_m;
  return runStages(options, out, err);
}

}  // namespace hsmap
