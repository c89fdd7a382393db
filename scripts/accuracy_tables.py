#!/usr/bin/python3
"""Markdown tables for ACCURACY.md from `bezinv stress --json` output (one JSON object).

    /usr/bin/python3 scripts/accuracy_tables.py stress.json

Per family: rows, wrong statuses, ambiguous rows, and the largest |t - t_true| and |t - t_true| /
bound over its cells, for bezinv's default path and for each baseline in the file; then the same
ratio by degree band for the families on and near the curve.
"""
import json
import math
import sys


def worst(cells, field, key):
    values = [c[field][key] for c in cells if c[field][key] is not None]
    return max(values) if values else math.nan


def fmt(x):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.2g}"


def main(path):
    report = json.load(open(path))
    cells = report["cells"]
    families = list(dict.fromkeys(c["family"] for c in cells))
    sources = list(dict.fromkeys(c["path"] for c in cells))
    baselines = [s for s in sources if s not in ("default", "svd-only", "no-refine")]

    head = "| family | rows | wrong status | ambiguous | bezinv max \\|dt\\| | bezinv max \\|dt\\|/bound |"
    rule = "|---|---|---|---|---|---|"
    for b in baselines:
        head += f" {b} rows | {b} no answer | {b} max \\|dt\\| | {b} max \\|dt\\|/bound |"
        rule += "---|---|---|---|"
    print(head)
    print(rule)
    for f in families:
        mine = [c for c in cells if c["family"] == f and c["path"] == "default"]
        line = (f"| {f} | {sum(c['rows'] for c in mine)} | {sum(c['wrong_status'] for c in mine)} | "
                f"{sum(c['ambiguous'] for c in mine)} | {fmt(worst(mine, 'abs_dt', 'max'))} | "
                f"{fmt(worst(mine, 'abs_dt_over_bound', 'max'))} |")
        for b in baselines:
            theirs = [c for c in cells if c["family"] == f and c["path"] == b]
            line += (f" {sum(c['rows'] for c in theirs)} | {sum(c['nan_t'] for c in theirs)} | "
                     f"{fmt(worst(theirs, 'abs_dt', 'max'))} | {fmt(worst(theirs, 'abs_dt_over_bound', 'max'))} |")
        print(line)

    print()
    bands = [(1, 4), (5, 8), (9, 12), (13, 16), (17, 20), (21, 24), (25, 32)]
    degrees = {c["degree"] for c in cells}
    bands = [(lo, hi) for lo, hi in bands if any(lo <= d <= hi for d in degrees)]
    print("| family | source | " + " | ".join(f"degree {lo}-{hi}" for lo, hi in bands) + " |")
    print("|---|---|" + "---|" * len(bands))
    for f in ("on_curve", "near_ends", "noisy", "far"):
        if f not in families:
            continue
        for s in ["default"] + baselines:
            row = [c for c in cells if c["family"] == f and c["path"] == s]
            ratios = [fmt(worst([c for c in row if lo <= c["degree"] <= hi], "abs_dt_over_bound", "p999"))
                      for lo, hi in bands]
            print(f"| {f} | {'bezinv' if s == 'default' else s} | " + " | ".join(ratios) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
