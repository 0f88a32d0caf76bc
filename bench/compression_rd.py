#!/usr/bin/python3
"""Rate-distortion of MFA models against ZFP, at equal bytes: bits per input sample (file bytes
x 8 / samples) against volume PSNR (value range over the RMS error at every input sample).

    bench/compression_rd.py [--rates 0.25,0.5,1,2,4] [--out DIR] [--plot] [VOLUME.raw ...]

Volumes: raw files named NAME_XxYxZ_TYPE.raw (uint8, uint16, int16, float32, float64); without
any, every raw volume in ../shared/data plus two smooth float fields written by this script:
Marschner-Lobb 64^3 (mfadvr's builtin) and VTK's Wavelet source (vtkRTAnalyticSource) 128^3.

Per volume and rate B:
- MFA: `mfadvr encode VOLUME --bits-per-sample B` (the encoder chooses control counts and the ZFP
  tolerance of the control points); the model is decoded with `mfadvr decode` and its PSNR
  computed here, independently of the encoder's report.
- ZFP fixed-rate at rate B (random access, like the model) and ZFP fixed-accuracy with the
  largest tolerance whose stream is no larger than the MFA file (ZFP's best at equal bytes);
  both on the samples as float32 (float64 volumes as float64), via python3-zfpy. A dash: ZFP's
  fixed-accuracy mode cannot make a stream that small (its block headers alone exceed it).
- Downsampling: the volume resampled (cubic B-spline, scipy.ndimage.zoom) to as many samples of
  its own type as the MFA file's bytes hold, and back to the full grid with the same cubic
  spline.
Also the default model of integer volumes (no budget). Prints a Markdown table; --out writes
it with a CSV and, with --plot, one rate-distortion plot per volume (python3-matplotlib).
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

try:
    import zfpy
except ImportError:
    sys.exit("needs ZFP's Python module: apt-get install python3-zfpy")

HERE = os.path.dirname(os.path.abspath(__file__))
TYPES = {"uint8": np.uint8, "uint16": np.uint16, "int16": np.int16, "float32": np.float32,
         "float64": np.float64}


def read_raw(path):
    m = re.search(r"_(\d+)x(\d+)x(\d+)_(\w+)\.raw$", path)
    if not m or m.group(4) not in TYPES:
        sys.exit(path + ": expected NAME_XxYxZ_TYPE.raw with TYPE in " + ", ".join(TYPES))
    dims = tuple(int(m.group(i)) for i in (1, 2, 3))
    data = np.fromfile(path, dtype=TYPES[m.group(4)])
    if data.size != dims[0] * dims[1] * dims[2]:
        sys.exit(path + ": size does not match its name")
    return data.reshape(dims[2], dims[1], dims[0]), m.group(4)


def psnr(ref, test):
    ref = ref.astype(np.float64)
    rng = float(ref.max() - ref.min())
    rms = float(np.sqrt(np.mean((test.astype(np.float64) - ref) ** 2)))
    return math.inf if rms == 0 else 20 * math.log10(rng / rms)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(" ".join(cmd) + "\n" + r.stderr)
    return r.stdout


def mfa_point(exe, path, rate, tmp):
    model = os.path.join(tmp, "m.mfa")
    args = [exe, "encode", path, "-q", "--json", "-o", model]
    if rate is not None:
        args += ["--bits-per-sample", str(rate)]
    report = json.loads(run(args))
    decoded = os.path.join(tmp, "d.raw")
    run([exe, "decode", model, "-q", "-o", decoded, "--type", "float64"])
    values = np.fromfile(decoded, dtype=np.float64)
    return os.path.getsize(model), values, report


def zfp_accuracy_at_bytes(a, budget):
    """ZFP fixed-accuracy with the smallest tolerance whose stream fits `budget` bytes."""
    rng = float(a.max() - a.min()) or 1.0
    lo, hi = -30, 10  # tolerance rng * 2^k
    best = None
    if len(zfpy.compress_numpy(a, tolerance=rng * 2.0 ** hi)) > budget:
        return None
    while lo < hi:
        mid = (lo + hi) // 2
        if len(zfpy.compress_numpy(a, tolerance=rng * 2.0 ** mid)) <= budget:
            hi = mid
        else:
            lo = mid + 1
    best = zfpy.compress_numpy(a, tolerance=rng * 2.0 ** hi)
    return best


def downsampled(data, dtype, budget_bytes):
    """PSNR and bytes of the volume kept at fewer samples of its own type, cubic both ways."""
    from scipy import ndimage
    item = np.dtype(TYPES[dtype]).itemsize
    share = (budget_bytes / item) / data.size
    if share >= 1:
        return data.size * item, math.inf
    small_shape = [max(4, int(round(n * share ** (1 / 3)))) for n in data.shape]
    f = data.astype(np.float64)
    small = ndimage.zoom(f, [m / n for m, n in zip(small_shape, data.shape)], order=3,
                         mode="nearest", grid_mode=False)
    if np.issubdtype(TYPES[dtype], np.integer):
        info = np.iinfo(TYPES[dtype])
        small = np.clip(np.rint(small), info.min, info.max)
    else:
        small = small.astype(TYPES[dtype]).astype(np.float64)
    back = ndimage.zoom(small, [n / m for n, m in zip(data.shape, small.shape)], order=3,
                        mode="nearest", grid_mode=False)
    return small.size * item, psnr(data, back)


def write_smooth_fields(tmp, exe):
    out = []
    ml = os.path.join(tmp, "marschner-lobb_64x64x64_float32.raw")
    model = os.path.join(tmp, "ml.mfa")
    run([exe, "encode", "builtin:marschner-lobb:64", "-q", "--lossless", "-o", model])
    run([exe, "decode", model, "-q", "-o", ml, "--type", "float32"])
    out.append(ml)
    try:
        from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
        from vtkmodules.util.numpy_support import vtk_to_numpy
        src = vtkRTAnalyticSource()
        src.SetWholeExtent(0, 127, 0, 127, 0, 127)
        src.Update()
        values = vtk_to_numpy(src.GetOutput().GetPointData().GetScalars()).astype(np.float32)
        wavelet = os.path.join(tmp, "wavelet_128x128x128_float32.raw")
        values.tofile(wavelet)
        out.append(wavelet)
    except ImportError:
        print("note: VTK's Python modules are missing: no Wavelet field", file=sys.stderr)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("volumes", nargs="*")
    parser.add_argument("--rates", default="0.25,0.5,1,2,4")
    parser.add_argument("--mfadvr", default=os.path.join(HERE, "../build/release/src/app/mfadvr"))
    parser.add_argument("--data", default=os.path.join(HERE, "../../shared/data"))
    parser.add_argument("--out", help="folder for rd.md, rd.csv and plots")
    parser.add_argument("--plot", action="store_true")
    args = parser.parse_args()
    rates = [float(r) for r in args.rates.split(",")]
    tmp = tempfile.mkdtemp(prefix="mfadvr-rd-")
    volumes = list(args.volumes)
    if not volumes:
        if os.path.isdir(args.data):
            volumes = sorted(os.path.join(args.data, f) for f in os.listdir(args.data)
                             if re.search(r"_\d+x\d+x\d+_\w+\.raw$", f))
        volumes += write_smooth_fields(tmp, args.mfadvr)
    rows = []
    for path in volumes:
        data, dtype = read_raw(path)
        n = data.size
        name = os.path.basename(path).rsplit(".", 1)[0]
        zfp_input = data.astype(np.float64 if dtype == "float64" else np.float32)
        points = [None] + rates if dtype in ("uint8", "uint16", "int16") else rates
        for rate in points:
            try:
                size, values, report = mfa_point(args.mfadvr, path, rate, tmp)
            except RuntimeError as e:
                print("note: " + str(e).strip().splitlines()[-1], file=sys.stderr)
                continue
            mfa_bps = 8.0 * size / n
            row = {"volume": name, "budget": "default" if rate is None else rate,
                   "mfa_bits": mfa_bps, "mfa_psnr": psnr(data, values.reshape(data.shape)),
                   "mfa_ctrl": "x".join(str(c) for c in report["control_counts"]),
                   "mfa_tolerance": report["coding"]["tolerance"]}
            fixed = zfpy.compress_numpy(zfp_input, rate=mfa_bps)
            row["zfp_rate_bits"] = 8.0 * len(fixed) / n
            row["zfp_rate_psnr"] = psnr(data, zfpy.decompress_numpy(fixed))
            acc = zfp_accuracy_at_bytes(zfp_input, size)
            row["zfp_acc_bits"] = 8.0 * len(acc) / n if acc else math.nan
            row["zfp_acc_psnr"] = psnr(data, zfpy.decompress_numpy(acc)) if acc else math.nan
            row["down_bits"], row["down_psnr"] = downsampled(data, dtype, size)
            row["down_bits"] = 8.0 * row["down_bits"] / n
            rows.append(row)
            print(f"{name} {row['budget']}: MFA {mfa_bps:.3f} b/s {row['mfa_psnr']:.2f} dB, "
                  f"ZFP rate {row['zfp_rate_psnr']:.2f} dB, ZFP accuracy "
                  f"{row['zfp_acc_bits']:.3f} b/s {row['zfp_acc_psnr']:.2f} dB, downsampled "
                  f"{row['down_psnr']:.2f} dB", file=sys.stderr)
    lines = ["| volume | budget (bits/sample) | MFA bits/sample | MFA PSNR | control points | "
             "ZFP fixed-rate PSNR | ZFP fixed-accuracy bits/sample | ZFP fixed-accuracy PSNR | "
             "downsampled + cubic PSNR |",
             "|---|---|---|---|---|---|---|---|---|"]
    dash = lambda v, f: "—" if math.isnan(v) else format(v, f)
    for r in rows:
        lines.append(f"| {r['volume']} | {r['budget']} | {r['mfa_bits']:.3f} | "
                     f"{r['mfa_psnr']:.2f} | {r['mfa_ctrl']} | {r['zfp_rate_psnr']:.2f} | "
                     f"{dash(r['zfp_acc_bits'], '.3f')} | {dash(r['zfp_acc_psnr'], '.2f')} | "
                     f"{r['down_psnr']:.2f} |")
    table = "\n".join(lines)
    print(table)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        open(os.path.join(args.out, "rd.md"), "w").write(table + "\n")
        with open(os.path.join(args.out, "rd.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
        if args.plot:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            for name in dict.fromkeys(r["volume"] for r in rows):
                rs = [r for r in rows if r["volume"] == name and r["budget"] != "default"]
                fig, ax = plt.subplots(figsize=(5, 3.6))
                ax.plot([r["mfa_bits"] for r in rs], [r["mfa_psnr"] for r in rs], "o-",
                        label="MFA (coded control points)")
                ax.plot([r["zfp_rate_bits"] for r in rs], [r["zfp_rate_psnr"] for r in rs], "s--",
                        label="ZFP fixed-rate")
                ax.plot([r["zfp_acc_bits"] for r in rs], [r["zfp_acc_psnr"] for r in rs], "^:",
                        label="ZFP fixed-accuracy")
                ax.plot([r["mfa_bits"] for r in rs], [r["down_psnr"] for r in rs], "x-.",
                        label="downsampled + cubic")
                ax.set_xscale("log", base=2)
                ax.set_xlabel("bits per sample")
                ax.set_ylabel("volume PSNR (dB)")
                ax.set_title(name)
                ax.grid(True, alpha=0.3)
                ax.legend(fontsize=8)
                fig.tight_layout()
                fig.savefig(os.path.join(args.out, f"rd-{name}.png"), dpi=110)
                plt.close(fig)


if __name__ == "__main__":
    main()
