#!/usr/bin/env python3
"""Reports every C++ function whose body is longer than a limit (default 120 lines).

Usage: check_function_length.py [--max-lines N] DIR_OR_FILE...

Scans *.cpp and *.h under each directory. A function body is a `{` block at namespace or class
scope whose opening brace follows a `)`, possibly with qualifiers (const, noexcept, override,
final, mutable, a trailing `-> type`) or a constructor's initializer list in between. Its length
counts the lines from the opening brace to the closing brace, both included. Lambdas and local
classes inside a function count toward that function. Comments, string literals (raw strings
included) and character literals are skipped. Exits 1 if any function is too long, 0 otherwise.
"""

import argparse
import os
import re
import sys

SOURCE_SUFFIXES = (".cpp", ".h")
# Keywords whose `(...)` is followed by a block that is not a function body.
CONTROL_KEYWORDS = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype",
                    "alignof", "noexcept", "requires", "static_assert", "alignas", "defined"}
# Scopes whose braces hold declarations (the scan looks inside them for functions).
SCOPE_KEYWORDS = ("namespace", "class", "struct", "union", "enum", "extern")


def strip_code(text):
    """Returns `text` with comments, strings and character literals blanked out (newlines and
    offsets kept), so that braces and parentheses can be matched by position."""
    out = list(text)
    i, n = 0, len(text)

    def blank(start, end):
        for k in range(start, end):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            blank(i, end)
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            blank(i, end)
            i = end
        elif c == '"' or (c == "R" and text.startswith('R"', i) and
                          (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_"))):
            if c == "R":
                match = re.match(r'R"([^()\\\s]{0,16})\(', text[i:])
                if match:
                    close = ")" + match.group(1) + '"'
                    end = text.find(close, i + match.end())
                    end = n if end < 0 else end + len(close)
                    blank(i, end)
                    i = end
                    continue
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != '"' and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            blank(i, min(j + 1, n))
            i = j + 1
        elif c == "'":
            # A digit separator (1'000'000) is not a character literal.
            if i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_") and \
                    i + 1 < n and text[i + 1].isalnum() and not is_char_prefix(text, i):
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != "'" and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            blank(i, min(j + 1, n))
            i = j + 1
        elif c == "#" and line_start(text, i):
            # Preprocessor line (with continuations): not code for the brace scan.
            j = i
            while j < n:
                end = text.find("\n", j)
                end = n if end < 0 else end
                if end > 0 and text[end - 1] == "\\":
                    j = end + 1
                    continue
                j = end
                break
            blank(i, j)
            i = j
        else:
            i += 1
    return "".join(out)


def is_char_prefix(text, i):
    """True if the quote at `i` follows a character-literal prefix (u8, u, U, L)."""
    for prefix in ("u8", "u", "U", "L"):
        start = i - len(prefix)
        if start >= 0 and text[start:i] == prefix and \
                (start == 0 or not (text[start - 1].isalnum() or text[start - 1] == "_")):
            return True
    return False


def line_start(text, i):
    j = i - 1
    while j >= 0 and text[j] in " \t":
        j -= 1
    return j < 0 or text[j] == "\n"


def matching_open_paren(code, close):
    """Index of the `(` matching the `)` at `close`, or -1."""
    depth = 0
    for k in range(close, -1, -1):
        if code[k] == ")":
            depth += 1
        elif code[k] == "(":
            depth -= 1
            if depth == 0:
                return k
    return -1


def word_before(code, k):
    """The name (qualified, destructor or operator) ending just before the `(` at `k`."""
    head = code[:k].rstrip()
    match = re.search(r"operator\s*(\(\)|\[\]|[^\w\s(]+|\w[\w:<>]*)$", head)
    if match:
        start = match.start()
        qualified = re.search(r"[\w:~]*$", head[:start])
        return head[qualified.start():].strip()
    match = re.search(r"[A-Za-z_~][\w:~]*$", head)
    return match.group(0) if match else ""


def initializer_separator(before):
    """True if `before` (the code before a name) ends with the `,` or `:` of a constructor's
    initializer list (not `::` and not an access specifier's colon)."""
    if before.endswith(","):
        return True
    if not before.endswith(":") or before.endswith("::"):
        return False
    return re.search(r"\b(public|private|protected)\s*:$", before) is None


def function_head(code, brace):
    """If the `{` at `brace` opens a function body, returns the function's name, else None."""
    j = brace - 1
    # Walk back over the tail between `)` and `{`: qualifiers, a trailing return type, or an
    # initializer list `: a_(x), b_{y}`.
    text = code[:brace]
    tail_end = brace
    while True:
        j = tail_end - 1
        while j >= 0 and text[j].isspace():
            j -= 1
        if j < 0:
            return None
        if text[j] == ")":
            open_paren = matching_open_paren(code, j)
            if open_paren < 0:
                return None
            name = word_before(code, open_paren)
            last = re.split(r"::", name)[-1] if name else ""
            if not name or last in CONTROL_KEYWORDS:
                return None
            # An initializer-list entry `member_(x)`: keep walking back to the `:`.
            before = code[:open_paren].rstrip()
            before = before[:len(before) - len(name)].rstrip() if before.endswith(name) else before
            if initializer_separator(before):
                tail_end = len(before) - 1
                continue
            return name
        if text[j] == "}":
            # An initializer-list entry with braces `member_{x}`.
            depth = 0
            k = j
            while k >= 0:
                if code[k] == "}":
                    depth += 1
                elif code[k] == "{":
                    depth -= 1
                    if depth == 0:
                        break
                k -= 1
            before = code[:k].rstrip()
            match = re.search(r"[A-Za-z_]\w*$", before)
            if not match:
                return None
            before = before[:match.start()].rstrip()
            if initializer_separator(before):
                tail_end = len(before) - 1
                continue
            return None
        match = re.search(r"(const|noexcept|override|final|mutable|volatile|&&|&)$",
                          text[:j + 1])
        if match:
            tail_end = match.start()
            continue
        # A trailing return type `-> T`.
        arrow = text.rfind("->", 0, j + 1)
        if arrow >= 0 and ")" not in text[arrow:j + 1] and ";" not in text[arrow:j + 1] and \
                "{" not in text[arrow:j + 1] and "}" not in text[arrow:j + 1]:
            tail_end = arrow
            continue
        return None


def scan(path):
    """Yields (line, name, length) for every function body in the file at `path`."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    code = strip_code(text)
    line_of = []
    line = 1
    for c in code:
        line_of.append(line)
        if c == "\n":
            line += 1
    # Stack of open braces: each entry is ("scope" | "function" | "block", start, name).
    stack = []
    for i, c in enumerate(code):
        if c == "{":
            inside_function = any(kind == "function" for kind, _, _ in stack)
            enclosing_is_scope = all(kind == "scope" for kind, _, _ in stack)
            if inside_function or not enclosing_is_scope:
                stack.append(("block", i, None))
                continue
            name = function_head(code, i)
            if name is not None:
                stack.append(("function", i, name))
            elif is_scope_brace(code, i):
                stack.append(("scope", i, None))
            else:
                stack.append(("block", i, None))
        elif c == "}":
            if not stack:
                continue
            kind, start, name = stack.pop()
            if kind == "function":
                yield line_of[start], name, line_of[i] - line_of[start] + 1


def is_scope_brace(code, brace):
    """True if the `{` at `brace` opens a namespace, class, struct, union, enum or extern block
    (whose contents are declarations to scan)."""
    start = max(code.rfind(";", 0, brace), code.rfind("}", 0, brace), code.rfind("{", 0, brace))
    head = code[start + 1:brace]
    return re.search(r"\b(" + "|".join(SCOPE_KEYWORDS) + r")\b", head) is not None


def source_files(paths):
    for path in paths:
        if os.path.isfile(path):
            yield path
            continue
        for root, dirs, files in os.walk(path):
            dirs.sort()
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.join(root, name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="+", help="directories or files to scan")
    parser.add_argument("--max-lines", type=int, default=120,
                        help="longest allowed function body in lines (default 120)")
    args = parser.parse_args()
    offenders = []
    for path in source_files(args.paths):
        for line, name, length in scan(path):
            if length > args.max_lines:
                offenders.append((path, line, name, length))
    for path, line, name, length in offenders:
        print(f"{path}:{line}: {name}: {length} lines (limit {args.max_lines}); split it "
              "into named steps")
    if offenders:
        print(f"{len(offenders)} function(s) longer than {args.max_lines} lines")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
