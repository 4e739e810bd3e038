#!/usr/bin/env python3
"""Markdown table and linearity figures from a glcollide_bench_dynamics JSON file.

Usage: bench/dynamics_table.py bench/results/llvmpipe-dynamics.json
Uses the *_median aggregate rows when the run had repetitions, else the single rows.
Prints the table that goes between the bench-table markers of bench/README.md, then the
per-spring cost of each size and its ratio to the previous size.
"""
import json
import sys


def rows(doc):
    runs = [b for b in doc["benchmarks"] if not b.get("error_occurred")]
    medians = [b for b in runs if b.get("aggregate_name") == "median"]
    return medians if medians else [b for b in runs if b.get("run_type") == "iteration"]


def main(path):
    with open(path) as f:
        doc = json.load(f)
    ctx = doc["context"]
    runs = rows(doc)
    kind = "median of %d repetitions" % runs[0]["repetitions"] if runs and runs[0].get("aggregate_name") else "single run"
    print("Device: %s (%s), %s; EGL: %s; commit %s; %s; %s." % (
        ctx.get("gl_renderer"), ctx.get("gl_version"), ctx.get("cpu_model"),
        ctx.get("egl_device"), ctx.get("git_commit"), ctx.get("date_utc"), kind))
    print()
    print("| cloth | nodes | springs | NodeForce ms | SpringUpdate ms | NodeUpdate ms | step GPU ms | springs/s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for b in runs:
        side = int(b["name"].split("side:")[1].split("/")[0])
        print("| %d×%d | %d | %d | %.3f | %.3f | %.3f | %.3f | %.1f M |" % (
            side, side, b["nodes"], b["springs"], b["NodeForce_ms"], b["SpringUpdate_ms"],
            b["NodeUpdate_ms"], b["gpu_ms"], b["springs_per_second"] / 1e6))
    print()
    prev = None
    for b in runs:
        ns = b["gpu_ms"] * 1e6 / b["springs"]
        shares = " ".join("%s %.0f%%" % (p, 100 * b[p + "_ms"] / b["gpu_ms"])
                          for p in ("NodeForce", "SpringUpdate", "NodeUpdate"))
        line = "%s: %.1f ns/spring/step; %s" % (b["name"].split("/")[1], ns, shares)
        if prev:
            line += "; vs previous: springs x%.2f, time x%.2f, per-spring x%.2f" % (
                b["springs"] / prev["springs"], b["gpu_ms"] / prev["gpu_ms"],
                ns / (prev["gpu_ms"] * 1e6 / prev["springs"]))
        print(line)
        prev = b
    if len(runs) > 1:
        a, z = runs[0], runs[-1]
        print("first to last: springs x%.1f, time x%.1f, per-spring x%.2f" % (
            z["springs"] / a["springs"], z["gpu_ms"] / a["gpu_ms"],
            (z["gpu_ms"] / z["springs"]) / (a["gpu_ms"] / a["springs"])))


if __name__ == "__main__":
    main(sys.argv[1])
