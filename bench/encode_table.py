#!/usr/bin/env python3
"""Encoding benchmarks through the command line: adaptive grids and scattered meshes.

Runs `mfadvr encode --json` for each case REPEATS times and prints a Markdown table with the
median fit time and the final size and errors (which do not vary between runs).

  bench/encode_table.py [--mfadvr build/release/src/app/mfadvr] [--data ../shared/data]
                        [--repeats 3] [--only adaptive|scattered]

Cases whose input file is absent are listed as skipped.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

ADAPTIVE = [(name, e) for name in ("fuel_64x64x64_uint8.raw", "nucleon_41x41x41_uint8.raw",
                                   "bonsai.nrrd") for e in ("1e-2", "1e-3")]
SCATTERED = [("bluntfin_tets.vtu", "Density", n) for n in (32, 64)]


def run(exe, args):
    out = subprocess.run([exe, "encode", *args, "--json", "-q"], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--mfadvr", default=os.path.join(root, "build/release/src/app/mfadvr"))
    p.add_argument("--data", default=os.environ.get("MFADVR_DATA_DIR",
                                                    os.path.join(root, "../shared/data")))
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--only", choices=("adaptive", "scattered"))
    a = p.parse_args()
    if not os.access(a.mfadvr, os.X_OK):
        sys.exit(f"no mfadvr executable at {a.mfadvr}; build the release preset first")

    if a.only in (None, "adaptive"):
        print("| input | E | rounds | reached | control points | max rel. error | rms rel. error "
              "| model bytes | input bytes | median fit s |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for name, e in ADAPTIVE:
            path = os.path.join(a.data, name)
            if not os.path.exists(path):
                print(f"| {name} | {e} | skipped (file absent) |||||||")
                continue
            runs = [run(a.mfadvr, [path, "--max-error", e]) for _ in range(a.repeats)]
            j = runs[0]
            n = "x".join(str(c) for c in j["control_counts"])
            t = statistics.median(r["fit_seconds"] for r in runs)
            print(f"| {name} | {e} | {j['adaptive']['rounds']} | {j['adaptive']['reached']} | {n} "
                  f"| {j['max_relative_error']:.2e} | {j['rms_relative_error']:.2e} "
                  f"| {j['model_bytes']:,} | {j['input_bytes']:,} | {t:.2f} |")
            sys.stdout.flush()
    if a.only in (None, "scattered"):
        print()
        print("| input | points | control points | max rel. error | rms rel. error | CG iterations "
              "| mask | model bytes | median fit s |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, field, n in SCATTERED:
            path = os.path.join(a.data, name)
            if not os.path.exists(path):
                print(f"| {name} | skipped (file absent) ||||||||")
                continue
            runs = [run(a.mfadvr, [path, "--field", field, "--ctrl", str(n)])
                    for _ in range(a.repeats)]
            j = runs[0]
            t = statistics.median(r["fit_seconds"] for r in runs)
            m = j["mask"]
            mask = f"{'x'.join(str(d) for d in m['dims'])}, {100 * m['inside_fraction']:.0f}% inside"
            print(f"| {name} ({field}) | {j['points']:,} | {n}^3 | {j['max_relative_error']:.3e} "
                  f"| {j['rms_relative_error']:.3e} | {j['solver']['iterations']} | {mask} "
                  f"| {j['model_bytes']:,} | {t:.2f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
