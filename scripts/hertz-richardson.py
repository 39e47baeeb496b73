#!/usr/bin/env python3
"""Tables of the Hertz study from the logs of scripts/hertz-levels.sh (one log per level).

Per level: tets, Newton iterations, wall time, peak memory, fitted exponent and the error
F / F_Hertz - 1 per frame. Over the last three levels, per frame: the observed order p of
the error in the cell size h = 1 / res (e_h = e + K h^p, solved exactly through the three
levels) and the Richardson limit e. Then the finite-sphere compliance C of
`delta = delta_Hertz(F) - C F / (E R)` (validation/tests/hertz.rs, `Sample::compliance`):
per frame from the limit, and one C fitted by least squares over the frames, with the
limit's error against Hertz once that C is accounted for (frames of order 1 and more).
"""

import math
import re
import sys

# The sphere of validation/tests/hertz.rs.
RADIUS, YOUNG, NU = 0.01, 1e5, 0.4999
E_STAR = YOUNG / (1.0 - NU * NU)

HEADER = re.compile(
    r"^hertz \S+ (\S+) (\S+) res (\d+) .*\((\d+) tets per body\): ([\d.]+) s, (\d+) Newton iterations, exponent ([\d.]+)"
)
FRAME = re.compile(r"approach/R ([\d.]+) .* F (\S+) N .* ([+-][\d.]+)%\s+gap/dhat ([\d.]+)\s+rings (\d+)\s+C (\S+)")
WALL = re.compile(r"Elapsed \(wall clock\) time .*: (\S+)")
RSS = re.compile(r"Maximum resident set size \(kbytes\): (\d+)")
LOAD = re.compile(r"load average (\S+) (\S+) (\S+) at (start|end)")


def hertz_force(delta):
    return 4.0 / 3.0 * E_STAR * math.sqrt(RADIUS) * delta**1.5


def hertz_approach(force):
    return (0.75 * force / (E_STAR * math.sqrt(RADIUS))) ** (2.0 / 3.0)


def seconds(clock):
    parts = [float(p) for p in clock.split(":")]
    return sum(p * 60.0**k for k, p in enumerate(reversed(parts)))


def read(path):
    level = {"frames": [], "loads": {}}
    for line in open(path):
        if m := HEADER.search(line):
            level.update(element=m[1], method=m[2], res=int(m[3]), tets=int(m[4]),
                         solve_s=float(m[5]), newton=int(m[6]), exponent=float(m[7]))
        elif m := FRAME.search(line):
            level["frames"].append({"approach": float(m[1]) * RADIUS, "force": float(m[2]),
                                    "error": float(m[3]) / 100.0, "rings": int(m[5]),
                                    "c": float(m[6])})
        elif m := WALL.search(line):
            level["wall_s"] = seconds(m[1])
        elif m := RSS.search(line):
            level["rss_mb"] = int(m[1]) / 1024.0
        elif m := LOAD.search(line):
            level["loads"][m[4]] = m[1]
    if "res" not in level:
        sys.exit(f"{path}: no study line (the run failed or is still going)")
    return level


def order(h, e):
    """The p and limit of e_i = e + K h_i^p through three levels, or None."""
    (h1, h2, h3), (e1, e2, e3) = h, e
    if (e1 - e2) * (e2 - e3) <= 0.0:
        return None  # not monotone: no asymptotic range
    ratio = (e1 - e2) / (e2 - e3)
    g = lambda p: (h1**p - h2**p) / (h2**p - h3**p) - ratio
    lo, hi = 0.05, 8.0
    if g(lo) * g(hi) > 0.0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(lo) * g(mid) > 0.0 else (lo, mid)
    p = 0.5 * (lo + hi)
    return p, e3 - (e2 - e3) * h3**p / (h2**p - h3**p)


def compliance(delta, force):
    """C = (delta_Hertz(F) - delta) E R / F."""
    return (hertz_approach(force) - delta) * YOUNG * RADIUS / force


def pct(x):
    return f"{100.0 * x:+.1f}%"


def main(paths):
    levels = [read(p) for p in paths]
    frames = len(levels[0]["frames"])
    names = [f"{levels[0]['frames'][k]['approach'] / RADIUS:.2f}" for k in range(frames)]
    print(f"{levels[0]['element']} {levels[0]['method']}: F / F_Hertz - 1 at delta / R")
    print("| res | tets | " + " | ".join(names) + " | rings | Newton | exponent | wall | peak memory | load (start / end) |")
    print("|---" * (frames + 8) + "|")
    for lv in levels:
        errs = " | ".join(pct(f["error"]) for f in lv["frames"])
        rings = "/".join(str(f["rings"]) for f in lv["frames"])
        print(f"| {lv['res']} | {lv['tets']:,} | {errs} | {rings} | {lv['newton']} | {lv['exponent']:.3f} "
              f"| {lv.get('wall_s', float('nan')):.0f} s | {lv.get('rss_mb', float('nan')):,.0f} MB "
              f"| {lv['loads'].get('start', '?')} / {lv['loads'].get('end', '?')} |")
    for lv in levels:
        cs = " ".join(f"{f['c']:+.3f}" for f in lv["frames"])
        print(f"C per frame at res {lv['res']}: {cs}")
    if len(levels) < 3:
        return
    last = levels[-3:]
    h = [1.0 / lv["res"] for lv in last]
    print(f"\nRichardson over res {', '.join(str(lv['res']) for lv in last)} (h = 1 / res):")
    print("| delta / R | " + " | ".join(names) + " |")
    print("|---" * (frames + 1) + "|")
    fits = [order(h, [lv["frames"][k]["error"] for lv in last]) for k in range(frames)]
    print("| observed order | " + " | ".join("-" if f is None else f"{f[0]:.2f}" for f in fits) + " |")
    print("| limit of the error | " + " | ".join("-" if f is None else pct(f[1]) for f in fits) + " |")
    # A frame whose three levels give an order below 1 is not in the asymptotic range (the
    # other frames give 1.9-2.4): its limit is shown but takes no part in C.
    limits = []
    for k, f in enumerate(fits):
        if f is None or f[0] < 1.0:
            continue
        delta = last[-1]["frames"][k]["approach"]
        limits.append((k, delta, hertz_force(delta) * (1.0 + f[1])))
    print("| C from the limit | " + " | ".join(
        next((f"{compliance(d, F):+.3f}" for j, d, F in limits if j == k), "-") for k in range(frames)) + " |")
    if not limits:
        return
    # One C for all frames: least squares of delta_Hertz(F) - delta against F / (E R).
    xs = [F / (YOUNG * RADIUS) for _, _, F in limits]
    ys = [hertz_approach(F) - d for _, d, F in limits]
    c = sum(x * y for x, y in zip(xs, ys)) / sum(x * x for x in xs)
    corrected = {k: F / hertz_force(d + c * F / (YOUNG * RADIUS)) - 1.0 for k, d, F in limits}
    print(f"| limit, C = {c:.3f} accounted for | " + " | ".join(
        pct(corrected[k]) if k in corrected else "-" for k in range(frames)) + " |")
    print(f"\nfitted C = {c:.4f} over the frames of order 1 and more")


if __name__ == "__main__":
    main(sys.argv[1:])
