"""Replies as arrays and pictures: :func:`to_numpy` and :func:`plot_pressure`.

Both need numpy (``pip install 'contact-client[plot]'`` brings numpy and matplotlib).
"""

from __future__ import annotations

import base64
import math
from typing import Any, Callable

from . import scenes

__all__ = ["to_numpy", "plot_pressure", "save_vtu"]

_POINT_FIELDS = ("x", "y", "gap", "pressure", "force", "weight")


def to_numpy(result: dict) -> list[dict]:
    """One dict of numpy arrays per contact pair, in request order.

    Keys: ``x``, ``y``, ``gap``, ``pressure``, ``force``, ``weight`` (float arrays over the
    pair's candidates, in the reply's order along the boundary), ``node`` (int array),
    ``normal`` (n x 2), ``zones`` (k x 2 intervals of x), ``zones_along`` (k x 2: each zone's
    arc length [s_start, s_end] along the pair's edge set, in its order) with ``zone_ends``
    (k x 2 x 2: the [x, y] of each zone's start and end), and ``body`` plus the pair's target
    (``obstacle``, ``against`` or ``foundation``) as strings. Units are the request's.
    """
    import numpy as np

    out = []
    for pair in result["pairs"]:
        pts = pair["points"]
        d: dict[str, Any] = {k: np.array([p[k] for p in pts], dtype=float) for k in _POINT_FIELDS}
        d["node"] = np.array([p["node"] for p in pts], dtype=int)
        d["normal"] = np.array([p["normal"] for p in pts], dtype=float).reshape(-1, 2)
        d["zones"] = np.array(pair["zones"], dtype=float).reshape(-1, 2)
        along = pair.get("zones_along", [])
        d["zones_along"] = np.array([[z["s_start"], z["s_end"]] for z in along], dtype=float).reshape(-1, 2)
        d["zone_ends"] = np.array([[z["start"], z["end"]] for z in along], dtype=float).reshape(-1, 2, 2)
        for k in ("body", "obstacle", "against", "foundation"):
            if k in pair:
                d[k] = pair[k]
        out.append(d)
    return out


def _hertz_overlay(request: dict, result: dict, pair: int) -> tuple[Callable[[float], float], str]:
    """Hertz's p(x) for a rigid circle on one elastic body (``scenes.hertz_cylinder``), for the reply's load."""
    body = request["bodies"][0]["material"]
    circles = [o["shape"]["circle"] for o in request.get("obstacles", []) if "circle" in o["shape"]]
    if len(request["bodies"]) != 1 or len(circles) != 1:
        raise ValueError("reference='hertz' needs the request of a Hertz scene: one body and one rigid circle")
    R = circles[0]["radius"]
    P = abs(result["pairs"][pair]["resultant"]["fy"])
    a, p0 = scenes.hertz_reference(P, R, body["youngs_modulus"], body["poisson_ratio"],
                                   request.get("analysis", "plane_strain"))
    cx = circles[0]["center"][0]
    return (lambda x: scenes.hertz_pressure(x - cx, a, p0)), f"Hertz (P = {P:.4g}, a = {a:.4g}, p0 = {p0:.4g})"


def _unit(result: dict, kind: str) -> str:
    """`` [name]`` of the reply's echoed unit of ``kind``, or nothing."""
    name = (result.get("units") or {}).get(kind)
    return f" [{name}]" if name else ""


def plot_pressure(result: dict, ax=None, reference: str | Callable[[float], float] | None = None,
                  request: dict | None = None, pairs: list[int] | None = None, title: str | None = None):
    """Contact pressure against x, one line per pair, contact zones shaded; returns the axes.

    The axes are labelled with the request's ``units`` when it names them (echoed in
    the reply); the title is ``title``, else the request's ``description``, else
    "Contact pressure". The solver's pressures are solid lines with open markers (a
    different marker per pair) and the reference is a black dashed line, so the
    figure reads in grey-scale print.

    ``reference``: ``"hertz"`` overlays Hertz's p0 sqrt(1 - x^2/a^2) for the load the reply
    reports (|resultant.fy| of the pair), computed from ``request`` (a rigid circle on one
    elastic body, e.g. ``scenes.hertz_cylinder``: radius, E, nu and the analysis are read
    from it; it is the half-plane theory, valid while a << R and a << the body); or any
    callable p(x) in the reply's units, drawn as given. No overlay is guessed: without
    ``reference`` only the solver's pressures are drawn.
    """
    import warnings

    import matplotlib.pyplot as plt
    import numpy as np

    if result.get("status", "solved") != "solved":
        warnings.warn(f"plotting a reply whose status is {result.get('status')!r}: its pressures are not an answer",
                      stacklevel=2)
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.axhline(0.0, color="0.6", lw=0.5)
    arrays = to_numpy(result)
    chosen = range(len(arrays)) if pairs is None else pairs
    xs_all = []
    for k in chosen:
        d = arrays[k]
        order = np.argsort(d["x"])
        target = d.get("obstacle") or d.get("against") or d.get("foundation") or "?"
        marker = "osD^v"[k % 5]
        line, = ax.plot(d["x"][order], d["pressure"][order], "-", marker=marker, ms=3.5, lw=1,
                        markerfacecolor="none", label=f"FE, pair {k}: {d['body']} / {target}")
        for i, (x0, x1) in enumerate(d["zones"]):
            ax.axvspan(x0, x1, color="0.5", alpha=0.12, lw=0,
                       label="contact zone" if i == 0 and k == next(iter(chosen)) else None)
        xs_all.append(d["x"])
    if reference is not None:
        if reference == "hertz":
            if request is None:
                raise ValueError("reference='hertz' needs request=<the Hertz scene's request>")
            p_ref, label = _hertz_overlay(request, result, next(iter(chosen)))
        elif callable(reference):
            p_ref, label = reference, "reference"
        else:
            raise ValueError(f"reference must be 'hertz' or a callable p(x), not {reference!r}")
        x = np.linspace(min(v.min() for v in xs_all), max(v.max() for v in xs_all), 801)
        ax.plot(x, [p_ref(v) for v in x], "k--", lw=1, label=label)
    ax.set_xlabel("x" + _unit(result, "length"))
    ax.set_ylabel("contact pressure" + _unit(result, "stress"))
    if title is None:
        title = (request or {}).get("description") or "Contact pressure"
    import textwrap

    ax.set_title(textwrap.fill(title, 80), fontsize=8)
    ax.legend(fontsize=8)
    return ax


def save_vtu(result: dict, path: str) -> None:
    """Write the reply's ``vtu`` (requested with ``outputs: ["vtu"]``) to ``path`` for ParaView."""
    if "vtu" not in result:
        raise ValueError("the reply has no 'vtu': add \"vtu\" to the request's outputs")
    with open(path, "wb") as f:
        f.write(base64.b64decode(result["vtu"]))

