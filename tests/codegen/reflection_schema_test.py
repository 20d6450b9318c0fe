#!/usr/bin/env python3
"""Validates spirec's reflection.json files against docs/reflection.schema.json.

Usage: reflection_schema_test.py SPIREC REPO_ROOT SCRATCH_DIR

Runs SPIREC (from REPO_ROOT, with relative paths) over examples/terrain.spire
without decisions and with every examples/decisions/*.decisions file, over
examples/terrain_five_world.spire without decisions and with every
examples/decisions/five_world/*.decisions file, over examples/couch.spire
without decisions and with every examples/decisions/couch/*.decisions file,
over examples/couch.spire instrumented (--instrument-hazards: hazard records
with checked operations), over examples/lod_library.spire and examples/lod_materials.spire
(instanceImport, textureArrayImport's "layer"), over the engine's test shaders
tests/data/engine/NAME.spire without decisions and with every
tests/data/engine/NAME_*.decisions file, and over a small pipeline written into SCRATCH_DIR
that exercises what the examples do not (bufferImport, bufferExport, hints,
array and matrix strides, a [Stage] attribute). Every reflection.json written
is validated against the schema (JSON Schema draft 2020-12) and checked for
what a schema cannot express:

- the `glsl` and `spirv` files a kernel names exist next to reflection.json,
  and are named after the kernel's world;
- each kernel's `hash` is the 64-bit FNV-1a of its .glsl file's bytes, and
  its `spirvHash` that of its .spv file's bytes;
- the directory is the shader name with `<` as `-` and `>` dropped;
- bindings are unique across the kernels of a variant, and an entry that
  names a `block` matches a block of its kernel (same binding, a member for
  the same component at the same offset).

Every schema variant of input, output and block must be seen at least once,
so that no part of the schema goes untested. Prints one line per file; exits
1 on any failure, 2 on bad usage.
"""

import json
import os
import shutil
import subprocess
import sys

try:
    from jsonschema import Draft202012Validator
except ImportError:  # pragma: no cover - environment problem, not a test result
    print("reflection_schema_test: the Python module 'jsonschema' is missing; "
          "install python3-jsonschema (scripts/install-deps.sh)", file=sys.stderr)
    sys.exit(1)

FNV_OFFSET = 14695981039346656037
FNV_PRIME = 1099511628211

# Schema variants ($defs names) that some entry of some file must match.
# pushConstantInput is not here: only a strategy an application registers
# makes it (the kernel generator's tests cover it).
VARIANTS = {
    "inputs": ["uniformMemberInput", "opaqueUniformInput", "inVariableInput", "textureInput", "bufferInput"],
    "outputs": ["outVariableOutput", "builtinOutput", "bufferOutput"],
    "blocks": ["uniformBlock", "storageBlock"],
}

# Covers the entry kinds the examples do not produce. Simulate is a compute
# kernel (bufferExport) reading particles through bufferImport; Vert reads its
# results through bufferImport at gl_VertexIndex.
SYNTHETIC_SPIRE = """\
pipeline SchemaPipeline {
    abstract world Params;
    abstract world Particles;
    abstract world Mesh;
    world Simulate : "GLSL" export bufferExport;
    [Stage: "vertex"] world Vert : "GLSL" export vertexExport(clipPos);
    world Frag : "GLSL" export standardExport;
    import Params->Simulate using uniformImport;
    import Params->Vert using uniformImport;
    import Params->Frag using uniformImport;
    import Particles->Simulate using bufferImport;
    import Simulate->Vert using bufferImport;
    import Mesh->Vert using standardImport;
    import Vert->Frag using standardImport;
    @Params mat4 viewProj;
    @Params float[3] weights;
    @Params mat3[2] rot;
    @Params float dt;
    @Params sampler2D ramp;
    @Particles vec3 pos;
    @Particles vec3 vel;
    @Mesh vec3 corner;
    @Mesh int id;
    abstract @Vert vec4 clipPos;
    abstract export @Frag vec4 output;
}

shader SchemaShader using SchemaPipeline {
    vec3 newPos = pos + vel * dt * weights[1];
    vec3 p = rot[0] * newPos + corner;
    vec4 clipPos = viewProj * vec4(p, 1.0);
    [Interpolation: "smooth"] [Debug] vec3 color = abs(p);
    mat3 basis = rot[1];
    int ident = id;
    vec4 output = texture(ramp, vec2(float(ident), 0.5)) * vec4(basis * color, 1.0);
}
"""

