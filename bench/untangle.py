#!/usr/bin/env python3
"""Recovery from intersecting input deeper than the contact thickness (issue 23, item 5; decision
0024, "Deep intersections"): two 10 cm tet boxes whose corners start 0.5–5 cm into each other
(thickness 1 cm), under implicit Euler at 1 substep per frame and symplectic Euler at its
automatic substeps, 40 frames each through `glcollide run --stats`. Reports the substeps until
the start of a substep is intersection-free (the engine's exact TriTri), the node steps Untangle
moved, the intersecting pairs without a segment to shrink, whether any pair intersected again, the
total energy at the first and last frame, and the median wall time per frame.

usage: bench/untangle.py [--glcollide build/src/glcollide] --out bench/results/<device>/untangle_<commit>
"""
import argparse
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def boxes(depth, integrator, substeps):
    box = {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}
    return {"format_version": 1, "name": f"boxes {depth * 100:g} cm into each other",
            "effects": ["springs", "collisions"],
            "time": {"dt": 1 / 60, "integrator": integrator, "substeps": substeps},
            "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 500,
                          "response": "intersection_free"},
            "objects": [{"name": "a", "generator": box, "mass": 0.2, "springs": {"stiffness": 400}},
                        {"name": "b", "generator": box, "transform": {"translate": [0.1 - depth, 0.1 - depth, 0.013]},
                         "mass": 0.2, "springs": {"stiffness": 400}}]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glcollide", default=os.path.join(ROOT, "build", "src", "glcollide"))
    ap.add_argument("--frames", type=int, default=40)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows, renderer = [], None
    with tempfile.TemporaryDirectory() as work:
        for integrator, substeps in [("implicit_euler", 1), ("symplectic_euler", "auto")]:
            for depth in [0.005, 0.01, 0.02, 0.03, 0.05]:
                scene = os.path.join(work, "scene.json")
                stats_path = os.path.join(work, "stats.json")
                with open(scene, "w") as f:
                    json.dump(boxes(depth, integrator, substeps), f)
                subprocess.run([args.glcollide, "run", scene, "--frames", str(args.frames), "--stats", stats_path,
                                "--quiet"], check=True, stdout=subprocess.DEVNULL)
                with open(stats_path) as f:
                    s = json.load(f)
                renderer = s["gl_renderer"]
                frames = s["frames"]
                until = frames[-1]["collision"]["substeps_until_intersection_free"]
                free_frame = until // s["substeps"] + 1 if until is not None else len(frames)
                untangle = [fr["safe_step"]["untangle"] for fr in frames]
                rows.append({
                    "integrator": integrator, "substeps_per_frame": s["substeps"], "depth_m": depth,
                    "substeps_until_intersection_free": until,
                    "untangle_node_steps": sum(u["node_steps"] for u in untangle),
                    "pairs_without_segment": sum(u["pairs_without_segment"] for u in untangle),
                    "intersecting_pairs_at_start": frames[0]["collision"]["max_intersecting_pairs"],
                    "intersecting_pairs_after_free": max((fr["collision"]["max_intersecting_pairs"]
                                                          for fr in frames[free_frame:]), default=0),
                    "energy_J_first_last_frame": [frames[0]["total_energy_J"], frames[-1]["total_energy_J"]],
                    "wall_ms_per_frame_median": sorted(fr["wall_ms"] for fr in frames)[len(frames) // 2]})
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump({"gl_renderer": renderer, "commit": commit, "frames": args.frames, "rows": rows}, f, indent=1)
    lines = [f"Untangling on {renderer}, commit {commit}, {args.frames} frames:", "",
             "| integrator | substeps/frame | depth | pairs at start | substeps until free | node steps moved | "
             "pairs without segment | pairs after free | energy J first → last frame | wall ms/frame |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|"]
    for r in rows:
        e = r["energy_J_first_last_frame"]
        lines.append(f"| {r['integrator']} | {r['substeps_per_frame']} | {r['depth_m'] * 100:g} cm | "
                     f"{r['intersecting_pairs_at_start']} | {r['substeps_until_intersection_free']} | "
                     f"{r['untangle_node_steps']} | {r['pairs_without_segment']} | {r['intersecting_pairs_after_free']} | "
                     f"{e[0]:.3f} → {e[1]:.3f} | {r['wall_ms_per_frame_median']:.1f} |")
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
