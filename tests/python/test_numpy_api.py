"""mfadvr's numpy functions against the command line on the same inputs: query values to float
precision, render pixels identical, decode round trips, errors raised with the CLI's messages.
Run by ctest (python.NumpyApi) with PYTHONPATH at the build's python folder and MFADVR_CLI the
command."""
import os
import subprocess

import numpy as np
import pytest

import mfadvr

CLI = os.environ.get("MFADVR_CLI", "mfadvr")


def sphere(nz=12, ny=14, nx=16, dtype=np.float32):
    z, y, x = np.meshgrid(np.linspace(-1, 1, nz), np.linspace(-1, 1, ny), np.linspace(-1, 1, nx),
                          indexing="ij")
    return (1.0 - (x * x + 0.5 * y * y + 0.8 * z * z)).astype(dtype)


def cli(*args):
    return subprocess.run([CLI, *map(str, args)], check=True, capture_output=True,
                          text=True).stdout


@pytest.fixture(scope="module")
def model():
    return mfadvr.encode(sphere(), spacing=(0.1, 0.2, 0.3), origin=(1.0, -2.0, 0.5))


def test_encode_places_the_array_z_y_x_with_spacing_and_origin(model):
    info = model.info
    assert info["control_counts"] == [16, 14, 12]  # x, y, z: interpolating
    assert np.allclose(info["domain_min"], [1.0, -2.0, 0.5])
    assert np.allclose(info["domain_max"], [1.0 + 1.5, -2.0 + 2.6, 0.5 + 3.3])
    report = model.report
    assert report["max_relative_error"] < 1e-4


def test_query_equals_the_command_line(model, tmp_path):
    path = tmp_path / "m.mfa"
    model.save(str(path))
    rng = np.random.default_rng(1)
    lo, hi = np.array(model.info["domain_min"]), np.array(model.info["domain_max"])
    points = lo + (hi - lo) * rng.random((200, 3))
    np.savetxt(tmp_path / "p.txt", points, fmt="%.17g")
    table = np.loadtxt(cli("query", path, "--points", tmp_path / "p.txt", "--derivatives", 2)
                       .splitlines()[1:], delimiter=",")
    ours = model.query(points, derivatives=2)
    assert ours.shape == (200, 10)
    assert np.allclose(table[:, :3], points)
    # The CLI prints floats with 9 significant digits: equal to float precision.
    assert np.allclose(ours, table[:, 3:], rtol=1e-6, atol=1e-6)
    assert np.array_equal(model(points), model.query(points))
    assert np.allclose(model(points), ours[:, 0], rtol=1e-6, atol=1e-6)
    assert model.query(points, derivatives=1).shape == (200, 4)
    # A model loaded from the file answers the same.
    assert np.array_equal(mfadvr.load(str(path)).query(points), model.query(points))


def test_decode_round_trips_in_the_input_type():
    volume = (100 * (1 + sphere())).astype(np.uint8)
    # Lossless: the default zfp coding of so small a volume is capped at its 2,688 bytes.
    m = mfadvr.encode(volume, coding="lossless")
    decoded = m.decode()
    assert decoded.dtype == np.uint8 and decoded.shape == volume.shape
    assert np.array_equal(decoded, volume)  # an interpolating model rounds back to every sample
    assert mfadvr.encode(volume).report["coding"]["method"] == "zfp"  # the integer-scan default
    floats = mfadvr.encode(sphere()).decode()
    assert floats.dtype == np.float32
    assert np.abs(floats - sphere()).max() < 1e-4
    assert m.decode(shape=(3, 4, 5), dtype="float64").shape == (3, 4, 5)
    # --dequantize: the smoothest model that still rounds back (a flag, or the step).
    smooth = mfadvr.encode(volume, dequantize=True)
    assert smooth.report["dequantize"]["rounds_back"]
    assert np.array_equal(smooth.decode(), volume)
    assert mfadvr.encode(volume / np.float32(4), dequantize=0.25).report["dequantize"]["step"] == 0.25


