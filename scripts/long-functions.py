#!/usr/bin/env python3
"""Lists the Rust functions of crates/*/src longer than a limit (80 lines by default), counted from
the line of `fn` to the line of its closing brace (rustfmt's layout: the brace at the indentation of
`fn`). Exits 1 when there is one. Usage: scripts/long-functions.py [LIMIT] [--skip PATH ...]"""

import pathlib
import re
import sys

FN = re.compile(r"^(\s*)(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?(extern\s+\"[^\"]*\"\s+)?fn\s+(\w+)")


def long_functions(root, limit, skip):
    found = []
    for path in sorted(root.glob("crates/*/src/**/*.rs")):
        rel = path.relative_to(root).as_posix()
        if any(rel == s or rel.startswith(s.rstrip("/") + "/") for s in skip):
            continue
        lines = path.read_text().splitlines()
        for i, line in enumerate(lines):
            m = FN.match(line)
            if not m:
                continue
            indent = m.group(1)
            end = None
            for j in range(i, len(lines)):
                text = lines[j]
                if j == i and (text.rstrip().endswith("}") or text.rstrip().endswith(";")):
                    end = i
                    break
                if j > i and text.startswith(indent) and text[len(indent):].startswith(("{", "}")) is False:
                    pass
                if j > i and text.rstrip() == indent + "}":
                    end = j
                    break
                if j > i and text.rstrip().endswith(";") and text.startswith(indent) and not text[len(indent):].startswith(" ") and end is None and "{" not in "".join(lines[i:j + 1]):
                    end = j  # a declaration without a body
                    break
            if end is None:
                continue
            length = end - i + 1
            if length > limit:
                found.append((length, rel, i + 1, m.group(8)))
    return found


def main():
    args = sys.argv[1:]
    skip = []
    if "--skip" in args:
        k = args.index("--skip")
        skip = args[k + 1:]
        args = args[:k]
    limit = int(args[0]) if args else 80
    root = pathlib.Path(__file__).resolve().parent.parent
    found = long_functions(root, limit, skip)
    for length, rel, line, name in sorted(found, reverse=True):
        print(f"{length:4d}  {rel}:{line}  {name}")
    print(f"{len(found)} function(s) over {limit} lines")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
