#!/usr/bin/env python3
"""Checks the size limits of the house: no function under Source/ longer than 100 lines, no source
file longer than 800 lines.

A function is a brace block opened at namespace or class scope after a parameter list (or a
lambda assigned at that scope); its length runs from the line of its opening brace to the line of
its closing brace. Comments, strings and character literals are blanked first, so braces inside
them do not count. Prints every offender and exits 1 if there is one; `--report N` lists every
function of N lines or more instead, longest first.

Utilities/size-exceptions.txt, when it exists, lists offenders allowed for a while ("LINES PATH
NAME", one a line, "#" starts a comment line; a file's NAME is "(file)"): a listed function or
file may not grow beyond its listed size. Keep it empty: a line there is work owed.
"""
import argparse
import pathlib
import re
import sys

FUNCTION_LIMIT = 100
FILE_LIMIT = 800


def blank_comments_and_strings(text):
    """Returns text with comments, string and character literals replaced by spaces (newlines
    kept), so line numbers and braces outside them stay where they are."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not text[i - 1].isalnum()):
            open_paren = text.find("(", i)
            delimiter = text[i + 2:open_paren]
            j = text.find(")" + delimiter + '"', open_paren)
            j = n if j < 0 else j + len(delimiter) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


SCOPE_WORDS = re.compile(r"\b(namespace|class|struct|union|enum)\b")


def functions(path):
    """Yields (name, first line, line count) for each function body in the file."""
    text = blank_comments_and_strings(path.read_text(encoding="utf-8", errors="replace"))
    stack = []  # one entry per open brace: True if it is a scope that may hold functions
    head_start = 0  # where the text before the next brace starts
    for i, c in enumerate(text):
        if c in ";":
            head_start = i + 1
        elif c == "{":
            head = text[head_start:i]
            at_scope = all(entry is True for entry in stack)
            if at_scope and SCOPE_WORDS.search(head) and "(" not in head.split("{")[-1]:
                stack.append(True)
            elif at_scope and ")" in head and not re.search(r"=\s*$", head.strip()):
                stack.append(("function", head, i))
            elif at_scope and head.strip().startswith("extern"):
                stack.append(True)
            else:
                stack.append(False)
            head_start = i + 1
        elif c == "}":
            if stack:
                top = stack.pop()
                if isinstance(top, tuple):
                    _, head, start = top
                    first = text.count("\n", 0, start) + 1
                    last = text.count("\n", 0, i) + 1
                    name = re.findall(r"([~\w:]+)\s*\(", head)
                    yield (name[0] if name else "?"), first, last - first + 1
            head_start = i + 1
    # An unbalanced file is reported by the compiler, not here.


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--report", type=int, metavar="N",
        help="list every function of N lines or more instead of checking")
    parser.add_argument("root", nargs="?", default=pathlib.Path(__file__).resolve().parent.parent)
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    sources = sorted(p for p in (root / "Source").rglob("*") if p.suffix in (".h", ".cxx", ".txx"))
    found = []
    long_files = []
    for path in sources:
        lines = path.read_text(encoding="utf-8", errors="replace").count("\n")
        if lines > FILE_LIMIT:
            long_files.append((lines, path.relative_to(root)))
        for name, first, count in functions(path):
            found.append((count, f"{path.relative_to(root)}:{first}", name))
    if args.report is not None:
        for count, where, name in sorted(found, reverse=True):
            if count >= args.report:
                print(f"{count:5d}  {where}  {name}")
        for lines, path in sorted(long_files, reverse=True):
            print(f"{lines:5d}  {path}  (file)")
        return 0
    allowed = {}
    exceptions = root / "Utilities" / "size-exceptions.txt"
    if exceptions.exists():
        for line in exceptions.read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                size, path, name = line.split()
                allowed[(path, name)] = int(size)
    bad = False
    for count, where, name in sorted(found, reverse=True):
        key = (where.split(":")[0], name)
        if count > FUNCTION_LIMIT and count > allowed.get(key, 0):
            print(f"{where}: function {name} has {count} lines (limit {FUNCTION_LIMIT}"
                + (f", {allowed[key]} until it is split" if key in allowed else "") + ")")
            bad = True
    for lines, path in sorted(long_files, reverse=True):
        key = (str(path), "(file)")
        if lines > allowed.get(key, 0):
            print(f"{path}: {lines} lines (limit {FILE_LIMIT}"
                + (f", {allowed[key]} until it is split" if key in allowed else "") + ")")
            bad = True
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
