#!/usr/bin/env python3
"""Runs a scene and copies of it drawn in other units, and says whether the engine's answers are the
same bits (decision 0020, "Units"). Each copy scales every length by 2^k, every mass (and so every
stiffness and damping) by 2^j, or every time by 2^t (and so velocities, accelerations, stiffnesses
and dampings); with powers of two every float operation is the original one scaled, exactly, so a
constant with a unit is the only way for a copy to part from the original.

    bench/units_probe.py build/src/glcollide scenes/mask_fold.json --frames 10

Prints, for every copy, the first exported frame whose positions (unscaled) differ from the
original's and how many nodes differ there, or "same bits". Needs the scene's effects to hold the
keys it scales (gravity only with the gravity effect); wind and per-area densities are refused
(their units are not rescaled here). Copies and exports go to a temporary folder.
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile

from perturb_scene import strip_comments

COPIES = [("lengths x 2^-12", "length", -12), ("lengths x 2^12", "length", 12),
          ("masses x 2^-10", "mass", -10), ("masses x 2^10", "mass", 10),
          ("times x 2^-3", "time", -3), ("times x 2^3", "time", 3)]


def scaled(scene, kind, e, base_dir):
    d = json.loads(json.dumps(scene))
    if "wind" in d or any("density" in o for o in d["objects"]):
        sys.exit("units_probe.py: wind and densities are not rescaled; remove them")
    s = 2.0 ** e
    c = d.get("collision")
    gravity = "gravity" in d.get("effects", [])
    g = d.get("gravity", [0, -9.81, 0])
    if kind == "length":
        if gravity:
            d["gravity"] = [x * s for x in g]
        if "ground" in d:
            d["ground"]["height"] = d["ground"].get("height", 0.0) * s
        if c is not None:
            c["thickness"] = c.get("thickness", 0.01) * s
            if "ghost_max_perimeter" in c:
                c["ghost_max_perimeter"] *= s
            if "min_separation" in c.get("ccd", {}):
                c["ccd"]["min_separation"] *= s
    if kind == "mass" and c is not None:
        c["stiffness"] = c.get("stiffness", 1e4) * s
        if "damping" in c:
            c["damping"] *= s
    if kind == "time":
        d["time"]["dt"] = d["time"].get("dt", 1.0 / 60.0) * s
        if gravity:
            d["gravity"] = [x / s / s for x in g]
        if "damping" in d:
            d["damping"] /= s
        if c is not None:
            c["stiffness"] = c.get("stiffness", 1e4) / s / s
            if "damping" in c:
                c["damping"] /= s
            if c.get("response", "intersection_free") != "penalty":
                c["relaxation_time"] = c.get("relaxation_time", 0.01) * s
    for o in d["objects"]:
        if "mesh" in o and not os.path.isabs(o["mesh"]):
            o["mesh"] = os.path.join(base_dir, o["mesh"])
        springs = o.get("springs", {})
        if kind == "length":
            t = o.setdefault("transform", {})
            if "translate" in t:
                t["translate"] = [x * s for x in t["translate"]]
            sc = t.get("scale", 1)
            t["scale"] = [x * s for x in sc] if isinstance(sc, list) else sc * s
            if "velocity" in o:
                o["velocity"] = [x * s for x in o["velocity"]]
            pin = o.get("pinned")
            if isinstance(pin, dict):
                pin["inside"] = {k: [x * s for x in v] for k, v in pin["inside"].items()}
        if kind == "mass":
            o["mass"] *= s
            for k in list(springs):
                if "stiffness" in k or k == "damping":
                    springs[k] *= s
        if kind == "time":
            for k in ("velocity", "angular_velocity"):
                if k in o:
                    o[k] = [x / s for x in o[k]]
            for k in list(springs):
                if "stiffness" in k:
                    springs[k] /= s * s
                elif k == "damping":
                    springs[k] /= s
    d.pop("camera", None)
    return d


def positions(path):
    """An OBJ export's vertices as the floats the engine wrote (9 digits round-trip a float)."""
    f32 = lambda x: struct.unpack("f", struct.pack("f", float(x)))[0]
    return [[f32(x) for x in line.split()[1:4]] for line in open(path) if line.startswith("v ")]


def run(binary, scene_path, frames, out):
    subprocess.run([binary, "run", scene_path, "--frames", str(frames), "--quiet", "--export", out],
                   check=True, stdout=subprocess.DEVNULL)
    return sorted(f for f in os.listdir(out) if f.endswith(".obj"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("glcollide")
    ap.add_argument("scene")
    ap.add_argument("--frames", type=int, default=10)
    a = ap.parse_args()
    scene = json.loads(strip_comments(open(a.scene).read()))
    base_dir = os.path.dirname(os.path.abspath(a.scene))
    with tempfile.TemporaryDirectory() as tmp:
        original = os.path.join(tmp, "original.json")
        json.dump(scaled(scene, "none", 0, base_dir), open(original, "w"))
        frames = run(a.glcollide, original, a.frames, os.path.join(tmp, "original"))
        reference = {f: positions(os.path.join(tmp, "original", f)) for f in frames}
        parted = 0
        for name, kind, e in COPIES:
            path = os.path.join(tmp, f"{kind}{e}.json")
            json.dump(scaled(scene, kind, e, base_dir), open(path, "w"))
            run(a.glcollide, path, a.frames, os.path.join(tmp, f"{kind}{e}"))
            unscale = 2.0 ** -e if kind == "length" else 1.0
            verdict = "same bits"
            for f in frames:
                copy = positions(os.path.join(tmp, f"{kind}{e}", f))
                differing = sum(1 for p, q in zip(reference[f], copy) if p != [x * unscale for x in q])
                if differing or len(copy) != len(reference[f]):
                    verdict = f"parts at {f}: {differing} of {len(reference[f])} nodes differ"
                    parted += 1
                    break
            print(f"{name:16} {verdict}")
    return 1 if parted else 0


if __name__ == "__main__":
    sys.exit(main())
