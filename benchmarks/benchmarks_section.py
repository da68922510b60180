#!/usr/bin/env python3
"""Replaces one section of BENCHMARKS.md (or of another Markdown file: the README's asset gallery,
samples/asset_gallery.sh), the text between <!-- NAME:begin --> and <!-- NAME:end -->, with the
file BODY; a section not yet there is appended under HEADING. Every other section stays as it is,
so each script rewrites only its own figures.

    python3 benchmarks/benchmarks_section.py NAME HEADING BODY [BENCHMARKS.md]
"""
import os
import sys


def main() -> int:
    if len(sys.argv) not in (4, 5):
        print(__doc__, file=sys.stderr)
        return 2
    name, heading, body_path = sys.argv[1:4]
    path = sys.argv[4] if len(sys.argv) == 5 else "BENCHMARKS.md"
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    body = open(body_path).read().rstrip("\n")
    text = open(path).read() if os.path.exists(path) else "# Benchmarks\n"
    if begin not in text or end not in text:
        text = text.rstrip("\n") + f"\n\n## {heading}\n\n{begin}\n{end}\n"
    head, _, rest = text.partition(begin)
    _, _, tail = rest.partition(end)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(f"{head}{begin}\n{body}\n{end}{tail}")
    os.replace(tmp, path)  # never a half-written file
    return 0


if __name__ == "__main__":
    sys.exit(main())
