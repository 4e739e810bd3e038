#!/usr/bin/env python3
"""Markdown table of a collision benchmark JSON (bench/run_collision.sh output)."""
import json
import sys


def main(path):
    d = json.load(open(path))
    ctx = d["context"]
    rows = {}
    for b in d["benchmarks"]:
        name = b["name"].split("/iterations")[0]
        kind, cells, mode, depth, precision = name.split("/")
        faces = int(b["faces_per_body"])
        label = kind.lower()
        if kind == "Octree":
            label = f"octree d{depth.split(':')[1]}" + (" fast" if precision.endswith(":0") else "")
        rows.setdefault(faces, {})[label] = b
    print(f"Collision detection per call (BBUpdate + BBCollision + TriTri), two tet boxes pushed into each")
    print(f"other, robust TriTri unless marked fast, GPU ms from GL timestamp pairs, mean of 3 calls.")
    print(f"**{ctx.get('gl_renderer')} ({ctx.get('gl_version')}), {ctx.get('num_cpus')} CPUs: a CPU rasteriser,")
    print(f"not GPU numbers.** Commit {ctx.get('git_commit')}, {ctx.get('date')}.")
    print()
    print("| faces/body | octree d1 | octree d2 | octree d3 | octree d2 fast | masked | all pairs | all pairs ÷ best octree | candidates | intersecting | tests/intersecting (octree, all pairs) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for faces in sorted(rows):
        r = rows[faces]
        def ms(k):
            return f"{r[k]['gpu_ms']:.1f}" if k in r else "—"
        octs = [r[k]["gpu_ms"] for k in ("octree d1", "octree d2", "octree d3") if k in r]
        ratio = f"{r['allpairs']['gpu_ms'] / min(octs):.0f}×" if "allpairs" in r and octs else "—"
        ref = r.get("octree d3") or r.get("octree d2")
        tpi = f"{ref['tests_per_intersection']:.1f}"
        if "allpairs" in r:
            tpi += f", {r['allpairs']['tests_per_intersection']:.0f}"
        print(f"| {faces} | {ms('octree d1')} | {ms('octree d2')} | {ms('octree d3')} | {ms('octree d2 fast')} | "
              f"{ms('masked')} | {ms('allpairs')} | {ratio} | {int(ref['candidates'])} | {int(ref['intersections'])} | {tpi} |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "bench/results/llvmpipe-collision.json")
