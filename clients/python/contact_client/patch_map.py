"""A 3D solid's contact patches as a pressure map: :func:`plot_patch`.

The candidate points (``solid.points``) are projected on the obstacle's tangent
plane and triangulated there (Delaunay); the triangles whose three corners all
press are filled with the pressure, interpolated linearly between the points
(Gouraud shading), so separate patches stay separate and the map's edge is the
last pressed points, as the reply's patch ``area`` is. Each patch's outline
(``patches[k].outline``) is drawn on top.

Needs numpy and matplotlib (``pip install 'contact-client[plot]'``).
"""

from __future__ import annotations

import math
import textwrap
import warnings

from . import closed_forms

__all__ = ["plot_patch", "tangent_frame"]


def _unit(v):
    n = math.sqrt(sum(c * c for c in v))
    if n == 0.0:
        raise ValueError("a zero vector has no direction")
    return [c / n for c in v]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def tangent_frame(normal) -> tuple[list[float], list[float]]:
    """Two unit vectors (e1, e2) spanning the plane across ``normal``: x and y
    themselves when the normal is ±z, so a patch on a horizontal plane is drawn in
    the body's own x, y; otherwise (e1, e2, normal) right-handed, e1 the part across
    the normal of the axis least along it."""
    n = _unit(normal)
    if abs(n[2]) > 1.0 - 1e-12:
        return [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]
    axis = min(range(3), key=lambda c: abs(n[c]))
    e = [1.0 if c == axis else 0.0 for c in range(3)]
    e1 = _unit([e[c] - _dot(e, n) * n[c] for c in range(3)])
    return e1, _cross(n, e1)


def _obstacle_normal(solid: dict, request: dict | None) -> list[float]:
    """The normal of the tangent plane the map is drawn on: a plane's own normal, a
    paraboloid's at its apex; on a sphere or a cylinder, the direction of the
    contact's resultant (the mean normal over the patch); else z."""
    shape = (((request or {}).get("solid") or {}).get("obstacle") or {}).get("shape") or {}
    for kind in ("plane", "paraboloid"):
        if kind in shape:
            return _unit(shape[kind]["normal"])
    force = solid.get("resultant", {}).get("force", [0.0, 0.0, 0.0])
    if any(f != 0.0 for f in force):
        return _unit(force)
    return [0.0, 0.0, 1.0]


def _hertz_circle(request: dict, solid: dict, normal) -> tuple[list[float], float, str]:
    """The centre and radius of Hertz's contact circle for a ball scene (a flat face
    with a paraboloid gap, or a rigid sphere), under the load the reply carries times
    the model's symmetry (each roller plane through the apex doubles it)."""
    spec = request["solid"]
    body, gap = spec["body"], (spec["contact"].get("initial_gap") or {}).get("paraboloid")
    shape = spec["obstacle"]["shape"]
    if gap is not None:
        apex, radius = gap["apex"], gap["radius"]
    elif "sphere" in shape:
        radius = shape["sphere"]["radius"]
        apex = shape["sphere"]["centre"]
    else:
        raise ValueError("a Hertz circle needs a ball: a paraboloid initial gap or a sphere obstacle")
    box = body["mesh"].get("box")
    copies = 1
    if box is not None:
        for s in body.get("supports", []):
            faces = s["faces"]
            if faces[0] in "xyz" and faces[1:] in ("_min", "_max"):
                c = "xyz".index(faces[0])
                at = box["corner"][c] + (box["lengths"][c] if faces.endswith("_max") else 0.0)
                fixed = [k for k in ("ux", "uy", "uz") if s.get(k) is not None]
                if fixed == ["u" + faces[0]] and s["u" + faces[0]] == 0.0 and abs(apex[c] - at) < 1e-12 * max(
                        box["lengths"]):
                    copies *= 2
    load = copies * abs(_dot(solid["resultant"]["force"], normal))
    m = body["material"]
    a, _ = closed_forms.hertz_sphere_reference(load, radius, m["youngs_modulus"], m["poisson_ratio"])
    return apex, a, f"Hertz, a = {a:.4g} (P = {load:.4g})"


