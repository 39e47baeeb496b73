"""A soft bending actuator made with Gmsh's Python API and run by isochor, end to end: a
silicone bar with a closed chamber under its top, clamped at one end, bends down when the
chamber is pressurized (its top wall stretches more than the thick base).

    python gmsh_actuator.py [--size 2.5e-3] [--pressure 20e3] [--out DIR]

Needs the `gmsh` package (pip install gmsh). Writes DIR/actuator.msh; prints the mesh, each
step and the tip's deflection.
"""

import argparse
import pathlib

import gmsh

import isochor

# The bar (m): 40 mm long (x), 10 wide (y), 10 high (z); the chamber 30 x 6 x 4 mm, 1.5 mm
# under the top.
LENGTH, WIDTH, HEIGHT = 0.04, 0.01, 0.01
CHAMBER = (0.003, 0.002, 0.0045, 0.03, 0.006, 0.004)  # x, y, z of a corner, then its size
TOL = 1e-6  # Gmsh pads bounding boxes by 1e-7


def mesh(path: pathlib.Path, size: float) -> None:
    """Meshes the bar with its chamber into `path` (Gmsh 4.1), with the physical groups
    `clamped` (the face x = 0), `chamber` (the cavity's walls) and `bar` (the volume)."""
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("actuator")
        occ = gmsh.model.occ
        bar = occ.addBox(0, 0, 0, LENGTH, WIDTH, HEIGHT)
        cavity = occ.addBox(*CHAMBER)
        [(_, solid)], _ = occ.cut([(3, bar)], [(3, cavity)])
        occ.synchronize()
        clamped, chamber = [], []
        for _, face in gmsh.model.getBoundary([(3, solid)], oriented=False):
            x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, face)
            if x1 < TOL:
                clamped.append(face)
            elif x0 > CHAMBER[0] - TOL and x1 < CHAMBER[0] + CHAMBER[3] + TOL and z0 > CHAMBER[2] - TOL:
                if y0 > CHAMBER[1] - TOL and y1 < CHAMBER[1] + CHAMBER[4] + TOL:
                    chamber.append(face)
        gmsh.model.addPhysicalGroup(2, clamped, name="clamped")
        gmsh.model.addPhysicalGroup(2, chamber, name="chamber")
        gmsh.model.addPhysicalGroup(3, [solid], name="bar")
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


def scene(path: pathlib.Path, pressure: float) -> isochor.Scene:
    """The actuator's scene: Ecoflex-like silicone, the chamber's pressure ramped in four
    steps."""
    return isochor.Scene.from_dict(
        {
            "name": "gmsh-actuator",
            "method": "mixed-p1",
            "mesh": {"generator": "file", "path": str(path)},
            "material": {"young": 100e3, "nu": 0.4999, "rho": 1070.0},
            "selections": {
                "clamped": {"physical": "clamped"},
                "chamber": {"physical": "chamber"},
            },
            "dirichlet": [{"selection": "clamped"}],
            "loads": {"pressure": [{"selection": "chamber", "pressure": pressure}]},
            "stepping": {"mode": "quasi-static", "steps": 4},
            "probes": {
                "tip_deflection": {
                    "kind": "displacement",
                    "point": [LENGTH, WIDTH / 2, HEIGHT / 2],
                    "component": "z",
                    "scale": -1.0,
                },
            },
        }
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=float, default=2.5e-3, help="largest element size (m)")
    parser.add_argument("--pressure", type=float, default=20e3, help="chamber pressure (Pa)")
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("."))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "actuator.msh"
    mesh(path, args.size)
    mesh_read = isochor.read_mesh(path)
    print(f"mesh: {mesh_read.num_nodes} nodes, {mesh_read.num_elements} tets, groups {sorted(mesh_read.groups)}")
    result = isochor.run(scene(path, args.pressure), progress=lambda step, t, _: print(f"step {step}: t = {t:.2f}"))
    if not result.converged:
        raise SystemExit(f"the run failed: {result.error}")
    print(f"tip deflection: {1e3 * result.probes['tip_deflection']:.3f} mm")


if __name__ == "__main__":
    main()
