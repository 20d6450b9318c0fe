#!/usr/bin/env python3
"""Checks that the folder tree's layers hold: no source includes a header of a
layer that may not see it.

Usage: layering_test.py REPO_ROOT

Every `#include "folder/..."` in compiler/ and engine-demo/ is checked
against ALLOWED below (a layer may always include its own headers). The
table is the architecture: the compiler's stages in order, the engine's
libraries above the compiler's public API. Adding an edge here is a design
decision, so it belongs in review, not in a quiet include. Prints one line per
violation and exits 1 if there is any, 2 on bad usage.
"""

import os
import re
import sys

ALLOWED = {
    # compiler/, one static library per stage
    "support": set(),
    "reflection": {"support"},
    "syntax": {"support"},
    "sema": {"support", "syntax"},
    "graph": {"support", "syntax", "sema"},
    "codegen": {"support", "syntax", "sema", "graph", "reflection"},
    "driver": {"support", "syntax", "sema", "graph", "reflection", "codegen"},
    "simplify": {"support", "syntax", "sema", "graph", "reflection", "codegen", "driver"},
    # engine-demo/
    "vk": {"support"},
    "scene": {"support"},
    "measure": {"support", "scene"},
    "lod": {"support", "scene"},
    "renderer": {"support", "reflection", "graph", "codegen", "driver", "vk", "scene", "measure", "lod"},
    "tool": {"support", "driver", "renderer", "vk", "scene", "measure", "lod"},
    "tune": {"support", "graph", "driver", "renderer", "tool", "vk", "scene", "measure", "lod"},
    "demo": {"support", "driver", "renderer", "tool", "vk", "scene", "measure", "lod"},
    "search": {"support", "syntax", "sema", "graph", "driver", "simplify", "renderer", "tool", "vk", "scene",
               "measure", "lod", "tune"},
    "explore": {"support", "graph", "driver", "renderer", "tool", "vk", "scene", "measure", "lod", "demo", "tune"},
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def violations(root):
    found = []
    for top in ("compiler", "engine-demo"):
        for layer in sorted(os.listdir(os.path.join(root, top))):
            folder = os.path.join(root, top, layer)
            if not os.path.isdir(folder):
                continue
            if layer not in ALLOWED:
                found.append(f"{top}/{layer}: a folder the layering table does not know; add it to ALLOWED")
                continue
            for dirpath, _, files in os.walk(folder):
                for name in sorted(files):
                    if not name.endswith((".h", ".cpp")):
                        continue
                    path = os.path.join(dirpath, name)
                    with open(path, encoding="utf-8") as f:
                        for number, line in enumerate(f, 1):
                            match = INCLUDE.match(line)
                            if not match:
                                continue
                            target = match.group(1)
                            if target != layer and target not in ALLOWED[layer]:
                                found.append(f"{os.path.relpath(path, root)}:{number}: {layer} may not include "
                                             f"{target}/ (allowed: {', '.join(sorted(ALLOWED[layer])) or 'nothing'})")
    return found


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = violations(argv[1])
    for line in found:
        print(line)
    print(f"layering: {len(found)} violation(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
