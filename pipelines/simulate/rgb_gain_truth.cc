#include "pipelines/simulate/rgb_gain_truth.h"

#include <fstream>
#include <stdexcept>

#include "core/survey/number_text.h"

namespace hsmap {

void writeRgbGainTruth(const std::filesystem::path& file, const std::vector<double>& times,
                       const std::vector<double>& gains_db) {
  std::ofstream out(file);
  out << "t,gain_db\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    out << formatDouble(times[k]) << ',' << formatDouble(gains_db[k]) << '\n';
  }
  if (!out.good()) throw std::runtime_error("simulate: cannot write " + file.string());
}

}  // namespace hsmap