def test_fortran_ordered_arrays_are_read_by_index():
    volume = sphere()
    a = mfadvr.encode(volume).query([[0.3, 0.4, 0.5]])
    b = mfadvr.encode(np.asfortranarray(volume)).query([[0.3, 0.4, 0.5]])
    assert np.array_equal(a, b)


def test_options_are_the_command_line_s(model):
    coarse = mfadvr.encode(sphere(), ctrl=(8, 7, 6), degree=2)
    assert coarse.info["control_counts"] == [8, 7, 6]
    assert coarse.info["degree"] == [2, 2, 2]
    adaptive = mfadvr.encode(sphere(24, 24, 24), max_error=1e-3)
    assert adaptive.report["adaptive"]["reached"]
    assert adaptive.report["max_relative_error"] <= 1e-3


def test_render_gives_the_command_line_s_pixels(model, tmp_path):
    path = tmp_path / "m.mfa"
    model.save(str(path))
    options = dict(tf="ramp", shade=True, azimuth=30, elevation=20, blend="composite")
    image = mfadvr.render(model, size=(64, 48), **options)
    assert image.shape == (48, 64, 3) and image.dtype == np.uint8
    assert image.max() > 40
    cli("render", path, "-o", tmp_path / "r.png", "--size", "64x48", "--tf", "ramp", "--shade",
        "--azimuth", 30, "--elevation", 20, "-q")
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(str(tmp_path / "r.png"))
    reader.Update()
    png = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).reshape(48, 64, -1)
    assert np.array_equal(image, png[::-1, :, :3])  # PNG rows from the top, VTK's from the bottom
    rgba = mfadvr.render(model, size=(64, 48), alpha=True, **options)
    assert rgba.shape == (48, 64, 4)
    linear = mfadvr.render(model, size=(64, 48), float=True, **options)
    assert linear.dtype == np.float32 and linear.shape == (48, 64, 4)
    # An array renders with a grid filter, or encoded.
    assert mfadvr.render(sphere(), size=(32, 32), method="trilinear").shape == (32, 32, 3)
    assert mfadvr.render(sphere(), size=(32, 32), blend="max").max() > 0
    # A mesh's own field renders from a mesh file only.
    with pytest.raises(ValueError, match="mfadvr render MESH --method mesh"):
        mfadvr.render(sphere(), size=(32, 32), method="mesh")


def cube_mesh(n, hollow=lambda i, j, k: False):
    """The unit cubes of an n^3 grid but the hollow ones, 6 tetrahedra a cube (the points of the
    (n+1)^3 grid, x fastest)."""
    m = n + 1
    grid = np.stack(np.meshgrid(np.arange(m), np.arange(m), np.arange(m), indexing="ij"), -1)
    points = grid.transpose(2, 1, 0, 3).reshape(-1, 3).astype(float)  # x fastest
    index = lambda i, j, k: i + m * (j + m * k)
    tets = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                if hollow(i, j, k):
                    continue
                for order in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
                    at = [i, j, k]
                    tet = [index(*at)]
                    for axis in order:
                        at[axis] += 1
                        tet.append(index(*at))
                    tets.append(tet)
    return points, np.array(tets)


def test_mesh_encode():
    # A mesh given as arrays gets what a mesh file gets: an exact boundary (here around a
    # cavity), and one sample of its linear field in every tetrahedron.
    points, tets = cube_mesh(4, lambda i, j, k: 1 <= i <= 2 and 1 <= j <= 2 and 1 <= k <= 2)
    values = points[:, 0] + 2 * points[:, 1] - points[:, 2]
    m = mfadvr.encode_points(points, values, tets=tets, ctrl=6)
    assert m.report["cell_samples"] == len(tets) == 6 * (64 - 8)
    assert m.info["boundary"]["triangles"] == 6 * 16 * 2 + 6 * 4 * 2
    assert abs(m.query(np.array([[0.5, 0.5, 3.5]]))[0] - (0.5 + 1.0 - 3.5)) < 1e-3
    assert mfadvr.encode_points(points, values, tets=tets, ctrl=6,
                                cell_samples=0).report["cell_samples"] == 0
    for bad in (tets[:, :3], tets.astype(float), tets + len(points)):
        with pytest.raises(ValueError, match="tets"):
            mfadvr.encode_points(points, values, tets=bad)


