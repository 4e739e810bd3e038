#!/usr/bin/env bash
# CI's smoke run of `glcollide bench` (the built-in smoke suite: every experiment kind, tiny
# scenes, one frame; the bvh experiment at quick sizes, also alone with --only bvh; the ccd experiment
# on the Sample-Queries unit-tests files, its counts checked against their truth column) and checks of
# what it writes: Google Benchmark JSON with the run context,
# one entry per pass, well-formed SVG plots, the Markdown report; and clear errors for a bad
# suite and an unknown experiment.
# usage: bench_test.sh GLCOLLIDE_BINARY
set -u
bin=$1
. "$(dirname "$0")/check_lib.sh"

"$bin" bench --suite smoke --out "$work/{device}" >"$work/stdout" 2>"$work/stderr"
rc=$?
check "smoke suite exits 0" test "$rc" -eq 0
[ "$rc" -eq 0 ] || cat "$work/stderr"
out=$(ls -d "$work"/*/ 2>/dev/null | head -1)
check "{device} became the renderer's name" test -f "$out/bench.json"
check "table on stdout" grep -q "== broad_phase" "$work/stdout"
check "progress on stderr" grep -q "glcollide bench: broad_phase 1/3" "$work/stderr"
check "report.md" grep -q "### Broad phase (smoke)" "$out/report.md"
check "report.md has the bvh seed tables" grep -q "Seed Tables 1-3 layout" "$out/report.md"
check "report.md has the ccd tables" grep -q "CCD query sets: glcollide GPU" "$out/report.md"
check "the smoke ccd run says the peer is off" grep -q "Tight-Inclusion: not run" "$out/report.md"
check "headline.md" grep -q "least error: config" "$out/headline.md"

GLCOLLIDE_SAMPLE_QUERIES="$(cd "$(dirname "$0")/../data/external/ccd-sample-queries" && pwd)" python3 - "$out" <<'PY'
import json, os, sys, xml.dom.minidom
out = sys.argv[1]
doc = json.load(open(os.path.join(out, "bench.json")))
ctx = doc["context"]
for key in ["date", "gl_renderer", "gl_version", "egl_device", "git_commit", "date_utc", "library_build_type"]:
    assert ctx.get(key), "context lacks " + key
names = [b["name"] for b in doc["benchmarks"]]
for b in doc["benchmarks"]:
    for key in ["name", "run_name", "run_type", "iterations", "real_time", "cpu_time", "time_unit"]:
        assert key in b, b["name"] + " lacks " + key
    assert b["time_unit"] == "ms"
# Every experiment kind and every pass of a collision run are there.
for prefix in ["broad_phase/", "narrow_phase/", "integration_ballistic/", "integration_cloth/", "contact/", "scaling/", "bvh/", "ccd/", "response/"]:
    assert any(n.startswith(prefix) for n in names), "no entry for " + prefix
for p in ["BBUpdate", "BBCollision", "TriTri", "ContactResponse", "NodeUpdate", "gpu_total", "wall"]:
    assert "broad_phase/two tet boxes/octree d2/" + p in names, "missing pass " + p
# The ground truth was applied: every broad phase found every exact pair, robust disagrees nowhere.
for b in doc["benchmarks"]:
    if b["name"].startswith("broad_phase/") and b["pass"] == "gpu_total":
        assert b["exact_intersecting_pairs"] > 0 and b["accuracy_error"] == 0, b["name"]
    if b["name"].startswith("narrow_phase/") and b["config"] == "robust" and b["pass"] == "gpu_total":
        assert b["accuracy_error"] == 0, b["name"]
# The bvh experiment (quick sizes): per-pass times, equal candidates, bytes per face, feature pairs.
bvh = [b for b in doc["benchmarks"] if b["experiment"] == "bvh" and b["pass"] == "gpu_total"]
for size in ["1,000", "2,244", "4,000"]:
    for config in ["bvh", "octree d1", "octree d2", "octree d3"]:
        name = "bvh/folded cloth %s faces/%s/gpu_total" % (size, config)
        assert name in names, "missing " + name
for b in bvh:
    assert not b.get("error_occurred"), b["name"] + ": " + b.get("error_message", "")
    if b.get("engine_step") == 1:
        assert b["gpu_ms_per_substep"] > 0, b["name"]
        continue
    for key in ["candidate_pairs", "broad_phase_ms", "detection_ms", "broad_phase_bytes_per_face",
                "feature_pairs_without_ownership", "feature_pairs_with_ownership", "reference_candidate_pairs"]:
        assert key in b, b["name"] + " lacks " + key
    assert b["candidate_pairs"] == b["reference_candidate_pairs"] and b["accuracy_error"] == 0, b["name"]
    assert b["vf_pairs_gpu"] == b["vf_pairs_with_ownership"] and b["ee_pairs_gpu"] == b["ee_pairs_with_ownership"], b["name"]
    assert b["cpu_checked"] == 1, b["name"]
    if b["config"].startswith("octree"):
        assert "bbupdate_ms" in b and "bbcollision_ms" in b, b["name"]
    else:
        assert "build_ms" in b and "refit_ms" in b and "traverse_ms" in b, b["name"]
summary = [s for s in doc["experiment_summaries"] if s["experiment"] == "bvh"][0]
assert summary["metrics"]["candidates_equal_in_every_configuration"] == 1
assert summary["metrics"]["feature_pairs_gpu_equal_cpu_in_every_run"] == 1
assert summary["metrics"]["bytes_per_face_target"] == 192
assert summary["metrics"]["max_bytes_per_face/bvh"] <= 192
assert summary["metrics"]["slope_detection/bvh"] is not None
titles = [t["title"] for t in summary["tables"]]
for want in ["Seed Tables 1-3 layout", "Cost exponent", "two tet spheres touching", "Memory", "Feature pairs"]:
    assert any(want in t for t in titles), "no table " + want
seed = [t for t in summary["tables"] if t["title"].startswith("Seed Tables 1-3 layout")][0]
assert seed["rows"][0][0] == "2,244" and seed["rows"][0][2] == "23.94 ms", seed["rows"][0]
# The ccd experiment (smoke: the Sample-Queries unit-tests files, no peer): its query counts and
# true positives equal those counted here from the files' own truth column, with no false negative.
import glob
data = os.environ["GLCOLLIDE_SAMPLE_QUERIES"] + "/unit-tests"
for kind, folder in [("vf", "vertex-face"), ("ee", "edge-edge")]:
    rows = []
    for f in sorted(glob.glob(os.path.join(data, folder, "*.csv"))):
        rows += [line.strip().split(",") for line in open(f) if line.strip()]
    queries, positives = len(rows) // 8, sum(int(r[6]) for r in rows[::8])
    b = [b for b in doc["benchmarks"] if b["name"] == "ccd/sample-queries unit-tests %s/glcollide GPU/gpu_total" % kind]
    assert b, "no ccd entry for " + kind
    b = b[0]
    assert b["queries"] == queries and b["truth_positives"] == positives, (kind, b["queries"], queries, b["truth_positives"], positives)
    assert b["false_negatives"] == 0, b["name"]
    assert b["positives"] == positives + b["false_positives"], b["name"]
    assert b["queries_per_second_wall"] > 0, b["name"]
ccd = [s for s in doc["experiment_summaries"] if s["experiment"] == "ccd"][0]
ccd_titles = [t["title"] for t in ccd["tables"]]
for want in ["CCD query sets", "budget", "minimum separation", "2^k"]:
    assert any(want in t for t in ccd_titles), "no ccd table " + want
# The response experiment (smoke: a ball onto a small pinned cloth, every response): its metrics are
# there, and the intersection-free response left no face pair intersecting in any substep.
resp = [b for b in doc["benchmarks"] if b["experiment"] == "response" and b["pass"] == "gpu_total"]
assert sorted(b["config"] for b in resp) == ["bridson", "intersection_free", "penalty"], [b["name"] for b in resp]
for b in resp:
    for key in ["max_intersecting_pairs", "energy_start_j", "energy_end_j", "energy_max_rise_j", "safe_step_fraction",
                "safe_step_froze_all", "solver_iterations_per_substep", "wall_ms_per_substep", "gpu_ms_per_substep"]:
        assert key in b, b["name"] + " lacks " + key
    if b["config"] == "intersection_free":
        assert b["max_intersecting_pairs"] == 0 and 0 <= b["safe_step_fraction"] <= 1, b["name"]
        # The energy guard: how often it acted, and no frame rose beyond the float allowance.
        assert 0 <= b["energy_guard_fraction"] <= 1 and 0 <= b["energy_guard_pull_back_fraction"] <= 1, b["name"]
        assert 0 <= b["energy_guard_back_to_start_fraction"] <= b["energy_guard_pull_back_fraction"], b["name"]
        assert 0 <= b["energy_rise_over_allowance"] <= 1, b["name"]
svgs = [f for f in os.listdir(out) if f.endswith(".svg")]
assert len(svgs) >= 6, svgs
for f in svgs:
    text = open(os.path.join(out, f)).read()
    xml.dom.minidom.parseString(text)
    assert "nan" not in text.lower().replace("nan-", ""), f
    assert f in open(os.path.join(out, "report.md")).read(), f + " not linked from report.md"
print("ok   bench.json schema, %d entries, %d well-formed SVGs" % (len(names), len(svgs)))
PY
check "outputs validated" test $? -eq 0

printf '{"name": "x", "experiments": [{"name": "e", "kind": "speed"}]}' >"$work/bad.json"
"$bin" bench --suite "$work/bad.json" --out "$work/bad" >/dev/null 2>"$work/err"
rc=$?
check "bad suite exits non-zero" test "$rc" -ne 0
check "bad suite names the pointer" grep -q "bad.json: /experiments/0/kind: unknown kind" "$work/err"
"$bin" bench --suite smoke --only bvh --out "$work/bvh" >"$work/bvh.stdout" 2>"$work/bvh.stderr"
rc=$?
check "--only bvh (quick sizes) exits 0" test "$rc" -eq 0
check "--only bvh runs the bvh experiment alone" grep -q "glcollide bench: suite smoke (1 experiments)" "$work/bvh.stderr"
check "--only bvh prints the seed tables" grep -q -- "-- Seed Tables 1-3 layout" "$work/bvh.stdout"
"$bin" bench --suite smoke --only nonsense --out "$work/bad" >/dev/null 2>"$work/err"
rc=$?
check "unknown experiment exits non-zero" test "$rc" -ne 0
check "unknown experiment is an error naming it" grep -q -- "--only nonsense: no such experiment" "$work/err"

[ "$failures" -eq 0 ] && echo "all bench CLI checks passed"
exit "$failures"
