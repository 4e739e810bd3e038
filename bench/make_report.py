#!/usr/bin/env python3
"""Assembles docs/benchmarks.md and the headline tables of docs/benchmark-snapshots.md from `glcollide bench` outputs.

Every folder bench/results/<device>/ holding a report.md (written by `glcollide bench --out
bench/results/{device}`) becomes one section of docs/benchmarks.md, between the markers
<!-- results:begin --> and <!-- results:end -->, with its plot links made relative to docs/.
The block of docs/benchmark-snapshots.md between <!-- bench-headline:begin --> and <!-- bench-headline:end --> gets
every device's headline table (GPUs first), each under a line naming the device, the commit and
the suite it was measured with (from its bench.json context).
Run by scripts/bench-report.sh; it only rearranges text, it measures nothing.
"""
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, "bench", "results")


def splice(path, begin, end, body):
    text = open(path, encoding="utf-8").read()
    pattern = re.compile(re.escape(begin) + r".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        sys.exit(f"{path}: markers {begin} ... {end} not found")
    text = pattern.sub(lambda _: begin + "\n" + body.rstrip() + "\n" + end, text)
    open(path, "w", encoding="utf-8").write(text)


def devices():
    found = []
    for name in sorted(os.listdir(RESULTS)):
        folder = os.path.join(RESULTS, name)
        if os.path.isfile(os.path.join(folder, "report.md")):
            found.append(name)
    # GPUs first: their numbers are the ones that matter; llvmpipe is the CI reference.
    return sorted(found, key=lambda d: (d == "llvmpipe", d))


def label(device):
    """'NVIDIA H100 80GB HBM3, commit fabad4e, suite `default`' from the device's bench.json."""
    try:
        ctx = json.load(open(os.path.join(RESULTS, device, "bench.json"), encoding="utf-8"))["context"]
    except (OSError, ValueError, KeyError):
        return device + " (no bench.json: device and commit unknown)"
    renderer = ctx.get("gl_renderer", device).split("/")[0]
    commit = (ctx.get("git_commit") or "unknown").split()[0]
    return f"{renderer}, commit {commit}, suite `{ctx.get('suite', '?')}`"


def main():
    found = devices()
    if not found:
        sys.exit("no bench/results/<device>/report.md: run `glcollide bench --out 'bench/results/{device}'` first")
    sections = []
    for device in found:
        report = open(os.path.join(RESULTS, device, "report.md"), encoding="utf-8").read()
        report = re.sub(r"\]\(([^)/]+\.svg)\)", lambda m: f"](../bench/results/{device}/{m.group(1)})", report)
        sections.append(report.rstrip() + f"\n\nRaw results: [bench/results/{device}/bench.json](../bench/results/{device}/bench.json).\n")
    splice(os.path.join(ROOT, "docs", "benchmarks.md"), "<!-- results:begin -->", "<!-- results:end -->",
           "\n".join(sections))
    headlines = []
    for device in found:
        headline = open(os.path.join(RESULTS, device, "headline.md"), encoding="utf-8").read()
        headlines.append(f"#### {label(device)}\n\n" + headline.rstrip() + "\n")
    splice(os.path.join(ROOT, "docs", "benchmark-snapshots.md"), "<!-- bench-headline:begin -->", "<!-- bench-headline:end -->",
           "\n".join(headlines) + "\nAll tables and plots: [docs/benchmarks.md](benchmarks.md).")
    print("docs/benchmarks.md: " + ", ".join(found))


if __name__ == "__main__":
    main()
