#!/usr/bin/env python3
"""Every file the docs name exists: the raw outputs figures come from, the scripts that make them,
the sources they cite. Scans README.md and docs/*.md for repository paths (a known top folder, then
a path ending in a file extension, outside URLs) and fails, naming document, line and path, for
each that is not in the tree. A library's public header may be named short: runtime/lanes.h for
runtime/include/zhf/runtime/lanes.h. Placeholders (order_N.json, t_T.json, xyz.cc) are skipped, and
so are provenance lines ("Run: ..."): they quote a raw file's command as it ran at its commit.

Usage: check_doc_files.py [ROOT]   (default: the repository holding this script)
"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
TOPS = sorted(d for d in os.listdir(ROOT) if os.path.isdir(os.path.join(ROOT, d)) and not d.startswith(".") and not d.startswith("build")
              and d not in ("tools", "tour"))
PATH = re.compile(r"(?<![\w/.:-])((?:%s)/[\w./+-]*\w\.(?:txt|json|svg|csv|md|cc|h|py|sh|ply|sog|spz|glb|cmake|wgsl|hlsl|glsl|cu))(?![\w/])"
                  % "|".join(re.escape(t) for t in TOPS))


def main():
    documents = [os.path.join(ROOT, "README.md")] + sorted(
        os.path.join(ROOT, "docs", f) for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md"))
    missing, named = [], 0
    for document in documents:
        for number, line in enumerate(open(document, encoding="utf-8"), 1):
            if line.startswith("Run: "):
                continue
            for match in PATH.finditer(re.sub(r"https?://\S+", "", line)):
                named += 1
                path = match.group(1)
                if re.search(r"_[A-Z]\.|\bxyz", path):
                    continue
                top, rest = path.split("/", 1)
                if not any(os.path.exists(os.path.join(ROOT, p)) for p in (path, f"{top}/include/zhf/{top}/{rest}")):
                    missing.append(f"{os.path.relpath(document, ROOT)}:{number}: {path} does not exist")
    for m in missing:
        print(m, file=sys.stderr)
    print(f"check_doc_files: {named} paths named in {len(documents)} documents, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
