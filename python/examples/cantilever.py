"""The locking study from Python: the cantilever bending under gravity, swept over Poisson's
ratio for three methods. The standard neo-Hookean element locks (its deflection vanishes as
nu -> 0.5); the mixed and zonal methods do not (Francu et al. 2021, Table 2).

    python cantilever.py [--res 2] [--element tet4] [--out DIR]

Prints the tip deflection per (method, nu) and, with matplotlib installed, plots the locking
curve into DIR/cantilever-locking.png.
"""

import argparse
import pathlib

import isochor

METHODS = ["standard", "mixed-p1", "zonal"]
NUS = [0.49, 0.499, 0.4999, 0.49999]


def sweep(res: int, element: str) -> dict[str, list[float]]:
    """Tip deflection (m) per method, one per value of NUS."""
    base = isochor.Scene.builtin("cantilever").set("res", res).set("element", element)
    table = {}
    for method in METHODS:
        table[method] = []
        for nu in NUS:
            result = isochor.run(base.set("method", method).set("nu", nu), frames=False)
            if not result.converged:
                raise SystemExit(f"{method} at nu = {nu}: {result.error}")
            table[method].append(result.probes["tip_deflection"])
    return table


def plot(table: dict[str, list[float]], path: pathlib.Path) -> bool:
    """The locking curve: deflection against 0.5 - nu; False without matplotlib."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    fig, ax = plt.subplots(figsize=(6, 4))
    for method, deflections in table.items():
        ax.plot([0.5 - nu for nu in NUS], [1e3 * d for d in deflections], "o-", label=method)
    ax.set_xscale("log")
    ax.invert_xaxis()
    ax.set_xlabel("0.5 - nu")
    ax.set_ylabel("tip deflection (mm)")
    ax.set_title("cantilever under gravity: locking")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    return True


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--res", type=int, default=2)
    parser.add_argument("--element", default="tet4", choices=["tet4", "tet10"])
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("."))
    args = parser.parse_args()
    table = sweep(args.res, args.element)
    print(f"tip deflection (mm), cantilever res {args.res}, {args.element}")
    print(f"{'nu':>8} " + " ".join(f"{m:>10}" for m in METHODS))
    for i, nu in enumerate(NUS):
        print(f"{nu:>8} " + " ".join(f"{1e3 * table[m][i]:>10.4f}" for m in METHODS))
    args.out.mkdir(parents=True, exist_ok=True)
    png = args.out / "cantilever-locking.png"
    if plot(table, png):
        print(f"plot: {png}")
    else:
        print("plot: skipped (matplotlib is not installed)")


if __name__ == "__main__":
    main()
