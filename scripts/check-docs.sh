#!/usr/bin/env bash
# Docs that cannot drift (issue 25 item 5). Fails, printing FILE:LINE and what is wrong, when
#  (a) a repository path written in the docs does not exist in the tree: every backticked token in
#      a tracked Markdown file, every relative Markdown link target, and every path-like word in
#      a comment of a tracked source file (C++, GLSL, CMake, shell, Python);
#  (b) a Markdown block marked `<!-- check-docs: help -->` (the README's CLI synopsis, the
#      --help pages of docs/cli.md) differs from what the binary prints: the block is a
#      transcript of `$ glcollide ... --help` lines, each followed by that command's output, and
#      every line is compared exactly (the binary's path written as `glcollide`). The README must
#      hold one such block with `$ glcollide --help`.
# Usage: scripts/check-docs.sh [GLCOLLIDE_BINARY]   (default: ${GLCOLLIDE_BUILD_DIR:-build}/src/glcollide)
#        scripts/check-docs.sh --paths-only          (part (a) only: no binary needed)
set -euo pipefail
cd "$(dirname "$0")/.."
binary=${1:-${GLCOLLIDE_BUILD_DIR:-build}/src/glcollide}
if [ "$binary" != --paths-only ] && [ ! -x "$binary" ]; then
  echo "check-docs: error: $binary is not an executable (build first: scripts/build.sh)" >&2
  exit 1
fi
exec python3 - "$binary" <<'PY'
import os, re, shlex, subprocess, sys

binary = sys.argv[1]
# The tree: tracked files plus new files not ignored (what a commit would hold; on a clean clone
# exactly the tracked files).
files = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                       check=True, capture_output=True, text=True).stdout.split("\0")
files = sorted(f for f in files if f and os.path.lexists(f))
dirs = {os.path.dirname(f) for f in files}
for d in list(dirs):
    while d:
        dirs.add(d)
        d = os.path.dirname(d)
entries = set(files) | dirs
top_dirs = sorted({f.split("/", 1)[0] for f in files if "/" in f})
top_files = sorted(f for f in files if "/" not in f)
failures = []
checked = 0

def fail(path, line, message):
    failures.append(f"{path}:{line}: {message}")

# A path-like word: starts with a top-level directory and a slash, or is a top-level file name.
# It must not continue a longer path (build/src/..., ../tests/...) or a URL.
path_chars = r"(?:[\w.\-/*?<>…+~:#@]|\{[^{}\s]*\})"
path_re = re.compile(r"(?<![\w./\-])(?:(?:" + "|".join(re.escape(d) for d in top_dirs) + r")/" +
                     path_chars + r"*|(?:" + "|".join(re.escape(f) for f in top_files) + r")(?![\w\-]))")

def glob_re(pattern):
    out = ""
    i = 0
    while i < len(pattern):
        c = pattern[i]
        if pattern.startswith("**", i):
            out += ".*"; i += 2; continue
        out += {"*": "[^/]*", "?": "[^/]"}.get(c, re.escape(c))
        i += 1
    return re.compile(out + "/?")

stems = {os.path.splitext(f)[0] for f in files}

def exists(path):
    path = path.rstrip("/")
    if any(c in path for c in "*?"):          # a glob matches at least one file or folder
        r = glob_re(path)
        return any(r.fullmatch(e) for e in entries)
    # A C++ module may be named without its extension (`src/cpu/oracle/exact_tri_tri`: .hpp, .cpp).
    return path in entries or ("." not in os.path.basename(path) and path in stems)

# Skip rules, applied only to paths that do not exist (an existing path always passes):
PLACEHOLDER = re.compile(
    r"[<>{}]"             # src/<module>, bench/results/{device}/
    r"|\.\.\.|…"          # src/... (an elided path)
    r"|(?<![A-Za-z])(?!README|LICENSE|CMAKE)[A-Z][A-Z0-9_]*[A-Z](?![a-z])")  # scenes/NAME.json, frame_NNNNNN.png

def check(src, line, token):
    global checked
    checked += 1
    token = re.split(r"[:#]", token, maxsplit=1)[0]   # path:line, path#anchor
    token = token.rstrip(".,;!?)'\"")                  # sentence punctuation after a path
    m = re.search(r"\{([^{}]*,[^{}]*)\}", token)       # x.{hpp,cpp}: each alternative must exist
    if m:
        for alt in m.group(1).split(","):
            check(src, line, token[:m.start()] + alt + token[m.end():])
        return
    if not token or exists(token):
        return
    if PLACEHOLDER.search(token):
        if os.environ.get("CHECK_DOCS_VERBOSE"):
            print(f"check-docs: {src}:{line}: skipped placeholder `{token}`", file=sys.stderr)
        return
    fail(src, line, f"`{token}` does not exist")

def line_of(text, offset):
    return text.count("\n", 0, offset) + 1

