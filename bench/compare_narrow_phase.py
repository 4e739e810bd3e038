#!/usr/bin/env python3
"""Compares the narrow-phase experiment of two builds measured in alternating runs.

usage: compare_narrow_phase.py A_RUN_DIR... -- B_RUN_DIR...
Each RUN_DIR holds the bench.json of one `glcollide bench --only narrow_phase` run. Prints, per
scene (in-scene TriTri GPU ms per frame, or GPU ms per batch of a pair family), the median over the
runs of fast and robust for A and for B, and the median over the runs of each run's own
robust / fast ratio (ratios measured within one run are what compare across runs).
"""
import json
import statistics
import sys


def load(run_dir):
    with open(f"{run_dir}/bench.json") as f:
        data = json.load(f)
    times = {}
    for b in data["benchmarks"]:
        if b["experiment"] == "narrow_phase" and b.get("pass", "TriTri") == "TriTri":
            times[(b["scene"], b["config"])] = b["real_time"]
    return times, data["context"]["git_commit"], data["context"]["gl_renderer"]


def summarize(dirs):
    runs = [load(d) for d in dirs]
    scenes = sorted({scene for times, _, _ in runs for scene, _ in times})
    rows = {}
    for s in scenes:
        fast = [t[(s, "fast")] for t, _, _ in runs]
        robust = [t[(s, "robust")] for t, _, _ in runs]
        rows[s] = (statistics.median(fast), statistics.median(robust),
                   statistics.median(r / f for f, r in zip(fast, robust)))
    return rows, runs[0][1], runs[0][2]


def main(argv):
    if "--" not in argv:
        sys.exit(__doc__)
    split = argv.index("--")
    a, commit_a, renderer = summarize(argv[:split])
    b, commit_b, _ = summarize(argv[split + 1:])
    print(f"{renderer}; medians of {split} and {len(argv) - split - 1} alternating runs; GPU ms\n")
    print(f"| scene | fast ({commit_a}) | robust ({commit_a}) | robust / fast | fast ({commit_b}) | "
          f"robust ({commit_b}) | robust / fast |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for s in a:
        fa, ra, qa = a[s]
        fb, rb, qb = b.get(s, (float("nan"),) * 3)
        print(f"| {s} | {fa:.3g} | {ra:.3g} | {qa:.3g} | {fb:.3g} | {rb:.3g} | {qb:.3g} |")


if __name__ == "__main__":
    main(sys.argv[1:])
