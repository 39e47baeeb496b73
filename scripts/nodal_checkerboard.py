#!/usr/bin/env python3
"""The roughness of the nodal pressure of a run's last frame: the mean absolute jump of the
point field `pressure` along the mesh's edges, divided by the same mean for the field's values
shuffled over the nodes (white noise on the same graph, 20 shuffles averaged). About 1 for a
checkerboard or noise, well below 1 for a smooth field. The per-tet probe
`pressure-checkerboard` averages each element's nodal pressures first, in which a nodal
checkerboard can cancel; this reads the nodal field itself (docs/francu-2021.md, Fig. 15;
docs/sheen-2021.md, Fig. 7).

    isochor run SCENE --set output.vtu_encoding=ascii --out DIR [--set ...]
    python3 scripts/nodal_checkerboard.py DIR

Pure Python (ASCII VTU only). Only vertices carry a nodal pressure on 4-node tets; the
edges are those of the tets. Not part of `cargo test`.
"""

import random
import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def read_last_frame(folder: Path):
    frames = sorted(folder.glob("frame_*.vtu"))
    if not frames:
        sys.exit(f"{folder}: no frame_*.vtu")
    root = ET.parse(frames[-1]).getroot()
    if any(d.get("format") != "ascii" for d in root.iter("DataArray")):
        sys.exit(f"{frames[-1]}: not ASCII (run with --set output.vtu_encoding=ascii)")
    point = {d.get("Name"): d for d in root.find(".//PointData")}
    if "pressure" not in point:
        sys.exit(f"{frames[-1]}: no nodal `pressure` (a mixed method with nodal pressures)")
    pressure = [float(v) for v in point["pressure"].text.split()]
    cells = {d.get("Name"): d for d in root.find(".//Cells")}
    connectivity = [int(v) for v in cells["connectivity"].text.split()]
    offsets = [int(v) for v in cells["offsets"].text.split()]
    return frames[-1], pressure, connectivity, offsets


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    frame, pressure, connectivity, offsets = read_last_frame(Path(sys.argv[1]))
    edges = set()
    start = 0
    for end in offsets:
        corners = connectivity[start : start + 4]
        for i in range(4):
            for j in range(i + 1, 4):
                a, b = corners[i], corners[j]
                edges.add((min(a, b), max(a, b)))
        start = end
    vertices = sorted({v for e in edges for v in e})

    def mean_jump(field) -> float:
        return sum(abs(field[a] - field[b]) for a, b in edges) / len(edges)

    rough = mean_jump(pressure)
    rng = random.Random(1)
    noise = 0.0
    for _ in range(20):
        values = [pressure[v] for v in vertices]
        rng.shuffle(values)
        shuffled = list(pressure)
        for v, p in zip(vertices, values):
            shuffled[v] = p
        noise += mean_jump(shuffled) / 20
    print(f"{frame}: {len(vertices)} vertices, {len(edges)} edges")
    print(f"mean edge jump {rough:.6g}, shuffled {noise:.6g}, roughness {rough / noise:.4f}")


if __name__ == "__main__":
    main()
