#!/usr/bin/env python3
"""Checks the VTU frames of an `isochor run --out DIR` folder with meshio (and pyvista, if
installed): the frame.pvd lists every frame_*.vtu and nothing else, every frame reads with the
point and cell counts of summary.json (`nodes`, `tets`) and carries a displacement array, and
the frames' points are the rest positions of the first frame (the default `output.points =
"rest"`: warp them by `displacement`) or, with `output.points = "deformed"`, those rest
positions plus `displacement`.
Given a second folder of the same scene (e.g. one written with --set vtu_encoding=binary and
one with vtu_encoding=ascii), it also checks that the two runs' displacements agree frame by
frame.

    pip install meshio            # pyvista optional
    python3 scripts/check_vtu.py OUT_BINARY [OUT_ASCII]

Exits with status 1 on the first folder that fails a check. Not part of `cargo test`.
"""

import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np

try:
    import pyvista
except ImportError:
    pyvista = None

# Displacements of two runs agree to this fraction of the largest displacement (the two runs
# solve the same problem; parallel sums may round differently).
RELATIVE_TOLERANCE = 1e-9


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def encoding(path):
    head = path.read_bytes()[:4096]
    return "binary" if b'format="appended"' in head or b'format="binary"' in head else "ascii"


def check_folder(folder):
    """The displacement of every frame, by file name, after checking the folder."""
    summary = json.loads((folder / "summary.json").read_text())
    nodes, tets = summary["nodes"], summary["tets"]
    pvd = folder / "frame.pvd"
    if not pvd.is_file():
        fail(f"{pvd} is missing")
    listed = [d.get("file") for d in ET.parse(pvd).getroot().iter("DataSet")]
    on_disk = sorted(p.name for p in folder.glob("*.vtu"))
    if sorted(listed) != on_disk:
        fail(f"{pvd} lists {listed}, the folder has {on_disk}")
    displacements = {}
    rest = None
    for name in listed:
        path = folder / name
        mesh = meshio.read(path)
        cells = sum(len(block.data) for block in mesh.cells)
        kinds = sorted({block.type for block in mesh.cells})
        if (len(mesh.points), cells) != (nodes, tets):
            fail(f"{path}: meshio reads {len(mesh.points)} points and {cells} cells, "
                 f"summary.json has {nodes} nodes and {tets} tets")
        if "displacement" not in mesh.point_data:
            fail(f"{path}: no displacement point data (has {list(mesh.point_data)})")
        displacements[name] = np.asarray(mesh.point_data["displacement"])
        if rest is None:
            rest = np.asarray(mesh.points)
        at_rest = np.array_equal(mesh.points, rest)
        deformed = np.allclose(mesh.points, rest + displacements[name], rtol=0, atol=1e-12
                               * max(1.0, float(np.abs(rest).max())))
        if not (at_rest or deformed):
            fail(f"{path}: the points are neither the rest positions nor the rest positions "
                 "plus the displacement")
        if pyvista is not None:
            grid = pyvista.read(path)
            if (grid.n_points, grid.n_cells) != (nodes, tets):
                fail(f"{path}: pyvista reads {grid.n_points} points and {grid.n_cells} cells")
            if not np.array_equal(grid.point_data["displacement"], displacements[name]):
                fail(f"{path}: pyvista and meshio read different displacements")
    if pyvista is not None:
        reader = pyvista.get_reader(str(pvd))
        if len(reader.time_values) != len(listed):
            fail(f"{pvd}: pyvista finds {len(reader.time_values)} time steps, "
                 f"expected {len(listed)}")
    first = folder / listed[0]
    size = sum((folder / n).stat().st_size for n in listed) / len(listed)
    print(f"{folder}: {len(listed)} frames ({encoding(first)}, {'/'.join(kinds)}), "
          f"{nodes} points and {tets} cells each, {size / 1e3:,.1f} kB per frame; "
          f"meshio{' and pyvista' if pyvista else ''} read them all")
    return displacements


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    folders = [Path(a) for a in sys.argv[1:]]
    if pyvista is None:
        print("pyvista is not installed: checking with meshio only")
    runs = [check_folder(f) for f in folders]
    if len(runs) == 2:
        a, b = runs
        if sorted(a) != sorted(b):
            fail(f"the folders hold different frames: {sorted(a)} and {sorted(b)}")
        worst = 0.0
        for name in a:
            scale = max(np.abs(a[name]).max(), np.abs(b[name]).max(), 1e-300)
            worst = max(worst, np.abs(a[name] - b[name]).max() / scale)
        exact = all(np.array_equal(a[n], b[n]) for n in a)
        if worst > RELATIVE_TOLERANCE:
            fail(f"displacements differ by {worst:.3e} of the largest displacement")
        print(f"displacements of the {len(a)} frames agree: "
              + ("bit for bit" if exact else f"to {worst:.3e} of the largest displacement"))
    print("OK")


if __name__ == "__main__":
    main()
