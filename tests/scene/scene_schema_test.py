#!/usr/bin/env python3
"""Checks docs/scene.schema.json against the scene files of the repository.

Usage: scene_schema_test.py REPO_ROOT

- The schema is a valid JSON Schema (draft 2020-12).
- Every examples/scenes/*.json validates against it.
- Every bad scene of the golden diagnostics (tests/golden/scene/*.json) that
  is JSON at all is rejected by the schema, except those whose only errors
  are beyond what a schema can express (SCHEMA_BLIND below), which must be
  accepted, so that this list stays accurate. Files that are not JSON test
  the reader's syntax errors and are skipped.

Prints one line per file; exits 1 on any failure, 2 on bad usage.
"""

import glob
import json
import os
import sys

try:
    from jsonschema import Draft202012Validator
except ImportError:  # pragma: no cover - environment problem, not a test result
    print("scene_schema_test: the Python module 'jsonschema' is missing; "
          "install python3-jsonschema (scripts/install-deps.sh)", file=sys.stderr)
    sys.exit(1)

# Golden scenes whose errors only the loader finds: names that are not
# defined, names defined twice (Python's json keeps the last duplicate key),
# and relations between fields (far > near, a view's direction, cells <= size).
SCHEMA_BLIND = {"unknown_names", "duplicate_names", "semantic_checks"}


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def error_lines(validator, document):
    return [f"{'/'.join(str(p) for p in e.absolute_path) or '(root)'}: {e.message}"
            for e in sorted(validator.iter_errors(document), key=lambda e: list(map(str, e.absolute_path)))]


def main(argv):
    if len(argv) != 2:
        print(f"usage: {os.path.basename(argv[0])} REPO_ROOT", file=sys.stderr)
        return 2
    root = os.path.abspath(argv[1])
    schema = load(os.path.join(root, "docs", "scene.schema.json"))
    Draft202012Validator.check_schema(schema)
    validator = Draft202012Validator(schema)
    failures = 0

    examples = sorted(glob.glob(os.path.join(root, "examples", "scenes", "*.json")))
    if not examples:
        print("FAIL no examples/scenes/*.json found")
        failures += 1
    for path in examples:
        label = os.path.relpath(path, root)
        problems = error_lines(validator, load(path))
        if problems:
            failures += 1
            print(f"FAIL {label}")
            for problem in problems:
                print(f"     {problem}")
        else:
            print(f"ok   {label}")

    seen_blind = set()
    for path in sorted(glob.glob(os.path.join(root, "tests", "golden", "scene", "*.json"))):
        label = os.path.relpath(path, root)
        name = os.path.splitext(os.path.basename(path))[0]
        try:
            document = load(path)
        except ValueError:
            print(f"skip {label} (not JSON: a syntax-error case)")
            continue
        rejected = not validator.is_valid(document)
        if name in SCHEMA_BLIND:
            seen_blind.add(name)
            if rejected:
                failures += 1
                print(f"FAIL {label}: listed as beyond the schema, but the schema rejects it:")
                for problem in error_lines(validator, document):
                    print(f"     {problem}")
            else:
                print(f"ok   {label} (accepted: only the loader finds its errors)")
        elif rejected:
            print(f"ok   {label} (rejected)")
        else:
            failures += 1
            print(f"FAIL {label}: the loader rejects it but the schema accepts it")

    for name in sorted(SCHEMA_BLIND - seen_blind):
        failures += 1
        print(f"FAIL SCHEMA_BLIND names tests/golden/scene/{name}.json, which does not exist")

    print(f"{failures} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
