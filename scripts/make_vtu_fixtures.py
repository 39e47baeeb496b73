#!/usr/bin/env python3
"""Writes the VTU test fixtures of mesh/tests/data/vtu/ with VTK and meshio.

The source is an ASCII frame written by isochor: the cantilever on 10-node tets after one
step (81 nodes, 24 cells; point data displacement, cell data pressure, J and zone):

    isochor run cantilever --set res=1 --set steps=1 --set element=tet10 \
        --set method=zonal --set vtu_encoding=ascii --out OUT
    python3 scripts/make_vtu_fixtures.py OUT/frame_00001.vtu mesh/tests/data/vtu

VTK (the `vtk` package, which pyvista installs) and meshio then write the same grid in the
binary layouts the mesh crate's reader must accept; mesh/tests/io.rs checks that each reads
back bit for bit equal to the source. Needs `pip install meshio vtk`; the tests do not.
"""

import shutil
import sys
from pathlib import Path

import meshio
import vtk


def vtk_write(grid, path, *, mode, compressed, header64, big_endian=False):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetInputData(grid)
    w.SetFileName(str(path))
    if mode == "appended":
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()  # raw bytes after `_`
    else:
        w.SetDataModeToBinary()  # inline base64
    if compressed:
        w.SetCompressorTypeToZLib()
    else:
        w.SetCompressorTypeToNone()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetByteOrderToBigEndian() if big_endian else w.SetByteOrderToLittleEndian()
    if not w.Write():
        sys.exit(f"VTK could not write {path}")


def main():
    source, out = Path(sys.argv[1]), Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(source, out / "isochor-ascii.vtu")
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(source))
    r.Update()
    grid = r.GetOutput()
    vtk_write(grid, out / "vtk-appended-zlib-uint64.vtu",
              mode="appended", compressed=True, header64=True)
    vtk_write(grid, out / "vtk-appended-raw-uint32-big-endian.vtu",
              mode="appended", compressed=False, header64=False, big_endian=True)
    vtk_write(grid, out / "vtk-inline-zlib-uint32.vtu",
              mode="binary", compressed=True, header64=False)
    mesh = meshio.read(source)
    meshio.write(out / "meshio-inline-zlib-uint32.vtu", mesh, binary=True, compression="zlib")
    meshio.write(out / "meshio-inline-raw-uint64.vtu", mesh, binary=True, compression=None,
                 header_type="UInt64")
    for f in sorted(out.iterdir()):
        print(f"{f.name}: {f.stat().st_size} bytes")


if __name__ == "__main__":
    main()
