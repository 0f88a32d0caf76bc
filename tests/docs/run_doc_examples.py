#!/usr/bin/env python3
"""run_doc_examples.py DOC.md WORKDIR [--link NAME=PATH]... [--python-as NAME]
run_doc_examples.py --check DOCS_DIR TESTED.md...

Runs the code examples of a Markdown page as written, so that the documentation cannot drift
from the product: every fenced block tagged `sh` is run by bash (with `set -e`), in the order of
the page, in WORKDIR. A block tagged `python` is not run by itself: it is written to WORKDIR
under the name the page's shell blocks run it by (`script.py`, or --python-as), as a user who
copies it would save it; the shell blocks then run it (e.g. with pvpython or mpiexec pvbatch).
A page with a python block and no shell block that runs it gets the block run by `python3`.

A block right after the line `<!-- doc-test: skip (REASON) -->` is left out; the reason is
printed (e.g. the block builds and runs this very test suite).

--link NAME=PATH makes WORKDIR/NAME a symbolic link to PATH before the blocks run: the build
tree (`build`) for examples that name build/..., and input files the examples open.
Exit status: that of the first block that fails (its text and output are printed), else 0.

--check lists every `sh`, `bash` or `python` block of DOCS_DIR/*.md that is neither in one of
the TESTED pages (whose tests run them) nor marked with a skip reason, and fails if there is
one: a new example must be run by a test or say why it is not.
"""
import argparse
import os
import re
import subprocess
import sys

FENCE = re.compile(r"^```(\w*)\s*$")
SKIP = re.compile(r"^<!--\s*doc-test:\s*skip\s*\((.*)\)\s*-->\s*$")


def blocks(path):
    """(language, text, line, skip_reason) of each fenced block, in order."""
    out = []
    lines = open(path, encoding="utf-8").read().splitlines()
    i = 0
    skip = None
    while i < len(lines):
        m = SKIP.match(lines[i])
        if m:
            skip = m.group(1)
            i += 1
            continue
        m = FENCE.match(lines[i])
        if m:
            start = i + 1
            j = start
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            out.append((m.group(1), "\n".join(lines[start:j]) + "\n", start, skip))
            skip = None
            i = j + 1
            continue
        if lines[i].strip():
            skip = None
        i += 1
    return out


def check(docs_dir, tested):
    tested = {os.path.basename(t) for t in tested}
    loose = []
    for name in sorted(os.listdir(docs_dir)):
        if not name.endswith(".md") or name in tested:
            continue
        for lang, _, line, reason in blocks(os.path.join(docs_dir, name)):
            if lang in ("sh", "bash", "python") and reason is None:
                loose.append("%s:%d (%s)" % (name, line, lang))
    for item in loose:
        print("not run by a test and not marked '<!-- doc-test: skip (reason) -->':", item)
    print("%d example block(s) unaccounted for" % len(loose))
    return 1 if loose else 0


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--check":
        return check(sys.argv[2], sys.argv[3:])
    parser = argparse.ArgumentParser()
    parser.add_argument("doc")
    parser.add_argument("workdir")
    parser.add_argument("--link", action="append", default=[])
    parser.add_argument("--python-as", default="script.py")
    parser.add_argument("--timeout", type=int, default=600)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    for item in args.link:
        name, target = item.split("=", 1)
        link = os.path.join(args.workdir, name)
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.abspath(target), link)
    found = blocks(args.doc)
    python = [b for b in found if b[0] == "python" and b[3] is None]
    shell = [b for b in found if b[0] in ("sh", "bash") and b[3] is None]
    for lang, _, line, reason in found:
        if reason is not None:
            print("%s:%d: %s block skipped (%s)" % (args.doc, line, lang, reason))
    if len(python) > 1:
        sys.exit("%s: %d python blocks; this runner saves one as %s" %
                 (args.doc, len(python), args.python_as))
    runs = []
    if python:
        with open(os.path.join(args.workdir, args.python_as), "w") as f:
            f.write(python[0][1])
        if not any(args.python_as in b[1] for b in shell):
            runs.append(("python3 " + args.python_as, python[0][2]))
    runs = [("set -e\n" + b[1], b[2]) for b in shell] + runs
    if not runs:
        sys.exit("%s: no runnable examples" % args.doc)
    for text, line in runs:
        print("== %s:%d" % (args.doc, line), flush=True)
        run = subprocess.run(["bash", "-c", text], cwd=args.workdir, capture_output=True,
                             text=True, timeout=args.timeout)
        if run.returncode != 0:
            print(text)
            print(run.stdout[-4000:])
            print(run.stderr[-4000:])
            print("%s:%d: the example failed (exit %d)" % (args.doc, line, run.returncode))
            return run.returncode
    print("%s: %d example(s) ran" % (args.doc, len(runs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
