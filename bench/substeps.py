#!/usr/bin/env python3
"""Fewer substeps at the same visual result (issue 23, target "the cloth scenes of scenes/ at the
same visual result with at least 10x fewer substeps than today"; docs/benchmarks.md).

"Today" is each shipped cloth scene as it is (symplectic Euler at the automatic stable substep
count, its own response). Each is run again under implicit Euler with the intersection-free
response and continuous detection at a tenth of that substep count (rounded down) and at each count
of --substeps, and every --every-th frame is compared with the shipped run's, relative to the
diagonal of the bounding box, at frame 0, of the nodes that move in the shipped run:
- node by node: the RMS and the largest node distance;
- by shape, which does not ask which node lies where: the centroid's distance, and the largest
  difference over the three axes of the bounding box's extent and of the radius of gyration
  (RMS distance of the nodes from their centroid along the axis).
"The same visual result" is read here as at most 5 % of that diagonal in every compared frame (a
cloth drawn at 1,000 pixels across is then within 50 pixels of the reference): by node RMS, and
separately by shape (centroid, extents and radii of gyration all within 5 %) — measures chosen for
this benchmark, not standard ones; the table gives the numbers so that another threshold can be
read off. Where the cloth crumples, which fold lands where depends on any change (the step, the
response), so two runs can agree in shape and still lie 10 % apart node by node. Two rows show how
much: the shipped scene at twice its substeps (the reference's own spread), and the shipped scene
with only its response changed to the intersection-free one (`--response-row`, costly: the new
response at today's substeps). Wall time per frame and the most intersecting face pairs of any
substep come from `glcollide run --stats`.

usage: bench/substeps.py [--glcollide build/src/glcollide] [--scenes crumpled_cloth,cloth_on_sphere,cloth_stack]
                         [--frames 120] [--every 10] [--substeps 2,1] [--response-row]
                         [--out bench/results/<device>/substeps_<commit>]
"""
import argparse
import json
import math
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAME_VISUAL_RESULT = 0.05  # node RMS, or each shape measure, / diagonal in every compared frame


def load_scene(path):
    # Scene files allow // comments on lines of their own or after a value (never inside a string).
    with open(path) as f:
        return json.loads("".join(line.split("//")[0] + "\n" for line in f))


def merge(base, patch):
    """JSON merge patch (RFC 7386), as the bench suites apply them."""
    if not isinstance(patch, dict):
        return patch
    out = dict(base) if isinstance(base, dict) else {}
    for k, v in patch.items():
        if v is None:
            out.pop(k, None)
        else:
            out[k] = merge(out.get(k), v)
    return out


def read_obj_nodes(path):
    with open(path) as f:
        return [tuple(float(c) for c in line.split()[1:4]) for line in f if line.startswith("v ")]


