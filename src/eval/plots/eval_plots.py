#!/usr/bin/env python3
"""Figures for `mfadvr eval paper`.

`mfadvr eval paper --out DIR` writes CSV files into DIR, copies this script to
DIR/plots.py and runs `/usr/bin/python3 DIR/plots.py DIR`. The script reads
whichever of those CSVs exist and writes PNG figures into DIR/plots/:

  fig05_value_accuracy.csv  -> fig05_value_accuracy, fig04_value_images, fig06_error_images
  table1_gradient.csv, table2_overall.csv -> fig07_marschner_lobb, tables_psnr
  figNN_*.csv (08 to 13)    -> figNN_*.png of the same name

A figure whose CSV is missing or has no data rows is skipped with a note.
Needs only the standard library and matplotlib (Debian python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys
import textwrap

USAGE = "eval_plots.py DIR"
DPI = 120
TABLES = [("table1_gradient.csv", "Table 1: gradient only"),
          ("table2_overall.csv", "Table 2: value + gradient")]
# Fixed colours so a method looks the same in every figure; the MFA variants
# get warm colours so they stand out against the baselines.
METHOD_COLOURS = {
    "truth": "#000000", "mfa": "#d62728", "mfa-grid": "#ff7f0e",
    "mfa-scattered": "#e377c2", "trilinear": "#1f77b4", "tricubic": "#2ca02c",
    "catmull-rom": "#9467bd", "bspline": "#8c564b", "vtk-fixedpoint": "#17becf",
    "vtk-bunyk": "#bcbd22", "vtk-zsweep": "#7f7f7f", "vtk-pt": "#393b79",
}
# Markers as well as colours, so lines stay distinguishable in greyscale print.
MARKERS = "osD^vP*Xph<>"
FAMILY_MARKERS = {"structured": "o", "unstructured": "^", "mfa": "s"}
METRICS = [("mse", "MSE (8-bit units\u00b2)", True), ("psnr", "PSNR (dB)", False),
           ("ssim", "SSIM", False)]
_styles = {}
# Imported in main() so that a missing matplotlib gives a clear message, not a traceback.
matplotlib = plt = ticker = None


class Skip(Exception):
    """A figure cannot be drawn from the data that is there."""


def method_style(method):
    """(colour, marker) of a method, stable for the whole run."""
    if method not in _styles:
        colour = METHOD_COLOURS.get(method)
        if colour is None:
            used = set(METHOD_COLOURS.values()) | {c for c, _ in _styles.values()}
            tab20 = [matplotlib.colors.to_hex(c) for c in plt.get_cmap("tab20").colors]
            colour = ([c for c in tab20 if c not in used] or tab20)[0]
        _styles[method] = (colour, MARKERS[len(_styles) % len(MARKERS)])
    return _styles[method]


def num(value):
    """Float of a CSV cell; empty or unparsable cells are NaN (missing)."""
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def fmt(value):
    """Cell text as written, but 64.0 -> '64'."""
    v = num(value)
    return str(int(v)) if math.isfinite(v) and v == int(v) else str(value)


def count(value):
    v = num(value)
    return "{:,}".format(int(v)) if math.isfinite(v) else str(value)


def cube(n):
    return fmt(n) + "\u00b3"


def grid_text(grid):
    """'256x256x256' -> '256³'; uneven grids stay as written."""
    parts = str(grid).split("x")
    return cube(parts[0]) if len(parts) == 3 and len(set(parts)) == 1 else str(grid)


def read_csv(path):
    if not os.path.isfile(path):
        return None
    with open(path, newline="") as f:
        return [r for r in csv.DictReader(f) if any((v or "").strip() for v in r.values())]


def unique(rows, key):
    """Distinct values of a column in first-appearance order."""
    seen = []
    for r in rows:
        if r[key] not in seen:
            seen.append(r[key])
    return seen


def without_truth(rows):
    rows = [r for r in rows if r["method"] != "truth"]
    if not rows:
        raise Skip("only truth rows")
    return rows


def finish(fig, outdir, name, title):
    """Title, layout and an atomic save to DIR/plots/NAME.png."""
    width = int(fig.get_size_inches()[0] * 11)  # about 11 title characters per inch
    fig.suptitle("\n".join(textwrap.fill(t, width) for t in title.split("\n")), fontsize=12)
    fig.tight_layout()  # matplotlib >= 3.3 leaves room for the suptitle itself
    final = os.path.join(outdir, "plots", name + ".png")
    tmp = final + ".tmp.png"  # savefig picks the format from the suffix
    fig.savefig(tmp, dpi=DPI)
    plt.close(fig)
    os.replace(tmp, final)
    print("wrote plots/%s.png" % name)


# ---- shared helpers -------------------------------------------------------

def load_image(outdir, rel):
    if not rel:
        return None
    path = os.path.join(outdir, rel)
    return matplotlib.image.imread(path) if os.path.isfile(path) else "missing"


def image_grid(outdir, name, title, row_labels, col_titles, cells):
    """cells[r][c] is (relative png path or '', caption or '')."""
    images = [[load_image(outdir, path) for path, _ in row] for row in cells]
    shapes = [im.shape for row in images for im in row if hasattr(im, "shape")]
    aspect = shapes[0][0] / shapes[0][1] if shapes else 1.0
    nr, nc = len(row_labels), len(col_titles)
    fig, axes = plt.subplots(nr, nc, squeeze=False,
                             figsize=(0.6 + 2.2 * nc, 1.2 + (2.2 * aspect + 0.45) * nr))
    for r in range(nr):
        for c in range(nc):
            ax, im, (path, caption) = axes[r][c], images[r][c], cells[r][c]
            ax.set_xticks([])
            ax.set_yticks([])
            if hasattr(im, "shape"):
                ax.imshow(im, cmap="gray" if im.ndim == 2 else None, interpolation="nearest")
            else:
                ax.set_box_aspect(aspect)
                ax.text(0.5, 0.5, im or "n/a", ha="center", va="center",
                        transform=ax.transAxes, color="grey", fontsize=12)
            if caption and path:  # no render time under a failed render
                ax.set_xlabel(caption, fontsize=8)
            if r == 0:
                ax.set_title(col_titles[c], fontsize=10, color=method_style(col_titles[c])[0])
            if c == 0:
                ax.set_ylabel(row_labels[r], fontsize=9)
    finish(fig, outdir, name, title)


def method_grid(outdir, name, title, rows, row_key, row_label, image_col, caption):
    """Image grid: one row per distinct row_key, one column per method (truth first)."""
    methods = sorted(unique(rows, "method"), key=lambda m: m != "truth")
    keys = unique(rows, row_key)
    lookup = {(r[row_key], r["method"]): r for r in rows}
    cells = [[(lookup[(k, m)].get(image_col) or "", caption(lookup[(k, m)]))
              if (k, m) in lookup else ("", "") for m in methods] for k in keys]
    labels = [row_label(next(r for r in rows if r[row_key] == k)) for k in keys]
    image_grid(outdir, name, title, labels, methods, cells)


def psnr_caption(row):
    p = num(row.get("psnr"))
    return "PSNR %.1f dB" % p if math.isfinite(p) else ""


def time_caption(row):
    t = num(row.get("render_seconds"))
    return "%.3g s" % t if math.isfinite(t) else ""


def finite_points(rows, x, y):
    pts = sorted((num(r[x]), num(r[y])) for r in rows)
    return [(a, b) for a, b in pts if math.isfinite(a) and math.isfinite(b)]


def plot_lines(ax, rows, x, y, series, style, label):
    """One line per distinct value of `series`, sorted by x, non-finite points dropped."""
    for s in unique(rows, series):
        pts = finite_points([r for r in rows if r[series] == s], x, y)
        if pts:
            colour, marker = style(s)
            ax.plot(*zip(*pts), color=colour, marker=marker, label=label(s))
    if not ax.lines:
        ax.text(0.5, 0.5, "no data", ha="center", va="center", transform=ax.transAxes,
                color="grey")
    ax.grid(True, which="major", alpha=0.3)


def ordered_style(rows, key):
    """Colours along viridis for an ordered numeric series (degree, ctrl)."""
    values = sorted(unique(rows, key), key=num)
    cmap = plt.get_cmap("viridis")
    table = {v: (cmap(0.9 * i / max(1, len(values) - 1)), MARKERS[i % len(MARKERS)])
             for i, v in enumerate(values)}
    return table.__getitem__


def legend(ax, outside=False, **kw):
    if outside:  # right of the axes, so it never hides data
        kw.update(loc="upper left", bbox_to_anchor=(1.02, 1.0))
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, **kw)


def log_axis(ax, which):
    """Log scale labelled 0.01, 1, 100 (and 2, 5 within short ranges) instead of 10^k."""
    axis = ax.xaxis if which == "x" else ax.yaxis
    (ax.set_xscale if which == "x" else ax.set_yscale)("log")

    def minor(v, _):  # evaluated at draw time, when the final range is known
        lo, hi = axis.get_view_interval()
        return "%g" % v if hi < 100 * lo and ("%.0e" % v)[0] in "25" else ""
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: "%g" % v))
    axis.set_minor_formatter(ticker.FuncFormatter(minor))


def sweep_grid(rows, panels):
    """2 x len(panels): top vs ctrl (line per degree), bottom vs degree (line per ctrl).

    panels: list of (rows, y column, y label, log y?, panel title)."""
    fig, axes = plt.subplots(2, len(panels), figsize=(5 * len(panels), 8), squeeze=False)
    deg_style, ctrl_style = ordered_style(rows, "degree"), ordered_style(rows, "ctrl")
    for c, (sub, ycol, ylabel, log, title) in enumerate(panels):
        for ax, x, series, style, xlabel, label in (
                (axes[0][c], "ctrl", "degree", deg_style, "control points per axis",
                 lambda s: "degree " + fmt(s)),
                (axes[1][c], "degree", "ctrl", ctrl_style, "B-spline degree",
                 lambda s: fmt(s) + " ctrl pts")):
            plot_lines(ax, sub, x, ycol, series, style, label)
            if log:
                log_axis(ax, "y")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.set_title(title, fontsize=10)
            ax.xaxis.get_major_locator().set_params(integer=True)
            if c == len(panels) - 1:  # same series in every column: one legend per row
                legend(ax, outside=True)
    return fig


# ---- figures --------------------------------------------------------------

def fig05(outdir, rows):
    rows = without_truth(rows)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    zooms = sorted({num(r["zoom"]) for r in rows if math.isfinite(num(r["zoom"]))})
    spb = {num(r["zoom"]): r["samples_per_beam"] for r in rows}
    for ax, (col, label, log) in zip(axes, METRICS):
        plot_lines(ax, rows, "zoom", col, "method", method_style, str)
        if log:
            log_axis(ax, "y")
        ax.set_xticks(zooms)
        ax.set_xticklabels(["%s (%s)" % (fmt(z), cube(spb[z])) for z in zooms])
        ax.set_xlabel("zoom level (samples per beam)")
        ax.set_ylabel(label)
        ax.set_title(label.split(" ")[0] + " vs truth", fontsize=10)
    legend(axes[-1], outside=True)
    finish(fig, outdir, "fig05_value_accuracy",
           "Value accuracy (Gaussian beams, unshaded) vs zoom level")


def zoom_label(row):
    return "zoom %s (%s)" % (fmt(row["zoom"]), cube(row["samples_per_beam"]))


def fig04(outdir, rows):
    method_grid(outdir, "fig04_value_images",
                "Gaussian beams (unshaded) rendered per method and zoom level",
                rows, "zoom", zoom_label, "image", psnr_caption)


def fig06(outdir, rows):
    rows = without_truth(rows)
    gains = [g for g in (num(r.get("error_gain")) for r in rows) if math.isfinite(g)]
    how = "\u00d7 %s" % fmt(gains[0]) if gains else "amplified"
    method_grid(outdir, "fig06_error_images", "Error images, Gaussian beams (unshaded)\n"
                "|method \u2212 truth| per channel, %s" % how,
                rows, "zoom", zoom_label, "error_image", psnr_caption)


def table_rows(tables):
    """Both tables in one list, each row tagged with its (table, grid) group."""
    return [dict(r, key="%s\n%s grid" % (label, grid_text(r["grid"])))
            for (_, label), rows in zip(TABLES, tables) for r in rows or []]


def fig07(outdir, tables):
    method_grid(outdir, "fig07_marschner_lobb",
                "Marschner\u2013Lobb: reconstruction methods per table and input grid",
                table_rows(tables), "key", lambda r: r["key"], "image", psnr_caption)


def tables_psnr(outdir, tables):
    rows = without_truth(table_rows(tables))
    groups, methods = unique(rows, "key"), unique(rows, "method")
    width = 0.8 / len(methods)
    fig, ax = plt.subplots(figsize=(max(7, 1.2 + 0.45 * len(methods) * len(groups)), 5))
    psnr = {(r["key"], r["method"]): num(r["psnr"]) for r in rows}
    for i, m in enumerate(methods):
        bars = [(g + (i - (len(methods) - 1) / 2) * width, psnr.get((k, m), math.nan))
                for g, k in enumerate(groups)]
        bars = [(x, y) for x, y in bars if math.isfinite(y)]
        if bars:
            drawn = ax.bar(*zip(*bars), width=width, label=m, color=method_style(m)[0])
            ax.bar_label(drawn, fmt="%.1f", fontsize=7)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels(groups, fontsize=9)
    ax.set_ylabel("PSNR vs truth (dB)")
    ax.grid(True, axis="y", alpha=0.3)
    legend(ax, outside=True)
    finish(fig, outdir, "tables_psnr",
           "Marschner\u2013Lobb image quality: PSNR per method, table and input grid")


def fig08(outdir, rows):
    method_grid(outdir, "fig08_structured",
                "Structured datasets rendered per method (caption: render time)",
                rows, "dataset", lambda r: "%s (%s)" % (r["dataset"], r["dims"]),
                "image", time_caption)


def fig09(outdir, rows):
    for r in rows:  # one row of pictures per data set and view (whole, zoom)
        r["dataset_view"] = "%s %s" % (r["dataset"], r.get("view", "whole"))
    method_grid(outdir, "fig09_unstructured",
                "Unstructured (tetrahedral) datasets rendered per method "
                "(caption: render time)", rows, "dataset_view",
                lambda r: "%s, %s\n(%s pts, %s tets)" % (r["dataset"], r.get("view", "whole"),
                                                         count(r["points"]), count(r["cells"])),
                "image", time_caption)


def fig10(outdir, rows):
    fig = sweep_grid(rows, [(rows, col, label, log, label.split(" ")[0] + " vs truth")
                            for col, label, log in METRICS])
    grids = ", ".join(grid_text(g) for g in unique(rows, "grid"))
    finish(fig, outdir, "fig10_param_quality",
           "MFA fit quality vs control points and degree (Marschner\u2013Lobb %s)" % grids)


def fig12(outdir, rows):
    present = unique(rows, "query")
    queries = [q for q in ("value", "gradient", "both") if q in present]
    queries += [q for q in present if q not in queries]
    fig = sweep_grid(rows, [([r for r in rows if r["query"] == q], "ns_per_query",
                             "time per query (ns)", True, "query: " + q) for q in queries])
    finish(fig, outdir, "fig12_query_time",
           "MFA point-query cost vs control points and degree")


def fig11(outdir, rows):
    # x is the point count; a structured row may leave `points` empty (size^3 then).
    rows = [dict(r, x=num(r.get("points")) if math.isfinite(num(r.get("points")))
                 else num(r.get("size")) ** 3) for r in rows]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5), sharey=True)
    for ax, family in zip(axes, ("structured", "unstructured")):
        sub = [r for r in rows if r["family"] == family and r["x"] > 0
               and math.isfinite(num(r["render_seconds"]))]
        plot_lines(ax, sub, "x", "render_seconds", "method", method_style, str)
        log_axis(ax, "x")
        log_axis(ax, "y")
        ticks = {r["x"]: cube(r["size"]) if r.get("size") else count(r["x"]) for r in sub}
        ax.set_xticks(sorted(ticks))
        ax.set_xticklabels([ticks[t] for t in sorted(ticks)])
        ax.xaxis.set_minor_locator(ticker.NullLocator())
        ax.set_xlabel("data points (grid size)")
        ax.set_title("%s data" % family, fontsize=10)
        legend(ax)
    axes[0].set_ylabel("median frame time (s)")
    finish(fig, outdir, "fig11_render_time", "Render time vs data size (%s\u00d7%s image)"
           % (fmt(rows[0].get("width")), fmt(rows[0].get("height"))))


def fig13(outdir, rows):
    fig, ax = plt.subplots(figsize=(9, 6))
    for r in rows:
        x, y = num(r["render_seconds"]), num(r["rmse"])
        if math.isfinite(x) and math.isfinite(y) and x > 0:
            ax.scatter([x], [y], s=60, marker=FAMILY_MARKERS.get(r["family"], "D"),
                       color=method_style(r["method"])[0], edgecolors="black",
                       linewidths=0.5, zorder=3)
            ax.annotate(r["method"], (x, y), textcoords="offset points", xytext=(6, 4),
                        fontsize=8)
    log_axis(ax, "x")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("RMSE vs truth (8-bit units)")
    ax.grid(True, which="major", alpha=0.3)
    # Colour and label already name the method; the legend explains marker shape only.
    for family in unique(rows, "family"):
        ax.plot([], [], linestyle="", marker=FAMILY_MARKERS.get(family, "D"), label=family,
                color="lightgrey", markeredgecolor="black")
    legend(ax, title="family")
    finish(fig, outdir, "fig13_quality_vs_time",
           "Quality vs render time (%s)" % rows[0].get("scene", ""))


# (id for messages, CSV names, function). A function with several CSVs gets a
# list of row lists (None for a missing CSV) and needs at least one of them.
FIGURES = [
    ("fig05", ["fig05_value_accuracy.csv"], fig05),
    ("fig04", ["fig05_value_accuracy.csv"], fig04),
    ("fig06", ["fig05_value_accuracy.csv"], fig06),
    ("fig07", [t for t, _ in TABLES], fig07),
    ("tables_psnr", [t for t, _ in TABLES], tables_psnr),
    ("fig08", ["fig08_structured.csv"], fig08),
    ("fig09", ["fig09_unstructured.csv"], fig09),
    ("fig10", ["fig10_param_quality.csv"], fig10),
    ("fig11", ["fig11_render_time.csv"], fig11),
    ("fig12", ["fig12_query_time.csv"], fig12),
    ("fig13", ["fig13_quality_vs_time.csv"], fig13),
]


def run(outdir):
    os.makedirs(os.path.join(outdir, "plots"), exist_ok=True)
    failed = 0
    for fig_id, names, func in FIGURES:
        tables = [read_csv(os.path.join(outdir, n)) for n in names]
        if all(t is None for t in tables):
            print("skipped %s: no %s" % (fig_id, " or ".join(names)))
            continue
        if not any(tables):
            print("skipped %s: %s has no data rows" % (fig_id, " / ".join(
                n for n, t in zip(names, tables) if t is not None)))
            continue
        try:
            func(outdir, tables if len(names) > 1 else tables[0])
        except Skip as e:
            print("skipped %s: %s" % (fig_id, e))
        except Exception as e:  # one malformed CSV should not cost the other figures
            plt.close("all")
            failed += 1
            print("error: %s failed: %s: %s" % (fig_id, type(e).__name__, e), file=sys.stderr)
    return 1 if failed else 0


def main(argv):
    parser = argparse.ArgumentParser(
        usage=USAGE, description="Draw the evaluation figures from the CSV files that "
        "`mfadvr eval paper` wrote into DIR; PNGs go to DIR/plots/.")
    parser.add_argument("dir", metavar="DIR", help="evaluation output folder")
    args = parser.parse_args(argv)
    if not os.path.isdir(args.dir):
        print("error: %s is not a directory\nusage: %s" % (args.dir, USAGE), file=sys.stderr)
        return 1
    global matplotlib, plt, ticker
    try:
        import matplotlib
        matplotlib.use("Agg")  # no display on build machines
        import matplotlib.image
        import matplotlib.pyplot as plt
        from matplotlib import ticker
    except ImportError:
        print("python3-matplotlib is required for the plots: "
              "sudo apt-get install python3-matplotlib", file=sys.stderr)
        return 1
    return run(args.dir)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
