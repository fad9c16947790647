#!/usr/bin/python3
"""The scene format's key tables (`renderer keys`: every reader's keys, with kind, range,
default and meaning) made into configs/schema/scene.schema.json and into the key tables of
configs/README.md, and the check that the committed files are what the tables make.

  tests/scene_keys.py write   # regenerate both files from the renderer's tables
  tests/scene_keys.py check   # fail when either file differs from what the tables make, when
                              # a scene in configs/scenes or configs/stress fails the schema, or
                              # when the renderer and the schema disagree on a bad value (an
                              # unknown key, or a number just outside its range, in every
                              # integrator and estimator type)

configs/README.md holds blocks `<!-- keys: NAME -->` ... `<!-- /keys -->`: NAME is a table
(`camera`, `integrator/tais`) or `category: NAME` (every type of a category, one table each).
RENDERER_BINARY names the renderer (default build/bin/renderer).
"""
import difflib
import json
import os
import pathlib
import re
import subprocess
import sys

import jsonschema

ROOT = pathlib.Path(__file__).resolve().parent.parent
RENDERER = os.environ.get("RENDERER_BINARY", str(ROOT / "build" / "bin" / "renderer"))
SCHEMA_FILE = ROOT / "configs" / "schema" / "scene.schema.json"
README = ROOT / "configs" / "README.md"
SCENE_DIRS = [ROOT / "configs" / "scenes", ROOT / "configs" / "stress"]
BLOCK = re.compile(r"(<!-- keys: (?P<name>[^>]+?) -->\n)(?P<body>.*?)(<!-- /keys -->)", re.S)


