#!/usr/bin/env python3
"""Restitution between bodies against the step and the rounds (decision 0024, "Restitution between bodies").

    bench/restitution_bodies.py build/src/glcollide --out bench/results/llvmpipe/restitution_bodies_<commit>

Drops a flat cloth (0.4 m, 8 x 8, turned 33 degrees about y so that no edge is parallel to the
sheet's) 1 m onto a pinned sheet (1 m, 7 x 7) with collision.restitution e under implicit Euler,
and compares the highest frame-end height of the cloth after its bounce with the oracle of
bench/restitution.py (the sheet is pinned: a pair's free flight is the cloth node's fall). Rows:
e = 0.3 and 0.6 at 1, 2, 4 and 16 substeps per frame (16 rounds, the default); the rounds 1, 4, 16
and 64 at 1 substep per frame (the accuracy and its cost: wall milliseconds per frame, in one run);
e = 0 (the pass not built: the cost's baseline, and the bounce without it); and symplectic Euler at
its automatic substeps. Writes results.json
(renderer, commit, every run) and prints a Markdown table.
"""
import argparse
import json
import os
import subprocess
import tempfile

from restitution import DT, TOP, oracle_apex, run, summary

CLOTH_NODES = 64  # the cloth comes first: its 8 x 8 nodes


def scene(substeps, e, rounds, integrator="implicit_euler"):
    collision = {"thickness": 0.01, "restitution": e}
    if e > 0:
        collision["restitution_iterations"] = rounds
    return {
        "format_version": 1, "name": "flat cloth onto a pinned sheet",
        "effects": ["gravity", "springs", "collisions"],
        "time": {"dt": DT, "integrator": integrator, "substeps": substeps},
        "collision": collision,
        "objects": [
            {"name": "cloth", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [8, 8]},
             "transform": {"translate": [0.013, 1.0 + TOP, 0.021], "rotate_deg": [90, 33, 0]},
             "mass": 0.1, "springs": {"stiffness": 1000}},
            {"name": "sheet", "generator": {"type": "cloth", "size": [1.0, 1.0], "resolution": [7, 7]},
             "transform": {"rotate_deg": [90, 0, 0]}, "mass": 1.0, "springs": {"stiffness": 1000},
             "pinned": {"inside": {"min": [-1, -1, -1], "max": [1, 1, 1]}}}]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("--out", required=True)
    parser.add_argument("--no-symplectic", action="store_true", help="skip the slow symplectic run")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    runs = [(n, e, 16, "implicit_euler") for e in (0.3, 0.6) for n in (1, 2, 4, 16)]
    runs += [(1, 0.6, r, "implicit_euler") for r in (1, 4, 64)]
    runs += [(1, 0.0, 16, "implicit_euler"), (4, 0.0, 16, "implicit_euler")]
    if not args.no_symplectic:
        runs.append(("auto", 0.6, 16, "symplectic_euler"))
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for substeps, e, rounds, integrator in runs:
            name = f"sheet_{integrator}_{substeps}_{e}_{rounds}"
            heights, stats = run(args.binary, scene(substeps, e, rounds, integrator), 60, work, name, CLOTH_NODES)
            # The impact's frame: the first frame end in the band, or the first turn upwards
            # (restitution.py's bounce() looks for a turn, which a run that does not bounce never makes).
            landing = next(i for i in range(1, len(heights) - 1)
                           if heights[i] <= TOP + 0.001 or heights[i + 1] > heights[i])
            apex = max(heights[landing:])
            expected = oracle_apex(1.0 + TOP, e, stats["substeps"]) if e > 0 else TOP
            rows.append({"integrator": integrator, "restitution": e, "rounds": rounds if e > 0 else None, "landing_frame": landing,
                         "apex_m": apex, "oracle_apex_m": expected, "error_m": apex - expected, **summary(stats)})
            print(name, apex, expected, flush=True)
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump({"commit": commit, "renderer": rows[0]["renderer"], "runs": rows}, f, indent=1)
    print("\n| integrator | substeps/frame | e | rounds | apex (m) | oracle (m) | error (mm) | ms/frame | guard | cut |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        rounds = r["rounds"] if r["rounds"] else "(not built)"
        print(f"| {r['integrator']} | {r['substeps_per_frame']} | {r['restitution']} | {rounds} | {r['apex_m']:.4f} | "
              f"{r['oracle_apex_m']:.4f} | {1000 * r['error_m']:+.1f} | {r['wall_ms_per_frame']:.0f} | "
              f"{r['guard_acted']} | {r['substeps_cut']} |")


if __name__ == "__main__":
    main()
