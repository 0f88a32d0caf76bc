#!/usr/bin/env python3
"""Smoke test of `mfadvr eval paper --quick` (ctest EvalPaper.QuickSmoke).

Runs the quick evaluation into a fresh folder, then checks what a reader of the report relies
on: every CSV has the columns and the number of rows the configuration implies, every number
that must be finite is, MFA beats trilinear in Table 2's PSNR at both grids, the report has all
its sections and the plot script made its figures. The galleries of real data are checked when
the data folder holds them (they are skipped otherwise, and the report must say so).
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

EXPERIMENTS = ["value", "tables", "structured", "unstructured", "params", "query", "performance",
               "compression", "denoise", "time"]


def read(out, name):
    with open(os.path.join(out, name), newline="") as f:
        rows = list(csv.DictReader(f))
        return rows


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def expect(condition, message):
    if not condition:
        fail(message)


def expect_columns(out, name, columns, rows):
    with open(os.path.join(out, name), newline="") as f:
        header = next(csv.reader(f))
    expect(header == columns, "%s: columns %s, expected %s" % (name, header, columns))
    data = read(out, name)
    expect(len(data) == rows, "%s: %d rows, expected %d" % (name, len(data), rows))
    return data


def finite(rows, column, name):
    for r in rows:
        v = float(r[column])
        expect(math.isfinite(v) and v >= 0, "%s: %s = %s" % (name, column, r[column]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", required=True, help="the mfadvr program")
    ap.add_argument("--xvfb-run", help="run it under this xvfb-run (VTK's renderers need X)")
    ap.add_argument("--out", required=True)
    ap.add_argument("--data", required=True)
    args = ap.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    command = [args.exe, "eval", "paper", "--quick", "--out", args.out, "--data", args.data]
    if args.xvfb_run:
        command = [args.xvfb_run, "-a", "-s", "-screen 0 1280x1024x24 -noreset"] + command
    print(" ".join(command), flush=True)
    run = subprocess.run(command)
    expect(run.returncode == 0, "eval exited with %d" % run.returncode)
    out = args.out

    # Value accuracy: 4 zoom levels x (truth, 4 filters, 2 MFA models, 3 VTK renderers).
    value = expect_columns(out, "fig05_value_accuracy.csv",
                           ["zoom", "samples_per_beam", "method", "family", "mse", "psnr", "ssim",
                            "render_seconds", "image", "error_image", "error_gain"], 40)
    expect(sorted({r["zoom"] for r in value}) == ["1", "2", "3", "4"], "zoom levels")
    expect([r["samples_per_beam"] for r in value if r["method"] == "truth"] == ["32", "16", "8", "4"],
           "samples per beam of the quick grid")
    finite([r for r in value if r["method"] != "truth"], "psnr", "value accuracy")
    for r in value:
        expect(os.path.isfile(os.path.join(out, r["image"])), "missing image " + r["image"])
    expect_columns(out, "fig13_quality_vs_time.csv",
                   ["method", "family", "rmse", "render_seconds", "scene"], 9)

    # Tables 1 and 2: 2 grids x (truth + 6 methods); MFA above trilinear in Table 2.
    for name in ["table1_gradient.csv", "table2_overall.csv"]:
        rows = expect_columns(out, name, ["grid", "method", "mse", "psnr", "ssim",
                                          "render_seconds", "image"], 14)
        finite([r for r in rows if r["method"] != "truth"], "psnr", name)
    table2 = read(out, "table2_overall.csv")
    for grid in ["64x64x64", "41x41x41"]:
        psnr = {r["method"]: float(r["psnr"]) for r in table2 if r["grid"] == grid}
        expect(psnr["mfa"] > psnr["trilinear"],
               "Table 2 at %s: MFA %.2f dB not above trilinear %.2f dB"
               % (grid, psnr["mfa"], psnr["trilinear"]))
        print("Table 2 %s: mfa %.2f dB > trilinear %.2f dB" % (grid, psnr["mfa"], psnr["trilinear"]))

    # Parameter studies: 4 degrees x 5 control counts; 4 degrees x 3 counts x (value, both).
    params = expect_columns(out, "fig10_param_quality.csv",
                            ["grid", "degree", "ctrl", "mse", "psnr", "ssim", "encode_seconds",
                             "render_seconds"], 20)
    finite(params, "psnr", "parameter study")
    query = expect_columns(out, "fig12_query_time.csv", ["degree", "ctrl", "query", "ns_per_query"], 24)
    finite(query, "ns_per_query", "query time")

    # Performance: structured 2 sizes x 6 methods, unstructured 2 sizes x 4 methods.
    perf = expect_columns(out, "fig11_render_time.csv",
                          ["family", "method", "size", "points", "cells", "render_seconds",
                           "first_seconds", "width", "height"], 20)
    finite(perf, "render_seconds", "render time")

    # Real data: rows for the data sets that are present.
    structured = [f for f in ["fuel_64x64x64_uint8.raw", "nucleon_41x41x41_uint8.raw"]
                  if os.path.isfile(os.path.join(args.data, f))]
    if structured:
        expect_columns(out, "fig08_structured.csv",
                       ["dataset", "dims", "method", "render_seconds", "image"], 6 * len(structured))
    unstructured = [f for f in ["bluntfin_tets.vtu", "spx.vtk"]
                    if os.path.isfile(os.path.join(args.data, f))]
    if unstructured:
        # Two views (whole, zoom) of Bunyk, ZSweep, PT, the mesh's own field through our ray
        # caster, the model with its exact boundary and with its mask alone.
        gallery = expect_columns(out, "fig09_unstructured.csv",
                                 ["dataset", "points", "cells", "view", "method", "render_seconds",
                                  "psnr_vs_bunyk", "ssim_vs_bunyk", "psnr_vs_mesh", "ssim_vs_mesh",
                                  "encode_seconds", "image"],
                                 12 * len(unstructured))
        # Through the same rays the model is nearer the mesh's own field than Bunyk's image is.
        for r in gallery:
            if r["method"] == "mfa" and r["view"] == "whole":
                expect(float(r["psnr_vs_mesh"]) > max(30.0, float(r["psnr_vs_bunyk"])),
                       "fig09: the model is far from the mesh's own field: %s" % r)

    # Compression: Marschner-Lobb and the small scans present, 3 rates, 5 methods (ZFP's
    # fixed-accuracy mode may be missing at a rate where it cannot make a stream that small).
    compression = read(out, "compression_rd.csv")
    volumes = 1 + len(structured)
    expect({r["volume"] for r in compression} == {"marschner-lobb 32^3"} | set(structured),
           "compression volumes: %s" % sorted({r["volume"] for r in compression}))
    expect(4 * 3 * volumes <= len(compression) <= 5 * 3 * volumes,
           "compression: %d rows" % len(compression))
    for r in compression:
        expect(float(r["bits_per_sample"]) > 0 and float(r["volume_psnr"]) > 10,
               "compression row %s" % r)
        if r["method"] == "mfa-coded":
            # The budget bounds the control points; the header and knots add under 2 KB.
            samples = 32 ** 3 if r["volume"].startswith("marschner") else \
                (64 ** 3 if r["volume"].startswith("fuel") else 41 ** 3)
            expect(float(r["bits_per_sample"]) <= float(r["rate"]) + 8 * 2048 / samples,
                   "compression: the coded model exceeds its budget: %s" % r)

    # Noise reduction: two functions x 41^3 x (8-bit, 3% noise): 9 methods and 5 swept lambdas.
    denoise = read(out, "denoise.csv")
    expect(len(denoise) == 2 * 2 * (9 + 5), "denoise: %d rows" % len(denoise))
    for r in denoise:
        expect(float(r["psnr"]) > 10 and float(r["samples_psnr"]) > 15, "denoise row %s" % r)
    noisy = {r["method"]: r for r in denoise
             if r["function"] == "ct-head" and r["degradation"] == "n3"}
    expect(float(noisy["mfa-auto"]["lambda"]) > 0 and
           float(noisy["mfa-auto"]["samples_psnr"]) > float(noisy["mfa"]["samples_psnr"]) + 2,
           "denoise: --smooth auto does not reduce 3%% noise: %s" % noisy["mfa-auto"])

    # Quantized samples: soft-and-sharp 33^3 at 8 bits, 5 methods. Every model rounds back to
    # the samples; the dequantized one's picture and soft surfaces are nearer the truth's.
    quantized = {r["method"]: r for r in read(out, "denoise_quantized.csv")}
    expect(sorted(quantized) == sorted(["trilinear", "tricubic", "mfa", "mfa-auto",
                                        "mfa-dequantize"]), "quantized: %s" % sorted(quantized))
    for name in ("mfa", "mfa-dequantize"):
        expect(float(quantized[name]["max_sample_error_levels"]) <= 0.5,
               "quantized: %s does not round back: %s" % (name, quantized[name]))
    expect(float(quantized["mfa-dequantize"]["psnr"]) > float(quantized["mfa"]["psnr"]),
           "quantized: the --dequantize image is not nearer the truth: %s" % quantized)
    expect(float(quantized["mfa-dequantize"]["soft_angle_deg"]) <
           float(quantized["mfa"]["soft_angle_deg"]),
           "quantized: --dequantize gradients not nearer the truth: %s" % quantized)

    # Time series: 8 and 16 steps; at 16 (a blob moves its half width per step) the 4-D model is
    # above linear interpolation halfway between steps, at 8 neither recovers the motion.
    halfway = {int(r["steps"]): r for r in read(out, "time/halfway_values.csv")}
    expect(sorted(halfway) == [8, 16], "time: steps %s" % sorted(halfway))
    expect(float(halfway[16]["psnr_4d"]) > float(halfway[16]["psnr_linear"]) + 3,
           "time: the 4-D model is not above linear interpolation: %s" % halfway[16])
    images = {r["method"]: r for r in read(out, "time/halfway_images.csv")}
    expect(float(images["4d"]["image_psnr"]) > float(images["linear"]["image_psnr"]),
           "time: images %s" % images)
    expect(len(read(out, "time/sizes.csv")) == 5 * 4, "time: sizes.csv rows")

    with open(os.path.join(out, "report.md")) as f:
        report = f.read()
    for number in range(1, len(EXPERIMENTS) + 1):
        expect("\n## %d. " % number in report, "report lacks section %d" % number)
    expect("Matches." in report and "Differs." in report, "report lacks the comparison")
    if len(structured) < 2 or len(unstructured) < 2:
        expect("skipped" in report, "report does not say which data sets were skipped")
    figures = ["fig04_value_images", "fig05_value_accuracy", "fig06_error_images",
               "fig07_marschner_lobb", "tables_psnr", "fig10_param_quality", "fig11_render_time",
               "fig12_query_time", "fig13_quality_vs_time"]
    for fig in figures:
        expect(os.path.isfile(os.path.join(out, "plots", fig + ".png")), "missing plot " + fig)
    print("quick evaluation: all checks passed")


if __name__ == "__main__":
    main()