def catalogue():
    out = subprocess.run([RENDERER, "keys"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def def_name(table):
    """A $defs name for a table or category ("shape/sphere" -> "shape.sphere")."""
    return table.replace("/", ".")


def ref(name):
    return {"$ref": f"#/$defs/{def_name(name)}"}


# --- the schema ----------------------------------------------------------------------------

SCHEMA_BOUND = {"minimum": "minimum", "maximum": "maximum",
                "exclusive_minimum": "exclusiveMinimum", "exclusive_maximum": "exclusiveMaximum"}


def bounds(spec):
    return {SCHEMA_BOUND[k]: v for k, v in spec.get("range", {}).items()}


def number(spec, kind="number"):
    return {"type": kind, **bounds(spec)}


def triple(items):
    return {"type": "array", "items": items, "minItems": 3, "maxItems": 3}


def colour(spec):
    return {"anyOf": [number(spec), triple(number(spec))]}


def key_schema(spec):
    kind = spec["kind"]
    schema = {
        "number": lambda: number(spec),
        "integer": lambda: number(spec, "integer"),
        "boolean": lambda: {"type": "boolean"},
        "string": lambda: {"type": "string"},
        "choice": lambda: {"enum": spec["choices"]},
        "colour": lambda: colour(spec),
        "vector": lambda: triple({"type": "number"}),
        "numbers": lambda: {"type": "array", "items": number(spec),
                            "minItems": spec["count"], "maxItems": spec["count"]},
        "points": lambda: {"type": "array", "items": triple({"type": "number"}),
                           "minItems": spec["count"]},
        "colour_texture": lambda: {"anyOf": [*colour(spec)["anyOf"], ref("texture")]},
        "number_texture": lambda: {"anyOf": [number(spec), ref("texture")]},
        "object": lambda: ref(spec["refers"]),
        "one_of": lambda: ref(spec["refers"]),
        "list_of": lambda: {"type": "array", "items": ref(spec["refers"])},
        "map_of": lambda: {"type": "object", "additionalProperties": ref(spec["refers"])},
        "custom": lambda: spec["schema"],
    }[kind]()
    return {"description": spec["meaning"], **schema}


def object_schema(tables, extra=None):
    properties, required = {}, []
    for table in tables:
        for spec in table["keys"]:
            properties[spec["name"]] = key_schema(spec)
            if spec["required"]:
                required.append(spec["name"])
    properties.update(extra or {})
    schema = {"type": "object", "properties": properties, "additionalProperties": False}
    if required:
        schema["required"] = required
    return schema


def schema(cat):
    tables = cat["tables"]
    defs = {}
    for name, table in tables.items():
        defs[def_name(name)] = {"description": table["meaning"], **object_schema([table])}
    for name, category in cat["categories"].items():
        common = tables[category["common"]] if "common" in category else {"keys": []}
        common = {"keys": [k for k in common["keys"] if k["name"] != "type"]}
        names = [type_name for type_name, _ in category["types"]]
        branches = []
        for type_name, table in category["types"]:
            variant = object_schema([common, tables[table]],
                                    {"type": {"const": type_name}})
            defs[def_name(table)] = {"description": tables[table]["meaning"], **variant}
            match = {"properties": {"type": {"const": type_name}}, "required": ["type"]}
            if category.get("default_type") == type_name:
                match = {"anyOf": [match, {"not": {"required": ["type"]}}]}
            branches.append({"if": match, "then": ref(table)})
        defs[def_name(name)] = {
            "description": category["meaning"],
            "type": "object",
            "properties": {"type": {"enum": names}},
            **({} if "default_type" in category else {"required": ["type"]}),
            "allOf": branches,
        }
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "Scene file",
        "description": "Generated by tests/scene_keys.py from the renderer's key tables "
                       "(`renderer keys`); do not edit. The renderer also checks what a "
                       "schema cannot say: values that must agree with each other, files, "
                       "and the magnitude of real numbers (configs/README.md).",
        "$ref": f"#/$defs/{def_name(cat['root'])}",
        "$defs": defs,
    }


# --- the docs ------------------------------------------------------------------------------

def fmt(value):
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        value = int(value)
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def range_text(spec):
    r = spec.get("range", {})
    lo = ("(", r["exclusive_minimum"]) if "exclusive_minimum" in r else \
        ("[", r["minimum"]) if "minimum" in r else None
    hi = (")", r["exclusive_maximum"]) if "exclusive_maximum" in r else \
        ("]", r["maximum"]) if "maximum" in r else None
    if lo and hi:
        return f" in {lo[0]}{fmt(lo[1])}, {fmt(hi[1])}{hi[0]}"
    if lo:
        return f" {'>' if lo[0] == '(' else '≥'} {fmt(lo[1])}"
    if hi:
        return f" {'<' if hi[0] == ')' else '≤'} {fmt(hi[1])}"
    return ""


def value_text(spec):
    kind = spec["kind"]
    if kind == "custom":
        return spec["value_text"]
    if kind == "choice":
        return ", ".join(f'`"{c}"`' for c in spec["choices"])
    simple = {"number": "number", "integer": "integer", "colour": "colour",
              "colour_texture": "colour texture", "number_texture": "number texture"}
    if kind in simple:
        return simple[kind] + range_text(spec)
    return {
        "boolean": lambda: "boolean",
        "string": lambda: "string",
        "vector": lambda: "`[x, y, z]`",
        "numbers": lambda: f"{spec['count']} numbers{range_text(spec)}",
        "points": lambda: f"array of ≥ {spec['count']} points `[x, y, z]`",
        "object": lambda: f"`{spec['refers']}` object",
        "one_of": lambda: f"`{spec['refers']}` object",
        "list_of": lambda: f"array of `{spec['refers']}` objects",
        "map_of": lambda: f"name → `{spec['refers']}` object",
    }[kind]()


def plain(value):
    """A default as written in a scene: 1 rather than 1.0, a float's shortest digits."""
    if isinstance(value, list):
        return [plain(v) for v in value]
    if isinstance(value, float):
        return int(value) if value.is_integer() and abs(value) < 1e15 else float(f"{value:.6g}")
    return value


def default_text(spec):
    if "default" in spec:
        return f"`{json.dumps(plain(spec['default']), ensure_ascii=False)}`"
    if "default_text" in spec:
        return spec["default_text"]
    return "required" if spec["required"] else "—"


def key_table(table):
    rows = [f"| `{k['name']}` | {value_text(k)} | {default_text(k)} | {k['meaning']} |"
            for k in table["keys"] if k["name"] != "type"]
    if not rows:
        return "No keys besides `type`.\n"
    return "| key | value | default | meaning |\n| --- | --- | --- | --- |\n" + \
        "\n".join(rows) + "\n"


def block(cat, name):
    if name.startswith("category: "):
        category = cat["categories"][name[len("category: "):]]
        parts = []
        for type_name, table in category["types"]:
            parts.append(f"**`{type_name}`**: {cat['tables'][table]['meaning']}.\n\n" +
                         key_table(cat["tables"][table]))
        return "\n".join(parts)
    return key_table(cat["tables"][name])


def readme(cat, text):
    missing = [m.group("name") for m in BLOCK.finditer(text)
               if m.group("name") not in cat["tables"] and
               m.group("name")[len("category: "):] not in cat["categories"]]
    if missing:
        raise SystemExit(f"configs/README.md names unknown key tables: {missing}")
    return BLOCK.sub(lambda m: m.group(1) + block(cat, m.group("name")) + m.group(4), text)


# --- the commands --------------------------------------------------------------------------

def schema_text(cat):
    return json.dumps(schema(cat), indent=1, ensure_ascii=False) + "\n"


def scene_errors(schema_json):
    validator = jsonschema.Draft202012Validator(schema_json)
    errors = []
    for directory in SCENE_DIRS:
        for scene in sorted(directory.glob("*.json")):
            for error in validator.iter_errors(json.loads(scene.read_text())):
                where = "/" + "/".join(str(p) for p in error.absolute_path)
                errors.append(f"{scene.relative_to(ROOT)}: {where}: {error.message[:200]}")
    return errors


# --- probes: the renderer and the schema reject the same values -----------------------------

PROBE_SCENE = ROOT / "configs" / "scenes" / "cornell_spheres.json"


def out_of_range(spec):
    """Values just outside a numeric key's range (none for keys without a bound)."""
    r = spec.get("range", {})
    step = 1 if spec["kind"] == "integer" else 0.5
    values = []
    if "minimum" in r:
        values.append(r["minimum"] - step)
    if "exclusive_minimum" in r:
        values.append(r["exclusive_minimum"])
    if "maximum" in r and r["maximum"] < 1e9:
        values.append(r["maximum"] + step)
    if "exclusive_maximum" in r:
        values.append(r["exclusive_maximum"])
    return [int(v) if spec["kind"] == "integer" else v for v in values]


def valid_value(spec, cat):
    """A value a required key accepts (numbers at their lower bound, objects of the category's
    default or first type)."""
    r = spec.get("range", {})
    if spec["kind"] in ("number", "integer"):
        if "minimum" in r:
            return r["minimum"]
        return r["exclusive_minimum"] + 1 if "exclusive_minimum" in r else 1
    if spec["kind"] == "one_of":
        category = cat["categories"][spec["refers"]]
        return {"type": category.get("default_type", category["types"][0][0])}
    raise ValueError(f"no probe value for the required key {spec['name']}")


def probes(cat):
    """(integrator object, pointer the error must name) for every integrator and estimator
    type: an unknown key, and each numeric key just outside its range, each in an object that
    has its type's required keys."""
    slots = [("integrator", lambda obj: obj, "/integrator"),
             ("estimator", lambda obj: {"type": "path_mis", "estimator": obj},
              "/integrator/estimator")]
    for category, wrap, pointer in slots:
        for type_name, table in cat["categories"][category]["types"]:
            keys = cat["tables"][table]["keys"]
            # Keys required always, or by the type's default mode ("required for ...").
            needed = [k for k in keys
                      if k["required"] or k.get("default_text", "").startswith("required")]
            base = {"type": type_name, **{k["name"]: valid_value(k, cat) for k in needed}}
            yield wrap({**base, "no_such_key": 1}), f"{pointer}/no_such_key"
            for spec in keys:
                if spec["kind"] in ("number", "integer"):
                    for value in out_of_range(spec):
                        yield wrap({**base, spec["name"]: value}), f"{pointer}/{spec['name']}"


def names(error, pointer):
    """Whether a schema error is about the value at `pointer` (an unknown key is reported at
    the object that holds it)."""
    where = "/" + "/".join(map(str, error.absolute_path))
    parent, key = pointer.rsplit("/", 1)
    return where == pointer or (where == parent and f"'{key}'" in error.message)


def probe_disagreements(cat, schema_json):
    validator = jsonschema.Draft202012Validator(schema_json)
    scene = json.loads(PROBE_SCENE.read_text())
    problems, count = [], 0
    for integrator, pointer in probes(cat):
        count += 1
        document = {**scene, "integrator": integrator}
        proc = subprocess.run([RENDERER, "check", str(PROBE_SCENE), "--set",
                               "/integrator=" + json.dumps(integrator)],
                              capture_output=True, text=True)
        named = proc.stderr.startswith(f"error: {pointer}: ")
        in_schema = any(names(e, pointer) for e in validator.iter_errors(document))
        if proc.returncode != 2 or not named:
            problems.append(f"renderer accepts or misplaces {json.dumps(integrator)}: "
                            f"{proc.stderr.strip()[:160]}")
        if not in_schema:
            problems.append(f"schema accepts {json.dumps(integrator)} (expected an error at "
                            f"{pointer})")
    return problems, count


def differences(name, committed, generated):
    if committed == generated:
        return []
    diff = difflib.unified_diff(committed.splitlines(), generated.splitlines(),
                                f"{name} (committed)", f"{name} (from the key tables)",
                                lineterm="", n=1)
    return list(diff)[:60]


def main():
    if len(sys.argv) != 2 or sys.argv[1] not in ("write", "check"):
        print(__doc__, file=sys.stderr)
        return 2
    cat = catalogue()
    generated_schema = schema_text(cat)
    generated_readme = readme(cat, README.read_text())
    if sys.argv[1] == "write":
        SCHEMA_FILE.write_text(generated_schema)
        README.write_text(generated_readme)
        print(f"wrote {SCHEMA_FILE.relative_to(ROOT)} and {README.relative_to(ROOT)}")
        return 0
    problems = differences("configs/schema/scene.schema.json",
                           SCHEMA_FILE.read_text() if SCHEMA_FILE.exists() else "",
                           generated_schema)
    problems += differences("configs/README.md", README.read_text(), generated_readme)
    if problems:
        problems.append("the docs or the schema disagree with the renderer's key tables: "
                        "run tests/scene_keys.py write")
    problems += scene_errors(json.loads(generated_schema))
    disagreements, probed = probe_disagreements(cat, json.loads(generated_schema))
    problems += disagreements
    for line in problems:
        print(line)
    scenes = sum(len(list(d.glob("*.json"))) for d in SCENE_DIRS)
    print(f"{len(cat['tables'])} key tables; {scenes} scene files checked against the schema; "
          f"{probed} bad integrator and estimator objects rejected by both the renderer and "
          f"the schema; {'FAILED' if problems else 'ok'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
