#!/usr/bin/env python3
"""Plots one final metric of a drapelab sweep against its first varied key: one line per solver
(and per value of a second varied key, if any), from the sweep folder's sweep.csv.

    drapelab sweep scenes/cusick.yaml --vary cloth.springs.bend.ks=0.5,1,2,4 --out out/bend
    PYTHONPATH=build/python python3 tools/python/examples/plot_sweep.py out/bend \
        --metric drape_coefficient --out out/bend/drape_coefficient.png
"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402 (after choosing the backend)

import drapelab  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep", help="the sweep folder (drapelab sweep --out)")
    parser.add_argument("--metric", default="max_stretch", help="a column of sweep.csv")
    parser.add_argument("--out", help="the image to write (default: SWEEP/METRIC.png)")
    arguments = parser.parse_args()

    sweep = drapelab.read_sweep(arguments.sweep)
    table = sweep.table
    keys = [entry["key"] for entry in sweep.record["varied"]]
    if arguments.metric not in table:
        parser.error(f"sweep.csv has no column {arguments.metric!r}")

    # One line per solver and value of the second key; points of runs that failed are left out.
    lines = {}
    for row in range(len(table["combination"])):
        if table["status"][row] != "ok":
            continue
        label = str(table["solver"][row])
        if len(keys) > 1:
            label += f", {keys[1]} = {table[keys[1]][row]}"
        x, y = table[keys[0]][row], table[arguments.metric][row]
        if not (isinstance(y, float) and math.isnan(y)):
            lines.setdefault(label, []).append((x, y))

    figure, axes = plt.subplots(figsize=(6, 4), dpi=120)
    for label, points in sorted(lines.items()):
        points.sort()
        axes.plot([p[0] for p in points], [p[1] for p in points], marker="o", label=label)
    numeric = table[keys[0]].dtype.kind in "if"
    if numeric and min(table[keys[0]]) > 0 and max(table[keys[0]]) / min(table[keys[0]]) >= 10:
        axes.set_xscale("log")  # stiffness sweeps span decades
    axes.set_xlabel(keys[0])
    axes.set_ylabel(arguments.metric)
    axes.set_title(f"{sweep.record['scene']}: final {arguments.metric}")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="small")
    figure.tight_layout()
    out = arguments.out or f"{arguments.sweep}/{arguments.metric}.png"
    figure.savefig(out)
    print(out)


if __name__ == "__main__":
    main()
