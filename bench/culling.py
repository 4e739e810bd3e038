#!/usr/bin/env python3
"""Radial view-based culling's benchmark (issue 24, item 6; docs/culling.md, "Measured").

Runs scenes/cloth_ball.json (a soft ball of cloth crumpling on the ground) at several sizes, with
"culling": "none" and "radial", through `glcollide run --stats`, and reports per size the medians
over the frames after the first (whose start is not yet known to be intersection-free, so it never
culls): triangles certified positive, free triangles, CCD feature pairs and TriTri candidate pairs
tested with and without culling, and the GPU time of each detection stage. The detection time is
RadialCulling + BvhBuild + BvhRefit + BvhTraverse + TriTri + FeaturePairs + Ccd. The cost exponent
is the slope of log(detection time) against log(faces) between the smallest and largest size.

usage: bench/culling.py [--glcollide build/src/glcollide] [--frames 45] [--subdivisions 3,4,5]
                        [--out bench/results/<device>/culling_<commit>]
       bench/culling.py --write-scenes DIR ...   (only writes the scene variants, for a machine without
                                                python: run each with `glcollide run X.json --stats X_stats.json`)
       bench/culling.py --stats-dir DIR ...      (summarizes stats files written that way)
The frames of both runs are bit-identical (tests/gl/radial_culling_gl_test.cpp checks it); this
script measures only what culling costs and saves.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DETECTION = ["RadialCulling", "BvhBuild", "BvhRefit", "BvhTraverse", "TriTri", "FeaturePairs", "Ccd"]


def load_scene(path):
    # Scene files allow whole-line // comments (docs/scene-format.md); cloth_ball.json has only those.
    with open(path) as f:
        return json.loads("".join(line for line in f if not line.lstrip().startswith("//")))


def run(binary, scene, frames, workdir, tag, stats_dir=None, write_only=False):
    scene_path = os.path.join(workdir, tag + ".json")
    stats_path = os.path.join(stats_dir or workdir, tag + "_stats.json")
    if stats_dir is None:
        with open(scene_path, "w") as f:
            json.dump(scene, f)
    if write_only:
        return None
    if stats_dir is None:
        subprocess.run([binary, "run", scene_path, "--frames", str(frames), "--stats", stats_path, "--quiet"],
                       check=True, stdout=subprocess.DEVNULL)
    with open(stats_path) as f:
        return json.load(f)


def median(frames, key):
    return statistics.median(key(f) for f in frames)


def summarize(stats):
    frames = stats["frames"][1:]
    ms = lambda name: (lambda f: f["gpu_ms"].get(name, 0.0))
    row = {
        "faces": stats["faces"],
        "detection_ms": median(frames, lambda f: sum(f["gpu_ms"].get(p, 0.0) for p in DETECTION)),
        "stage_ms": {p: median(frames, ms(p)) for p in DETECTION},
        "wall_ms": median(frames, lambda f: f["wall_ms"]),
        "ccd_pairs_listed": median(frames, lambda f: f["collision"]["vertex_face_pairs"] + f["collision"]["edge_edge_pairs"]),
        "tri_tri_candidates": median(frames, lambda f: f["collision"]["candidate_pairs"]),
        "ccd_may_touch": median(frames, lambda f: f["ccd"]["vertex_face_may_touch"] + f["ccd"]["edge_edge_may_touch"]),
        "max_intersecting_pairs": max(f["collision"]["max_intersecting_pairs"] for f in stats["frames"]),
    }
    radial = [f.get("radial_culling") for f in frames]
    if all(r is not None for r in radial):
        observed = radial[0]["observed_faces"]
        row["positive_fraction"] = median(frames, lambda f: 1 - f["radial_culling"]["non_positive_faces"] / observed)
        row["min_positive_fraction"] = min(1 - r["non_positive_faces"] / observed for r in radial)
        row["free_fraction"] = median(frames, lambda f: f["radial_culling"]["free_faces"] / observed)
        row["ccd_pairs_tested"] = median(frames, lambda f: f["collision"]["vertex_face_pairs"] + f["collision"]["edge_edge_pairs"]
                                         - f["radial_culling"]["ccd_pairs_left_out"])
        row["tri_tri_tested"] = median(frames, lambda f: f["collision"]["candidate_pairs"] - f["radial_culling"]["tri_tri_pairs_left_out"])
        row["substeps_culled"] = sum(r["substeps_culled"] for r in radial)
    else:
        row["ccd_pairs_tested"] = row["ccd_pairs_listed"]
        row["tri_tri_tested"] = row["tri_tri_candidates"]
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glcollide", default=os.path.join(ROOT, "build", "src", "glcollide"))
    ap.add_argument("--frames", type=int, default=45)
    ap.add_argument("--subdivisions", default="3,4,5")
    ap.add_argument("--out", default=None)
    ap.add_argument("--write-scenes", default=None)
    ap.add_argument("--stats-dir", default=None)
    args = ap.parse_args()
    base = load_scene(os.path.join(ROOT, "scenes", "cloth_ball.json"))
    results = {"scene": "scenes/cloth_ball.json", "frames": args.frames, "sizes": []}
    with tempfile.TemporaryDirectory() as temp:
        work = args.write_scenes or temp
        for sub in [int(s) for s in args.subdivisions.split(",")]:
            size = {}
            for culling in ["none", "radial"]:
                scene = json.loads(json.dumps(base))
                scene["objects"][0]["generator"]["subdivisions"] = sub
                scene["collision"]["culling"] = culling
                stats = run(args.glcollide, scene, args.frames, work, f"ball{sub}_{culling}", args.stats_dir,
                            args.write_scenes is not None)
                if stats is None:
                    continue
                results.setdefault("device", stats["device"])
                results.setdefault("gl_renderer", stats["gl_renderer"])
                size[culling] = summarize(stats)
                print(f"subdivisions {sub} ({stats['faces']} faces), culling {culling}: "
                      f"detection {size[culling]['detection_ms']:.2f} ms", file=sys.stderr)
            if not size:
                continue
            none, radial = size["none"], size["radial"]
            size["ccd_pair_ratio"] = none["ccd_pairs_tested"] / max(radial["ccd_pairs_tested"], 1)
            size["tri_tri_ratio"] = none["tri_tri_tested"] / max(radial["tri_tri_tested"], 1)
            size["detection_speedup"] = none["detection_ms"] / radial["detection_ms"]
            size["same_exact_answers"] = (none["ccd_may_touch"] == radial["ccd_may_touch"]
                                          and none["max_intersecting_pairs"] == radial["max_intersecting_pairs"])
            results["sizes"].append(size)
    if args.write_scenes:
        return
    sizes = results["sizes"]
    if len(sizes) >= 2:
        for culling in ["none", "radial"]:
            a, b = sizes[0][culling], sizes[-1][culling]
            results[f"cost_exponent_{culling}"] = math.log(b["detection_ms"] / a["detection_ms"]) / math.log(b["faces"] / a["faces"])
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    results["commit"] = commit
    lines = [f"Radial culling on {results['gl_renderer']} ({results['device']}), commit {commit}, "
             f"{args.frames} frames, medians over frames 2..{args.frames}:", "",
             "| faces | positive | free | CCD pairs none → radial | ratio | TriTri pairs none → radial | ratio "
             "| detection ms none → radial (culling stage) | speed-up |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for s in sizes:
        n, r = s["none"], s["radial"]
        lines.append(f"| {n['faces']} | {100 * r['positive_fraction']:.1f} % (min {100 * r['min_positive_fraction']:.1f} %) "
                     f"| {100 * r['free_fraction']:.1f} % | {n['ccd_pairs_tested']:.0f} → {r['ccd_pairs_tested']:.0f} "
                     f"| {s['ccd_pair_ratio']:.1f}× | {n['tri_tri_tested']:.0f} → {r['tri_tri_tested']:.0f} | {s['tri_tri_ratio']:.1f}× "
                     f"| {n['detection_ms']:.2f} → {r['detection_ms']:.2f} ({r['stage_ms']['RadialCulling']:.2f}) "
                     f"| {s['detection_speedup']:.2f}× |")
    if "cost_exponent_none" in results:
        lines += ["", f"Cost exponent of detection time in faces: none {results['cost_exponent_none']:.2f}, "
                      f"radial {results['cost_exponent_radial']:.2f}."]
    table = "\n".join(lines)
    print(table)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        with open(os.path.join(args.out, "results.json"), "w") as f:
            json.dump(results, f, indent=1)
        with open(os.path.join(args.out, "table.md"), "w") as f:
            f.write(table + "\n")


if __name__ == "__main__":
    main()
