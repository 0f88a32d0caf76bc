"""Peak memory of mfadvr.encode per sample, against `mfadvr encode` of the same samples: a 192^3
uint8 volume, also written to /tmp/mem_192x192x192_uint8.raw for the command:

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_encode_memory.py
    build/release/src/app/mfadvr encode /tmp/mem_192x192x192_uint8.raw --json -q
"""
import resource, numpy as np, mfadvr
n = 192
t = np.linspace(-1, 1, n)
vol = np.empty((n, n, n), np.uint8)
for k in range(n):  # slice by slice: no temporaries of the whole volume
    vol[k] = 120 * (1 + np.sin(3 * t)[None, :] * np.cos(2 * t)[:, None] * np.sin(t[k]))
vol.tofile(f"/tmp/mem_{n}x{n}x{n}_uint8.raw")
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
m = mfadvr.encode(vol)
peak = m.report["peak_memory_bytes"]
print(f"python: peak {peak/2**20:.0f} MiB, before encode {base/2**20:.0f} MiB, "
      f"(peak - before) per sample {(peak-base)/vol.size:.1f} B, fit {m.report['fit_seconds']:.2f} s")
