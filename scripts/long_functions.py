#!/usr/bin/env python3
"""Lists the functions longer than a limit in C++ sources.

Usage: scripts/long_functions.py [--max N] FILE...

A function is a top-level brace block (outside namespaces, classes, structs,
enums and initialiser lists) whose opening brace ends a declaration; its
length counts the lines from the first line of the declaration to the line
of the matching closing brace. Member functions defined inside a class body
and lambdas are counted as part of what encloses them. Prints
`file:line: name N lines` for each function over the limit (default 120)
and exits 1 when there is one.
"""

import argparse
import re
import sys

SCOPE_RE = re.compile(r"^\s*(namespace\b|extern\s+\"C\"|(template\s*<.*>\s*)?"
                      r"(class|struct|union|enum)\b)")


def strip_code(text):
    """Blanks comments, string and character literals (keeps newlines)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (j - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    lines = strip_code(open(path, encoding="utf-8").read()).split("\n")
    # Stack of open braces: True for a transparent scope (namespace, ...).
    stack = []
    decl_start = None  # first line of the current top-level declaration
    current = None     # (start line, name) of the open function
    for number, line in enumerate(lines, 1):
        code = line.strip()
        in_function = any(not transparent for transparent in stack)
        if not in_function and decl_start is None and code and \
                not code.startswith("#"):
            decl_start = number
        for c in line:
            if c == "{":
                top = not any(not t for t in stack)
                header = " ".join(
                    l.strip() for l in lines[decl_start - 1:number]) \
                    if decl_start else code
                transparent = top and bool(SCOPE_RE.match(header))
                is_function = top and not transparent and "(" in header \
                    and not header.rstrip().endswith("= {") and \
                    not re.search(r"=\s*\{[^}]*$", header)
                if is_function:
                    decl_start = decl_start or number
                    name = re.findall(r"([\w:~<>]+)\s*\(", header)
                    current = (decl_start, name[0] if name else "?")
                stack.append(transparent if (transparent or is_function)
                             else (not top))
                if top and not transparent and not is_function:
                    # A top-level initialiser or similar: not a function.
                    stack[-1] = False
                    current = None
            elif c == "}" and stack:
                stack.pop()
                if not any(not t for t in stack):
                    if current is not None:
                        yield path, current[0], current[1], \
                            number - current[0] + 1
                        current = None
                    decl_start = None
            elif c == ";" and not any(not t for t in stack):
                decl_start = None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--max", type=int, default=120)
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    found = False
    for path in args.files:
        for file, line, name, length in functions(path):
            if length > args.max:
                print(f"{file}:{line}: {name} {length} lines")
                found = True
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