def test_points_encode():
    rng = np.random.default_rng(2)
    xyz = rng.random((3000, 3))
    values = xyz[:, 0] + 2 * xyz[:, 1]
    m = mfadvr.encode_points(xyz, values, ctrl=(6, 6, 6))
    probe = np.array([[0.5, 0.5, 0.5]])
    assert abs(m.query(probe)[0] - 1.5) < 0.05
    # smooth="auto": lambda by hold-out cross-validation, as `encode --smooth auto` on a mesh.
    noisy = values + rng.normal(0, 0.05, len(values))
    a = mfadvr.encode_points(xyz, noisy, ctrl=(6, 6, 6), smooth="auto")
    assert a.report["smoothing"]["automatic"]
    assert "hold-out" in a.report["smoothing"]["note"]
    assert abs(a.query(probe)[0] - 1.5) < 0.05


def test_bad_input_raises_the_command_line_s_message():
    with pytest.raises(ValueError, match="max-error"):
        mfadvr.encode(sphere(), max_error="abc")
    with pytest.raises(ValueError):
        mfadvr.encode(sphere(), no_such_option=3)
    with pytest.raises(ValueError, match="--ghost: applies with --blocks"):
        mfadvr.encode(sphere(), ghost=2)
    with pytest.raises(ValueError, match="each axis needs 1 to"):
        mfadvr.encode(sphere(), blocks=(0, 1, 1))
    with pytest.raises(ValueError, match="max-error"):
        mfadvr.encode(sphere(), blocks=2, max_error=1e-3)
    with pytest.raises(ValueError, match="memory-limit"):
        mfadvr.encode(sphere(), memory_limit="lots")
    with pytest.raises(ValueError, match="regular grids"):
        mfadvr.encode_points(np.zeros((10, 3)), np.zeros(10), blocks=2)
    with pytest.raises(ValueError, match="3 dimensions"):
        mfadvr.encode(np.zeros((4, 4)))
    bad = sphere()
    bad[1, 2, 3] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        mfadvr.encode(bad)
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        mfadvr.encode(sphere()).query(np.zeros((5, 2)))
    with pytest.raises(RuntimeError):
        mfadvr.load("/nonexistent/model.mfa")
    with pytest.raises(ValueError):
        mfadvr.render(sphere(), size=(32, 32), blend="nonsense")


def test_models_move_to_vtk_and_back_without_files(model, tmp_path):
    data = model.to_vtk()
    assert data.GetClassName() == "vtkMFAModelData"
    bounds = data.GetBounds()
    assert np.allclose(bounds[::2], model.info["domain_min"])
    back = mfadvr.Model.from_vtk(data)
    points = np.array([[1.5, -1.0, 2.0], [2.0, -0.5, 1.0]])
    assert np.array_equal(back.query(points), model.query(points))
    # A model read by VTK's pipeline (vtkMFAReader) comes to numpy.
    model.save(str(tmp_path / "m.mfa"))
    reader = mfadvr.vtkMFAReader()
    reader.SetFileName(str(tmp_path / "m.mfa"))
    reader.Update()
    assert np.array_equal(mfadvr.Model.from_vtk(reader.GetOutput()).query(points),
                          model.query(points))
    with pytest.raises(TypeError):
        mfadvr.Model.from_vtk(reader)
    with pytest.raises(TypeError):
        mfadvr.Model.from_vtk(3)


