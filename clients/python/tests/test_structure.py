"""The layout rules of the package, checked on its sources (as
crates/contact-core/tests/structure.rs does for the Rust):

- the modules of ``contact_client`` import each other without a cycle; an import
  anywhere in a module counts, at the top or inside a function (``client`` and
  ``reply`` once imported each other through a function-local import);
- a module over 500 lines says why in its module docstring (a line starting
  ``Length:``).

Imports are read from the syntax tree (``ast``), not by importing: ``import
contact_client.x``, ``from contact_client.x import y``, ``from .x import y`` and
``from . import x`` (an edge to the submodule ``x`` when there is one, else to the
package). The package's ``__init__`` is the node ``contact_client``; the implicit
import of a parent package that every submodule import makes is not an edge, and
the compiled ``_contact`` (no Python source) is not a node.
"""

from __future__ import annotations

import ast
from pathlib import Path

import contact_client

PACKAGE = "contact_client"
ROOT = Path(contact_client.__file__).resolve().parent
MAX_LINES = 500


def module_name(path: Path, root: Path = ROOT, package: str = PACKAGE) -> str:
    """``contact_client/scenes.py`` → ``contact_client.scenes``; an ``__init__.py`` is its package."""
    parts = [package, *path.relative_to(root).with_suffix("").parts]
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def sources(root: Path = ROOT, package: str = PACKAGE) -> dict[str, str]:
    """The text of every module of the package, by module name."""
    return {module_name(p, root, package): p.read_text(encoding="utf-8") for p in sorted(root.rglob("*.py"))}


def import_targets(module: str, text: str, modules: set[str]) -> set[str]:
    """The modules among ``modules`` that ``module`` imports, by any import statement
    anywhere in its ``text`` (itself excluded)."""
    is_package = any(m.startswith(module + ".") for m in modules)
    out: set[str] = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                # `import a.b.c` runs a.b.c (its parents are the implicit imports).
                parts = alias.name.split(".")
                found = [".".join(parts[:k]) for k in range(len(parts), 0, -1) if ".".join(parts[:k]) in modules]
                out.update(found[:1])
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                # Relative to the module's package (a package's __init__ is its own package).
                base = module.split(".") if is_package else module.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                origin = ".".join(base + ([node.module] if node.module else []))
            else:
                origin = node.module or ""
            for alias in node.names:
                # The submodule origin.x when there is one, else origin, where x is defined.
                sub = f"{origin}.{alias.name}"
                out.add(sub if sub in modules else origin)
    return {m for m in out if m in modules and m != module}