SYNTHETIC_DECISIONS = """\
[Format: "RGBA32F"] [Precision: "high"] SchemaShader.newPos = Simulate
SchemaShader.color = Vert
SchemaShader.basis = Vert
SchemaShader.ident = Vert
"""


def fnv1a64(data: bytes) -> str:
    h = FNV_OFFSET
    for byte in data:
        h ^= byte
        h = (h * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def closest_variant_errors(error):
    """For a oneOf failure, the errors of the variant the value comes closest to
    matching: the one with the fewest complaints about the object itself (missing
    or unexpected keys), then the fewest complaints overall."""
    if not error.context:
        return [error]
    by_variant = {}
    for sub in error.context:
        by_variant.setdefault(sub.schema_path[0], []).append(sub)
    closest = min(by_variant.values(),
                  key=lambda errors: (sum(1 for e in errors if not e.relative_path), len(errors)))
    return [leaf for sub in closest for leaf in closest_variant_errors(sub)]


def error_lines(validator, document):
    """Readable schema errors: the JSON path and the complaint."""
    lines = []
    for error in sorted(validator.iter_errors(document), key=lambda e: list(map(str, e.absolute_path))):
        for leaf in closest_variant_errors(error):
            path = "/".join(str(p) for p in leaf.absolute_path) or "(root)"
            lines.append(f"{path}: {leaf.message}")
    return lines


def contract_problems(path, document):
    """Checks that need the files on disk or relate several fields."""
    problems = []
    directory = os.path.dirname(path)
    expected_dir = document["shader"].replace("<", "-").replace(">", "")
    if os.path.basename(directory) != expected_dir:
        problems.append(f"directory is '{os.path.basename(directory)}', expected '{expected_dir}' for shader "
                        f"'{document['shader']}'")
    for k, kernel in enumerate(document["kernels"]):
        where = f"kernels/{k} ({kernel['world']})"
        for key, ext in (("glsl", ".glsl"), ("spirv", ".spv")):
            if kernel[key] != kernel["world"] + ext:
                problems.append(f"{where}: {key} is '{kernel[key]}', expected '{kernel['world'] + ext}'")
            if not os.path.isfile(os.path.join(directory, kernel[key])):
                problems.append(f"{where}: {key} file '{kernel[key]}' does not exist next to reflection.json")
        glsl_path = os.path.join(directory, kernel["glsl"])
        if os.path.isfile(glsl_path):
            with open(glsl_path, "rb") as f:
                actual = fnv1a64(f.read())
            if actual != kernel["hash"]:
                problems.append(f"{where}: hash is {kernel['hash']}, but FNV-1a 64 of {kernel['glsl']} is {actual}")
            with open(glsl_path, "rb") as f:
                key = kernel_key(f.read(), kernel)
            if key != kernel["key"]:
                problems.append(f"{where}: key is {kernel['key']}, but the text and interface give {key}")
        spirv_path = os.path.join(directory, kernel["spirv"])
        if "spirvHash" in kernel and os.path.isfile(spirv_path):
            with open(spirv_path, "rb") as f:
                actual = fnv1a64(f.read())
            if actual != kernel["spirvHash"]:
                problems.append(f"{where}: spirvHash is {kernel['spirvHash']}, but FNV-1a 64 of {kernel['spirv']} is "
                                f"{actual}")
        problems += binding_problems(where, kernel)

        blocks = {b["binding"]: b for b in kernel["blocks"]}
        for entry in kernel["inputs"] + kernel["outputs"]:
            if "block" not in entry:
                continue
            block = blocks.get(entry["binding"])
            if block is None or block["name"] != entry["block"]:
                problems.append(f"{where}: '{entry['component']}' names block '{entry['block']}' at binding "
                                f"{entry['binding']}, which this kernel does not declare")
                continue
            if not any(m["component"] == entry["component"] and m["offset"] == entry["offset"]
                       for m in block["members"]):
                problems.append(f"{where}: block '{block['name']}' has no member for '{entry['component']}' at "
                                f"offset {entry['offset']}")
    return problems


def kernel_key(glsl: bytes, kernel) -> str:
    """The content key docs/reflection.md defines: the text, then the interface as compact JSON."""
    interface = {field: kernel[field] for field in ("world", "stage", "inputs", "outputs", "blocks")}
    text = json.dumps(interface, separators=(",", ":"), ensure_ascii=False)
    return fnv1a64(glsl + b"\n" + text.encode("utf-8"))


def binding_problems(where, kernel):
    """Every resource is in the stage's set; no two resources of one kernel share a binding."""
    problems = []
    expected_set = 1 if kernel["stage"] == "fragment" else 0
    owners = {}  # binding -> the block name or component that owns it
    for entry in kernel["blocks"] + kernel["inputs"] + kernel["outputs"]:
        if "binding" not in entry:
            continue
        if entry["set"] != expected_set:
            problems.append(f"{where}: set {entry['set']} in a {kernel['stage']} kernel, expected {expected_set}")
        owner = entry.get("block") or entry.get("name") or entry["component"]
        if owners.setdefault(entry["binding"], owner) != owner:
            problems.append(f"{where}: binding {entry['binding']} holds both '{owners[entry['binding']]}' and '{owner}'")
    return problems


def run_spirec(spirec, root, out_dir, args):
    if os.path.isdir(out_dir):
        shutil.rmtree(out_dir)
    command = [spirec, *args, "-o", out_dir, "--emit", "both"]
    try:
        result = subprocess.run(command, cwd=root, capture_output=True, text=True, check=False)
    except OSError as e:
        return f"cannot run {spirec}: {e}"
    if result.returncode != 0:
        return f"spirec exited with {result.returncode}: {' '.join(command)}\n{result.stderr}"
    return None


def main(argv):
    if len(argv) != 4:
        print(f"usage: {os.path.basename(argv[0])} SPIREC REPO_ROOT SCRATCH_DIR", file=sys.stderr)
        return 2
    spirec, root, scratch = os.path.abspath(argv[1]), os.path.abspath(argv[2]), os.path.abspath(argv[3])
    os.makedirs(scratch, exist_ok=True)

    with open(os.path.join(root, "docs", "reflection.schema.json"), encoding="utf-8") as f:
        schema = json.load(f)
    Draft202012Validator.check_schema(schema)
    validator = Draft202012Validator(schema)
    variant_validators = {
        name: Draft202012Validator({"$schema": schema["$schema"], "$defs": schema["$defs"], "$ref": f"#/$defs/{name}"})
        for names in VARIANTS.values() for name in names
    }
    seen = set()

    synthetic_dir = os.path.join(scratch, "synthetic-src")
    os.makedirs(synthetic_dir, exist_ok=True)
    synthetic_spire = os.path.join(synthetic_dir, "schema_pipeline.spire")
    synthetic_decisions = os.path.join(synthetic_dir, "schema_pipeline.decisions")
    with open(synthetic_spire, "w", encoding="utf-8") as f:
        f.write(SYNTHETIC_SPIRE)
    with open(synthetic_decisions, "w", encoding="utf-8") as f:
        f.write(SYNTHETIC_DECISIONS)

    def decision_files(directory):
        """The .decisions files directly in REPO_ROOT/directory, by name."""
        return sorted(name[:-len(".decisions")] for name in os.listdir(os.path.join(root, directory))
                      if name.endswith(".decisions"))

    runs = []
    for case, source, decisions_dir in (("terrain", "examples/terrain.spire", "examples/decisions"),
                                        ("terrain_five_world", "examples/terrain_five_world.spire",
                                         "examples/decisions/five_world"),
                                        ("couch", "examples/couch.spire", "examples/decisions/couch")):
        runs.append((case, [source]))
        for name in decision_files(decisions_dir):
            runs.append((f"{case}-{name}", [source, "--decisions", f"{decisions_dir}/{name}.decisions"]))
    runs.append(("lod_library", ["examples/lod_library.spire"]))
    runs.append(("lod_materials", ["examples/lod_materials.spire"]))
    # The engine's test shaders: NAME.spire with each NAME_*.decisions.
    engine_dir = "tests/data/engine"
    engine_sources = sorted(name[:-len(".spire")] for name in os.listdir(os.path.join(root, engine_dir))
                            if name.endswith(".spire"))
    for source in engine_sources:
        runs.append((f"engine-{source}", [f"{engine_dir}/{source}.spire"]))
    for name in decision_files(engine_dir):
        owners = [source for source in engine_sources if name.startswith(source + "_")]
        if not owners:
            print(f"FAIL {engine_dir}/{name}.decisions: no {engine_dir}/NAME.spire for it (NAME_*.decisions)")
            return 1
        source = max(owners, key=len)
        runs.append((f"engine-{name}", [f"{engine_dir}/{source}.spire", "--decisions", f"{engine_dir}/{name}.decisions"]))
    runs.append(("synthetic", [synthetic_spire, "--decisions", synthetic_decisions]))
    # Instrumented kernels carry hazard records: the couch's functions and
    # divisions give them checked operations.
    runs.append(("couch-instrumented", ["examples/couch.spire", "--instrument-hazards"]))

    failures = 0
    files = 0
    for case, args in runs:
        out_dir = os.path.join(scratch, case)
        error = run_spirec(spirec, root, out_dir, args)
        if error:
            print(f"FAIL {case}: {error}")
            failures += 1
            continue
        paths = sorted(os.path.join(dirpath, "reflection.json")
                       for dirpath, _, filenames in os.walk(out_dir) if "reflection.json" in filenames)
        if not paths:
            print(f"FAIL {case}: spirec wrote no reflection.json under {out_dir}")
            failures += 1
            continue
        for path in paths:
            files += 1
            label = os.path.relpath(path, scratch)
            try:
                with open(path, encoding="utf-8") as f:
                    document = json.load(f)
            except (OSError, ValueError) as e:
                print(f"FAIL {label}: not readable JSON: {e}")
                failures += 1
                continue
            problems = error_lines(validator, document)
            if not problems:
                problems = contract_problems(path, document)
                for section, names in VARIANTS.items():
                    for kernel in document["kernels"]:
                        for entry in kernel[section]:
                            seen.update(n for n in names if variant_validators[n].is_valid(entry))
                            if "hints" in entry:
                                seen.add("hints")
                        if kernel.get("hazards", {}).get("operations"):
                            seen.add("hazards")
            if problems:
                failures += 1
                print(f"FAIL {label}")
                for problem in problems:
                    print(f"     {problem}")
            else:
                print(f"ok   {label} ({len(document['kernels'])} kernels)")

    missing = [name for names in VARIANTS.values() for name in names if name not in seen]
    if "hints" not in seen:
        missing.append("hints (an output with hints)")
    if "hazards" not in seen:
        missing.append("hazards (an instrumented kernel with checked operations)")
    if missing and failures == 0:
        print(f"FAIL coverage: no generated entry matched schema variant(s) {', '.join(missing)}")
        failures += 1

    print(f"{files} reflection file(s) checked, {failures} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
