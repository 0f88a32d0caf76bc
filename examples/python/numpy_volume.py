"""numpy in, numpy out: encode a volume, compare it with its decode, plot a slice and show a
rendered image (docs/python.md).

    PYTHONPATH=build/release/python python3 examples/python/numpy_volume.py [OUT.png]
"""
import sys

import numpy as np

import mfadvr

# A 64 x 56 x 48 volume indexed [z, y, x]: two Gaussian blobs.
z, y, x = np.meshgrid(np.linspace(-1, 1, 48), np.linspace(-1, 1, 56), np.linspace(-1, 1, 64),
                      indexing="ij")
volume = (np.exp(-6 * ((x - 0.3) ** 2 + y ** 2 + z ** 2)) +
          0.7 * np.exp(-10 * ((x + 0.4) ** 2 + (y - 0.2) ** 2 + z ** 2))).astype(np.float32)

model = mfadvr.encode(volume, spacing=1.0 / 32, max_error=1e-3)
report = model.report
print(f"{report['control_counts']} control points, max error "
      f"{report['max_relative_error']:.2e} of the range, {report['fit_seconds']:.2f} s")

decoded = model.decode()
print("decoded", decoded.shape, decoded.dtype, "max |decoded - volume|",
      float(abs(decoded - volume).max()))

centre = np.array([[1.0, 0.875, 0.75]])  # x, y, z of the volume's centre
print("value, dx, dy, dz at the centre:", model.query(centre, derivatives=1)[0])

image = mfadvr.render(model, size=(320, 240), tf="ramp", shade=True,
                      azimuth=30, elevation=20)

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no figure")
    sys.exit(0)
fig, axes = plt.subplots(1, 3, figsize=(12, 3.6))
k = volume.shape[0] // 2
axes[0].imshow(volume[k], origin="lower")
axes[0].set_title("slice z = %d: samples" % k)
axes[1].imshow(decoded[k] - volume[k], origin="lower", cmap="coolwarm")
axes[1].set_title("decoded - samples")
axes[2].imshow(image)
axes[2].set_title("mfadvr.render")
for a in axes:
    a.set_axis_off()
out = sys.argv[1] if len(sys.argv) > 1 else "numpy_volume.png"
fig.savefig(out, dpi=80, bbox_inches="tight")
print("wrote", out)
