#!/usr/bin/python3
"""Quick-look PNGs of a simulated survey for docs/SIMULATOR.md.

    scripts/simulator_quicklooks.py SURVEY_DIR OUT_DIR [PREFIX]

Writes PREFIX_rgb_N.png (three RGB frames spread over the survey, at half
resolution), PREFIX_uhi_stack.png (the UHI cube's scan lines stacked in time
order as a colour composite of the bands nearest 640, 550 and 460 nm, each
band stretched between its 1st and 99th percentiles) and PREFIX_truth.png
(the same composite of truth/reflectance). The quick-looks are subsampled to
keep them small (UHI every 2nd line and 4th sample, truth every 2nd pixel). Reads the ENVI files with numpy
(uint16 or float32, BIL, little endian), as written by hsmap simulate.
"""
import csv
import os
import re
import sys

import matplotlib.image as mpimg
import numpy as np


def read_envi_header(path):
    text = open(path).read()
    fields = {}
    for match in re.finditer(r"^\s*([a-z ]+?)\s*=\s*(\{[^}]*\}|[^\n]*)", text, re.M):
        fields[match.group(1).strip()] = match.group(2).strip()
    return fields


def read_envi_bil(hdr_path):
    header = read_envi_header(hdr_path)
    samples, lines, bands = (int(header[k]) for k in ("samples", "lines", "bands"))
    if header.get("interleave", "bil").lower() != "bil":
        raise SystemExit(f"{hdr_path}: expected interleave = bil")
    dtype = {"12": "<u2", "4": "<f4"}[header["data type"]]
    offset = int(header.get("header offset", "0"))
    raw = os.path.splitext(hdr_path)[0] + ".raw"
    cube = np.memmap(raw, dtype=dtype, mode="r", offset=offset, shape=(lines, bands, samples))
    wavelengths = [float(w) for w in header["wavelength"].strip("{}").split(",")]
    return cube, np.array(wavelengths)


def composite(cube, wavelengths, nm=(640.0, 550.0, 460.0)):
    channels = []
    for target in nm:
        band = cube[:, int(np.argmin(np.abs(wavelengths - target))), :].astype(np.float64)
        valid = band[np.isfinite(band)]
        low, high = np.percentile(valid, [1, 99])
        channels.append(np.clip((band - low) / max(high - low, 1e-12), 0, 1))
    image = np.dstack(channels)
    image[~np.isfinite(image)] = 1.0  # NaN (outside the footprint) shows white
    return image


def main():
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    survey, out = sys.argv[1], sys.argv[2]
    prefix = sys.argv[3] if len(sys.argv) == 4 else "survey"
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(survey, "rgb", "frames.csv")) as f:
        frames = [row["file"] for row in csv.DictReader(f)]
    for i, index in enumerate(np.linspace(0, len(frames) - 1, 5)[1:4].astype(int)):
        image = mpimg.imread(os.path.join(survey, "rgb", frames[index]))
        mpimg.imsave(os.path.join(out, f"{prefix}_rgb_{i + 1}.png"), image[::2, ::2])
    cube, wavelengths = read_envi_bil(os.path.join(survey, "uhi", "cube.hdr"))
    # Lines run forward in time; show them bottom to top (north up on a northbound transect).
    # Every 2nd line and 4th sample: the quick-look stays small, and at 1.3 cm per line and
    # ~1.4 mm per sample the ground's aspect is kept within a factor of two.
    stack = composite(cube, wavelengths)[::-2, ::4]
    mpimg.imsave(os.path.join(out, f"{prefix}_uhi_stack.png"), stack)
    truth, truth_wavelengths = read_envi_bil(os.path.join(survey, "truth", "reflectance.hdr"))
    mpimg.imsave(os.path.join(out, f"{prefix}_truth.png"), composite(truth, truth_wavelengths)[::2, ::2])
    print(f"wrote quick-looks of {survey} to {out}")


if __name__ == "__main__":
    main()
