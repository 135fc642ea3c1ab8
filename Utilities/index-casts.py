#!/usr/bin/env python3
"""Replaces static_cast<std::size_t>(x) in Source with msynth::ToIndex(x) (Core/Index.h) and
includes that header where it is used; idempotent, so it can be re-run after merges. Usage:
python3 Utilities/index-casts.py REPO [FILES...], then Utilities/check-style.sh --fix.
With --check first: changes nothing, lists the files that still hold a bare cast, exits 1 if any."""
import re, subprocess, sys, pathlib
check = sys.argv[1:2] == ["--check"]
args = sys.argv[2:] if check else sys.argv[1:]
root = pathlib.Path(args[0])
files = args[1:] or subprocess.run(
    ["git", "-C", str(root), "grep", "-l", "static_cast<std::size_t>(", "--", "Source"],
    text=True, stdout=subprocess.PIPE).stdout.split()
found = []
for rel in files:
    p = root / rel
    if not p.exists() or p.name == "Index.h":
        continue
    text = p.read_text()
    if not re.search(r"static_cast<std::size_t>\((?!\s*(denseSize|std::min\(std::max\(std::floor|std::max\(0\.0))", text):
        continue
    if check:
        found.append(rel)
        continue
    engine = rel.startswith("Source/Engine/")
    name = "ToIndex(" if engine else "msynth::ToIndex("
    # real conversions, not indices: a 128-bit count, rounded times
    keep = re.compile(r"static_cast<std::size_t>\((?=\s*(denseSize|std::min\(std::max\(std::floor|std::max\(0\.0))")
    text = keep.sub("\0KEEP\0", text).replace("static_cast<std::size_t>(", name)
    text = text.replace("\0KEEP\0", "static_cast<std::size_t>(")
    inc = '#include "Core/Index.h"\n' if engine else '#include "Core/Index.h"\n'
    if inc not in text:
        lines = text.split("\n")
        # after the last project include ("...") at the top, else after the first include
        idx = [i for i, l in enumerate(lines[:80]) if l.startswith('#include "')]
        if not idx:
            idx = [i for i, l in enumerate(lines[:80]) if l.startswith("#include")]
        at = idx[-1] + 1 if idx else next(i for i, l in enumerate(lines) if l.startswith("#pragma")) + 1
        lines.insert(at, inc.rstrip("\n"))
        text = "\n".join(lines)
    p.write_text(text)
    print(rel)
if found:
    print("index-casts: static_cast<std::size_t> where msynth::ToIndex (Core/Index.h) belongs "
          "(run python3 Utilities/index-casts.py . then Utilities/check-style.sh --fix):")
    print("\n".join("  " + f for f in found))
    sys.exit(1)
