"""Plot the CSV of ``contact-bench``: ``python -m contact_client.plot_bench CSV [--out PNG] [--title TEXT]``.

Two panels, written to PNG (default: the CSV path with a ``.png`` suffix):

* left: total time ``t_total`` (log x) against the relative L2 pressure error
  ``err_l2`` (log y), one line per method and element (colour = method, marker
  and line style = element), the rows of a line joined in order of ``dofs``.
  The Cholesky floor ``t_floor`` is drawn in grey dashes at the error of the
  exact method (``--exact``, default ``active_set``) on the same mesh: what the
  exact answer would cost if the contact solve were free.
* right: ``ratio_total_to_floor`` against ``dofs`` (log x), one line per
  method and element, with the 1.5 target as a horizontal line.

Rows whose ``status`` is not ``solved`` get hollow markers. Needs matplotlib
(``pip install 'contact-client[plot]'``); reads the CSV with the csv module only.
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

TARGET_RATIO = 1.5
DEFAULT_EXACT = "active_set"

_FLOAT = ("h_min", "t_total", "t_floor", "ratio_total_to_floor", "err_l2")
_INT = ("dofs",)
_REQUIRED = ("element", "method", "status", *_FLOAT, *_INT)

# Element -> (marker, line style). Anything else falls back to the last entries.
_ELEMENT_STYLE = {"T3": ("o", "-"), "T6": ("s", "-.")}
_EXTRA_STYLES = [("^", ":"), ("D", (0, (5, 1, 1, 1, 1, 1))), ("v", (0, (1, 2)))]


def read_rows(path: str | Path) -> list[dict]:
    """The CSV rows as dicts, numeric columns parsed (float, or int for ``dofs``)."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        missing = [c for c in _REQUIRED if c not in (reader.fieldnames or [])]
        if missing:
            raise ValueError(f"{path}: missing column(s) {', '.join(missing)}")
        rows = []
        for n, r in enumerate(reader, start=2):
            try:
                for k in _FLOAT:
                    r[k] = float(r[k])
                for k in _INT:
                    r[k] = int(r[k])
            except (TypeError, ValueError) as e:
                raise ValueError(f"{path}:{n}: {e}") from None
            r["method"] = r["method"].strip()
            r["element"] = r["element"].strip()
            r["status"] = r["status"].strip().lower()
            rows.append(r)
    if not rows:
        raise ValueError(f"{path}: no data rows")
    return rows


def _unique(seq):
    seen = {}
    for x in seq:
        seen.setdefault(x, None)
    return list(seen)


def _positive(*xs: float) -> bool:
    return all(math.isfinite(x) and x > 0 for x in xs)


def _dofs_label(x: float, _pos=None) -> str:
    if x >= 1e6:
        return f"{x / 1e6:g}M"
    if x >= 1e3:
        return f"{x / 1e3:g}k"
    return f"{x:g}"


def _series(rows, method, element):
    return sorted((r for r in rows if r["method"] == method and r["element"] == element), key=lambda r: r["dofs"])


def _draw(ax, xs, ys, solved, color, marker, ls, label, zorder=3, size=6.5):
    """A line through all points; filled markers where solved, hollow elsewhere."""
    ax.plot(xs, ys, color=color, ls=ls, lw=1.4, label=label, zorder=zorder)
    for x, y, ok in zip(xs, ys, solved):
        ax.plot([x], [y], ls="none", marker=marker, ms=size, mew=1.4, color=color,
                mfc=color if ok else "white", zorder=zorder + (0.1 if ok else 0.2))