def run(binary, scene, name, frames, every, workdir):
    """Runs `scene` (written next to the shipped scenes, whose mesh paths are relative to them)."""
    scene_path = os.path.join(ROOT, "scenes", f".substeps_{name}.json")
    export = os.path.join(workdir, name)
    stats_path = os.path.join(workdir, name + "_stats.json")
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    try:
        subprocess.run([binary, "run", scene_path, "--frames", str(frames), "--export", export, "--every",
                        str(every), "--stats", stats_path, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    finally:
        os.remove(scene_path)
    with open(stats_path) as f:
        stats = json.load(f)
    exported = {}
    for file in sorted(os.listdir(export)):
        if file.startswith("frame_") and file.endswith(".obj"):
            exported[int(file[6:-4])] = read_obj_nodes(os.path.join(export, file))
    return stats, exported


def distances(a, b):
    d = [math.dist(p, q) for p, q in zip(a, b)]
    return math.sqrt(sum(x * x for x in d) / len(d)), max(d)


def diagonal(nodes):
    lo = [min(p[k] for p in nodes) for k in range(3)]
    hi = [max(p[k] for p in nodes) for k in range(3)]
    return math.dist(lo, hi)


def shape(nodes):
    """Centroid, bounding-box extent per axis and radius of gyration per axis."""
    n = len(nodes)
    centroid = [sum(p[k] for p in nodes) / n for k in range(3)]
    extent = [max(p[k] for p in nodes) - min(p[k] for p in nodes) for k in range(3)]
    gyration = [math.sqrt(sum((p[k] - centroid[k]) ** 2 for p in nodes) / n) for k in range(3)]
    return centroid, extent, gyration


def compare(frames, reference, reference_shapes, scale):
    """Every compared frame of `frames` against `reference` (whose shape() per frame is
    `reference_shapes`, computed once per scene), divided by `scale` (the diagonal)."""
    measures = {"rms": [], "max_distance": [], "centroid": [], "extent": [], "gyration": []}
    keys = [k for k in sorted(reference) if k in frames]
    for k in keys:
        rms, far = distances(frames[k], reference[k])
        (c, e, g), (rc, re, rg) = shape(frames[k]), reference_shapes[k]
        measures["rms"].append(rms / scale)
        measures["max_distance"].append(far / scale)
        measures["centroid"].append(math.dist(c, rc) / scale)
        measures["extent"].append(max(abs(a - b) for a, b in zip(e, re)) / scale)
        measures["gyration"].append(max(abs(a - b) for a, b in zip(g, rg)) / scale)
    out = {"frames": keys, "by_frame": measures}
    for name, values in measures.items():
        out["worst_" + name] = max(values)
        out["final_" + name] = values[-1]
    out["worst_shape"] = max(out["worst_centroid"], out["worst_extent"], out["worst_gyration"])
    out["same_visual_result_by_nodes"] = out["worst_rms"] <= SAME_VISUAL_RESULT
    out["same_visual_result_by_shape"] = out["worst_shape"] <= SAME_VISUAL_RESULT
    return out


def summary(stats):
    frames = stats["frames"]
    return {
        "substeps": stats["substeps"],
        "wall_ms_per_frame": sum(f["wall_ms"] for f in frames) / len(frames),
        "max_intersecting_pairs": max((f.get("collision") or {}).get("max_intersecting_pairs", 0) for f in frames),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--glcollide", default=os.path.join(ROOT, "build", "src", "glcollide"))
    parser.add_argument("--scenes", default="crumpled_cloth,cloth_on_sphere,cloth_stack")
    parser.add_argument("--frames", type=int, default=120)
    parser.add_argument("--every", type=int, default=10)
    parser.add_argument("--substeps", default="2,1")
    parser.add_argument("--response-row", action="store_true",
                        help="also run the shipped scene with only its response changed (slow)")
    parser.add_argument("--out")
    args = parser.parse_args()
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    results = {"commit": commit, "frames": args.frames, "every": args.every, "threshold": SAME_VISUAL_RESULT,
               "scenes": []}
    with tempfile.TemporaryDirectory() as temp:
        for name in args.scenes.split(","):
            shipped = load_scene(os.path.join(ROOT, "scenes", name + ".json"))
            ref_stats, ref_frames = run(args.glcollide, shipped, name + "_shipped", args.frames, args.every, temp)
            results.setdefault("gl_renderer", ref_stats["gl_renderer"])
            results.setdefault("device", ref_stats["device"])
            # Only the nodes that move in the shipped run (a pinned sphere would dilute the RMS).
            moving = [i for i in range(len(ref_frames[0]))
                      if any(frame[i] != ref_frames[0][i] for frame in ref_frames.values())]
            ref_frames = {k: [v[i] for i in moving] for k, v in ref_frames.items()}
            extent = diagonal(ref_frames[0])
            reference = summary(ref_stats)
            ref_shapes = {k: shape(v) for k, v in ref_frames.items()}

            def row(label, patch):
                stats, frames = run(args.glcollide, merge(shipped, patch), f"{name}_{label}", args.frames,
                                    args.every, temp)
                frames = {k: [v[i] for i in moving] for k, v in frames.items()}
                out = summary(stats)
                out.update(compare(frames, ref_frames, ref_shapes, extent))
                out["fewer_substeps"] = reference["substeps"] / out["substeps"]
                return out

            # The spread of the shipped run itself: the same scene at twice its substeps. Crumpling
            # and sliding cloth is sensitive to any change; a difference of this size is the
            # integrator's own, not the response's.
            spread = {"shipped at 2x substeps": row("shipped_double",
                                                    {"time": {"substeps": 2 * reference["substeps"]}})}
            if args.response_row:
                # Only the response changed, at today's integrator and substeps: what the new response
                # alone does to the result.
                spread["shipped, intersection_free response"] = row(
                    "shipped_intersection_free", {"time": {"substeps": reference["substeps"]},
                                                  "collision": {"response": "intersection_free",
                                                                "detection": "continuous"}})
            counts = [max(1, reference["substeps"] // 10)] + [int(s) for s in args.substeps.split(",")]
            rows = []
            for substeps in sorted(set(counts), reverse=True):
                rows.append(row(str(substeps), {
                    "time": {"integrator": "implicit_euler", "substeps": substeps},
                    "collision": {"response": "intersection_free", "detection": "continuous"}}))
            results["scenes"].append({"scene": name, "diagonal_m": extent, "shipped": reference,
                                      "spread": spread, "implicit": rows})

    lines = [f"Fewer substeps at the same visual result on {results['gl_renderer']} ({results['device']}), "
             f"commit {commit}, {args.frames} frames compared every {args.every}th (bench/substeps.py).", "",
             "| scene | run | substeps | fewer | worst RMS | final RMS | final max | worst centroid | "
             "worst extent | worst gyration | ms/frame | max intersecting | same result: by nodes | by shape |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"]

    def pct(x):
        return f"{100 * x:.1f} %"

    for s in results["scenes"]:
        ref = s["shipped"]
        lines.append(f"| {s['scene']} | shipped (reference) | {ref['substeps']} | 1x | | | | | | | "
                     f"{ref['wall_ms_per_frame']:.0f} | {ref['max_intersecting_pairs']} | | |")
        labelled = [(label, r) for label, r in s["spread"].items()]
        labelled += [("implicit, intersection_free", r) for r in s["implicit"]]
        for label, r in labelled:
            lines.append(f"| {s['scene']} | {label} | {r['substeps']} | {r['fewer_substeps']:.1f}x | "
                         f"{pct(r['worst_rms'])} | {pct(r['final_rms'])} | {pct(r['final_max_distance'])} | "
                         f"{pct(r['worst_centroid'])} | {pct(r['worst_extent'])} | {pct(r['worst_gyration'])} | "
                         f"{r['wall_ms_per_frame']:.0f} | {r['max_intersecting_pairs']} | "
                         f"{'yes' if r['same_visual_result_by_nodes'] else 'no'} | "
                         f"{'yes' if r['same_visual_result_by_shape'] else 'no'} |")
    lines.append("")
    lines.append("Distances relative to the diagonal of the bounding box, at frame 0, of the nodes that move in "
                 "the shipped run; worst over the compared frames. Same result: at most "
                 f"{pct(SAME_VISUAL_RESULT)} in every compared frame, by node RMS, or by shape (centroid, extents "
                 "and radii of gyration).")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        with open(os.path.join(args.out, "substeps.json"), "w") as f:
            json.dump(results, f, indent=1)
        with open(os.path.join(args.out, "README.md"), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
