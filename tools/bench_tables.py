#!/usr/bin/env python3
"""Markdown tables from bench/out/bench.csv (as written by `make bench`), for docs.

usage: python3 tools/bench_tables.py [bench/out/bench.csv] [--before BEFORE.csv]

Prints one table per scene (RMSE, SSIM, effective spp, independent 1-spp samples,
% of the oracle of the same pipeline, traced %, and where the CSV has them the RMSE over
the dim pixels and the bright pixels' share of the MSE), then two summary tables (effective
spp, and % of the oracle, of every method per scene), then the summary of the defaults
against the best baseline and the oracle. With --before, that summary also shows the
defaults of BEFORE.csv (a run of an earlier version).
"""
import csv
import sys
from collections import OrderedDict

args = [a for a in sys.argv[1:]]
before_path = None
if "--before" in args:
    i = args.index("--before")
    before_path = args[i + 1]
    del args[i:i + 2]
path = args[0] if args else "bench/out/bench.csv"


def load(p):
    scenes = OrderedDict()
    with open(p) as f:
        for row in csv.DictReader(f):
            scenes.setdefault(row["scene"], []).append(row)
    return scenes


def fnum(r, key):
    v = r.get(key)
    return float(v) if v not in (None, "") else float("nan")


scenes = load(path)

for scene, rows in scenes.items():
    print(f"### {scene}\n")
    dim = "rmse_dim" in rows[0]  # (CSVs before session 33 have no split)
    print("| method | RMSE | SSIM | eff spp | indep spp | % oracle | traced % |"
          + (" RMSE dim | bright % of MSE |" if dim else ""))
    print("|---|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if dim else ""))
    for r in rows:
        print(f"| {r['method']} | {fnum(r, 'rmse'):.5f} | {fnum(r, 'ssim'):.4f} | "
              f"{fnum(r, 'eff_spp'):.2f} | {fnum(r, 'indep_spp'):.2f} | "
              f"{fnum(r, 'oracle_pct'):.1f} | {fnum(r, 'traced_pct'):.2f} |"
              + (f" {fnum(r, 'rmse_dim'):.5f} | {fnum(r, 'bright_mse_pct'):.1f} |" if dim else ""))
    print()

names = list(scenes)
for key, title, fmt in (("eff_spp", "Effective spp", "{:.2f}"), ("oracle_pct", "% of the oracle", "{:.1f}")):
    print(f"{title} of every method on every scene:\n")
    print("| method | " + " | ".join(names) + " |")
    print("|---|" + "---:|" * len(names))
    for r in next(iter(scenes.values())):
        cells = []
        for s in names:
            m = [x for x in scenes[s] if x["method"] == r["method"]]
            cells.append(fmt.format(fnum(m[0], key)) if m else "")
        print(f"| {r['method']} | " + " | ".join(cells) + " |")
    print()

# the defaults against the best baseline and the oracle (effective spp)
TEMPORAL_BASELINES = ["const-0.1", "const-0.1+clamp", "const-0.1+varclip", "ema-0.2",
                      "progressive", "progressive+varclip", "paper", "paper-per-channel"]
COMBINED_BASELINES = TEMPORAL_BASELINES + ["paper+stereo-paper", "ema-0.2+stereo-beta-0.5"]
before = load(before_path) if before_path else None


def get(sc, s, m):
    rows = [x for x in sc.get(s, []) if x["method"] == m]
    return fnum(rows[0], "eff_spp") if rows else float("nan")


def best(s, ms):
    vals = [(get(scenes, s, m), m) for m in ms if [x for x in scenes[s] if x["method"] == m]]
    return max(vals) if vals else (float("nan"), "")


for label, default, extra, baselines, oracle in (
        ("temporal", "default", "robust", TEMPORAL_BASELINES, "oracle"),
        ("combined (temporal, then stereo blend)", "default-stereo", "robust+stereo-robust",
         COMBINED_BASELINES, "oracle+stereo-oracle")):
    print(f"Defaults, {label}: effective spp, and as % of the oracle\n")
    head = "| scene | "
    if before:
        head += "default before | "
    head += f"{default} | {extra} | best baseline | oracle |"
    print(head)
    print("|---|" + "---:|" * (head.count("|") - 2))
    for s in names:
        o = get(scenes, s, oracle)
        b, bm = best(s, baselines)
        cells = []
        if before:
            v = get(before, s, default)
            cells.append(f"{v:.2f} ({100 * v / o:.0f} %)" if v == v else "")
        for m in (default, extra):
            v = get(scenes, s, m)
            cells.append(f"{v:.2f} ({100 * v / o:.0f} %)")
        cells.append(f"{b:.2f} ({100 * b / o:.0f} %, {bm})")
        cells.append(f"{o:.2f}")
        print(f"| {s} | " + " | ".join(cells) + " |")
    print()