def plot(rows: list[dict], out: str | Path, title: str | None = None, exact: str = DEFAULT_EXACT) -> Path:
    """Draw the two panels for ``rows`` (as returned by :func:`read_rows`) into ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    methods = _unique(r["method"] for r in rows)
    elements = _unique(r["element"] for r in rows)
    cmap = plt.get_cmap("tab10")
    color = {m: cmap(i % 10) for i, m in enumerate(methods)}
    style = {}
    for i, e in enumerate(elements):
        style[e] = _ELEMENT_STYLE.get(e) or _EXTRA_STYLES[i % len(_EXTRA_STYLES)]

    fig, (ax_err, ax_ratio) = plt.subplots(1, 2, figsize=(15, 6.8), layout="constrained")

    # Left: time against error.
    for m in methods:
        for e in elements:
            s = [r for r in _series(rows, m, e) if _positive(r["t_total"], r["err_l2"])]
            if s:
                mk, ls = style[e]
                _draw(ax_err, [r["t_total"] for r in s], [r["err_l2"] for r in s],
                      [r["status"] == "solved" for r in s], color[m], mk, ls, f"{m}, {e}")
    floor_drawn = False
    for e in elements:
        s = [r for r in _series(rows, exact, e) if _positive(r["t_floor"], r["err_l2"])]
        if s:
            mk, _ = style[e]
            ax_err.plot([r["t_floor"] for r in s], [r["err_l2"] for r in s], color="0.45", ls="--", lw=1.3,
                        marker=mk, ms=4.5, mfc="0.45", zorder=2)
            floor_drawn = True
    ax_err.set_xscale("log")
    ax_err.set_yscale("log")
    ax_err.set_xlabel("total time t_total [s]")
    ax_err.set_ylabel("relative L2 pressure error err_l2 (vs Hertz)")
    ax_err.set_title("error against time")
    ax_err.grid(True, which="major", alpha=0.35)
    ax_err.grid(True, which="minor", alpha=0.12)

    # Right: ratio to the floor against size.
    for m in methods:
        for e in elements:
            s = [r for r in _series(rows, m, e) if _positive(r["dofs"]) and math.isfinite(r["ratio_total_to_floor"])]
            if s:
                mk, ls = style[e]
                _draw(ax_ratio, [r["dofs"] for r in s], [r["ratio_total_to_floor"] for r in s],
                      [r["status"] == "solved" for r in s], color[m], mk, ls, f"{m}, {e}")
    ax_ratio.axhline(TARGET_RATIO, color="black", lw=1.3, ls=(0, (6, 3)), zorder=1)
    # The label sits just outside the right spine, where no data line can cover it.
    ax_ratio.annotate("target", xy=(1.0, TARGET_RATIO), xycoords=("axes fraction", "data"),
                      xytext=(4, 0), textcoords="offset points", ha="left", va="center",
                      color="black", fontsize=10, fontweight="bold", annotation_clip=False)
    ax_ratio.set_xscale("log")
    # DOFs as 20k, 50k, 100k, ...: log ticks at 1, 2, 5 per decade, no crowded minor labels.
    ax_ratio.xaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax_ratio.xaxis.set_major_formatter(FuncFormatter(_dofs_label))
    ax_ratio.xaxis.set_minor_formatter(NullFormatter())
    ax_ratio.set_xlabel("DOFs")
    ax_ratio.set_ylabel("t_total / t_floor")
    ax_ratio.set_title("total time over the Cholesky floor")
    ax_ratio.grid(True, which="major", alpha=0.35)
    ax_ratio.grid(True, which="minor", alpha=0.12)
    lo, hi = ax_ratio.get_ylim()
    ax_ratio.set_ylim(min(lo, 0.0 if lo < 1.0 else 1.0), max(hi, TARGET_RATIO * 1.1))

    # One shared legend below the panels: methods by colour, elements by marker/line,
    # then the reference lines and the hollow-marker convention.
    handles = [Line2D([], [], color=color[m], lw=2.5, label=m) for m in methods]
    handles += [Line2D([], [], color="black", marker=style[e][0], ls=style[e][1], lw=1.4, ms=6.5, label=e)
                for e in elements]
    if floor_drawn:
        handles.append(Line2D([], [], color="0.45", ls="--", lw=1.3, label=f"floor t_floor at {exact}'s error"))
    handles.append(Line2D([], [], color="black", ls=(0, (6, 3)), lw=1.3, label=f"target ratio {TARGET_RATIO:g}"))
    unsolved = sorted({r["status"] for r in rows if r["status"] != "solved"})
    hollow = "not solved" + (f" ({', '.join(unsolved)})" if unsolved else "")
    handles.append(Line2D([], [], color="black", marker="o", ls="none", ms=6.5, mfc="white", mew=1.4, label=hollow))
    # Column-major fill: methods take the first columns, two entries each, then
    # the element styles, the reference lines and the hollow-marker key.
    ncol = math.ceil(len(handles) / 2)
    fig.legend(handles=handles, loc="outside lower center", ncol=ncol, frameon=False, fontsize=9.5,
               handlelength=3.2, columnspacing=1.6)

    scenes = ", ".join(_unique(r.get("scene", "") for r in rows if r.get("scene"))) or "contact"
    heading = f"contact-bench: {scenes}"
    if title:
        heading += f"\n{title}"
    fig.suptitle(heading, fontsize=12)
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=130)
    plt.close(fig)
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m contact_client.plot_bench",
                                description="Plot the CSV written by `contact-bench` (needs matplotlib).")
    p.add_argument("csv", help="CSV file from `contact-bench --csv`")
    p.add_argument("--out", help="PNG to write (default: the CSV path with a .png suffix)")
    p.add_argument("--title", help="second title line, e.g. the machine the bench ran on")
    p.add_argument("--exact", default=DEFAULT_EXACT,
                   help=f"method whose error places the floor line (default {DEFAULT_EXACT})")
    args = p.parse_args(argv)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("plot_bench needs matplotlib: pip install 'contact-client[plot]'", file=sys.stderr)
        return 2
    try:
        rows = read_rows(args.csv)
    except (OSError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    out = Path(args.out) if args.out else Path(args.csv).with_suffix(".png")
    plot(rows, out, title=args.title, exact=args.exact)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
