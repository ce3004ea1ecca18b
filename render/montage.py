#!/usr/bin/python3
"""Lay out PNG images in a grid with row and column labels (the paper's Figure 15:
original | union of spheres | garbing mesh, one model per row).

Usage:
  render/montage.py IMAGE... -o OUT.png --columns N
                    [--column-label TEXT ...] [--row-label TEXT ...]
                    [--gap PX] [--font-size PX]

Images fill the grid row by row; `-` leaves a cell empty. Each cell is as large as the largest
image, which is centred in it at its own pixel size (no resampling); transparent pixels are
composited over white. Labels are optional, but if given there is one per column / per row.
The output is written to a temporary file and renamed: a failure leaves no partial file.
Exit codes: 0 success, 2 bad usage or invalid input, 3 unreadable image or unwritable output.
Runs with Debian's /usr/bin/python3 (python3-matplotlib, python3-numpy).
"""
import argparse
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
import matplotlib.image as mpimg  # noqa: E402

DPI = 100


class MontageError(Exception):
    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


def read_rgb(path):
    """The image at `path` as an H x W x 3 float array in [0, 1], alpha composited on white."""
    if not os.path.isfile(path):
        raise MontageError("%s: cannot open for reading" % path, 3)
    try:
        img = mpimg.imread(path)
    except Exception as e:  # matplotlib/PIL raise various types for a bad file
        raise MontageError("%s: not a readable image (%s)" % (path, e), 3)
    img = np.asarray(img, dtype=np.float64)
    if img.dtype.kind in "ui" or img.max(initial=0) > 1.0:
        img = img / 255.0
    if img.ndim == 2:
        img = np.stack([img] * 3, axis=-1)
    if img.ndim != 3 or img.shape[2] not in (3, 4):
        raise MontageError("%s: unsupported image layout %s" % (path, img.shape), 2)
    if img.shape[2] == 4:
        alpha = img[:, :, 3:4]
        img = img[:, :, :3] * alpha + (1.0 - alpha)
    return img


def layout(images, columns, column_labels, row_labels, gap, font_px):
    """The canvas (H x W x 3) and the label positions [(text, x, y, rotation)] in pixels."""
    rows = (len(images) + columns - 1) // columns
    real = [im for im in images if im is not None]
    if not real:
        raise MontageError("every cell is empty", 2)
    cell_h = max(im.shape[0] for im in real)
    cell_w = max(im.shape[1] for im in real)
    band = int(round(2.0 * font_px))
    top = band if column_labels else 0
    left = band if row_labels else 0
    width = left + columns * cell_w + (columns - 1) * gap
    height = top + rows * cell_h + (rows - 1) * gap
    canvas = np.ones((height, width, 3))
    for i, im in enumerate(images):
        if im is None:
            continue
        r, c = divmod(i, columns)
        y = top + r * (cell_h + gap) + (cell_h - im.shape[0]) // 2
        x = left + c * (cell_w + gap) + (cell_w - im.shape[1]) // 2
        canvas[y:y + im.shape[0], x:x + im.shape[1]] = im
    labels = []
    for c, text in enumerate(column_labels):
        labels.append((text, left + c * (cell_w + gap) + cell_w / 2.0, top / 2.0, 0))
    for r, text in enumerate(row_labels):
        labels.append((text, left / 2.0, top + r * (cell_h + gap) + cell_h / 2.0, 90))
    return canvas, labels


def write_png(canvas, labels, font_px, output):
    height, width = canvas.shape[:2]
    fig = Figure(figsize=(width / DPI, height / DPI), dpi=DPI)
    FigureCanvasAgg(fig)
    fig.figimage(canvas, xo=0, yo=0, origin="upper")
    for text, x, y, rotation in labels:
        fig.text(x / width, 1.0 - y / height, text, ha="center", va="center", rotation=rotation,
                 fontsize=font_px * 72.0 / DPI)
    root, ext = os.path.splitext(output)
    tmp = "%s.partial-%d%s" % (root, os.getpid(), ext)
    try:
        fig.savefig(tmp, dpi=DPI, format="png", metadata={"Software": None})
        os.replace(tmp, output)
    except OSError as e:
        raise MontageError("%s: cannot write (%s)" % (output, e.strerror or e), 3)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def main(argv):
    parser = argparse.ArgumentParser(
        prog="montage", description="Lay out PNG images in a labelled grid (row by row).")
    parser.add_argument("images", nargs="+", help="PNG images, row by row; '-' = empty cell")
    parser.add_argument("-o", "--output", required=True, help="output image (.png)")
    parser.add_argument("--columns", type=int, required=True, help="images per row")
    parser.add_argument("--column-label", action="append", default=[], metavar="TEXT",
                        help="label above a column (repeat: one per column)")
    parser.add_argument("--row-label", action="append", default=[], metavar="TEXT",
                        help="label left of a row (repeat: one per row)")
    parser.add_argument("--gap", type=int, default=8, help="pixels between cells (default 8)")
    parser.add_argument("--font-size", type=float, default=0,
                        help="label height in pixels (default: cell height / 16, at least 14)")
    args = parser.parse_args(argv)

    try:
        if args.columns < 1:
            raise MontageError("--columns must be >= 1, got %d" % args.columns, 2)
        if args.gap < 0:
            raise MontageError("--gap must be >= 0, got %d" % args.gap, 2)
        if not args.output.lower().endswith(".png"):
            raise MontageError("%s: the output must be a .png file" % args.output, 2)
        out_dir = os.path.dirname(os.path.abspath(args.output))
        if not os.path.isdir(out_dir):
            raise MontageError("%s: output folder '%s' does not exist" % (args.output, out_dir), 2)
        for path in args.images:
            if path != "-" and os.path.exists(path) and os.path.exists(args.output) \
                    and os.path.samefile(path, args.output):
                raise MontageError("%s: output would overwrite the input %s" % (args.output, path), 2)
        rows = (len(args.images) + args.columns - 1) // args.columns
        if args.column_label and len(args.column_label) != args.columns:
            raise MontageError("%d column labels for %d columns" %
                               (len(args.column_label), args.columns), 2)
        if args.row_label and len(args.row_label) != rows:
            raise MontageError("%d row labels for %d rows (%d images, %d columns)" %
                               (len(args.row_label), rows, len(args.images), args.columns), 2)
        images = [None if p == "-" else read_rgb(p) for p in args.images]
        cell_h = max(im.shape[0] for im in images if im is not None) if any(
            im is not None for im in images) else 0
        font_px = args.font_size if args.font_size > 0 else max(14.0, cell_h / 16.0)
        canvas, labels = layout(images, args.columns, args.column_label, args.row_label,
                                args.gap, font_px)
        write_png(canvas, labels, font_px, args.output)
    except MontageError as e:
        print("montage: %s" % e, file=sys.stderr)
        return e.code
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
