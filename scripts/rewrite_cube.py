#!/usr/bin/python3
"""Rewrites a survey's UHI cube (SURVEY/uhi/cube.hdr and .raw, in place) as
another program might write it, to check that hsmap reads any cube the data
contract allows (docs/BENCHMARKS.md, "A lawnmower survey in the southern
hemisphere" and "A survey unlike the presets").

    scripts/rewrite_cube.py SURVEY [--interleave bil|bip|bsq] [--byte-order 0|1]
        [--float32] [--header-offset BYTES] [--micrometres]
        [--dead-samples S1,S2,...] [--bad-pixels-per-thousand N]
        [--bad-value nan|ignore] [--ignore-value V] [--seed N]

--float32 stores the values as float32 (needed for NaN pixels);
--dead-samples sets those sample columns to the ignore value in every line
and band; --bad-pixels-per-thousand spoils that many pixels (every band) per
thousand, at random: NaN (float32 only) or the ignore value (--bad-value);
--ignore-value (default -9999, or the data type's maximum for integers)
goes into the header as `data ignore value` when anything is spoiled;
--micrometres writes the wavelengths in micrometres. The cube is read whole
into memory (a survey's cube of a few hundred MB; not for transect-100m).
"""
import argparse
import os
import re
import sys

import numpy as np

ENVI_TYPES = {1: np.uint8, 2: np.int16, 3: np.int32, 4: np.float32, 5: np.float64, 12: np.uint16}


def header_value(header, key):
    match = re.search(r"^\s*" + re.escape(key) + r"\s*=\s*(\S+)", header, re.MULTILINE | re.IGNORECASE)
    if match is None:
        sys.exit(f"cube.hdr: key '{key}' missing")
    return match.group(1)


def set_header_value(header, key, value):
    pattern = re.compile(r"^\s*" + re.escape(key) + r"\s*=.*$", re.MULTILINE | re.IGNORECASE)
    if pattern.search(header):
        return pattern.sub(f"{key} = {value}", header, count=1)
    return header.rstrip("\n") + f"\n{key} = {value}\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("survey")
    parser.add_argument("--interleave", choices=["bil", "bip", "bsq"])
    parser.add_argument("--byte-order", type=int, choices=[0, 1])
    parser.add_argument("--float32", action="store_true")
    parser.add_argument("--header-offset", type=int, default=None)
    parser.add_argument("--micrometres", action="store_true")
    parser.add_argument("--dead-samples", default="")
    parser.add_argument("--bad-pixels-per-thousand", type=float, default=0.0)
    parser.add_argument("--bad-value", choices=["nan", "ignore"], default="nan")
    parser.add_argument("--ignore-value", type=float, default=None)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args()

    hdr = os.path.join(args.survey, "uhi", "cube.hdr")
    raw = os.path.join(args.survey, "uhi", "cube.raw")
    header = open(hdr).read()
    lines, samples, bands = (int(header_value(header, k)) for k in ("lines", "samples", "bands"))
    data_type = int(header_value(header, "data type"))
    if data_type not in ENVI_TYPES:
        sys.exit(f"cube.hdr: data type {data_type} not handled by this script")
    interleave = header_value(header, "interleave").lower()
    byte_order = int(header_value(header, "byte order"))
    offset = int(re.search(r"header offset\s*=\s*(\d+)", header).group(1)) if "header offset" in header else 0
    dtype = np.dtype(ENVI_TYPES[data_type]).newbyteorder(">" if byte_order == 1 else "<")
    flat = np.fromfile(raw, dtype=dtype, offset=offset, count=lines * samples * bands)
    # To (line, band, sample), BIL's order.
    if interleave == "bil":
        cube = flat.reshape(lines, bands, samples)
    elif interleave == "bip":
        cube = flat.reshape(lines, samples, bands).transpose(0, 2, 1)
    elif interleave == "bsq":
        cube = flat.reshape(bands, lines, samples).transpose(1, 0, 2)
    else:
        sys.exit(f"cube.hdr: interleave '{interleave}' unknown")

    out_type = np.float32 if args.float32 else ENVI_TYPES[data_type]
    cube = cube.astype(out_type)
    dead = [int(s) for s in args.dead_samples.split(",") if s.strip()]
    spoiled = bool(dead) or args.bad_pixels_per_thousand > 0
    ignore = args.ignore_value
    if ignore is None:
        ignore = -9999.0 if np.issubdtype(out_type, np.floating) else float(np.iinfo(out_type).max)
    for s in dead:
        if not 0 <= s < samples:
            sys.exit(f"--dead-samples: {s} outside [0, {samples})")
        cube[:, :, s] = ignore
    if args.bad_pixels_per_thousand > 0:
        rng = np.random.default_rng(args.seed)
        count = int(round(lines * samples * args.bad_pixels_per_thousand / 1000.0))
        if args.bad_value == "nan" and not np.issubdtype(out_type, np.floating):
            sys.exit("--bad-value nan needs float32 data (--float32)")
        bad = np.nan if args.bad_value == "nan" else ignore
        for _ in range(count):
            cube[rng.integers(lines), :, rng.integers(samples)] = bad

    new_interleave = args.interleave or interleave
    new_order = byte_order if args.byte_order is None else args.byte_order
    new_offset = offset if args.header_offset is None else args.header_offset
    layout = {"bil": (0, 1, 2), "bip": (0, 2, 1), "bsq": (1, 0, 2)}[new_interleave]
    out_dtype = np.dtype(out_type).newbyteorder(">" if new_order == 1 else "<")
    data = np.ascontiguousarray(cube.transpose(layout)).astype(out_dtype)
    temporary = raw + ".rewriting"
    with open(temporary, "wb") as f:
        f.write(b"\0" * new_offset)
        data.tofile(f)

    header = set_header_value(header, "interleave", new_interleave)
    header = set_header_value(header, "byte order", new_order)
    header = set_header_value(header, "header offset", new_offset)
    if args.float32:
        header = set_header_value(header, "data type", 4)
    if args.micrometres:
        match = re.search(r"wavelength\s*=\s*\{([^}]*)\}", header)
        if match is None:
            sys.exit("cube.hdr: no wavelength list to convert")
        units = re.search(r"wavelength units\s*=\s*(\S+)", header, re.IGNORECASE)
        if units is not None and units.group(1).lower() not in ("nanometers", "nanometres", "nm"):
            sys.exit(f"cube.hdr: wavelength units '{units.group(1)}', expected nanometers")
        micrometres = [float(x) / 1000.0 for x in match.group(1).split(",")]
        header = header[:match.start()] + "wavelength = {" + ", ".join(f"{w:.4f}" for w in micrometres) + "}" + \
            header[match.end():]
        header = set_header_value(header, "wavelength units", "Micrometers")
    if spoiled:
        header = set_header_value(header, "data ignore value", f"{ignore:g}")
    os.replace(temporary, raw)
    with open(hdr + ".rewriting", "w") as f:
        f.write(header)
    os.replace(hdr + ".rewriting", hdr)
    print(f"rewrote {raw}: {lines} lines x {samples} samples x {bands} bands, {np.dtype(out_type).name} "
          f"{new_interleave}, byte order {new_order}, header offset {new_offset}"
          + (f", {len(dead)} dead samples" if dead else "")
          + (f", {args.bad_pixels_per_thousand:g} bad pixels per thousand" if args.bad_pixels_per_thousand else ""))


if __name__ == "__main__":
    main()
