"""encode --dequantize against the interpolating model and --smooth auto on a smooth field
quantized to 8 bits, measured against the field itself (docs/encoding.md, "Quantized samples").

    PYTHONPATH=build/release/python /usr/bin/python3 bench/dequantize_smooth_field.py \
        [--cli build/release/src/app/mfadvr] [--n 96]

The field: a Gaussian blob (amplitude 200, variance 400 samples^2) plus 20 sin(x / 9) plus 25,
rounded to uint8. Value PSNR over 255 and the mean angle between the model's and the field's
gradients at 200,000 random points (between the samples), bits per sample, encode time, peak
memory of each encode.
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

import numpy as np

import mfadvr


def field(x, y, z, n):
    c = n / 96.0
    return (200 * np.exp(-((x - 48 * c) ** 2 + (y - 40 * c) ** 2 + (z - 50 * c) ** 2) / (800 * c * c))
            + 20 * np.sin(x / (9 * c)) + 25)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default="build/release/src/app/mfadvr")
    ap.add_argument("--n", type=int, default=96)
    args = ap.parse_args()
    n = args.n
    tmp = tempfile.mkdtemp()
    z, y, x = np.meshgrid(*(np.arange(n),) * 3, indexing="ij")
    raw = os.path.join(tmp, f"field_{n}x{n}x{n}_uint8.raw")
    np.rint(field(x, y, z, n)).astype(np.uint8).tofile(raw)
    rng = np.random.default_rng(0)
    p = rng.random((200000, 3)) * (n - 1)
    truth = field(p[:, 0], p[:, 1], p[:, 2], n)
    h = 1e-4
    grad = np.stack([(field(*(p + h * e).T, n) - field(*(p - h * e).T, n)) / (2 * h)
                     for e in np.eye(3)], axis=1)
    rows = [("interpolating (default)", []), ("--smooth auto", ["--smooth", "auto"]),
            ("--dequantize", ["--dequantize"])]
    print("| model | value PSNR vs field | mean gradient angle | max abs(model - sample) | "
          "bits/sample | encode | peak memory |")
    print("|---|---|---|---|---|---|---|")
    for name, options in rows:
        out = os.path.join(tmp, "m.mfa")
        start = time.perf_counter()
        r = subprocess.run(["/usr/bin/time", "-f", "%M", args.cli, "encode", raw, *options,
                            "--json", "-q", "-o", out], capture_output=True, text=True, check=True)
        seconds = time.perf_counter() - start
        report = json.loads(r.stdout)
        peak_kb = int(r.stderr.strip().splitlines()[-1])
        m = mfadvr.load(out)
        q = m.query(p, derivatives=1)
        rms = np.sqrt(np.mean((q[:, 0] - truth) ** 2))
        g = q[:, 1:4]
        cos = np.sum(g * grad, 1) / (np.linalg.norm(g, axis=1) * np.linalg.norm(grad, axis=1))
        angle = np.degrees(np.arccos(np.clip(cos[np.isfinite(cos)], -1, 1))).mean()
        print(f"| {name} | {20 * np.log10(255 / rms):.1f} dB | {angle:.2f} deg | "
              f"{report['max_error']:.3f} | {report['bits_per_sample']:.2f} | {seconds:.2f} s | "
              f"{peak_kb / 1024:.0f} MiB |")


if __name__ == "__main__":
    main()