# (a) Markdown: inline code spans outside fenced blocks (per paragraph, since a span may wrap but
# never crosses a blank line), and relative link targets.
fence_re = re.compile(r"^ {0,3}(```+|~~~+)")
span_re = re.compile(r"(?<!`)(`+)(?!`)(.+?)(?<!`)\1(?!`)", re.S)
link_re = re.compile(r"\]\(([^()\s]+)(?:\s+\"[^\"]*\")?\)")
help_blocks = {}
for md in (f for f in files if f.endswith(".md")):
    with open(md, encoding="utf-8") as fh:
        lines = fh.read().split("\n")
    prose = []          # (line number, text) outside fences
    fence = None
    marker_at = None
    for n, text in enumerate(lines, 1):
        m = fence_re.match(text)
        if fence is None and m:
            fence = (m.group(1)[0], len(m.group(1)), n)
            if marker_at == n - 1:
                help_blocks.setdefault(md, []).append([n, []])
            continue
        if fence is not None:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= fence[1] and not text.strip()[len(m.group(1)):]:
                fence = None
            elif help_blocks.get(md) and help_blocks[md][-1][0] == fence[2]:
                help_blocks[md][-1][1].append(text)
            continue
        if text.strip() == "<!-- check-docs: help -->":
            marker_at = n
        prose.append((n, text))
    # Paragraphs of prose.
    para, start = [], None
    for n, text in prose + [(None, "")]:
        if text.strip() and n is not None:
            if start is None:
                start = n
            para.append(text)
            continue
        if para:
            body = "\n".join(para)
            for m in span_re.finditer(body):
                ln = start + body.count("\n", 0, m.start(2))
                for w in path_re.finditer(m.group(2)):
                    check(md, ln, w.group(0))
            for m in link_re.finditer(body):
                target = m.group(1)
                ln = start + body.count("\n", 0, m.start(1))
                if re.match(r"[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                    continue   # URLs, mailto:, anchors in the same page
                target = target.split("#", 1)[0]
                resolved = os.path.normpath(os.path.join(os.path.dirname(md), target))
                if resolved.startswith("..") or not exists(resolved):
                    fail(md, ln, f"link target `{target}` does not exist")
        para, start = [], None

# (a) Source comments: every path-like word, backticked or not.
def c_comments(text):
    """(offset, comment text) of // and /* */ comments, skipping string and character literals."""
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            yield i, text[i:j]; i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            yield i, text[i:j]; i = j
        elif c == 'R' and text.startswith('R"', i) and not (i and (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                j = text.find(")" + m.group(1) + '"', i)
                i = n if j < 0 else j + len(m.group(1)) + 2
            else:
                i += 1
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        else:
            i += 1

def hash_comments(text):
    """(offset, comment text) of # comments: a # at a line start or after a blank, outside quotes."""
    offset = 0
    for line in text.split("\n"):
        quote = None
        for k, c in enumerate(line):
            if quote:
                if c == quote:
                    quote = None
            elif c in "\"'":
                quote = c
            elif c == "#" and (k == 0 or line[k - 1] in " \t"):
                yield offset + k, line[k:]
                break
        offset += len(line) + 1

C_LIKE = (".cpp", ".hpp", ".h", ".cpp.in", ".hpp.in", ".glsl", ".comp", ".frag", ".vert")
HASH = (".cmake", ".cmake.in", ".sh", ".py", "CMakeLists.txt")
for src in files:
    base = os.path.basename(src)
    if src.endswith(C_LIKE):
        comments = c_comments
    elif src.endswith(HASH) or src.startswith(("scripts/", ".ci/")) and "." not in base:
        comments = hash_comments
    else:
        continue
    with open(src, encoding="utf-8", errors="replace") as fh:
        text = fh.read()
    for offset, comment in comments(text):
        for w in path_re.finditer(comment):
            check(src, line_of(text, offset + w.start()), w.group(0))

# (b) --help transcripts.
def help_output(args):
    run = subprocess.run([binary] + args, capture_output=True, text=True)
    out = (run.stdout + run.stderr).replace("Usage: " + binary, "Usage: glcollide")
    lines = [l.rstrip() for l in out.split("\n")]
    while lines and not lines[-1]:
        lines.pop()
    return lines

if binary != "--paths-only":
    readme = [b for b in help_blocks.get("README.md", []) if b[1] and b[1][0].strip() == "$ glcollide --help"]
    if not readme:
        fail("README.md", 1, "no CLI synopsis: a ```-block after `<!-- check-docs: help -->` starting with `$ glcollide --help`")
    for md, blocks in sorted(help_blocks.items()):
        for first, body in blocks:
            commands = [k for k, l in enumerate(body) if l.startswith("$ ")]
            if not commands or commands[0] != 0:
                fail(md, first, "a check-docs help block must start with a `$ glcollide ... --help` line")
                continue
            for k, start in enumerate(commands):
                argv = shlex.split(body[start][2:])
                if argv[:1] != ["glcollide"] or argv[-1] not in ("--help", "-h"):
                    fail(md, first + 1 + start, f"not a `glcollide ... --help` command: {body[start]}")
                    continue
                want = [l.rstrip() for l in body[start + 1:commands[k + 1] if k + 1 < len(commands) else len(body)]]
                while want and not want[-1]:
                    want.pop()
                got = help_output(argv[1:])
                for j in range(max(len(want), len(got))):
                    w = want[j] if j < len(want) else "<no line>"
                    g = got[j] if j < len(got) else "<no line>"
                    if w != g:
                        fail(md, first + 2 + start + j,
                             f"differs from `{' '.join(argv)}`:\n  doc:    {w}\n  binary: {g}")
                        break

for f in failures:
    print(f"check-docs: {f}", file=sys.stderr)
if failures:
    print(f"check-docs: {len(failures)} problem(s)", file=sys.stderr)
    sys.exit(1)
print(f"check-docs: {checked} paths written in {sum(f.endswith('.md') for f in files)} Markdown files and in source comments exist"
      + ("" if binary == "--paths-only" else f"; {sum(len(b) for b in help_blocks.values())} --help block(s) match {binary}"))
PY
