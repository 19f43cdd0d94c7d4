#!/usr/bin/python3
"""The axis path of a cylinder run (docs/three-d.md): tilt_x against tilt_y (the top view of the
cylinder's axis) of the reference and every engine in a `rockbench run` folder, with the critical
angle atan(D / H) as a circle, and tilt_x, tilt_y against time below it.

Usage: scripts/cylinder_figure.py RUN_DIR OUT.png [--title TEXT] [--alpha RAD] [--until S]
Needs numpy and matplotlib (scripts/install-deps.sh installs Debian's)."""
import argparse
import csv
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    columns = {name: i for i, name in enumerate(header)}
    for name in ("t", "tilt_x1", "tilt_y1"):
        if name not in columns:
            raise SystemExit(f"{path}: no column {name}: not a cylinder's history")
    data = np.array([[float(r[columns[n]]) for n in ("t", "tilt_x1", "tilt_y1")] for r in rows[1:]])
    return data[:, 0], data[:, 1], data[:, 2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir", type=pathlib.Path)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--title", default="")
    parser.add_argument("--alpha", type=float, default=None, help="critical angle, rad")
    parser.add_argument("--until", type=float, default=None, help="last time drawn, s")
    args = parser.parse_args()
    runs = sorted(p.parent.name for p in args.run_dir.glob("*/history.csv"))
    if "reference" in runs:
        runs.remove("reference")
        runs.insert(0, "reference")
    if not runs:
        raise SystemExit(f"{args.run_dir}: no <engine>/history.csv")
    fig = plt.figure(figsize=(9, 4.2))
    path_ax = fig.add_subplot(1, 2, 1)
    time_ax = fig.add_subplot(2, 2, 2)
    time_ay = fig.add_subplot(2, 2, 4, sharex=time_ax)
    for name in runs:
        t, x, y = read_history(args.run_dir / name / "history.csv")
        if args.until is not None:
            keep = t <= args.until
            t, x, y = t[keep], x[keep], y[keep]
        style = dict(lw=1.6, color="black") if name == "reference" else dict(lw=0.9)
        path_ax.plot(x, y, label=name, **style)
        time_ax.plot(t, x, **style)
        time_ay.plot(t, y, **style)
    if args.alpha:
        a = np.linspace(0, 2 * np.pi, 200)
        path_ax.plot(args.alpha * np.cos(a), args.alpha * np.sin(a), ":", color="grey", lw=0.8,
                     label="critical angle")
    path_ax.set_aspect("equal", adjustable="datalim")
    path_ax.set_xlabel("tilt_x (rad, +x)")
    path_ax.set_ylabel("tilt_y (rad, +y)")
    path_ax.set_title("axis path (top view)")
    path_ax.legend(fontsize=7, loc="upper right")
    time_ax.set_ylabel("tilt_x (rad)")
    time_ay.set_ylabel("tilt_y (rad)")
    time_ay.set_xlabel("t (s)")
    if args.title:
        fig.suptitle(args.title, fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
