#!/usr/bin/env python3
"""Radial view-based culling's benchmark (issue 24, item 6; docs/culling.md, "Measured").

Runs scenes/cloth_ball.json (a very soft tet ball crumpling on the ground) at several sizes, the
same ball stretched 3x along x (a cigar: a long closed surface, for segment observers), and
the open surfaces that ghost triangles close — scenes/sleeve.json (a twisting tube) at several
resolutions, scenes/elbow.json (a bent tube folding, watched by a skeleton) and
scenes/mask_fold.json (DEDO's mask folding over a ball) — and the flat sheet that
clusters serve (scenes/sheet_fold.json, at several resolutions) with "culling": "none"
and "radial", through `glcollide run --stats`, and reports per size the medians over the frames
after the first (the first frame's wall time holds the start-up check of decision 0025, "Culling
from the first substep"; it gets a table of its own, and is left out of the medians as in earlier
runs, so rows compare): triangles certified positive, free triangles, CCD feature pairs and TriTri
candidate pairs tested with and without culling, and the GPU time of each detection stage. The detection time is
RadialCulling + BvhBuild + BvhRefit + BvhTraverse + TriTri + FeaturePairs + Ccd. The cost exponent
is the slope of log(detection time) against log(faces) between the smallest and largest size.

usage: bench/culling.py [--glcollide build/src/glcollide] [--frames 45] [--scenes ball,cigar,sleeve,elbow,mask,sheet]
                        [--observers auto|objects|clusters] [--observer X,Y,Z[;X,Y,Z]|none]
                        [--subdivisions 3,4,5] [--sleeve-resolutions 32x20,64x40] [--elbow-resolutions 32x31,64x61]
                        [--sheet-resolutions 32,48,96]
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
    # Scene files allow // comments (docs/scene-format.md); the shipped ones put them on lines of
    # their own, or after a value at the end of a line (never inside a string holding "//").
    with open(path) as f:
        return json.loads("".join(line.split("//")[0] + "\n" for line in f))


def variants(args):
    """(scene name, tag, scene) of every size to run."""
    out = []
    for name in args.scenes.split(","):
        if name == "ball":
            base = load_scene(os.path.join(ROOT, "scenes", "cloth_ball.json"))
            for sub in [int(s) for s in args.subdivisions.split(",")]:
                scene = json.loads(json.dumps(base))
                scene["objects"][0]["generator"]["subdivisions"] = sub
                out.append(("cloth_ball", f"ball{sub}", scene))
        elif name == "cigar":  # the cloth ball stretched 3x along x: a long closed surface
            base = load_scene(os.path.join(ROOT, "scenes", "cloth_ball.json"))
            for sub in [int(s) for s in args.subdivisions.split(",")]:
                scene = json.loads(json.dumps(base))
                scene["objects"][0]["generator"]["subdivisions"] = sub
                scene["objects"][0]["transform"]["scale"] = [3, 1, 1]
                out.append(("cloth_cigar", f"cigar{sub}", scene))
        elif name in ("sleeve", "elbow"):  # tube generators at each resolution AROUNDxALONG
            base = load_scene(os.path.join(ROOT, "scenes", name + ".json"))
            resolutions = args.sleeve_resolutions if name == "sleeve" else args.elbow_resolutions
            for res in resolutions.split(","):
                around, along = (int(v) for v in res.split("x"))
                scene = json.loads(json.dumps(base))
                scene["objects"][0]["generator"]["resolution"] = [around, along]
                out.append((name, f"{name}{around}x{along}", scene))
        elif name == "mask":
            scene = load_scene(os.path.join(ROOT, "scenes", "mask_fold.json"))
            for obj in scene["objects"]:
                if "mesh" in obj:  # the scene is written elsewhere: name its mesh by absolute path
                    obj["mesh"] = os.path.join(ROOT, "scenes", obj["mesh"])
            out.append(("mask_fold", "mask", scene))
        elif name == "sheet":
            base = load_scene(os.path.join(ROOT, "scenes", "sheet_fold.json"))
            for res in [int(r) for r in args.sheet_resolutions.split(",")]:
                scene = json.loads(json.dumps(base))
                scene["objects"][0]["generator"]["resolution"] = [res, res]
                out.append(("sheet_fold", f"sheet{res}", scene))
        else:
            sys.exit(f"culling.py: unknown scene {name!r}; expected ball, cigar, sleeve, elbow, mask or sheet")
    return out


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
    return statistics.median(key(f) for f in frames) if frames else float("nan")


def detection_ms(f):
    return sum(f["gpu_ms"].get(p, 0.0) for p in DETECTION)


def ccd_tested(f):
    listed = f["collision"]["vertex_face_pairs"] + f["collision"]["edge_edge_pairs"]
    return listed - (f.get("radial_culling") or {}).get("ccd_pairs_left_out", 0)


def tri_tri_tested(f):
    return f["collision"]["candidate_pairs"] - (f.get("radial_culling") or {}).get("tri_tri_pairs_left_out", 0)


def summarize(none_stats, radial_stats, first_frame):
    """Medians over two sets of frames of the bit-identical runs: every frame from `first_frame`,
    and the folded ones (some face not proven positive: the culling has work to do)."""
    none_frames = {f["frame"]: f for f in none_stats["frames"] if f["frame"] >= first_frame}
    radial_frames = {f["frame"]: f for f in radial_stats["frames"] if f["frame"] >= first_frame}
    observed = radial_stats["frames"][-1]["radial_culling"]["observed_faces"]
    folded = [k for k, f in radial_frames.items() if f["radial_culling"]["non_positive_faces"] > 0]
    out = {"faces": none_stats["faces"], "observed_faces": observed,
           "max_intersecting_pairs": {c: max(f["collision"]["max_intersecting_pairs"] for f in s["frames"])
                                      for c, s in [("none", none_stats), ("radial", radial_stats)]},
           "same_ccd_answers": all(
               none_frames[k]["ccd"]["vertex_face_may_touch"] == radial_frames[k]["ccd"]["vertex_face_may_touch"]
               and none_frames[k]["ccd"]["edge_edge_may_touch"] == radial_frames[k]["ccd"]["edge_edge_may_touch"]
               for k in radial_frames)}
    for name, keys in [("all", sorted(radial_frames)), ("folded", sorted(folded))]:
        n = [none_frames[k] for k in keys]
        r = [radial_frames[k] for k in keys]
        out[name] = {
            "frames": len(keys),
            "positive_fraction": median(r, lambda f: 1 - f["radial_culling"]["non_positive_faces"] / observed),
            "free_fraction": median(r, lambda f: f["radial_culling"]["free_faces"] / observed),
            "ccd_pairs": {"none": median(n, ccd_tested), "radial": median(r, ccd_tested)},
            "tri_tri_pairs": {"none": median(n, tri_tri_tested), "radial": median(r, tri_tri_tested)},
            "detection_ms": {"none": median(n, detection_ms), "radial": median(r, detection_ms)},
            "stage_ms": {c: {p: median(fs, lambda f, p=p: f["gpu_ms"].get(p, 0.0)) for p in DETECTION}
                         for c, fs in [("none", n), ("radial", r)]},
            "wall_ms": {"none": median(n, lambda f: f["wall_ms"]), "radial": median(r, lambda f: f["wall_ms"])},
        }
    # The first frame: its substeps cull from the start when the start check (decision 0025,
    # "Culling from the first substep") found no intersecting pair. Its wall time holds the check's
    # detection, which the GPU timer does not bracket.
    n1, r1 = none_stats["frames"][0], radial_stats["frames"][0]
    out["first_frame"] = {"culled_substeps": r1["radial_culling"]["substeps_culled"],
                          "start_free": r1["radial_culling"].get("start_free"),
                          "wall_ms": {"none": n1["wall_ms"], "radial": r1["wall_ms"]},
                          "detection_ms": {"none": detection_ms(n1), "radial": detection_ms(r1)}}
    out["culled_substeps"] = sum(f["radial_culling"]["substeps_culled"] for f in radial_stats["frames"])
    out["violated_substeps"] = sum(f["radial_culling"].get("substeps_violated", 0) for f in radial_stats["frames"])
    out["min_positive_fraction"] = min(1 - f["radial_culling"]["non_positive_faces"] / observed
                                       for f in radial_frames.values())
    return out


def ratio(a, b):
    return "all culled" if b == 0 else f"{a / b:.1f}×"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--glcollide", default=os.path.join(ROOT, "build", "src", "glcollide"))
    ap.add_argument("--frames", type=int, default=45)
    ap.add_argument("--scenes", default="ball")
    ap.add_argument("--subdivisions", default="3,4,5")
    ap.add_argument("--sleeve-resolutions", default="32x20,64x40")
    ap.add_argument("--elbow-resolutions", default="32x31,64x61")
    ap.add_argument("--sheet-resolutions", default="32,48,96")
    ap.add_argument("--observers", default=None,
                    help="collision.observers of the radial runs (auto, objects, clusters; default: the scene's)")
    ap.add_argument("--observer", default=None,
                    help="a user observer X,Y,Z, a segment X,Y,Z;X,Y,Z (m, the first object's own "
                         "coordinates) or none (the scene's observer or skeleton removed: the centroid) for the radial runs; "
                         "either replaces a skeleton (docs/culling.md, \"User observers\", \"Segment observers\", \"Skeletons\")")
    ap.add_argument("--out", default=None)
    ap.add_argument("--write-scenes", default=None)
    ap.add_argument("--stats-dir", default=None)
    args = ap.parse_args()
    results = {"scenes": args.scenes, "frames": args.frames, "observer": args.observer, "sizes": []}
    with tempfile.TemporaryDirectory() as temp:
        work = args.write_scenes or temp
        for scene_name, tag, base in variants(args):
            runs = {}
            for culling in ["none", "radial"]:
                scene = json.loads(json.dumps(base))
                scene["collision"]["culling"] = culling
                if culling == "none":  # the observers' settings serve radial culling only
                    for key in ["observers", "cluster_max_angle", "cluster_max_faces"]:
                        scene["collision"].pop(key, None)
                    for obj in scene["objects"]:
                        obj.pop("observer", None)
                        obj.pop("skeleton", None)
                else:
                    if args.observers:
                        scene["collision"]["observers"] = args.observers
                    if args.observer == "none":  # the automatic observer (the centroid)
                        scene["objects"][0].pop("observer", None)
                        scene["objects"][0].pop("skeleton", None)
                    elif args.observer:  # a point X,Y,Z or a segment X,Y,Z;X,Y,Z
                        scene["objects"][0].pop("skeleton", None)
                        points = [[float(v) for v in p.split(",")] for p in args.observer.split(";")]
                        scene["objects"][0]["observer"] = points[0] if len(points) == 1 else points
                runs[culling] = run(args.glcollide, scene, args.frames, work, f"{tag}_{culling}", args.stats_dir,
                                    args.write_scenes is not None)
            if args.write_scenes:
                continue
            results.setdefault("device", runs["none"]["device"])
            results.setdefault("gl_renderer", runs["none"]["gl_renderer"])
            size = summarize(runs["none"], runs["radial"], 2)
            size["scene"], size["variant"] = scene_name, tag
            print(f"{tag} ({size['faces']} faces): detection {size['all']['detection_ms']}", file=sys.stderr)
            results["sizes"].append(size)
    if args.write_scenes:
        return
    sizes = results["sizes"]
    for scene_name in dict.fromkeys(s["scene"] for s in sizes):
        mine = [s for s in sizes if s["scene"] == scene_name]
        if len(mine) < 2:
            continue
        for culling in ["none", "radial"]:
            a, b = mine[0]["all"]["detection_ms"][culling], mine[-1]["all"]["detection_ms"][culling]
            results[f"cost_exponent_{scene_name}_{culling}"] = math.log(b / a) / math.log(mine[-1]["faces"] / mine[0]["faces"])
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    results["commit"] = commit
    lines = [f"Radial culling on {results['gl_renderer']} ({results['device']}), commit {commit}, "
             f"{args.frames} frames; medians over frames 2..{args.frames} (all) and over the frames in which some "
             "face was not proven positive (folded):", "",
             "| scene | faces | frames | positive (min) | free | violated substeps | CCD pairs none → radial "
             "| TriTri pairs none → radial | detection ms none → radial (culling stage) | speed-up | same answers |",
             "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    for s in sizes:
        for name in ["all", "folded"]:
            x = s[name]
            if x["frames"] == 0:
                lines.append(f"| {s['variant']} | {s['faces']} | {name}: 0 | | | | | | | | |")
                continue
            c, t, d = x["ccd_pairs"], x["tri_tri_pairs"], x["detection_ms"]
            lines.append(f"| {s['variant']} | {s['faces']} | {name}: {x['frames']} | {100 * x['positive_fraction']:.1f} % "
                         f"({100 * s['min_positive_fraction']:.1f} %) | {100 * x['free_fraction']:.1f} % "
                         f"| {s['violated_substeps']} of {s['culled_substeps']} "
                         f"| {c['none']:.0f} → {c['radial']:.0f} ({ratio(c['none'], c['radial'])}) "
                         f"| {t['none']:.0f} → {t['radial']:.0f} ({ratio(t['none'], t['radial'])}) "
                         f"| {d['none']:.2f} → {d['radial']:.2f} ({x['stage_ms']['radial']['RadialCulling']:.2f}) "
                         f"| {d['none'] / d['radial']:.2f}× | {'yes' if s['same_ccd_answers'] else 'NO'} |")
    lines += ["", "First frame (left out above; the start check runs before it, untimed by the GPU timer):", "",
              "| scene | faces | start free | substeps culled | detection ms none → radial | wall ms none → radial |",
              "|---|---:|---|---:|---:|---:|"]
    for s in sizes:
        f1 = s["first_frame"]
        d, w = f1["detection_ms"], f1["wall_ms"]
        lines.append(f"| {s['variant']} | {s['faces']} | {f1['start_free']} | {f1['culled_substeps']} "
                     f"| {d['none']:.2f} → {d['radial']:.2f} | {w['none']:.0f} → {w['radial']:.0f} |")
    for scene_name in dict.fromkeys(s["scene"] for s in sizes):
        if f"cost_exponent_{scene_name}_none" in results:
            lines += ["", f"Cost exponent of the detection time in faces ({scene_name}, all frames): "
                          f"none {results[f'cost_exponent_{scene_name}_none']:.2f}, "
                          f"radial {results[f'cost_exponent_{scene_name}_radial']:.2f}."]
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
