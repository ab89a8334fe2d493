"""Every ```python block of the documentation site (docs/**/*.md) and of README.md runs (issue 39.1).

The blocks of a page are executed in order in one namespace per page, as a reader would paste them,
in a temporary working directory (figures a snippet saves land there), with matplotlib's Agg backend.
They solve in this process (`solve_local`, `Client(local=True)`); the service page starts `contact serve`
from $CONTACT_BIN, as conftest.py does. A block whose fence carries `no-run` (e.g.
```python title="no-run: a remote TLS router"``) is not executed: those are listed in NO_RUN, so that a
new one is a deliberate change.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from support import REPO

DOCS = REPO / "docs"
FENCE = re.compile(r"^```python(?P<info>[^\n]*)\n(?P<code>.*?)^```\s*$", re.M | re.S)
# Pages and the number of their blocks that are shown but not run.
NO_RUN = {"howto/security.md": 1}


def blocks(page: Path) -> list[tuple[str, str]]:
    """(info string, code) of every ```python fence of a page, in order."""
    return [(m.group("info").strip(), m.group("code")) for m in FENCE.finditer(page.read_text(encoding="utf-8"))]


def pages() -> list[Path]:
    return [REPO / "README.md", *sorted(p for p in DOCS.rglob("*.md") if blocks(p))]


def name(page: Path) -> str:
    return str(page.relative_to(DOCS)) if page.is_relative_to(DOCS) else page.name


def test_the_docs_have_snippets():
    assert DOCS.is_dir(), f"{DOCS} not found"
    n = sum(len(blocks(p)) for p in pages())
    assert n >= 20, f"only {n} python blocks under docs/"
    skipped = {name(p): sum("no-run" in i for i, _ in blocks(p)) for p in pages()}
    assert {k: v for k, v in skipped.items() if v} == NO_RUN
    long = [(name(p), line) for p in pages() for _, code in blocks(p) for line in code.splitlines() if len(line) > 120]
    assert not long, f"python lines over 120 columns: {long}"


@pytest.mark.parametrize("page", pages(), ids=name)
def test_page_snippets_run(page: Path, tmp_path, monkeypatch, contact_bin):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("CONTACT_BIN", str(contact_bin))
    namespace: dict = {"__name__": "__docs__"}
    ran = 0
    try:
        for k, (info, code) in enumerate(blocks(page)):
            if "no-run" in info:
                compile(code, f"{page.name}[{k}]", "exec")  # shown, not run: it must still parse
                continue
            exec(compile(code, f"{page.relative_to(REPO)} block {k}", "exec"), namespace)
            ran += 1
    finally:
        plt.close("all")
    assert ran > 0 or all("no-run" in info for info, _ in blocks(page))
