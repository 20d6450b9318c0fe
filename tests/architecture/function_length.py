#!/usr/bin/env python3
"""Checks that no function in the project's sources is longer than a limit, so
that a function stays one step a reader can hold at once: a longer one is
split into named steps (collectX, checkY, emitZ) rather than grown.

Usage: function_length.py REPO_ROOT LIMIT

Scans the .cpp files under compiler/, engine-demo/ and bench/ (any folder
named tests is skipped: test bodies are tables of cases, not steps). Prints
one line per function longer than LIMIT lines, longest first, as
"LINES FILE:LINE NAME", and exits 1 if there is any, 2 on bad usage.

The check is a heuristic, not a C++ parser:
- Comments, string and character literals, including raw string literals
  (R"(...)" and R"delim(...)delim", over any number of lines), are blanked
  before anything is matched, so that braces and quotes inside them do not
  count. Digit separators (1'000'000) are not character literals.
- A function starts at a line indented by at most two spaces that looks like
  a declarator (a name followed by "(") and is not a statement (return, if,
  for, while, switch), a preprocessor line or a declaration ending in ";". Its
  body is the first "{" within the next 15 lines, before any line that ends
  in ";"; its length runs from that first line to the matching "}",
  signature and braces included.
- So functions nested deeper than two spaces (in a namespace indented
  further, or in a class inside a function) are not seen on their own; they
  count towards their enclosing function, as do lambdas. Macros that expand
  to braces, and brace initializers in a signature's default arguments, can
  mislead it.
"""

import pathlib
import re
import sys

FOLDERS = ("compiler", "engine-demo", "bench")
SKIPPED_FOLDERS = {"tests"}
# How far below a function's first line its body may open.
MAX_SIGNATURE_LINES = 15

HEAD = re.compile(r"^(\s{0,2})([A-Za-z_][\w:<>,\s\*&~\[\]]*?)\b([\w:~]+)\s*\(")
NOT_A_HEAD = ("return", "if", "for", "while", "switch", "#")
RAW_PREFIXES = {"R", "LR", "uR", "UR", "u8R"}


def blank(text):
    """`text` with the contents of comments and literals replaced by spaces;
    newlines are kept, so line numbers do not change."""
    out = []
    i = 0
    n = len(text)

    def keep_newlines(chunk):
        return "".join(c if c == "\n" else " " for c in chunk)

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end == -1 else end
            out.append(keep_newlines(text[i:end]))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end == -1 else end + 2
            out.append(keep_newlines(text[i:end]))
            i = end
        elif c == '"':
            word = re.search(r"[A-Za-z_0-9]*$", "".join(out[-8:]) if out else "").group(0)
            if word in RAW_PREFIXES:
                # R"delim( ... )delim": no escapes, ends at the first )delim".
                open_paren = text.find("(", i + 1)
                delimiter = text[i + 1 : open_paren] if open_paren != -1 else ""
                end = text.find(")" + delimiter + '"', open_paren + 1) if open_paren != -1 else -1
                end = n if end == -1 else end + len(delimiter) + 2
            else:
                end = literal_end(text, i, '"')
            out.append('"' + keep_newlines(text[i + 1 : end - 1]) + '"' if end - i >= 2 else text[i:end])
            i = end
        elif c == "'" and not is_digit_separator(out):
            end = literal_end(text, i, "'")
            out.append("'" + keep_newlines(text[i + 1 : end - 1]) + "'" if end - i >= 2 else text[i:end])
            i = end
        else:
            out.append(c)
            i += 1
    return "".join(out)


def literal_end(text, start, quote):
    """The index after the literal opened by text[start], which is `quote`;
    an unterminated literal ends at the end of its line."""
    i = start + 1
    while i < len(text):
        if text[i] == "\\":
            i += 2
        elif text[i] == quote:
            return i + 1
        elif text[i] == "\n":
            return i
        else:
            i += 1
    return len(text)


def is_digit_separator(out):
    # A quote inside a number (1'000'000, 0xFF'FF) separates digits.
    tail = "".join(out[-32:]) if out else ""
    word = re.search(r"[A-Za-z_0-9']*$", tail).group(0)
    return bool(word) and word[0].isdigit()


def long_functions(path, limit):
    lines = blank(path.read_text(errors="replace")).split("\n")
    found = []
    i = 0
    while i < len(lines):
        line = lines[i]
        head = HEAD.match(line)
        if not head or line.strip().startswith(NOT_A_HEAD) or line.rstrip().endswith(";"):
            i += 1
            continue
        body = None
        for j in range(i, min(len(lines), i + MAX_SIGNATURE_LINES)):
            if "{" in lines[j]:
                body = j
                break
            if lines[j].rstrip().endswith(";"):
                break
        if body is None:
            i += 1
            continue
        depth = 0
        end = body
        while end < len(lines):
            depth += lines[end].count("{") - lines[end].count("}")
            if depth <= 0:
                break
            end += 1
        length = end - i + 1
        if length > limit:
            found.append((length, i + 1, head.group(3)))
        i = end + 1
    return found


def main(argv):
    if len(argv) != 3 or not argv[2].isdigit():
        print("usage: function_length.py REPO_ROOT LIMIT", file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1])
    limit = int(argv[2])
    offenders = []
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*.cpp")):
            if SKIPPED_FOLDERS & set(path.relative_to(root).parts):
                continue
            for length, line, name in long_functions(path, limit):
                offenders.append((length, f"{path.relative_to(root).as_posix()}:{line}", name))
    for length, where, name in sorted(offenders, key=lambda o: (-o[0], o[1])):
        print(f"{length} {where} {name}: longer than {limit} lines; split it into named steps")
    return 1 if offenders else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
