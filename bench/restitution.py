#!/usr/bin/env python3
"""The ground's restitution against the step (decision 0024, "Restitution at any step").

    bench/restitution.py build/src/glcollide --out bench/results/llvmpipe/restitution_<commit>

Drops a flat cloth (0.4 m, 8 x 8, every node alike) 1 m onto the ground at several substep counts
under implicit Euler (and once under symplectic Euler at its automatic substeps) and compares the
highest height of its centre after the bounce, sampled at frame ends as the exports are, with the
oracle: the integrators' shared free-flight recurrence (v += h*g, then y += h*v) until the substep
that reaches the band's top, the impact speed of the free fall to the top, then e times it upwards
from the top. Also drops a stiff tet box (k = 5e4 N/m, restitution 0.8) 1.25 m, whose bounce has no
oracle: its nodes' restitution holds, but how its springs pass the bounce on is the integrator's
(implicit Euler damps it at large steps). Writes results.json (renderer, commit, every run) and
prints a Markdown table.
"""
import argparse
import glob
import json
import math
import os
import subprocess
import tempfile

DT = 1.0 / 60.0
G = 9.81
TOP = 0.01  # the ground's band: thickness 0.01 above height 0


def cloth_scene(integrator, substeps, e, height):
    return {
        "format_version": 1, "name": "flat cloth drop",
        "effects": ["gravity", "springs", "ground", "self_collisions"],
        "time": {"dt": DT, "integrator": integrator, "substeps": substeps},
        "ground": {"height": 0.0, "restitution": e, "friction": 0.0},
        "collision": {"thickness": 0.01},
        "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [8, 8]},
                     "transform": {"translate": [0, height + TOP, 0], "rotate_deg": [90, 0, 0]},
                     "mass": 0.1, "springs": {"stiffness": 1000}}]}


def box_scene(substeps, e):
    return {
        "format_version": 1, "name": "stiff box drop",
        "effects": ["gravity", "springs", "ground", "collisions"],
        "time": {"dt": DT, "integrator": "implicit_euler", "substeps": substeps},
        "ground": {"height": 0.0, "restitution": e, "friction": 0.0},
        "objects": [{"name": "box", "generator": {"type": "tet_box", "size": [0.2, 0.2, 0.2], "resolution": [2, 2, 2]},
                     "transform": {"translate": [0, 1.35, 0]}, "mass": 1, "springs": {"stiffness": 50000}}]}


def oracle_apex(y0, e, substeps, frames=60):
    """Highest frame-end height after the impact of a node in the integrators' free flight."""
    h = DT / substeps
    y, v, landed, best = y0, 0.0, False, 0.0
    for k in range(1, frames * substeps + 1):
        v_next = v - h * G
        y_next = y + h * v_next
        if not landed and y_next <= TOP:  # this substep reaches the band's top: the impact
            landed = True
            v_next, y_next = e * math.sqrt(v * v + 2.0 * G * (y - TOP)), TOP
        y, v = y_next, v_next
        if landed and k % substeps == 0:
            best = max(best, y)
    return best


def mean_heights(folder, first_object_nodes=None):
    heights = []
    for path in sorted(glob.glob(os.path.join(folder, "frame_*.obj"))):
        ys = [float(line.split()[2]) for line in open(path) if line.startswith("v ")]
        if first_object_nodes:
            ys = ys[:first_object_nodes]
        heights.append(sum(ys) / len(ys))
    return heights


def run(binary, scene, frames, work, name, first_object_nodes=None):
    scene_path = os.path.join(work, name + ".json")
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    out = os.path.join(work, name)
    stats_path = os.path.join(work, name + "_stats.json")
    subprocess.run([binary, "run", scene_path, "--frames", str(frames), "--quiet", "--stats", stats_path,
                    "--export", out, "--every", "1"], check=True, stdout=subprocess.DEVNULL)
    with open(stats_path) as f:
        stats = json.load(f)
    return mean_heights(out, first_object_nodes), stats


def bounce(heights):
    """The frame of the first impact (the first frame-end height lower than the next, after the
    fall) and the highest frame-end height after it."""
    landing = next(i for i in range(1, len(heights) - 1) if heights[i] < heights[i - 1] and heights[i + 1] > heights[i])
    return landing, max(heights[landing + 1:])


def summary(stats):
    frames = stats["frames"]
    return {
        "substeps_per_frame": stats["substeps"],
        "wall_ms_per_frame": sum(f["wall_ms"] for f in frames) / len(frames),
        "guard_acted": sum(f["energy_guard"]["substeps_acted"] for f in frames),
        "substeps_cut": sum(f["safe_step"]["substeps_cut"] for f in frames),
        "renderer": stats["gl_renderer"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary")
    parser.add_argument("--out", required=True)
    parser.add_argument("--no-symplectic", action="store_true", help="skip the slow symplectic run")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        runs = [("implicit_euler", n, e) for e in (0.3, 0.6) for n in (1, 2, 4, 16)]
        if not args.no_symplectic:
            runs.append(("symplectic_euler", "auto", 0.6))
        for integrator, substeps, e in runs:
            name = f"cloth_{integrator}_{substeps}_{e}"
            heights, stats = run(args.binary, cloth_scene(integrator, substeps, e, 1.0), 60, work, name)
            landing, apex = bounce(heights)
            expected = oracle_apex(1.0 + TOP, e, stats["substeps"])
            rows.append({"body": "flat cloth", "integrator": integrator, "restitution": e, "landing_frame": landing,
                         "apex_m": apex, "oracle_apex_m": expected, "error_m": apex - expected, **summary(stats)})
            print(name, rows[-1]["apex_m"], expected, flush=True)
        for substeps in (1, 4, 16):
            name = f"box_{substeps}"
            heights, stats = run(args.binary, box_scene(substeps, 0.8), 90, work, name)
            rest = heights[-1]
            landing, _ = bounce(heights)
            rows.append({"body": "stiff tet box", "integrator": "implicit_euler", "restitution": 0.8,
                         "landing_frame": landing, "rebound_m": max(heights[landing:]) - rest,
                         "rigid_rebound_m": 0.8 ** 2 * (1.35 - rest), **summary(stats)})
            print(name, rows[-1]["rebound_m"], flush=True)
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump({"commit": commit, "renderer": rows[0]["renderer"], "runs": rows}, f, indent=1)
    print("\n| body | integrator | substeps/frame | e | apex (m) | oracle (m) | ms/frame | guard | cut |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        apex = f"{r['apex_m']:.4f}" if "apex_m" in r else f"rebound {r['rebound_m']:.3f}"
        oracle = f"{r['oracle_apex_m']:.4f}" if "oracle_apex_m" in r else f"rigid {r['rigid_rebound_m']:.3f}"
        print(f"| {r['body']} | {r['integrator']} | {r['substeps_per_frame']} | {r['restitution']} | {apex} | "
              f"{oracle} | {r['wall_ms_per_frame']:.0f} | {r['guard_acted']} | {r['substeps_cut']} |")


if __name__ == "__main__":
    main()
