#!/usr/bin/python3
"""Conformance sweep: runs `mfadvr encode` over every volume, mesh and point file of a local
copy of VTK's example data (the public pyvista/vtk-data repository, or VTK's own ExternalData)
and compares the outcome with what VTK 9.1's Python readers read from the same file.

    scripts/vtk-data-sweep.py PATH_TO_VTK_DATA [--mfadvr build/release/src/app/mfadvr]
                              [--csv out/sweep.csv] [--jobs 2] [--timeout 300]

Not a unit test: the data is not in this repository. Needs python3-vtk9 (Debian), which
scripts/install-deps.sh installs. Run it with /usr/bin/python3 when another python3 comes first
on the PATH.

What it does for each file with an extension of a VTK data-set format (.vti .vtk .vtu .vtp
.vts .vtr .mha .mhd .nrrd .nhdr .nii .nii.gz):
  1. reads it with VTK's reader in a child process (a reader that crashes takes only the
     child) and notes the data set type, points, cells, extent and arrays;
  2. decides from that what VTK holds: a 3-D scalar field ("field"), only multi-component
     arrays ("vector": encodes with --component magnitude), or a reason there is nothing to
     encode (the short list below);
  3. runs `mfadvr encode FILE` (defaults; with --component magnitude for "vector" files) and
     files its refusal under the same list of reasons, from the message it printed.

A file is conformant when both sides agree: VTK holds a field and mfadvr encodes it, or VTK
holds none and mfadvr refuses it with a reason of the list (the table shows both sides'
reasons). Anything else is printed as a
mismatch, and the exit status is 1 when there is one.

Reasons (in docs/input-formats.md):
  empty          the file holds no bytes
  unreadable     VTK's own reader fails on the file too
  no field       no numeric point-data or cell-data array
  2-D data       an image, grid or point set without extent along an axis
  not a data set composite data (multi-block), tables, graphs, hyper-tree grids
  non-finite     the field holds NaN or infinite values
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import subprocess
import sys

EXTENSIONS = (".vti", ".vtk", ".vtu", ".vtp", ".vts", ".vtr", ".mha", ".mhd", ".nrrd",
              ".nhdr", ".nii", ".nii.gz")

# Runs in a child process: prints a JSON summary of what VTK reads from argv[1].
PROBE = r'''
import json, sys
# The plain readers: importing the whole `vtk` package would also load the MPI readers that
# override them (vtkPNrrdReader fails without an MPI controller).
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkIOImage import vtkMetaImageReader, vtkNIFTIImageReader, vtkNrrdReader
from vtkmodules.vtkIOLegacy import vtkGenericDataObjectReader
from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader
import vtkmodules.vtkCommonDataModel  # noqa: F401  (the data set types)
path = sys.argv[1]
low = path.lower()
out = {"ok": False}
if low.endswith((".mha", ".mhd")):
    reader = vtkMetaImageReader()
elif low.endswith((".nrrd", ".nhdr")):
    reader = vtkNrrdReader()
elif low.endswith((".nii", ".nii.gz")):
    reader = vtkNIFTIImageReader()
elif low.endswith(".vtk"):
    reader = vtkGenericDataObjectReader()
    reader.ReadAllScalarsOn(); reader.ReadAllVectorsOn(); reader.ReadAllFieldsOn()
    reader.ReadAllTensorsOn(); reader.ReadAllColorScalarsOn(); reader.ReadAllNormalsOn()
else:
    reader = vtkXMLGenericDataObjectReader()
errors = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(errors)
reader.SetFileName(path)
reader.Update()
data = reader.GetOutputDataObject(0)
text = errors.GetOutput() or ""
out["errors"] = text[:300]
failed = "ERROR" in text or reader.GetErrorCode() != 0
out["type"] = data.GetClassName() if data is not None and not failed else None
if data is not None and not failed and data.IsA("vtkDataSet"):
    out["ok"] = True
    out["points"] = data.GetNumberOfPoints()
    out["cells"] = data.GetNumberOfCells()
    out["bounds"] = list(data.GetBounds()) if data.GetNumberOfPoints() else None
    if data.IsA("vtkImageData"):
        out["dims"] = list(data.GetDimensions())
    arrays = []
    for assoc, attrs in (("point", data.GetPointData()), ("cell", data.GetCellData())):
        for i in range(attrs.GetNumberOfArrays()):
            a = attrs.GetArray(i)
            if a is None or a.GetDataTypeAsString() == "bit":
                continue  # strings and other non-numeric arrays
            arrays.append({"assoc": assoc, "name": a.GetName() or "",
                           "components": a.GetNumberOfComponents(),
                           "tuples": a.GetNumberOfTuples()})
    out["arrays"] = arrays
print(json.dumps(out))
'''

REASONS = [
    ("empty", [r"the file is empty"]),
    ("no field", [r"no point-data or cell-data arrays", r"no numeric array",
                  r"no one-component numeric array", r"holds no samples", r"holds no points",
                  r"has no points"]),
    ("2-D data", [r"2-D data", r"span no extent"]),
    ("not a data set", [r"not a data set", r"composite", r"multi-block",
                        r"is not supported for scattered input", r"vtkTable", r"vtkGraph",
                        r"HyperTree"]),
    ("non-finite", [r"NaN and Inf", r"must be finite", r"NaN or infinite"]),
    ("unreadable", [r"cannot read "]),
]


def reason_of(message):
    for reason, patterns in REASONS:
        if any(re.search(p, message) for p in patterns):
            return reason
    return "other"


def vtk_view(path, timeout):
    try:
        run = subprocess.run([sys.executable, "-c", PROBE, path], capture_output=True,
                             text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"ok": False, "type": None, "crash": "timeout"}
    lines = [l for l in run.stdout.splitlines() if l.startswith("{")]
    if run.returncode != 0 or not lines:
        return {"ok": False, "type": None, "crash": f"exit {run.returncode}"}
    return json.loads(lines[-1])


def vtk_expectation(path, view):
    """'field', 'vector', or a reason from REASONS."""
    if os.path.getsize(path) == 0:
        return "empty"
    if view.get("type") is None:
        return "unreadable"
    if not view.get("ok"):
        return "not a data set"
    if view["points"] == 0:
        return "no field"
    image = view.get("dims")
    if image and min(image) < 2:
        return "2-D data"
    arrays = view["arrays"]
    if not arrays:
        return "no field"
    if image:
        point_flat = min(image) < 2
        cell_flat = min(max(d - 1, 1) for d in image) < 2
        usable = [a for a in arrays if (a["assoc"] == "point" and not point_flat) or
                  (a["assoc"] == "cell" and not cell_flat)]
        if not usable:
            return "2-D data"
    else:
        b = view["bounds"]
        if any(b[2 * i + 1] <= b[2 * i] for i in range(3)):
            return "2-D data"
        usable = arrays
    if any(a["components"] == 1 for a in usable):
        return "field"
    return "vector"


def mfadvr_run(binary, path, extra, timeout):
    cmd = [binary, "encode", path, "-q"] + extra
    try:
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, "timeout"
    message = (run.stderr.strip().splitlines() or [""])[-1]
    return run.returncode == 0, message


def sweep_one(args, path):
    view = vtk_view(path, args.timeout)
    expected = vtk_expectation(path, view)
    extra = ["--component", "magnitude"] if expected == "vector" else []
    ok, message = mfadvr_run(args.mfadvr, path, extra, args.timeout)
    got = "encodes" if ok else reason_of(message)
    if expected in ("field", "vector"):
        agree = ok
    else:
        # Refused with a reason of the list; the probe's guess at why VTK holds no field can
        # differ from mfadvr's more specific reason (a field-only legacy file, which VTK's
        # data-set readers cannot read, is 'not a data set' to mfadvr).
        agree = not ok and got != "other"
    return {"file": os.path.relpath(path, args.data), "vtk_type": view.get("type") or "",
            "vtk": expected, "mfadvr": got, "agree": agree,
            "message": "" if ok else message}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("data", help="a local copy of VTK's example data (e.g. pyvista/vtk-data)")
    parser.add_argument("--mfadvr", default="build/release/src/app/mfadvr")
    parser.add_argument("--csv", default="", help="write one row per file here")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=int, default=300, help="seconds per file and step")
    args = parser.parse_args()
    if not os.access(args.mfadvr, os.X_OK):
        sys.exit(f"{args.mfadvr}: not an executable (build first, or pass --mfadvr)")
    files = []
    for root, _, names in os.walk(args.data):
        if "/.git" in root:
            continue
        files += [os.path.join(root, n) for n in names if n.lower().endswith(EXTENSIONS)]
    files.sort()
    print(f"{len(files)} files of data-set formats under {args.data}", flush=True)
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for n, row in enumerate(pool.map(lambda p: sweep_one(args, p), files), 1):
            rows.append(row)
            if not row["agree"]:
                print(f"MISMATCH {row['file']}: VTK {row['vtk']} ({row['vtk_type']}), "
                      f"mfadvr {row['mfadvr']}: {row['message']}", flush=True)
            if n % 50 == 0:
                print(f"  {n} / {len(files)}", flush=True)
    if args.csv:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else ["file"])
            w.writeheader()
            w.writerows(rows)
    counts = {}
    for r in rows:
        key = (r["vtk"], r["mfadvr"])
        counts[key] = counts.get(key, 0) + 1
    print("\n| VTK 9.1 reads | mfadvr encode | files |\n|---|---|---|")
    for (vtk_side, ours), c in sorted(counts.items(), key=lambda kv: -kv[1]):
        print(f"| {vtk_side} | {ours} | {c} |")
    bad = sum(1 for r in rows if not r["agree"])
    print(f"\n{len(rows)} files, {len(rows) - bad} agree, {bad} mismatches")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
