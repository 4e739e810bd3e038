#!/usr/bin/env python3
"""Writes a copy of a scene with every object shifted and turned a little, for measurements that
one trajectory of one scene would not decide (a fail-safe rate that depends on where a contact
happens to fall). Each object's transform.translate moves by up to ±SHIFT m in x, y and z and its
transform.rotate_deg turns by up to ±TURN degrees about y, drawn from Python's random.Random(seed).

    bench/perturb_scene.py scenes/tet_pile.json 3 bench/scenes/tet_pile_shifted_3.json

The scene's // comments are dropped (the copy says where it came from in its name); relative
mesh paths are not rewritten, so the copy belongs in a folder at the same depth as the original.
"""
import argparse
import json
import random
import re


def strip_comments(text):
    # Whole-line and trailing // comments outside strings (the shipped scenes have no "//" in strings).
    out = []
    for line in text.splitlines():
        in_string = False
        for i, ch in enumerate(line):
            if ch == '"' and (i == 0 or line[i - 1] != "\\"):
                in_string = not in_string
            if not in_string and line.startswith("//", i):
                line = line[:i]
                break
        out.append(line)
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("seed", type=int)
    ap.add_argument("out")
    ap.add_argument("--shift", type=float, default=0.02, help="m, largest shift per axis (default 0.02)")
    ap.add_argument("--turn", type=float, default=15.0, help="degrees, largest turn about y (default 15)")
    a = ap.parse_args()
    scene = json.loads(strip_comments(open(a.scene).read()))
    rng = random.Random(a.seed)
    for obj in scene["objects"]:
        t = obj.setdefault("transform", {})
        translate = t.get("translate", [0.0, 0.0, 0.0])
        t["translate"] = [round(c + rng.uniform(-a.shift, a.shift), 6) for c in translate]
        rotate = t.get("rotate_deg", [0.0, 0.0, 0.0])
        t["rotate_deg"] = [rotate[0], round(rotate[1] + rng.uniform(-a.turn, a.turn), 4), rotate[2]]
    scene["name"] = f'{scene["name"]} (shifted, seed {a.seed})'
    with open(a.out, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
