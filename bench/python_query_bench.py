"""model.query from Python against the C++ query benchmark's case (degree 3, 64^3 control
points, 2^20 random points in the unit cube, values): median of 7 calls, one thread and all.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_query_bench.py
    build/release/bench/mfadvr_bench --benchmark_filter='Query_value_random/p:3/ctrl:64/' \
        --benchmark_repetitions=7 --benchmark_report_aggregates_only=true
"""
import os
import time, numpy as np, mfadvr
rng = np.random.default_rng(0)
vol = rng.random((64, 64, 64)).astype(np.float32)
m = mfadvr.encode(vol, spacing=1.0 / 63, coding="float32")
assert m.info["control_counts"] == [64, 64, 64] and m.info["degree"] == [3, 3, 3]
pts = np.random.default_rng(1).random((1 << 20, 3))
for threads in (1, 0):
    times = []
    for _ in range(7):
        t = time.perf_counter(); m.query(pts, threads=threads); times.append(time.perf_counter() - t)
    med = sorted(times)[3]
    n = 1 if threads == 1 else os.cpu_count()
    print(f"threads={threads or 'all'}: median {med*1e3:.2f} ms, {med/len(pts)*1e9*n:.2f} ns per point per thread")
