#!/usr/bin/env bash
# CI's smoke run of `glcollide bench` (the built-in smoke suite: every experiment kind, tiny
# scenes, one frame) and checks of what it writes: Google Benchmark JSON with the run context,
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
check "headline.md" grep -q "least error: config" "$out/headline.md"

python3 - "$out" <<'PY'
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
for prefix in ["broad_phase/", "narrow_phase/", "integration_ballistic/", "integration_cloth/", "contact/", "scaling/"]:
    assert any(n.startswith(prefix) for n in names), "no entry for " + prefix
for p in ["BBUpdate", "BBCollision", "TriTri", "ContactResponse", "NodeUpdate", "gpu_total", "wall"]:
    assert "broad_phase/two tet boxes/octree d2/" + p in names, "missing pass " + p
# The ground truth was applied: every broad phase found every exact pair, robust disagrees nowhere.
for b in doc["benchmarks"]:
    if b["name"].startswith("broad_phase/") and b["pass"] == "gpu_total":
        assert b["exact_intersecting_pairs"] > 0 and b["accuracy_error"] == 0, b["name"]
    if b["name"].startswith("narrow_phase/") and b["config"] == "robust" and b["pass"] == "gpu_total":
        assert b["accuracy_error"] == 0, b["name"]
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
"$bin" bench --suite smoke --only nonsense --out "$work/bad" >/dev/null 2>"$work/err"
rc=$?
check "unknown experiment exits non-zero" test "$rc" -ne 0
check "unknown experiment is an error naming it" grep -q -- "--only nonsense: no such experiment" "$work/err"

[ "$failures" -eq 0 ] && echo "all bench CLI checks passed"
exit "$failures"
