#!/usr/bin/env python3
"""Lists C++ functions longer than a limit (brace counting on comment- and string-free text).

    tools/long-functions.py [--limit N] FILE...    e.g. $(git ls-files "src/*.cpp" "apps/*.cpp")
    tools/long-functions.py --check [--limit N] FILE...

--check (CI): lists only the long functions without a reason, a `//` comment on the line right
above the declaration (or above its `template <...>` line), and exits 1 when there is one.

A function is a `{` at namespace or class scope whose preceding declaration has a parameter
list and is not a control statement, an initialiser or a type; its length counts from the
line where that declaration starts to the closing brace. A heuristic, not a parser:
brace-initialised members in a constructor's initialiser list can hide that constructor."""
import re
import sys

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|return)\b\s*\(?")
TYPE = re.compile(r"(^|[\s;}])(namespace|struct|class|union|enum)\b[^()]*$")


def strip(text):
    """Comments and literals replaced by spaces, newlines kept."""
    out, i, n = [], 0, len(text)
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:end]))
            i = end
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
    text = strip(open(path, encoding="utf-8").read())
    # Preprocessor lines are no part of a declaration.
    text = re.sub(r"(?m)^[ \t]*#.*$", lambda m: " " * len(m.group(0)), text)
    stack = []  # (kind, start line) per open brace: "scope", "function", "other"
    header_start = 0
    for i, c in enumerate(text):
        if c in ";{}":
            if c == "{":
                header = text[header_start:i]
                in_function = any(k == "function" for k, _, _ in stack)
                h = " ".join(header.split())
                kind = "other"
                if not in_function:
                    if TYPE.search(h) or h.startswith("extern"):
                        kind = "scope"
                    elif ")" in h and not CONTROL.match(h) and not h.endswith("=") and "=" not in h.split("(")[0]:
                        kind = "function"
                lead = len(header) - len(header.lstrip())
                start_line = text.count("\n", 0, header_start + lead) + 1
                stack.append((kind, start_line, h))
            elif c == "}" and stack:
                kind, start_line, h = stack.pop()
                if kind == "function":
                    end_line = text.count("\n", 0, i) + 1
                    name = re.sub(r"\s*\(.*", "", h).split()[-1] if "(" in h else h
                    yield end_line - start_line + 1, start_line, name
            header_start = i + 1


def has_reason(path, line):
    """Whether a `//` comment stands right above the declaration starting at `line` (1-based)."""
    lines = open(path, encoding="utf-8").read().split("\n")
    i = line - 2
    while i >= 0 and lines[i].strip().startswith("template"):
        i -= 1
    return i >= 0 and lines[i].strip().startswith("//")


def main(argv):
    limit, check = 80, False
    while argv[:1] in (["--limit"], ["--check"]):
        if argv[0] == "--check":
            check, argv = True, argv[1:]
        else:
            limit, argv = int(argv[1]), argv[2:]
    rows = [(n, f, line, name) for f in argv for n, line, name in functions(f) if n > limit]
    if check:
        rows = [r for r in rows if not has_reason(r[1], r[2])]
    for n, f, line, name in sorted(rows, reverse=True):
        print(f"{n:5d}  {f}:{line}  {name}")
    if check and rows:
        print(f"{len(rows)} function(s) over {limit} lines without a one-line reason above them")
        sys.exit(1)


if __name__ == "__main__":
    main(sys.argv[1:])