def import_graph(texts: dict[str, str]) -> dict[str, set[str]]:
    """module → the modules of ``texts`` it imports."""
    modules = set(texts)
    return {m: import_targets(m, text, modules) for m, text in texts.items()}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """A cycle of ``graph`` as its path [a, b, ..., a], or None (depth-first, in name order)."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(n: str) -> list[str] | None:
        if state.get(n) == 1:
            return [*path[path.index(n):], n]
        if state.get(n) == 2:
            return None
        state[n] = 1
        path.append(n)
        for m in sorted(graph.get(n, ())):
            found = visit(m)
            if found:
                return found
        path.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        found = visit(n)
        if found:
            return found
    return None


def unexplained_length(text: str, limit: int = MAX_LINES) -> int | None:
    """The line count of a module over ``limit`` lines whose docstring has no line
    starting ``Length:``; None for a module within the limit or one that says why."""
    lines = len(text.splitlines())
    if lines <= limit:
        return None
    doc = ast.get_docstring(ast.parse(text)) or ""
    return None if any(line.startswith("Length:") for line in doc.splitlines()) else lines


# The package.


def test_the_package_modules_import_no_cycle():
    graph = import_graph(sources())
    # The scan sees the package (a dozen modules and more) and its imports, function-local ones too.
    assert len(graph) > 10, sorted(graph)
    assert {"contact_client.reply", "contact_client.errors"} <= graph["contact_client.client"], graph
    assert "contact_client.secure" in graph["contact_client.load_test"], "load_test imports secure in a function"
    assert "contact_client.closed_forms" in graph["contact_client.scenes"], graph
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle among the package's modules: " + " -> ".join(cycle or [])


def test_the_old_circle_would_be_found():
    # reply once raised NotSolved through `from .client import NotSolved` in a method.
    graph = import_graph(sources())
    graph["contact_client.reply"] = graph["contact_client.reply"] | {"contact_client.client"}
    assert find_cycle(graph) == ["contact_client.client", "contact_client.reply", "contact_client.client"]


def test_long_modules_say_why():
    texts = sources()
    assert len(texts) > 10
    unexplained = {m: n for m, t in texts.items() if (n := unexplained_length(t)) is not None}
    assert not unexplained, (
        f"modules over {MAX_LINES} lines without a `Length:` line in their docstring saying why: {unexplained}"
    )


def test_moved_names_still_import_from_their_old_homes():
    # The closed forms left scenes, the exceptions left client: both re-export them.
    from contact_client import client, closed_forms, errors, scenes
    from contact_client.scenes import hertz_reference, lame_press_fit_pressure, sadowsky_pressure

    for name in closed_forms.__all__:
        assert getattr(scenes, name) is getattr(closed_forms, name), name
    assert hertz_reference is closed_forms.hertz_reference
    assert sadowsky_pressure is closed_forms.sadowsky_pressure
    assert lame_press_fit_pressure is closed_forms.lame_press_fit_pressure
    assert all(hasattr(scenes, name) for name in scenes.__all__)
    for name in errors.__all__:
        assert getattr(client, name) is getattr(errors, name) is getattr(contact_client, name), name


# The checks themselves, on synthetic graphs and sources.


def test_the_cycle_search_finds_a_circle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"d"}, "x": {"a"}}) is None
    # A diamond is not a cycle; a cycle below it is found, named from where the search enters it.
    assert find_cycle({"a": {"b", "c"}, "b": {"d"}, "c": {"d"}, "d": set()}) is None
    assert find_cycle({"a": {"b", "c"}, "b": {"d"}, "c": {"d"}, "d": {"e"}, "e": {"c"}}) == ["d", "e", "c", "d"]
    assert find_cycle({"a": {"a"}}) == ["a", "a"]


def test_a_planted_function_local_cycle_is_found():
    texts = {
        "pkg": "from . import x\nfrom .y import g\n",
        "pkg.x": "from .y import g\n\ndef f():\n    return g()\n",
        "pkg.y": "def g():\n    from . import x\n    return x\n",
        "pkg.z": "import pkg.x\nfrom pkg import g\n",
    }
    graph = import_graph(texts)
    assert graph == {
        "pkg": {"pkg.x", "pkg.y"},
        "pkg.x": {"pkg.y"},
        "pkg.y": {"pkg.x"},
        "pkg.z": {"pkg.x", "pkg"},
    }
    assert find_cycle(graph) == ["pkg.x", "pkg.y", "pkg.x"]
    texts["pkg.y"] = "def g():\n    return 1\n"
    assert find_cycle(import_graph(texts)) is None


def test_relative_imports_resolve_from_the_right_package():
    texts = {"pkg": "", "pkg.sub": "from .. import a\n", "pkg.sub.b": "from ..a import f\nfrom . import c\n",
             "pkg.sub.c": "", "pkg.a": "def f():\n    pass\n"}
    graph = import_graph(texts)
    assert graph["pkg.sub"] == {"pkg.a"}
    assert graph["pkg.sub.b"] == {"pkg.a", "pkg.sub.c"}
    assert find_cycle(graph) is None
    texts["pkg.a"] = "def f():\n    from .sub.b import g\n"
    assert find_cycle(import_graph(texts)) == ["pkg.a", "pkg.sub.b", "pkg.a"]


def test_a_long_module_needs_a_length_line():
    body = "x = 1\n" * MAX_LINES
    assert unexplained_length('"""Short."""\n' + body) == MAX_LINES + 1
    assert unexplained_length('"""Long.\n\nLength: a reason.\n"""\n' + body) is None
    assert unexplained_length('"""Mentions Length: inside a line."""\n' + body) == MAX_LINES + 1
    assert unexplained_length(body) is None  # exactly at the limit
