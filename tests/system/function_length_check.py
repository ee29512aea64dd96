#!/usr/bin/env python3
"""No function in engine/ or problems/ is longer than LIMIT lines (its signature to its closing
brace, as universal-ctags counts them), except those named in function_length_allowed.txt; and
that list may only shrink: an entry whose function is now within the limit, or gone, fails the
check too, so that it is struck off when the function is carved.

Usage: function_length_check.py ROOT [ALLOWED]   (ALLOWED defaults to the list beside this script)
"""
import json
import re
import pathlib
import subprocess
import sys

LIMIT = 200


def long_functions(root):
    """{(file, function): lines} for every function over LIMIT lines under root/engine and
    root/problems."""
    folders = [str(root / f) for f in ("engine", "problems") if (root / f).is_dir()]
    listing = subprocess.run(
        ["ctags-universal", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne",
         "--output-format=json", "-o", "-", *folders],
        check=True, capture_output=True, text=True).stdout
    found = {}
    for line in listing.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag:
            continue
        lines = tag["end"] - tag["line"] + 1
        if lines > LIMIT:
            name = tag["name"] if "scope" not in tag else tag["scope"] + "::" + tag["name"]
            # An anonymous namespace's tag changes with the file: "(anonymous)" instead.
            name = re.sub(r"__anon[0-9a-f]+", "(anonymous)", name)
            path = str(pathlib.Path(tag["path"]).relative_to(root))
            found[(path, name)] = max(lines, found.get((path, name), 0))
    return found


def allowed_entries(path):
    entries = set()
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            file, name = line.split(None, 1)
            entries.add((file, name.strip()))
    return entries


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    allowed_path = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else \
        pathlib.Path(__file__).with_name("function_length_allowed.txt")
    found = long_functions(root)
    allowed = allowed_entries(allowed_path)
    failures = []
    for (file, name), lines in sorted(found.items()):
        if (file, name) not in allowed:
            failures.append(f"{file}: {name} is {lines} lines, over {LIMIT}: carve it into "
                            "functions of one purpose each")
    for file, name in sorted(allowed - set(found)):
        failures.append(f"{allowed_path.name}: {file} {name} is within {LIMIT} lines now (or "
                        "gone): strike it off the list")
    for failure in failures:
        print(failure)
    print(f"{len(found)} function(s) over {LIMIT} lines, {len(allowed)} allowed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
