#!/usr/bin/python3
"""Quick-looks of several runs side by side, one panel per run, for docs.

    scripts/quicklooks_side_by_side.py OUT.png LABEL=RUN [LABEL=RUN ...] [--title TEXT]
        [--aspect LABEL=R] [--flip LABEL]

Each RUN's hyperspectral/ortho_rgb.png (the products stage's quick-look) is
shown at the same height, labelled. The `stacked` variant's quick-look has
one row per scan line and one column per sample; the others are north-up
ortho-images, so the panels compare what each variant makes of the same
survey, not pixel for pixel. --aspect gives a panel's pixel height over width
(e.g. the line spacing over the sample spacing for `stacked`, ~10 at 0.4 m/s
and 30 lines/s), --flip turns a panel upside down (stacked rows run in time,
an ortho-image's from north). A "|" in a label starts a new line.
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
    parser.add_argument("--dpi", type=int, default=80, help="resolution of OUT.png")
    parser.add_argument("--aspect", action="append", default=[], help="LABEL=R: pixel height / width")
    parser.add_argument("--flip", action="append", default=[], help="LABEL: upside down")
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
    aspects = {}
    for item in args.aspect:
        label, _, ratio = item.partition("=")
        aspects[label] = float(ratio)
    panels = [(label, image[::-1] if label in args.flip else image) for label, image in panels]
    widths = [image.shape[1] / (image.shape[0] * aspects.get(label, 1.0)) for label, image in panels]
    figure, axes = plt.subplots(1, len(panels), figsize=(max(6.0, 9.0 * sum(widths) + 1.5), 9),
                                gridspec_kw={"width_ratios": widths})
    if len(panels) == 1:
        axes = [axes]
    for axis, (label, image) in zip(axes, panels):
        axis.imshow(image, aspect=aspects.get(label, 1.0), interpolation="antialiased")
        axis.set_title(label.replace("|", "\n"), fontsize=10)
        axis.set_xticks([])
        axis.set_yticks([])
    if args.title:
        figure.suptitle(args.title)
    figure.tight_layout()
    figure.savefig(args.out, dpi=args.dpi)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
