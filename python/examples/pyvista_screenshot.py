"""A result in pyvista: the cantilever's last frame as an UnstructuredGrid, coloured by von
Mises stress on the deformed shape over the rest outline, saved as a screenshot off-screen.

    python pyvista_screenshot.py [--res 2] [--out DIR]

Needs the `pyvista` package (pip install pyvista); writes DIR/cantilever-von-mises.png.
"""

import argparse
import pathlib

import pyvista

import isochor


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--res", type=int, default=2)
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("."))
    args = parser.parse_args()
    scene = isochor.Scene.builtin("cantilever").set("res", args.res).set("nu", 0.45)
    result = isochor.run(scene)
    deformed = result.to_pyvista()
    rest = result.to_pyvista(deformed=False)
    print(f"grid: {deformed.n_points} points, {deformed.n_cells} cells, fields {sorted(deformed.array_names)}")
    plotter = pyvista.Plotter(off_screen=True, window_size=(800, 400))
    plotter.add_mesh(rest, style="wireframe", color="gray", opacity=0.3)
    plotter.add_mesh(deformed, scalars="von_mises", cmap="viridis", scalar_bar_args={"title": "von Mises (Pa)"})
    plotter.view_xy()
    args.out.mkdir(parents=True, exist_ok=True)
    png = args.out / "cantilever-von-mises.png"
    plotter.screenshot(str(png))
    plotter.close()
    print(f"screenshot: {png}")


if __name__ == "__main__":
    main()
