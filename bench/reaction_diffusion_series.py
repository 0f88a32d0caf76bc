"""One 4-D model of a slowly changing series against one coded 3-D model per step, at equal PSNR
(docs/time-varying.md, "Measured"): a Gray-Scott reaction-diffusion run in numpy, its v field
saved every `--every` iterations, the kind of series a simulation writes.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/reaction_diffusion_series.py \
        [--n 48] [--steps 24] [--every 40]

Both are fitted with the defaults (cubic, interpolating every sample; the 4-D model cubic and
interpolating in time too) and zfp-coded at the same tolerances; PSNR over every sample of every
step (the series' value range over the RMS error), bits per sample of the whole series.
"""
import argparse
import time

import numpy as np

import mfadvr


def gray_scott(n, steps, every, seed=1):
    """v of a 3-D Gray-Scott system (Du 0.16, Dv 0.08, F 0.035, k 0.065, dt 1, periodic), seeded
    with a few noisy cubes: spots that grow and split slowly."""
    rng = np.random.default_rng(seed)
    u = np.ones((n, n, n), np.float32)
    v = np.zeros((n, n, n), np.float32)
    for _ in range(4):
        c = rng.integers(n // 4, 3 * n // 4, size=3)
        s = tuple(slice(int(x) - 3, int(x) + 3) for x in c)
        u[s] = 0.5
        v[s] = 0.25 + 0.05 * rng.standard_normal(u[s].shape)

    def lap(a):
        return sum(np.roll(a, d, axis) for axis in range(3) for d in (-1, 1)) - 6 * a

    out = []
    for i in range(steps * every):
        uvv = u * v * v
        u += 0.16 * lap(u) - uvv + 0.035 * (1 - u)
        v += 0.08 * lap(v) + uvv - (0.035 + 0.065) * v
        if (i + 1) % every == 0:
            out.append(v.copy())
    return np.stack(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=48)
    ap.add_argument("--steps", type=int, default=24)
    ap.add_argument("--every", type=int, default=40)
    ap.add_argument("--time-ctrl", type=int, default=0,
                    help="control points in time of the 4-D model (default: as many as steps)")
    args = ap.parse_args()
    start = time.time()
    series = gray_scott(args.n, args.steps, args.every)
    rng_ = float(series.max() - series.min())
    step_change = float(np.sqrt(np.mean(np.diff(series, axis=0) ** 2))) / rng_
    print(f"# {args.steps} steps of {args.n}^3, every {args.every} iterations "
          f"({time.time() - start:.1f} s); mean change per step {100 * step_change:.2f} % of the "
          f"range")
    print("tolerance,method,bits_per_sample,psnr")
    samples = series.size
    curves = {"4d": [], "3d": []}
    for tol in (1.0, 0.3, 0.1, 3e-2, 1e-2, 3e-3):
        extra = {"time_ctrl": args.time_ctrl} if args.time_ctrl else {}
        m4 = mfadvr.encode(series, coding="zfp", coding_tolerance=tol, **extra)
        bits4 = 8.0 * m4.report["model_bytes"] / samples
        curves["4d"].append((m4.report["psnr"], bits4))
        print(f"{tol:g},4d-model,{bits4:.4f},{m4.report['psnr']:.2f}")
        bytes3, squared = 0, 0.0
        for step in series:
            m3 = mfadvr.encode(step, coding="zfp", coding_tolerance=tol)
            bytes3 += m3.report["model_bytes"]
            squared += m3.report["rms_error"] ** 2
        psnr3 = 20 * np.log10(rng_ / np.sqrt(squared / len(series)))
        bits3 = 8.0 * bytes3 / samples
        curves["3d"].append((psnr3, bits3))
        print(f"{tol:g},3d-models,{bits3:.4f},{psnr3:.2f}")
    # The 4-D model's bytes over the per-step models' at the same PSNR (linear between points).
    p3 = sorted(curves["3d"])
    print("psnr,bits_4d,bits_3d_models,ratio")
    for psnr, bits in curves["4d"]:
        for (a, ba), (b, bb) in zip(p3, p3[1:]):
            if a <= psnr <= b:
                b3 = ba + (psnr - a) / (b - a) * (bb - ba)
                print(f"{psnr:.2f},{bits:.4f},{b3:.4f},{bits / b3:.3f}")


if __name__ == "__main__":
    main()
