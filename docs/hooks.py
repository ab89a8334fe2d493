"""MkDocs hook: the reference pages generated at build time, never committed.

- reference/request.md, reply.md, error.md and progress-message.md from proto/*.schema.json (every
  field, its type, default, description, and every enum's values); every schema file there has a page
  (`SCHEMAS`): one without fails the build;
- reference/cli.md from the `--help` of the built `contact` binary and of each of its subcommands.

The binary is $CONTACT_BIN, else target/release/contact (or $CARGO_TARGET_DIR/release/contact).
Without it the build fails, naming the path: a stale or missing `--help` page is an error, not a skip.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

from mkdocs.structure.files import File

REPO = Path(__file__).resolve().parents[1]
PROTO = REPO / "proto"
SCHEMAS = {
    "request": ("The request", "What a client sends to `contact/solve` (or `contact solve FILE` reads)."),
    "reply": ("The reply", "What a solved request answers (also when its `status` is not `solved`)."),
    "error": (
        "The error reply",
        "What a refused request answers (`reply_err` on zenoh; exit code 1 of `contact solve`).",
    ),
    "progress": (
        "The progress message",
        "What a solve publishes on `contact/progress/<key>` while it runs, and what the Python progress callback"
        " receives (without `request_id`, `round`); see [Progress and errors](progress.md).",
    ),
}
#: The page of each schema (reference/progress.md is the hand-written guide to progress and errors).
PAGES = {"progress": "progress-message"}


def schema_pages() -> dict[str, str]:
    """{page URI: kind} of every proto/*.schema.json; a schema without a title in `SCHEMAS` fails the build."""
    kinds = sorted(p.name.removesuffix(".schema.json") for p in PROTO.glob("*.schema.json"))
    missing = [k for k in kinds if k not in SCHEMAS]
    if missing:
        raise RuntimeError(f"docs/hooks.py: proto/{missing[0]}.schema.json has no page: add it to SCHEMAS")
    return {f"reference/{PAGES.get(k, k)}.md": k for k in kinds}


def _text(text: str) -> str:
    """A description as one Markdown line: brackets such as `[length]` are units, not links."""
    return " ".join(str(text).split()).replace("[", "\\[").replace("]", "\\]")


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _anchor(name: str) -> str:
    return name.lower()


def _ref_name(ref: str) -> str:
    return ref.rsplit("/", 1)[-1]


def _consts(variants: list) -> list | None:
    """The (value, description) of a oneOf whose every variant is a constant string, else None."""
    out = []
    for v in variants:
        if "const" in v:
            out.append((v["const"], v.get("description", "")))
        elif "enum" in v:
            out.extend((e, v.get("description", "")) for e in v["enum"])
        else:
            return None
    return out


def type_of(s: dict) -> str:
    """A short Markdown type of a schema node, $refs linked to their section."""
    if "$ref" in s:
        n = _ref_name(s["$ref"])
        return f"[{n}](#{_anchor(n)})"
    if "const" in s:
        return f"`{json.dumps(s['const'])}`"
    if "enum" in s:
        return "one of " + ", ".join(f"`{json.dumps(v)}`" for v in s["enum"])
    for key in ("anyOf", "oneOf"):
        if key in s:
            consts = _consts(s[key])
            if consts is not None:
                return "one of " + ", ".join(f"`{json.dumps(v)}`" for v, _ in consts)
            parts = [type_of(v) for v in s[key]]
            return " or ".join(dict.fromkeys(parts))
    t = s.get("type")
    if isinstance(t, list):
        parts = [type_of({**s, "type": x}) for x in t]
        return " or ".join(dict.fromkeys(parts))
    if t == "array":
        item = type_of(s.get("items", {}))
        n = s.get("minItems")
        if n is not None and n == s.get("maxItems"):
            return f"[{item}; {n}]"
        return f"array of {item}"
    if t == "object" and "additionalProperties" in s and isinstance(s["additionalProperties"], dict):
        return f"map of string to {type_of(s['additionalProperties'])}"
    if t == "integer":
        lo = s.get("minimum")
        return "integer" + (f" ≥ {lo}" if lo is not None else "")
    return t or "any"


def _props_table(s: dict, prefix: str = "") -> list[str]:
    """Rows of a field table for an object node; inline objects are flattened as `a.b`."""
    rows = []
    required = set(s.get("required", []))
    for name, p in sorted(s.get("properties", {}).items()):
        full = f"{prefix}{name}"
        default = f"`{json.dumps(p['default'])}`" if "default" in p else ""
        req = "yes" if name in required else ""
        desc = _text(p.get("description", ""))
        rows.append(f"| `{full}` | {_cell(type_of(p))} | {req} | {_cell(default)} | {_cell(desc)} |")
        if p.get("type") == "object" and "properties" in p:
            rows.extend(_props_table(p, full + "."))
    return rows


_HEADER = ["| field | type | required | default | description |", "|---|---|---|---|---|"]


def render_node(name: str, s: dict) -> list[str]:
    out = [f"## {name}", ""]
    if s.get("description"):
        out += [_text(s["description"]), ""]
    if "properties" in s:
        out += _HEADER + _props_table(s) + [""]
    if "enum" in s:
        out += ["| value |", "|---|"] + [f"| `{json.dumps(v)}` |" for v in s["enum"]] + [""]
    for key in ("oneOf", "anyOf"):
        variants = s.get(key)
        if not variants:
            continue
        consts = _consts(variants)
        if consts is not None:
            out += ["| value | meaning |", "|---|---|"]
            out += [f"| `{json.dumps(v)}` | {_cell(_text(d))} |" for v, d in consts] + [""]
            continue
        out += ["One of:", ""]
        for v in variants:
            props = v.get("properties", {})
            tag = next(iter(props)) if len(props) == 1 and v.get("required") == list(props) else None
            desc = _cell(v.get("description", ""))
            if tag is not None:
                inner = props[tag]
                out += [f"- **`{tag}`**: {type_of(inner) if 'properties' not in inner else 'object'}. {_text(desc)}"]
                if "properties" in inner:
                    out += ["", *("    " + r for r in _HEADER + _props_table(inner, f"{tag}."))]
                out += [""]
            elif "properties" in v:
                out += [f"- an object. {_text(desc)}", "", *("    " + r for r in _HEADER + _props_table(v)), ""]
            else:
                out += [f"- {type_of(v)}. {_text(desc)}", ""]
    return out


def render_schema(kind: str) -> str:
    title, lead = SCHEMAS[kind]
    path = PROTO / f"{kind}.schema.json"
    schema = json.loads(path.read_text(encoding="utf-8"))
    out = [
        f"# {title}",
        "",
        f"{lead} Generated at build time from `proto/{kind}.schema.json` (draft 2020-12), which `contact schema`",
        "writes from the Rust types and a test keeps current.",
        "",
    ]
    if kind == "request":
        out[-1:] = [
            "Fields not marked required may be left out; no field outside these tables is accepted",
            "(`additionalProperties: false`: `invalid_request` at its path).",
            "",
        ]
    out += render_node(schema.get("title", kind), schema)
    for name, node in sorted(schema.get("$defs", {}).items()):
        out += render_node(name, node)
    return "\n".join(out) + "\n"


def contact_bin() -> Path:
    env = os.environ.get("CONTACT_BIN")
    if env:
        return Path(env)
    target = os.environ.get("CARGO_TARGET_DIR")
    return (Path(target) if target else REPO / "target") / "release" / "contact"


def _help(binary: Path, *args: str) -> str:
    run = subprocess.run([str(binary), *args, "--help"], capture_output=True, text=True, timeout=60, check=True)
    return run.stdout


def render_cli() -> str:
    binary = contact_bin()
    if not (binary.is_file() and os.access(binary, os.X_OK)):
        raise RuntimeError(
            f"docs/hooks.py: the contact binary is not at {binary}: build it (`cargo build --release`) "
            "or set CONTACT_BIN; reference/cli.md is generated from its --help"
        )
    top = _help(binary)
    commands = []
    section = False
    for line in top.splitlines():
        if line.startswith("Commands:"):
            section = True
            continue
        if section:
            m = re.match(r"^  (\S+)", line)
            if not line.strip():
                break
            if m and m.group(1) != "help":
                commands.append(m.group(1))
    out = [
        "# The command line",
        "",
        "`contact` is the solver's command line: the Rust binary (`cargo build --release`: `target/release/contact`)",
        "and the `contact` command the Python package installs (the same code, run in process). This page is",
        "the binary's own `--help` and each subcommand's, captured when the site is built.",
        "",
        "Its exit codes: [Validity warnings and exit codes](validity.md).",
        "",
        "## contact",
        "",
        "```text",
        top.rstrip(),
        "```",
        "",
    ]
    for cmd in commands:
        out += [f"## contact {cmd}", "", "```text", _help(binary, cmd).rstrip(), "```", ""]
    return "\n".join(out)


def on_files(files, config):
    pages = {uri: render_schema(kind) for uri, kind in schema_pages().items()}
    pages["reference/cli.md"] = render_cli()
    for uri, text in pages.items():
        files.append(File.generated(config, uri, content=text))
    return files
