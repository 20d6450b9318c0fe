#!/usr/bin/env python3
"""Rewrites the catalogue table in docs/diagnostics.md from
compiler/support/diagnostic_codes.def (the single source of codes)."""
import pathlib
import re

root = pathlib.Path(__file__).resolve().parent.parent
codes = re.findall(r'^SPIRE_DIAG\((\w+), (\w+), "([^"]+)"\)', (root / "compiler/support/diagnostic_codes.def").read_text(), re.M)
table = ["| Code | Severity | Meaning |", "|---|---|---|"]
table += [f"| {code} | {severity.lower()} | {summary} |" for code, severity, summary in codes]
doc = root / "docs/diagnostics.md"
text = doc.read_text()
start = text.index("| Code | Severity | Meaning |")
end = text.index("\n\n", start)
doc.write_text(text[:start] + "\n".join(table) + text[end:])
