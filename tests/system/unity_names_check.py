#!/usr/bin/env python3
"""File-local names that would collide in a unity build.

With VESSELID_UNITY on, CMake compiles a library's sources eight to a translation unit, so two
sources of one library that define the same name in their anonymous namespaces (a constant
`kUnknown`, a helper `EndsWith(const std::string&, const std::string&)`) stop compiling as
soon as adding a file puts them into one batch. This lists every such pair, whatever the
batches are today:

  * a constant `k<Name>` defined at file level in two sources;
  * a function defined at file level in two sources with the same name and parameter list.

Only sources compiled in batches count (a library's *.cc; the problem families' handle_*.cc
are compiled one per unit), and only pairs within one C++ namespace.
Usage: unity_names_check.py ROOT   (exit 1 and the list when a pair is found)
"""
import collections
import os
import re
import sys

LIBRARIES = ["engine", "problems"]
CONSTANT = re.compile(r"^(?:static )?(?:inline )?(?:constexpr|const) [\w:<>, ]+? (k[A-Z]\w*)\b")
FUNCTION = re.compile(r"^(?:static |inline )*[\w:<>,* &]+? \**&?([A-Z]\w*)\(([^)]*)\)\s*(?:const\s*)?\{")
NAMESPACE = re.compile(r"^namespace ([\w:]+) \{")


def sources(root, library):
    for folder, _, files in os.walk(os.path.join(root, library)):
        for name in sorted(files):
            if name.endswith(".cc") and not name.startswith("handle_"):
                yield os.path.join(folder, name)


def local_names(path):
    """(namespace, kind, name, signature) of each file-level definition in anonymous
    namespaces."""
    names = []
    namespace = ""
    anonymous = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = NAMESPACE.match(line)
            if m:
                namespace = m.group(1)
                continue
            if line.startswith("namespace {"):
                anonymous = True
                continue
            if line.startswith("}  // namespace\n") or line.startswith("}  // namespace\r"):
                anonymous = False
                continue
            if not anonymous:
                continue
            m = CONSTANT.match(line)
            if m:
                names.append((namespace, "constant", m.group(1), ""))
                continue
            m = FUNCTION.match(line)
            if m:
                signature = re.sub(r"\s+", " ", m.group(2)).strip()
                # parameter names do not make an overload: keep the types only
                types = ",".join(re.sub(r"\s*\w+$", "", p.strip()) for p in signature.split(","))
                names.append((namespace, "function", m.group(1), types))
    return names


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    found = []
    for library in LIBRARIES:
        where = collections.defaultdict(list)
        for path in sources(root, library):
            for key in set(local_names(path)):
                where[key].append(os.path.relpath(path, root))
        for (namespace, kind, name, types), paths in sorted(where.items()):
            if len(paths) > 1:
                found.append("%s %s%s in namespace %s: %s" % (
                    kind, name, "(" + types + ")" if kind == "function" else "", namespace,
                    ", ".join(sorted(paths))))
    if found:
        print("file-local names defined in more than one source of a library (they collide "
              "when a unity batch joins the sources; rename one or share it from a header):")
        for line in found:
            print("  " + line)
        return 1
    print("no file-local name is defined twice within a library")
    return 0


if __name__ == "__main__":
    sys.exit(main())
