#pragma once
// exportEnviToCog: the hyperspectral ortho-image as a Cloud-Optimized GeoTIFF
// (RUN/hyperspectral/ortho.tif, DATASET.md "Results folder"), written from the
// ENVI image hsmap wrote (ortho.hdr/.raw) through GDAL, so that GIS tools
// (QGIS, gdalinfo, rasterio) place it on the map without the ENVI header.
//
// What the GeoTIFF carries
//   pixels          the ENVI values, same data type, every band (read by GDAL's
//                   ENVI driver from the data file: any interleave, byte order
//                   and header offset)
//   CRS             EPSG:326zz (North) or EPSG:327zz (South), WGS 84 / UTM, from
//                   the header's `map info` zone and hemisphere
//   geotransform    {x0, px, 0, y0, 0, -py}: (x0, y0) is the map position of the
//                   upper-left corner of the upper-left pixel, i.e.
//                   x0 = easting - (ref_x - 1) px, y0 = northing + (ref_y - 1) py
//                   (ENVI's reference pixel is 1-based; north-up, so y falls
//                   with the row)
//   nodata          the header's `data ignore value` when it has one; else NaN
//                   for float data (hsmap writes NaN where the ortho is empty)
//                   and none for integer data
//   band text       description "<wavelength> nm" (e.g. "450.2 nm"; the units
//                   of `wavelength units`, nm when absent), metadata items
//                   `wavelength` and `wavelength_units` as GDAL's ENVI driver
//                   names them, and `fwhm` when the header has one; without
//                   wavelengths, the header's band names
//   layout          cloud-optimized: tiled (block_size), compressed, band-
//                   interleaved, every IFD first, then the overviews' tiles
//                   (smallest first), then the full-resolution tiles (what
//                   GDAL's validate_cloud_optimized_geotiff.py checks)
//
// How it is written, and why not with GDAL's COG driver: GDAL 3.6's COG
// driver is always pixel-interleaved, and a 512 x 512 tile of 211 float bands
// is 221 MB to buffer and compress (several at once with threads): 3.9 GB of
// RSS and 160-170 s of CPU for a 2 GB ortho (half that CPU now). Band-interleaved tiles are 1 MB, and a GIS that
// shows three bands reads three bands. The steps are those of the COG driver:
// overviews (GDALBuildOverviews on the VRT, saved as `<tif>.partial.vrt`, into
// `<tif>.partial.vrt.ovr`, ZSTD level 1, removed at the end), then GTiff with
// COPY_SRC_OVERVIEWS=YES, which lays the file out as above. Peak memory stays
// at 200-300 MB whatever the image size: GDAL's block cache (process-wide) is
// capped at 64 MB while an export runs, and memory freed by GDAL is returned
// to the system as the copy goes (benchmarks: docs/BENCHMARKS.md, "GeoTIFF
// export"). GDAL 3.6 writes no COG "ghost" header for band-interleaved files,
// so it reports no LAYOUT=COG; the layout is the same.
//
// Why the header is read by hsmap and the pixels by GDAL: GDAL's (3.6) ENVI
// driver reads hsmap's headers correctly (checked in the tests), but silently
// assumes NAD27 when `map info` names no datum, gives its CRS no EPSG code and
// describes bands as "450.2 Nanometers". The georeferencing is therefore set
// from readEnviHeader's values on a VRT over the ENVI dataset (the ENVI files
// are never modified, and GDAL's .aux.xml side files are switched off).
//
// Contract
// - The header must have `map info` in UTM on WGS-84 (datum WGS-84 or
//   absent, units Meters or absent), as hsmap writes results: otherwise an
//   InputError naming the header, e.g.
//     "ortho.hdr:key map info: required to export a GeoTIFF: expected
//      {UTM, 1, 1, easting, northing, px, px, zone, North|South, WGS-84, units=Meters}, found none"
//   Header problems are readEnviHeader's InputErrors, a missing or short data
//   file EnviReader's (GDAL's ENVI driver would read missing bytes as zeros,
//   silently).
// - The GeoTIFF is written as `<tif_path>.partial` and renamed onto tif_path
//   when GDAL has closed it (AtomicFile): on any failure nothing is left under
//   either name, and an older tif_path is kept.
// - GDAL's messages are not printed: a GDAL failure is a std::runtime_error
//   naming the file and carrying GDAL's message (InputError when GDAL cannot
//   read the ENVI data). Thread-safe: GDAL is registered once, its error
//   handler and configuration options are set for the calling thread only,
//   and the block-cache cap is counted across concurrent exports (the last
//   one to finish restores the caller's limit).
// - Working files beside tif_path (`.partial`, `.partial.vrt`,
//   `.partial.vrt.ovr`) are removed on success and on failure; they need
//   about a third of the uncompressed image size on disk while overviews are
//   copied.

#include <filesystem>
#include <string>

namespace hsmap {

struct GeoTiffExportOptions {
  // Tile width and height in pixels. A multiple of 16 in
  // [16, 4096] (TIFF tiles). 512 is what COG readers expect; smaller tiles
  // only pay for tiny images.
  int block_size = 512;
  // Lossless codec: DEFLATE (readable everywhere), ZSTD (faster, needs
  // GDAL >= 2.3 on the reader's side), LZW, LZMA or NONE.
  std::string compression = "DEFLATE";
  // Predictor before compression: floating-point (TIFF predictor 3) for
  // float data, horizontal differencing (2) for integers. Halves the size of
  // smooth float images for a small cost in speed; off for noise-like data.
  bool predictor = true;
  // Reduced-resolution overviews (as GDAL's COG OVERVIEWS=AUTO: halving
  // until the image fits in one tile), so a GIS can show the whole survey
  // quickly.
  bool overviews = true;
  // How overview pixels are made from the image: AVERAGE keeps spectra
  // physical (no overshoot, nodata skipped); NEAREST keeps original values.
  // One of NEAREST, AVERAGE, BILINEAR, CUBIC, CUBICSPLINE, LANCZOS, MODE, RMS.
  std::string overview_resampling = "AVERAGE";
  // Compression and overview threads (GDAL NUM_THREADS); 0 = every CPU.
  int threads = 0;

  // std::invalid_argument saying which field is wrong and what is allowed.
  void validate() const;
};

// Reads the ENVI image at `envi_header` and writes it as a COG at `tif_path`
// (contract above). Validates `options` first.
void exportEnviToCog(const std::filesystem::path& envi_header, const std::filesystem::path& tif_path,
                     const GeoTiffExportOptions& options = {});

// GDAL's drivers, registered once per process by whichever thread asks
// first: every writer in hsmap calls this rather than GDALAllRegister, which
// must not run on two threads at once (the products stage writes the RGB
// ortho-image's GeoTIFF on one thread while exporting the hyperspectral one
// may start on another).
void registerGdalDrivers();

}  // namespace hsmap
