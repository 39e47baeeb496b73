#!/usr/bin/env python3
"""Log-log plot of a scale study (the CSV of scripts/scale-study.sh): time per Newton
iteration and peak memory against the tet count, one line per configuration, with the
least-squares growth exponent of each (points from 10,000 tets) in the legend.

    scripts/scale-plot.py scale-study.csv scale-study.png
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402


def slope(points):
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(source, target):
    rows = list(csv.DictReader(open(source)))
    configs = list(dict.fromkeys(r["config"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    panels = [
        ("per_iteration_s", "time per Newton iteration (s)"),
        ("peak_rss_mb", "peak resident memory (MB)"),
    ]
    for ax, (key, label) in zip(axes, panels):
        for config in configs:
            points = [(int(r["tets"]), float(r[key])) for r in rows if r["config"] == config]
            fitted = [p for p in points if p[0] >= 10000]
            name = config
            if len(fitted) >= 2:
                name += f" (~ tets^{slope(fitted):.2f})"
            ax.loglog(*zip(*points), marker="o", label=name)
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("tets")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("Cantilever box, one load step at nu = 0.4999 (direct solver unless the label says)")
    fig.tight_layout()
    fig.savefig(target, dpi=100)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