def test_blocks_encode_query_decode_save_and_render_as_the_command_line(tmp_path):
    volume = sphere(20, 22, 24)
    spacing, origin = (0.1, 0.2, 0.3), (1.0, -2.0, 0.5)
    m = mfadvr.encode(volume, spacing=spacing, origin=origin, blocks=(2, 1, 2), ghost=3)
    assert m.blocks == (2, 1, 2)
    report = m.report
    assert report["blocks"] == [2, 1, 2] and report["ghost_layers"] == 3
    assert len(report["block_reports"]) == 4 and report["max_relative_error"] < 1e-4
    info = m.info
    assert info["format"] == "mfadvr-blocks" and len(info["entries"]) == 4
    assert np.allclose(info["box"], [1.0, 1.0 + 2.3, -2.0, -2.0 + 4.2, 0.5, 0.5 + 5.7])

    # Interpolating in every block: the samples come back, and so does the whole grid.
    decoded = m.decode()
    assert decoded.shape == volume.shape and decoded.dtype == np.float32
    assert np.abs(decoded - volume).max() < 1e-4
    z, y, x = np.meshgrid(*(o + s * np.arange(n) for o, s, n in
                            zip(origin[::-1], spacing[::-1], volume.shape)), indexing="ij")
    grid_points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    assert np.allclose(m.query(grid_points), volume.ravel(), atol=1e-4)
    # Near the one model of the whole grid everywhere (each block's ghost layers).
    whole = mfadvr.encode(volume, spacing=spacing, origin=origin)
    rng = np.random.default_rng(3)
    lo, hi = np.array(info["box"][::2]), np.array(info["box"][1::2])
    points = lo + (hi - lo) * rng.random((500, 3))
    assert np.allclose(m.query(points, derivatives=1)[:, 0], m(points))
    assert np.abs(m(points) - whole(points)).max() < 2e-3

    # Saved as the command line's multi-block file; loaded back the same.
    path = tmp_path / "b.mfa"
    m.save(str(path))
    import json
    assert json.loads(cli("info", "--json", path))["blocks"] == [2, 1, 2]
    back = mfadvr.load(str(path))
    assert back.blocks == (2, 1, 2) and back.report is None
    assert np.array_equal(back(points), m(points))
    # The CLI's encode of the same samples (a raw file) gives the same blocks.
    raw = tmp_path / "v_24x22x20_float32.raw"
    volume.tofile(raw)
    cli("encode", raw, "--spacing", "0.1,0.2,0.3", "--origin",
        "1,-2,0.5", "--blocks", "2,1,2", "--ghost", 3, "-q", "-o", tmp_path / "c.mfa")
    assert np.allclose(mfadvr.load(str(tmp_path / "c.mfa"))(points), m(points), rtol=1e-6,
                       atol=1e-6)

    # Rendered: the pixels of `mfadvr render` of the saved file.
    image = mfadvr.render(m, size=(40, 30), tf="ramp", shade=True)
    cli("render", path, "-o", tmp_path / "b.png", "--size", "40x30", "--tf", "ramp", "--shade",
        "-q")
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtkPNGReader()
    reader.SetFileName(str(tmp_path / "b.png"))
    reader.Update()
    png = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).reshape(30, 40, -1)
    assert image.max() > 40 and np.array_equal(image, png[::-1, :, :3])
    with pytest.raises(ValueError, match="vtkMFAReader"):
        m.to_vtk()


def test_time_varying_models_load_query_in_time_and_give_any_instant(tmp_path):
    path = tmp_path / "blobs.mfa"
    cli("encode", "builtin:orbiting-blobs:12x12x12x5", "-q", "-o", path)
    series = mfadvr.load(str(path))
    assert series.times == [0.0, 0.25, 0.5, 0.75, 1.0]
    assert series.info["time"]["control_count"] == 5
    # x, y, z, t rows: the values and derivatives of `mfadvr query` with four columns.
    points = np.array([[0.5, 0.0, 0.0, 0.1], [0.0, 0.5, 0.2, 0.6], [-0.3, 0.1, 0.0, 1.0]])
    rows = series.query(points, derivatives=1)
    assert rows.shape == (3, 5)
    for p, row in zip(points, rows):
        text = cli("query", path, *p, "-d", "1").splitlines()
        assert text[0] == "x,y,z,t,value,dx,dy,dz,dt"
        expected = [float(v) for v in text[1].split(",")[4:]]
        np.testing.assert_allclose(row, expected, rtol=1e-6, atol=1e-6)
    # One time for every point, and the instant as a 3-D model, agree.
    at = series.query(points[:, :3], times=0.6)
    instant = series.at(0.6)
    assert instant.times is None
    np.testing.assert_allclose(at, instant.query(points[:, :3]), atol=1e-5)
    with pytest.raises(ValueError, match="outside the time range"):
        series.at(2.0)
    with pytest.raises(ValueError, match=r"\(N, 4\)"):
        series.query(points[:, :3])
    with pytest.raises(ValueError, match="model.at"):
        series.query(points, derivatives=2)
    with pytest.raises(ValueError, match="no time axis"):
        instant.query(points[:, :3], times=0.5)
    # Saved again, the same time axis.
    again = tmp_path / "again.mfa"
    series.save(str(again))
    assert mfadvr.load(str(again)).times == series.times


