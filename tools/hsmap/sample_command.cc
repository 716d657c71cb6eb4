#include "tools/hsmap/sample_command.h"
#include "tools/hsmap/output_folder.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <ostream>

#include "pipelines/sample_survey.h"

namespace hsmap {

CLI::App* addSampleCommand(CLI::App& app, SampleOptions& options) {
  CLI::App* command =
      app.add_subcommand("sample", "Write the small built-in sample survey to a folder");
  command->footer(
      "The sample survey is about 3 s long: 75 RGB frames of 160x120, a UHI cube of 90 lines x 64 "
      "samples x 16 bands (400-800 nm, uint16, bil), an INS with attitude at 1 Hz, and a "
      "survey.yaml with an origin. It is deterministic and meant for trying the tools and for "
      "tests; it is not a simulation and has no ground truth.");
  command
      ->add_option("--out", options.out,
                   "Folder to write the sample survey into; created if missing. It must be "
                   "empty or absent unless --force is given.")
      ->required();
  command->add_flag("--force", options.force,
                    "Replace --out even if it is not empty: its previous contents are deleted.");
  return command;
}

int runSampleCommand(const SampleOptions& options, std::ostream& out, std::ostream& err) {
  if (!outputFolderUsable(options.out, options.force, err)) return 1;
  const SampleSurveyContents written = writeSampleSurvey(options.out);
  char duration[32];
  std::snprintf(duration, sizeof(duration), "%.2f", written.duration_s);
  out << "wrote the sample survey (" << duration << " s) to " << written.folder.string() << ":\n"
      << "  survey.yaml\n"
      << "  rgb/frames.csv and " << written.rgb_frames << " PNG frames of " << written.rgb_width
      << "x" << written.rgb_height << "\n"
      << "  uhi/cube.hdr, uhi/cube.raw: " << written.uhi_lines << " lines x " << written.uhi_samples
      << " samples x " << written.uhi_bands << " bands, uint16, bil\n"
      << "  uhi/lines.csv: " << written.uhi_lines << " scan line times\n"
      << "  nav/ins.csv: " << written.ins_fixes << " fixes with attitude\n"
      << "check it with: hsmap inspect " << written.folder.string() << "\n";
  return 0;
}

}  // namespace hsmap
