#!/usr/bin/env python3
"""Fails when a C++ file of the repository differs from .clang-format.

Usage: format_test.py CLANG_FORMAT REPO_ROOT

The files are the tracked *.h and *.cpp files (git ls-files) when REPO_ROOT
is a git checkout, else every such file under the source folders. To apply
the style: git ls-files '*.h' '*.cpp' | xargs clang-format -i
"""
import pathlib
import subprocess
import sys

FOLDERS = ("compiler", "engine-demo", "bench", "tests")


def cpp_files(root: pathlib.Path) -> list[str]:
    listed = subprocess.run(["git", "-C", str(root), "ls-files", "*.h", "*.cpp"], capture_output=True, text=True)
    if listed.returncode == 0 and listed.stdout.strip():
        return [str(root / name) for name in listed.stdout.split()]
    return sorted(str(p) for folder in FOLDERS for pattern in ("*.h", "*.cpp") for p in (root / folder).rglob(pattern))


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    clang_format, root = sys.argv[1], pathlib.Path(sys.argv[2])
    files = cpp_files(root)
    if not files:
        print(f"format_test: no C++ files under {root}", file=sys.stderr)
        return 2
    checked = subprocess.run([clang_format, "--dry-run", "--Werror", f"--style=file:{root / '.clang-format'}", *files],
                             capture_output=True, text=True)
    if checked.returncode != 0:
        offenders = sorted({line.split(":")[0] for line in checked.stderr.splitlines() if ": error:" in line})
        print("\n".join(offenders), file=sys.stderr)
        print(f"format_test: {len(offenders)} file(s) differ from .clang-format; apply it with "
              "git ls-files '*.h' '*.cpp' | xargs clang-format -i", file=sys.stderr)
        return 1
    print(f"format_test: {len(files)} files follow .clang-format")
    return 0


if __name__ == "__main__":
    sys.exit(main())
