"""The keys of a world file (docs/worlds.md), written once in the package's config/world_schema.yaml and read both
here and by the simulator (cpp/unexmin/sim/world_schema.h): every Python tool that reads a world file calls
read_world() or check_world(), so an unknown key, a value of the wrong type or out of its range stops it with one
line naming the file and the key's path (`meshes[1].albdo`), as the simulator's start-up does. Needs only PyYAML."""

import difflib
import functools
import math
import os
from pathlib import Path

import yaml

#: Environment variable naming the schema file when the package's config/ folder is not beside this package.
SCHEMA_ENV = "UNEXMIN_WORLD_SCHEMA"


class WorldFileError(ValueError):
    """A world file that does not follow the schema; its message is one line naming the file and the key."""


def schema_path():
    """The schema file: $UNEXMIN_WORLD_SCHEMA if set, else config/world_schema.yaml of the package this Python
    package belongs to; FileNotFoundError naming both places when it is missing."""
    env = os.environ.get(SCHEMA_ENV)
    path = Path(env) if env else Path(__file__).resolve().parents[3] / "config" / "world_schema.yaml"
    if not path.is_file():
        raise FileNotFoundError(
            f"world-file schema {path} not found: expected the unexmin package's config/world_schema.yaml "
            f"(or a file named by ${SCHEMA_ENV})"
        )
    return path


@functools.lru_cache(maxsize=None)
def _load(path):
    with open(path) as f:
        return yaml.safe_load(f)


def schema():
    """The schema as a dict (see the header of config/world_schema.yaml)."""
    return _load(str(schema_path()))


def visibility_levels():
    """The visibility levels a world file and the `visibility` setting accept, as the schema lists them (tuple)."""
    return tuple(schema()["keys"]["visibility"]["keys"]["level"]["choices"])


def key_paths(node=None, prefix=""):
    """Every key path of the schema, depth first in the schema's order: `name`, `water`, `water.density`, ...,
    `meshes[]`, `meshes[].material.kind`, ..."""
    node = schema() if node is None else node
    out = []
    if node.get("type") == "list":
        return key_paths(node["items"], prefix + "[]")
    for key, sub in (node.get("keys") or {}).items():
        path = f"{prefix}.{key}" if prefix else key
        out.append(path + ("[]" if sub.get("type") == "list" else ""))
        out.extend(p for p in key_paths(sub, path) if p != out[-1])
    return out


def _bounds(spec, at_least=">=", at_most="<="):
    """The bounds of a value of `spec`, e.g. ["> 0", "<= 1"]."""
    signs = (("exclusive_min", ">"), ("min", at_least), ("max", at_most))
    return [f"{sign} {spec[key]}" for key, sign in signs if key in spec]


def _range(spec):
    choices = [" \\| ".join(f"`{c}`" for c in spec["choices"])] if spec.get("choices") else []
    return ", ".join(choices + _bounds(spec, "≥", "≤"))


def markdown_table():
    """The table of every key (docs/worlds.md, "Every key"), made from the schema: path, type, unit, range or
    choices, meaning; a required key is marked."""
    rows = ["| key | type | unit | range | meaning |", "| --- | --- | --- | --- | --- |"]

    def walk(node, prefix):
        if node.get("type") == "list":
            return walk(node["items"], prefix + "[]")
        for key, sub in (node.get("keys") or {}).items():
            path = f"{prefix}.{key}" if prefix else key
            shown = path + ("[]" if sub["type"] == "list" else "")
            doc = sub.get("doc", "") + (" (required)" if sub.get("required") else "")
            kind = sub["type"] + (f" or {sub['or']['type']} [{sub['or'].get('unit', '')}]" if sub.get("or") else "")
            rows.append(f"| `{shown}` | {kind} | {sub.get('unit', '')} | {_range(sub)} | {doc} |")
            walk(sub, path)

    walk(schema(), "")
    return "\n".join(rows) + "\n"


