"""Paths and helpers shared by the tests (imported by conftest.py and the test modules)."""

from __future__ import annotations

import json
from pathlib import Path

from contact_client.local import free_loopback_port  # noqa: F401  (re-exported for the tests)

# tests/ -> python/ -> clients/ -> repository root
REPO = Path(__file__).resolve().parents[3]
PROTO = REPO / "proto"
EXAMPLES = PROTO / "examples"
HERTZ_EXAMPLE = EXAMPLES / "signorini_hertz_cylinder.json"


def load_json(path: Path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def validator_for(schema: dict):
    """A jsonschema validator of the draft the schema declares in "$schema" (2020-12 expected)."""
    import jsonschema

    cls = jsonschema.validators.validator_for(schema, default=jsonschema.Draft202012Validator)
    cls.check_schema(schema)
    return cls(schema)


# Leaf keys whose values share one scale when comparing near-zero numbers
# (fx ~ 0 by symmetry is measured against fy, not against itself).
_SCALE_GROUPS = {"fx": "force", "fy": "force"}


def _leaf_scales(obj, out: dict, key: str = "") -> dict:
    if isinstance(obj, dict):
        for k, v in obj.items():
            _leaf_scales(v, out, k)
    elif isinstance(obj, list):
        for v in obj:
            _leaf_scales(v, out, key)
    elif isinstance(obj, float) or (isinstance(obj, int) and not isinstance(obj, bool)):
        g = _SCALE_GROUPS.get(key, key)
        out[g] = max(out.get(g, 0.0), abs(float(obj)))
    return out


def diff_replies(a, b, rel: float = 1e-12, skip: tuple[str, ...] = ("timings", "cache")) -> list[str]:
    """Differences between two replies, ignoring the top-level keys in ``skip``.

    Strings, integers and structure must be identical. Floats must agree to
    ``rel`` relative to the larger of the two, or to ``rel`` times the largest
    magnitude of the same field in the reply (so that values that are zero up
    to round-off, like a symmetric fx, compare against their natural scale).
    """
    scales = _leaf_scales(a, {})
    _leaf_scales(b, scales)
    out: list[str] = []

    def walk(x, y, path: str, key: str):
        if isinstance(x, dict) and isinstance(y, dict):
            kx = set(x) - set(skip if path == "" else ())
            ky = set(y) - set(skip if path == "" else ())
            if kx != ky:
                out.append(f"{path or '/'}: keys {sorted(kx ^ ky)} in only one reply")
            for k in sorted(kx & ky):
                walk(x[k], y[k], f"{path}/{k}", k)
        elif isinstance(x, list) and isinstance(y, list):
            if len(x) != len(y):
                out.append(f"{path}: lengths {len(x)} != {len(y)}")
            for i, (u, v) in enumerate(zip(x, y)):
                walk(u, v, f"{path}/{i}", key)
        elif isinstance(x, float) or isinstance(y, float):
            if isinstance(x, bool) or isinstance(y, bool) or not isinstance(x, (int, float)) \
                    or not isinstance(y, (int, float)):
                out.append(f"{path}: {x!r} != {y!r}")
                return
            scale = scales.get(_SCALE_GROUPS.get(key, key), 0.0)
            tol = rel * max(abs(x), abs(y)) + rel * scale
            if abs(x - y) > tol:
                out.append(f"{path}: {x!r} != {y!r} (tol {tol:.3g})")
        elif x != y or type(x) is not type(y):
            out.append(f"{path}: {x!r} != {y!r}")

    walk(a, b, "", "")
    return out
