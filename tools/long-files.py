#!/usr/bin/env python3
"""Fails when a C++ file is longer than a limit: one line per such file, naming it and its length.

    tools/long-files.py [--limit N] PATH...    e.g. --limit 150 apps/cropsight

A PATH that is a folder stands for its .cpp and .hpp files, sub-folders included. Lines are
counted as `wc -l` counts them. Exit 1 when a file is over the limit (default 150), else 0 and
no output. CI holds the CLI to it (.ci/run): a command parses options, calls the library and
formats what it returns, and that fits in 150 lines; a longer one computes what the library
should."""
import os
import sys

SOURCES = (".cpp", ".hpp")


def files(paths):
    for p in paths:
        if os.path.isdir(p):
            for root, dirs, names in os.walk(p):
                dirs.sort()
                yield from (os.path.join(root, n) for n in sorted(names) if n.endswith(SOURCES))
        else:
            yield p


def main(argv):
    limit = 150
    if argv[:1] == ["--limit"]:
        limit, argv = int(argv[1]), argv[2:]
    if not argv:
        sys.exit(__doc__)
    failed = False
    for f in files(argv):
        with open(f, encoding="utf-8") as text:
            n = text.read().count("\n")
        if n > limit:
            print(f"{f}: {n} lines, over the limit of {limit}")
            failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main(sys.argv[1:])