def unknown_key_message(path, key, accepted):
    """`unknown key '<path>' (accepted: ...)` and, when one is close, `; did you mean '<nearest>'?`."""
    text = f"unknown key '{path}' (accepted: {', '.join(accepted)})"
    near = difflib.get_close_matches(str(key), accepted, n=1)
    return text + (f"; did you mean '{near[0]}'?" if near else "")


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _expected(spec):
    what = {
        "string": "a string",
        "number": "a finite number",
        "integer": "an integer",
        "bool": "true or false",
        "vec3": "a list of 3 finite numbers",
        "map": "a map",
        "list": "a list",
    }[spec["type"]]
    bounds = _bounds(spec)
    if spec.get("choices"):
        what += " among " + "|".join(spec["choices"])
    if bounds:
        what += (", each " if spec["type"] == "vec3" else ", ") + " and ".join(bounds)
    return what + (f" [{spec['unit']}]" if spec.get("unit") else "")


def _in_range(spec, x):
    return (
        ("exclusive_min" not in spec or x > spec["exclusive_min"])
        and ("min" not in spec or x >= spec["min"])
        and ("max" not in spec or x <= spec["max"])
    )


def _check(spec, value, path, fail, keys_only=False):
    """Checks `value` at `path` against `spec`; with keys_only, only that every key of every map is known."""
    kind = spec["type"]
    if spec.get("or") and kind == "map" and not isinstance(value, dict):  # the key's second form (e.g. a vec3)
        return _check(spec["or"], value, path, fail, keys_only)
    if keys_only and kind not in ("map", "list"):
        return
    bad = lambda: fail(f"'{path}' = {value!r}: expected {_expected(spec)}")  # noqa: E731
    if kind == "map":
        if not isinstance(value, dict):
            return None if keys_only else bad()
        keys = spec.get("keys") or {}
        for key, sub in value.items():
            sub_path = f"{path}.{key}" if path else str(key)
            if key not in keys:
                fail(unknown_key_message(sub_path, key, list(keys)))
            _check(keys[key], sub, sub_path, fail, keys_only)
        for key, sub in keys.items() if not keys_only else ():
            if sub.get("required") and key not in value:
                fail(f"missing '{path + '.' if path else ''}{key}' ({_expected(sub)})")
    elif kind == "list":
        if not isinstance(value, list):
            return None if keys_only else bad()
        for i, item in enumerate(value):
            _check(spec["items"], item, f"{path}[{i}]", fail, keys_only)
    elif kind == "vec3":
        if not (isinstance(value, list) and len(value) == 3 and all(_number(v) and _in_range(spec, v) for v in value)):
            bad()
    elif kind == "number":
        if not (_number(value) and _in_range(spec, value)):
            bad()
    elif kind == "integer":
        if not (isinstance(value, int) and not isinstance(value, bool) and _in_range(spec, value)):
            bad()
    elif kind == "bool":
        if not isinstance(value, bool):
            bad()
    elif kind == "string":
        if value is None or isinstance(value, (dict, list)):
            bad()
        if "choices" in spec and str(value) not in spec["choices"]:
            bad()
    else:
        raise ValueError(f"{schema_path()}: '{path}' has an unknown type {kind!r}")


def check_world(data, file):
    """Checks the parsed world file `data` (read from `file`) against the schema; WorldFileError
    "<file>: <problem>" at the first unknown key (at any level), else the first missing required key or bad value."""

    def fail(problem):
        raise WorldFileError(f"{file}: {problem}")

    if not isinstance(data, dict):
        fail("the world file must be a YAML map (name, gravity, water, meshes, robots, ...)")
    _check(schema(), data, "", fail, keys_only=True)  # an unknown key first, as the simulator reports it
    _check(schema(), data, "", fail)
    return data


def read_world(file):
    """The world file `file` parsed and checked (check_world)."""
    try:
        with open(file) as f:
            data = yaml.safe_load(f)
    except yaml.YAMLError as e:
        raise WorldFileError(f"{file}: not valid YAML: {' '.join(str(e).split())}") from None
    return check_world(data, file)


def main(argv=None):
    import argparse

    argparse.ArgumentParser(
        description="Print the world-file keys of config/world_schema.yaml as the Markdown table of docs/worlds.md."
    ).parse_args(argv)
    print(markdown_table(), end="")


if __name__ == "__main__":
    main()