def test_a_four_dimensional_array_encodes_as_the_series_of_its_steps(tmp_path):
    # A blob moving along x, five uint8 steps [t, z, y, x]; the same steps as numbered NRRD files
    # through `mfadvr encode` give the same model.
    z, y, x = np.meshgrid(np.arange(8), np.arange(10), np.arange(12), indexing="ij")
    steps = np.stack([np.rint(220 * np.exp(-((x - 3 - s) ** 2 + (y - 4.5) ** 2 + (z - 3.5) ** 2)
                                           / 8.0)).astype(np.uint8) for s in range(5)])
    times = [0.0, 0.5, 0.75, 1.5, 2.0]
    series = mfadvr.encode(steps, spacing=0.5, times=times, time_degree=2)
    assert series.times == times
    assert series.report["time"]["steps"] == 5
    assert series.report["time"]["degree"] == 2
    assert series.report["max_error"] <= 0.5  # every step rounds back
    for s in range(5):
        header = ("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 12 10 8\nspacings: 0.5 0.5 0.5\n"
                  "encoding: raw\n\n")
        (tmp_path / f"f_{s:03d}.nrrd").write_bytes(header.encode() + steps[s].tobytes())
    path = tmp_path / "cli.mfa"
    cli("encode", tmp_path / "f_%03d.nrrd", "--times", ",".join(map(str, times)),
        "--time-degree", "2", "-q", "-o", path)
    from_cli = mfadvr.load(str(path))
    points = np.array([[1.5, 2.0, 1.5, 0.6], [3.0, 2.5, 2.0, 1.1], [0.5, 1.0, 3.0, 2.0]])
    np.testing.assert_allclose(series.query(points), from_cli.query(points), atol=1e-4)
    np.testing.assert_array_equal(series.at(0.75).decode(), steps[2])
    saved = tmp_path / "saved.mfa"
    series.save(str(saved))
    assert mfadvr.load(str(saved)).times == times
    with pytest.raises(ValueError, match="4 times for the 5 steps"):
        mfadvr.encode(steps, times=times[:4])
    with pytest.raises(ValueError, match="must be finite and increase"):
        mfadvr.encode(steps, times=[0, 1, 3, 2, 4])
    with pytest.raises(ValueError, match="time series"):
        mfadvr.encode(steps, blocks=2)
    with pytest.raises(ValueError, match=r"\[t, z, y, x\]"):
        mfadvr.encode(steps[0], times=[0.0])
    # The options that choose the model from the data apply to the 4-D model, as on the CLI.
    bounded = mfadvr.encode(steps, times=times, max_error=0.02)
    assert bounded.report["adaptive"]["reached"]
    assert bounded.report["max_error"] <= 0.02 * 220
    smooth = mfadvr.encode(steps, times=times, dequantize=True)
    assert smooth.report["encoder"] == "time-series-dequantize"
    for s in range(5):
        np.testing.assert_array_equal(smooth.at(times[s]).decode(), steps[s])
    assert mfadvr.encode(steps, times=times, psnr=40).report["psnr"] >= 40
    with pytest.raises(RuntimeError, match="interpolates in time"):
        mfadvr.encode(steps, times=times, max_error=0.02, time_ctrl=4)
