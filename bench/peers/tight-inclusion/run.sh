#!/usr/bin/env bash
# Runs the Tight-Inclusion peer (built by build.sh) on one CPU core: the CCD benchmark's
# Sample-Queries shipped in tests/data/external/ccd-sample-queries (all vertex-face files
# together, then all edge-edge files), and, when a folder of them is given, the Scalable-CCD sets as
# written by glcollide_ccd_sets_csv (cloth-funnel, the funnel's whole broad phase and cloth-ball,
# vf and ee). Double first, then
# float. One JSON object per line on stdout (ti_queries.cpp documents the fields), after a first
# line describing the machine.
#
#   bench/peers/tight-inclusion/run.sh [SETS_CSV_DIR]
#     TI_CORE: the core to pin to with taskset (default 0).
#     GLCOLLIDE_PEER_DIR: where build.sh put the binaries (default /tmp/glcollide-peers).
set -euo pipefail
cd "$(dirname "$0")/../../.."
bin=${GLCOLLIDE_PEER_DIR:-/tmp/glcollide-peers}/tight-inclusion/bin
core=${TI_CORE:-0}
sets_dir=${1:-}
for precision in double float; do
  [ -x "$bin/ti_queries_$precision" ] || { echo "run.sh: $bin/ti_queries_$precision missing: run build.sh first" >&2; exit 1; }
done
command -v taskset >/dev/null || { echo "run.sh: taskset (util-linux) is needed to pin one core" >&2; exit 1; }

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
printf '{"date": "%s", "cpu": "%s", "cores": %s, "pinned_core": %s, "load_average": "%s", "tight_inclusion": "%s"}\n' \
  "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$cpu" "$(nproc)" "$core" "$(cut -d' ' -f1-3 /proc/loadavg)" \
  "$(cat "$bin/../source-commit.txt" 2>/dev/null || echo unknown)"

sample=tests/data/external/ccd-sample-queries
for precision in double float; do
  for kind in vf ee; do
    folder=$([ "$kind" = vf ] && echo vertex-face || echo edge-edge)
    mapfile -t files < <(find "$sample" -path "*/$folder/*" -name '*.csv' | sort)
    taskset -c "$core" "$bin/ti_queries_$precision" --kind "$kind" --set "sample-queries $kind" "${files[@]}"
  done
  if [ -n "$sets_dir" ]; then
    for scene in cloth-funnel cloth-funnel-candidates cloth-ball; do
      for kind in vf ee; do
        taskset -c "$core" "$bin/ti_queries_$precision" --kind "$kind" --set "$scene $kind" "$sets_dir/$scene-$kind.csv"
      done
    done
  fi
done