def plot_patch(result: dict, ax=None, request: dict | None = None, reference: bool | str | float | None = None,
               step: int | None = None, title: str | None = None, cmap: str = "viridis"):
    """The contact pressure of a 3D solid's reply as a filled map over its candidate
    points in contact, each patch's outline on top and a colour bar in the reply's
    stress unit; returns the axes.

    The points are drawn in the obstacle's tangent plane (:func:`tangent_frame` of a
    plane's or a paraboloid's normal; on a sphere or a cylinder, of the resultant's
    direction), so a patch on a horizontal flat reads in the body's x and y. The
    colour range is the pressed points' pressure range. ``step`` draws a
    ``load_factors`` step's answer instead of the last one.

    ``reference``: ``True`` (or ``"hertz"``) draws Hertz's circle of a ball scene (a flat face with a
    paraboloid ``initial_gap``, or a rigid sphere; the load is the reply's resultant
    along the normal, doubled for each roller plane of a box through the apex, so a
    quarter model counts four times), dashed; a number draws a circle of that radius
    around the apex; ``request`` is the request the reply answers (a
    :class:`~contact_client.Reply` knows its own).
    """
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    import numpy as np

    if result.get("status", "solved") != "solved":
        warnings.warn(f"plotting a reply whose status is {result.get('status')!r}: its pressures are not an answer",
                      stacklevel=2)
    if request is None:
        request = getattr(result, "request", None)
    solid = result["solid"] if step is None else result["steps"][step]["solid"]
    normal = _obstacle_normal(solid, request)
    e1, e2 = tangent_frame(normal)
    # With the normal along ±z the in-plane axes are the body's x and y.
    names = ("x", "y") if abs(normal[2]) > 1.0 - 1e-12 else ("s", "t")
    length = (result.get("units") or {}).get("length")
    stress = (result.get("units") or {}).get("stress")
    unit = f" [{length}]" if length else ""
    if ax is None:
        _, ax = plt.subplots(figsize=(5.6, 4.8))
    pts = solid["points"]
    xy = np.array([[_dot(q["at"], e1), _dot(q["at"], e2)] for q in pts]).reshape(-1, 2)
    p = np.array([q["pressure"] for q in pts])
    pressed = np.array([q["in_contact"] for q in pts], dtype=bool)
    ax.plot(xy[~pressed, 0], xy[~pressed, 1], ".", color="0.7", ms=2, label="open points")
    mappable = None
    if pressed.sum() >= 3:
        lo, hi = float(p[pressed].min()), float(p[pressed].max())
        tri = mtri.Triangulation(xy[:, 0], xy[:, 1])
        tri.set_mask(~pressed[tri.triangles].all(axis=1))
        if (~tri.mask).any():
            mappable = ax.tripcolor(tri, p, shading="gouraud", cmap=cmap, vmin=lo, vmax=hi)
    if mappable is None and pressed.any():
        # Too few pressed points for a triangle: the points themselves.
        lo, hi = float(p[pressed].min()), float(p[pressed].max())
        mappable = ax.scatter(xy[pressed, 0], xy[pressed, 1], c=p[pressed], cmap=cmap, vmin=lo, vmax=hi, s=12)
    if mappable is not None:
        bar = ax.figure.colorbar(mappable, ax=ax)
        bar.set_label("contact pressure" + (f" [{stress}]" if stress else ""))
    for k, patch in enumerate(solid["patches"]):
        for i, ring in enumerate(patch["outline"]):
            loop = np.array([[_dot(x, e1), _dot(x, e2)] for x in ring + ring[:1]])
            ax.plot(loop[:, 0], loop[:, 1], "k-", lw=1, label="patch outline" if k == 0 and i == 0 else None)
    if reference is not None and reference is not False:
        if request is None:
            raise ValueError("a reference circle needs request=<the request the reply answers>")
        if reference is True or reference in ("hertz", "closed_form"):
            centre, a, label = _hertz_circle(request, solid, normal)
        elif isinstance(reference, (int, float)):
            gap = (request["solid"]["contact"].get("initial_gap") or {}).get("paraboloid")
            (shape,) = request["solid"]["obstacle"]["shape"].values()
            centre = (gap or {}).get("apex") or shape.get("apex") or shape.get("centre") or shape["point"]
            a, label = float(reference), f"circle a = {float(reference):.4g}"
        else:
            raise ValueError(f"a patch's reference is True, 'hertz' or a radius, not {reference!r}")
        c = (_dot(centre, e1), _dot(centre, e2))
        t = np.linspace(0.0, 2.0 * math.pi, 361)
        ax.plot(c[0] + a * np.cos(t), c[1] + a * np.sin(t), "w--", lw=1.2, label=label)
        ax.plot(c[0] + a * np.cos(t), c[1] + a * np.sin(t), "k:", lw=0.6)
    if pressed.any():
        # The pressed points and a margin of half their extent: the patch fills the view.
        lo_xy, hi_xy = xy[pressed].min(axis=0), xy[pressed].max(axis=0)
        pad = 0.5 * max(float((hi_xy - lo_xy).max()), 1e-12)
        ax.set_xlim(lo_xy[0] - pad, hi_xy[0] + pad)
        ax.set_ylim(lo_xy[1] - pad, hi_xy[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(names[0] + unit)
    ax.set_ylabel(names[1] + unit)
    if title is None:
        title = (request or {}).get("description") or "Contact pressure"
    ax.set_title(textwrap.fill(title, 70), fontsize=8)
    ax.legend(fontsize=7, loc="upper right")
    return ax
