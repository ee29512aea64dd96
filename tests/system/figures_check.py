#!/usr/bin/env python3
"""The figures rule of docs/figures.md, checked on README.md and docs/*.md.

1. Every Markdown table with a number in its rows names where its numbers come from within
   the lines above it (back to the previous table or heading): a benchmark, test, script or
   command (`build/tests/benchmarks/benchmark_x`, `tests/system/x_test.cc`, `python3 ...`,
   `ctest -R ...`), or a line `Figures from: ...` saying so.
2. Every benchmark, test source, script or config named anywhere in those files exists, so a
   renamed or deleted command leaves no figure without its source.

Exit status 1 with one line per violation (file:line), 0 otherwise.
"""
import glob
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                       os.path.join(os.path.dirname(__file__), "..", ".."))

SOURCE = re.compile(
    r"(build/tests/benchmarks/benchmark_\w+|build/tests/\w+|build/vesselid|\bbenchmark_\w+"
    r"|tests/[\w/.-]+\.(?:cc|py|h|sh|yaml)|\.ci/\w+|python3 \S+|ctest\b[^`|]*|`vesselid [a-z]+"
    r"|Figures from:)")
# A named file: a path under one of the tree's folders, with an extension.
PATHS = re.compile(r"(?<![\w/.-])((?:tests|configs|engine|problems|examples|docs|\.ci)/[\w/.-]*\.\w+)")
# Figure blocks the docs say no command reproduces yet. The count may only fall: a new figure
# comes with its command.
UNREPRODUCED = "Figures from: not reproduced by a command yet"
MAX_UNREPRODUCED = 0


def exists(reference):
    """Whether a named benchmark, test binary or path is in the tree."""
    name = reference
    if name.startswith("build/tests/benchmarks/") or re.fullmatch(r"benchmark_\w+", name):
        base = os.path.basename(name)
        return (os.path.exists(os.path.join(ROOT, "tests", "benchmarks", base + ".cc")) or
                os.path.exists(os.path.join(ROOT, "tests", "benchmarks", base + ".h")))
    if name.startswith("build/tests/"):
        base = os.path.basename(name)
        return bool(glob.glob(os.path.join(ROOT, "tests", "*", base + ".cc")))
    return os.path.exists(os.path.join(ROOT, name))


def check(path, problems):
    lines = open(path, encoding="utf-8").read().split("\n")
    rel = os.path.relpath(path, ROOT)
    # 2: every named benchmark and path exists.
    for number, line in enumerate(lines, 1):
        for match in re.finditer(r"build/tests/benchmarks/benchmark_\w+|\bbenchmark_\w+", line):
            if not exists(match.group(0)):
                problems.append("%s:%d: names %s, which is not in tests/benchmarks/" %
                                (rel, number, match.group(0)))
        for match in PATHS.finditer(line):
            name = match.group(1).rstrip(".")
            if any(c in name for c in "*{<") or name.endswith("/"):
                continue
            if not exists(name) and not glob.glob(os.path.join(ROOT, name + "*")):
                problems.append("%s:%d: names %s, which is not in the tree" % (rel, number, name))
    # 1: every table of numbers names its source above it.
    start = 0  # first line after the previous table or heading
    number = 0
    while number < len(lines):
        line = lines[number]
        if line.startswith("#"):
            start = number + 1
        if line.startswith("|"):
            end = number
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            rows = lines[number + 2:end]
            if any(re.search(r"\d", row) for row in rows):
                above = "\n".join(lines[max(start, number - 14):number])
                if not SOURCE.search(above):
                    problems.append("%s:%d: a table of numbers without the command or test "
                                    "that gives them (docs/figures.md)" % (rel, number + 1))
            start = end
            number = end
            continue
        number += 1


def main():
    problems = []
    files = [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    for path in files:
        check(path, problems)
    unreproduced = sum(line.startswith(UNREPRODUCED)
                       for path in files for line in open(path, encoding="utf-8"))
    if unreproduced > MAX_UNREPRODUCED:
        problems.append("%d figure blocks say they are not reproduced by a command, more than "
                        "the %d allowed (docs/figures.md)" % (unreproduced, MAX_UNREPRODUCED))
    for problem in problems:
        print(problem)
    print("figures: %d file(s), %d problem(s)" % (len(files), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
