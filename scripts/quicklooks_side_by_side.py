#!/usr/bin/python3
"""Quick-looks of several runs side by side, one panel per run, for docs.

    scripts/quicklooks_side_by_side.py OUT.png LABEL=RUN [LABEL=RUN ...] [--title TEXT]

Each RUN's hyperspectral/ortho_rgb.png (the products stage's quick-look) is
shown at the same height, labelled. The `stacked` variant's quick-look has
one row per scan line and one column per sample; the others are north-up
ortho-images, so the panels compare what each variant makes of the same
survey, not pixel for pixel.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="PNG to write")
    parser.add_argument("runs", nargs="+", help="LABEL=RUN_FOLDER")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    panels = []
    for item in args.runs:
        if "=" not in item:
            sys.exit(f"error: '{item}': expected LABEL=RUN_FOLDER")
        label, run = item.split("=", 1)
        png = os.path.join(run, "hyperspectral", "ortho_rgb.png")
        if not os.path.isfile(png):
            sys.exit(f"error: {png} not found: run the products stage first")
        panels.append((label, mpimg.imread(png)))
    widths = [image.shape[1] / image.shape[0] for _, image in panels]
    figure, axes = plt.subplots(1, len(panels), figsize=(2.2 * sum(widths) * 3 + 1, 7),
                                gridspec_kw={"width_ratios": widths})
    if len(panels) == 1:
        axes = [axes]
    for axis, (label, image) in zip(axes, panels):
        axis.imshow(image)
        axis.set_title(label)
        axis.set_xticks([])
        axis.set_yticks([])
    if args.title:
        figure.suptitle(args.title)
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
