#!/usr/bin/env python3
"""Markdown tables from bench/out/bench.csv (as written by `make bench`), for docs.

usage: python3 tools/bench_tables.py [bench/out/bench.csv]
"""
import csv
import sys
from collections import OrderedDict

path = sys.argv[1] if len(sys.argv) > 1 else "bench/out/bench.csv"
scenes = OrderedDict()
with open(path) as f:
    for row in csv.DictReader(f):
        scenes.setdefault(row["scene"], []).append(row)

for scene, rows in scenes.items():
    print(f"### {scene}\n")
    print("| method | RMSE | SSIM | eff spp | traced % |")
    print("|---|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['method']} | {float(r['rmse']):.5f} | {float(r['ssim']):.4f} | "
              f"{float(r['eff_spp']):.2f} | {float(r['traced_pct']):.2f} |")
    print()

# one summary table: RMSE of every method (rows) per scene (columns)
names = list(scenes)
print("| method | " + " | ".join(names) + " |")
print("|---|" + "---:|" * len(names))
for i, r in enumerate(next(iter(scenes.values()))):
    cells = []
    for s in names:
        cells.append(f"{float(scenes[s][i]['rmse']):.4f}")
    print(f"| {r['method']} | " + " | ".join(cells) + " |")
