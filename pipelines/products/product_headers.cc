#include "pipelines/products/product_headers.h"

#include "core/io/envi_ignore_value.h"

namespace hsmap {

EnviHeader spectralProductHeader(const EnviReader& cube, const std::vector<double>& wavelengths_nm, int rows,
                                 int cols, EnviInterleave interleave) {
  const EnviHeader& in = cube.header();
  EnviHeader header;
  header.samples = cols;
  header.lines = rows;
  header.bands = in.bands;
  header.data_type = EnviDataType::float32;
  header.interleave = interleave;
  header.wavelength = wavelengths_nm;
  header.wavelength_units = "Nanometers";
  // fwhm in the cube's wavelength units, converted like the wavelengths.
  if (!in.fwhm.empty() && in.wavelength.size() == in.fwhm.size()) {
    header.fwhm.resize(in.fwhm.size());
    for (std::size_t b = 0; b < in.fwhm.size(); ++b) {
      const double scale = in.wavelength[b] != 0.0 ? wavelengths_nm[b] / in.wavelength[b] : 1.0;
      header.fwhm[b] = in.fwhm[b] * scale;
    }
  }
  header.band_names = in.band_names;
  setDataIgnoreValueNaN(header);
  return header;
}

EnviHeader ancillaryProductHeader(int rows, int cols) {
  EnviHeader header;
  header.samples = cols;
  header.lines = rows;
  header.bands = 4;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.band_names = {"scan line", "sample", "range (m)", "incidence (deg)"};
  setDataIgnoreValueNaN(header);
  return header;
}

}  // namespace hsmap
