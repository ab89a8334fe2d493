"""Replies as arrays and pictures: :func:`to_numpy` and :func:`plot_pressure`.

Both need numpy (``pip install 'contact-client[plot]'`` brings numpy and matplotlib).
"""

from __future__ import annotations

import base64
import math
from typing import Any, Callable

# The closed forms of plot_pressure's reference curves.
from . import closed_forms

__all__ = ["to_numpy", "described_pressure", "plot_pressure", "save_vtu"]

_POINT_FIELDS = ("x", "y", "gap", "pressure", "force", "weight")


def to_numpy(result: dict) -> list[dict]:
    """One dict of numpy arrays per contact pair, in request order.

    Keys: ``x``, ``y``, ``gap``, ``pressure``, ``force``, ``weight`` (float arrays over the
    pair's candidates, in the reply's order along the boundary), ``node`` (int array),
    ``normal`` (n x 2), ``zones`` (k x 2 intervals of x), ``zones_along`` (k x 2: each zone's
    arc length [s_start, s_end] along the pair's edge set, in its order) with ``zone_ends``
    (k x 2 x 2: the [x, y] of each zone's start and end) and ``fitted_ends`` (k x 2 x 2: the
    [x, y] of each zone's fitted smooth edge, NaN where none is fitted), and ``body`` plus the pair's target
    (``obstacle``, ``against`` or ``foundation``) as strings. Units are the request's.

    Friction: ``tangential_traction`` and ``slip`` (float arrays: the tangential traction on
    the body and the slip in the last load step, along the point's tangent) and ``state``
    (str array: ``"stick"``, ``"slip"``, ``"open"`` or ``"prescribed"``, where the supports fix
    the slip and take the friction force, none of which the model applies), ``mu``, the pair's coefficient, and
    ``stick_zones`` (k x 2 x-intervals of the runs that stick). On a pair without friction
    the float arrays and ``mu`` are NaN, ``state`` holds ``""`` and ``stick_zones`` is empty,
    so the keys are the same on every reply.
    """
    import numpy as np

    out = []
    for pair in result["pairs"]:
        pts = pair["points"]
        d: dict[str, Any] = {k: np.array([p[k] for p in pts], dtype=float) for k in _POINT_FIELDS}
        d["node"] = np.array([p["node"] for p in pts], dtype=int)
        for k in ("tangential_traction", "slip"):
            d[k] = np.array([math.nan if p.get(k) is None else p[k] for p in pts], dtype=float)
        d["state"] = np.array([p.get("state") or "" for p in pts], dtype=str)
        fr = pair.get("friction") or {}
        d["mu"] = fr.get("coefficient", math.nan)
        d["stick_zones"] = np.array(fr.get("stick_zones", []), dtype=float).reshape(-1, 2)
        d["normal"] = np.array([p["normal"] for p in pts], dtype=float).reshape(-1, 2)
        d["zones"] = np.array(pair["zones"], dtype=float).reshape(-1, 2)
        along = pair.get("zones_along", [])
        d["zones_along"] = np.array([[z["s_start"], z["s_end"]] for z in along], dtype=float).reshape(-1, 2)
        d["zone_ends"] = np.array([[z["start"], z["end"]] for z in along], dtype=float).reshape(-1, 2, 2)
        d["fitted_ends"] = np.array([[[math.nan, math.nan] if f is None else [f["x"], f["y"]]
                                      for f in z.get("fitted", [None, None])] for z in along],
                                    dtype=float).reshape(-1, 2, 2)
        for k in ("body", "obstacle", "against", "foundation"):
            if k in pair:
                d[k] = pair[k]
        out.append(d)
    return out


def described_pressure(pair: dict, samples: int = 8):
    """The pressure the reply describes along a pair's surface, as arrays ``(x, y, p)``.

    It is the field that ``accuracy.pressure_l2`` estimates the error of: p² linear
    between consecutive contact points (``samples`` points per segment), and on the
    segment from a zone's last point in contact to the next, open one, p falling as
    p_last √(1 − d/d_edge) to zero at the zone's fitted edge (``zones_along[].fitted``),
    then 0. Where no edge is fitted (a sharp punch corner, a foundation), the segment is
    drawn as the others. Points are ordered by x, then y, as ``plot_pressure`` draws them.
    ``pair`` is one entry of the reply's ``pairs``.
    """
    x, y, p, _ = _described(pair, samples)
    return x, y, p


def _described(pair: dict, samples: int):
    """``described_pressure``, with the index of each contact point among the samples."""
    import numpy as np

    pts = sorted(([p["x"], p["y"], p["pressure"]] for p in pair["points"]), key=lambda q: (q[0], q[1]))
    reach = {}
    for z in pair.get("zones_along", []):
        ends = zip((z["start"], z["end"]), z.get("fitted", [None, None]), (1.0, -1.0), (z["s_start"], z["s_end"]))
        for end, fit, inward, s_end in ends:
            if fit is None:
                continue
            if (fit["s"] - s_end) * inward <= 0.0:
                reach[(end[0], end[1])] = (fit["x"], fit["y"])
                continue
            # An edge fitted inward of the end's node (a mortar row's last
            # node past the edge): the field ends on the facet from the node
            # before, and the end's node reads 0 in it.
            i = next((k for k, q in enumerate(pts) if (q[0], q[1]) == (end[0], end[1])), None)
            if i is None:
                continue
            inner = [k for k in (i - 1, i + 1) if 0 <= k < len(pts) and pts[k][2] > 0.0]
            if not inner:
                continue
            j = min(inner, key=lambda k: math.hypot(pts[k][0] - fit["x"], pts[k][1] - fit["y"]))
            pts[i][2] = 0.0
            reach[(pts[j][0], pts[j][1])] = (fit["x"], fit["y"])
    xs, ys, ps, nodes = [], [], [], []
    t = np.arange(samples) / samples
    for (xa, ya, pa), (xb, yb, pb) in zip(pts, pts[1:]):
        seg_x, seg_y = xa + t * (xb - xa), ya + t * (yb - ya)
        seg_p = np.sqrt(np.maximum(pa * pa + t * (pb * pb - pa * pa), 0.0))
        seg_p[0] = pa
        if (pa > 0.0) != (pb > 0.0):
            end, p_end, other = ((xa, ya), pa, (xb, yb)) if pa > 0.0 else ((xb, yb), pb, (xa, ya))
            fit = reach.get(end)
            if fit is not None:
                # Sample to the edge itself, then the open rest of the segment.
                d_edge = math.hypot(fit[0] - end[0], fit[1] - end[1])
                length = math.hypot(other[0] - end[0], other[1] - end[1])
                u = np.linspace(0.0, 1.0, 4 * samples + 1)
                dist = np.concatenate([u * d_edge, [length]])
                prof = p_end * np.sqrt(np.maximum(1.0 - dist / max(d_edge, 1e-300), 0.0))
                prof[-1] = 0.0
                f = dist / length if length > 0.0 else dist * 0.0
                sx, sy = end[0] + f * (other[0] - end[0]), end[1] + f * (other[1] - end[1])
                if pa > 0.0:
                    seg_x, seg_y, seg_p = sx[:-1], sy[:-1], prof[:-1]
                else:
                    seg_x, seg_y, seg_p = sx[::-1][:-1], sy[::-1][:-1], prof[::-1][:-1]
        nodes.append(sum(len(v) for v in xs))
        xs.append(seg_x)
        ys.append(seg_y)
        ps.append(seg_p)
    if pts:
        nodes.append(sum(len(v) for v in xs))
        xs.append(np.array([pts[-1][0]]))
        ys.append(np.array([pts[-1][1]]))
        ps.append(np.array([pts[-1][2]]))
    if not xs:
        return np.zeros(0), np.zeros(0), np.zeros(0), []
    return np.concatenate(xs), np.concatenate(ys), np.concatenate(ps), nodes


def _curvature_radius(mesh: dict, edges: str) -> float:
    """The radius of a generated disk's arc (``edges`` "arc"), or inf for a flat face
    of a rectangle or of a disk; anything else has no closed form here."""
    for kind in ("half_disk", "quarter_disk"):
        if kind in mesh:
            return mesh[kind]["radius"] if edges == "arc" else math.inf
    if "rectangle" in mesh:
        return math.inf
    raise ValueError("the closed form needs generated meshes (rectangle, half_disk, quarter_disk)")


def _closed_form(request: dict, result: dict, pair: int) -> tuple[Callable[[float], float], str]:
    """The closed-form pressure of the scene ``request`` describes, for the load the
    reply reports on ``pair``: Hertz for a cylinder (or, in axisymmetry, a ball) on a
    flat, rigid or elastic, whatever body is curved (``scenes.hertz_cylinder``,
    ``roller_on_floor``, ``roller_on_plate``, ``two_cylinders``, ``ball_on_flat``,
    ``punch_on_block`` with a circle); Sadowsky (Boussinesq in axisymmetry) for a
    centred flat punch (``punch_on_block``, ``flat_punch_of_revolution``). These are
    half-space theories: they hold while the zone is small against the bodies."""
    analysis = request.get("analysis", "plane_strain")
    axi = analysis == "axisymmetric"
    bodies = {b["name"]: b for b in request["bodies"]}
    contact = request["contacts"][pair]
    body = bodies[contact["body"]]
    mat = body["material"]
    E, nu = mat["youngs_modulus"], mat["poisson_ratio"]
    pr = result["pairs"][pair]
    P = abs(pr["resultant"]["fy"])
    if "against" in contact:
        if axi:
            raise ValueError("no closed form for two bodies of revolution here")
        other = bodies[contact["against"]["body"]]
        R1 = _curvature_radius(body["mesh"], contact["edges"])
        R2 = _curvature_radius(other["mesh"], contact["against"]["edges"])
        m2 = other["material"]
        a, p0 = closed_forms.hertz_two_cylinders(P, R1, R2, E, nu, m2["youngs_modulus"], m2["poisson_ratio"], analysis)
        disk = body["mesh"].get("half_disk") or other["mesh"].get("half_disk") or {"center": [0.0, 0.0]}
        cx = disk["center"][0]
        label = f"Hertz (P = {P:.4g}, a = {a:.4g}, p0 = {p0:.4g})"
        return (lambda x: closed_forms.hertz_pressure(x - cx, a, p0)), label
    if "obstacle" not in contact:
        raise ValueError("no closed form for a foundation pair here: give reference= a callable p(x)")
    obstacle = next(o for o in request.get("obstacles", []) if o["name"] == contact["obstacle"])
    shape = obstacle["shape"]
    if "circle" in shape or ("profile" in shape and "circle" in shape["profile"]["psi"]):
        if "circle" in shape:
            R, cx = shape["circle"]["radius"], shape["circle"]["center"][0]
        else:
            R, cx = shape["profile"]["psi"]["circle"]["radius"], shape["profile"]["reference"][0]
    elif "line" in shape:
        R = _curvature_radius(body["mesh"], contact["edges"])
        if not math.isfinite(R):
            raise ValueError("a flat face on a flat obstacle has no Hertz pressure")
        disk = body["mesh"].get("half_disk") or body["mesh"].get("quarter_disk")
        cx = disk["center"][0]
    elif "profile" in shape and "flat" in shape["profile"]["psi"]:
        b = shape["profile"]["psi"]["flat"]["half_width"]
        cx = shape["profile"]["reference"][0]
        if axi:
            return (lambda x: closed_forms.boussinesq_pressure(x - cx, P, b)), f"Boussinesq (P = {P:.4g}, a = {b:.4g})"
        return (lambda x: closed_forms.sadowsky_pressure(x - cx, P, b)), f"Sadowsky (P = {P:.4g}, b = {b:.4g})"
    else:
        raise ValueError(f"no closed form known for obstacle {obstacle['name']!r}: give reference= a callable p(x)")
    if axi:
        a, p0 = closed_forms.hertz_sphere_reference(P, R, E, nu)
        label = "Hertz, sphere"
    else:
        a, p0 = closed_forms.hertz_reference(P, R, E, nu, analysis)
        label = "Hertz"
    return (lambda x: closed_forms.hertz_pressure(x - cx, a, p0)), f"{label} (P = {P:.4g}, a = {a:.4g}, p0 = {p0:.4g})"


def _unit(result: dict, kind: str) -> str:
    """`` [name]`` of the reply's echoed unit of ``kind``, or nothing."""
    name = (result.get("units") or {}).get(kind)
    return f" [{name}]" if name else ""


#: The contact zone is zoomed on by default when it is narrower than this share
#: of the contact surface's candidates' x-extent.
ZOOM_BELOW = 0.1


def _zoom_range(zones: list, x_min: float, x_max: float) -> tuple[float, float] | None:
    """The x-range shown when zoomed: the zones' extent and half its width on
    either side (so the pressure's fall to zero and some of the open gap show),
    within the surface."""
    if not zones:
        return None
    z0, z1 = min(z[0] for z in zones), max(z[1] for z in zones)
    w = max(z1 - z0, 1e-12 * max(abs(x_min), abs(x_max), 1.0))
    return max(x_min, z0 - 0.5 * w), min(x_max, z1 + 0.5 * w)


def plot_pressure(result: dict, ax=None, reference: str | bool | Callable[[float], float] | None = None,
                  request: dict | None = None, pairs: list[int] | None = None, title: str | None = None,
                  zoom: bool | None = None, shear: bool | None = None, shear_ax=None):
    """Contact pressure against x (r in axisymmetry), one line per pair, contact zones
    shaded; returns the axes (of the pressure). A 3D solid's reply is drawn as its
    patches' pressure map instead (:func:`~contact_client.patch_map.plot_patch`, with
    ``ax``, ``request``, ``reference`` and ``title``).

    With friction on a pair drawn (``shear`` None, the default; ``shear=False`` leaves
    it out), a second panel below, sharing x, draws each such pair's tangential
    traction t with the Coulomb bounds ±μp dashed and its stick zones shaded: t
    touches a bound where the contact slips. It is ``ax.figure.axes[1]`` of the figure
    made here; with ``ax`` given, the panel is drawn on ``shear_ax`` if given, and not
    drawn otherwise.

    ``request`` is the request the reply answers; a :class:`~contact_client.Reply`
    from ``solve_local`` or ``Client.solve`` knows its own (``result.request``), so it
    need not be given. From it come the axis (``r`` for a body of revolution) and the
    closed form.

    The axes are labelled with the request's ``units`` when it names them (echoed in
    the reply); the title is ``title``, else the request's ``description``, else
    "Contact pressure". The solver's pressures are solid lines with open markers (a
    different marker per pair) and the reference is a black dashed line, so the
    figure reads in grey-scale print.

    ``zoom``: show the contact zones and half their width on either side instead of
    the whole contact surface; by default (None) when the zones span less than a
    tenth of the surface (``ZOOM_BELOW``), where the whole surface would show the
    zone as a spike.

    ``reference``: ``True`` (or ``"closed_form"``) overlays the closed form of the
    scene the request describes, for the load the reply reports (|resultant.fy| of
    the first pair drawn): Hertz for a cylinder or, in axisymmetry, a ball on a flat
    (rigid or elastic: ``scenes.hertz_cylinder``, ``roller_on_floor``,
    ``roller_on_plate``, ``two_cylinders``, ``ball_on_flat``, a circular punch),
    Sadowsky or Boussinesq for a centred flat punch (``punch_on_block``,
    ``flat_punch_of_revolution``); a scene without one raises ValueError.
    ``"hertz"`` is the same where the scene is a Hertz scene. They are half-space
    theories, valid while the zone is small against the bodies. Or any callable p(x)
    in the reply's units, drawn as given. No overlay is guessed: without
    ``reference`` only the solver's pressures are drawn.
    """
    import textwrap
    import warnings

    import matplotlib.pyplot as plt
    import numpy as np

    if result.get("solid"):
        # A 3D solid's contact is a patch, not a line: its pressure map.
        from .patch_map import plot_patch

        return plot_patch(result, ax=ax, request=request, reference=reference, title=title)
    if result.get("status", "solved") != "solved":
        warnings.warn(f"plotting a reply whose status is {result.get('status')!r}: its pressures are not an answer",
                      stacklevel=2)
    if request is None:
        request = getattr(result, "request", None)
    axi = (request or {}).get("analysis") == "axisymmetric"
    arrays = to_numpy(result)
    chosen = list(range(len(arrays)) if pairs is None else pairs)
    frictional = [k for k in chosen if not math.isnan(arrays[k]["mu"])]
    if shear is None:
        shear = bool(frictional)
    if ax is None:
        if shear:
            _, (ax, shear_ax) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.4), height_ratios=[3, 2])
        else:
            _, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.axhline(0.0, color="0.6", lw=0.5)
    xs_all, zones_all = [], []
    for k in chosen:
        d = arrays[k]
        target = d.get("obstacle") or d.get("against") or d.get("foundation") or "?"
        marker = "osD^v"[k % 5]
        # The nodal values as markers, the described field (p² linear between them, the
        # square-root facet to each fitted zone edge) as the line: the curve whose error
        # `accuracy.pressure_l2` estimates.
        cx, _, cp, at_nodes = _described(result["pairs"][k], 8)
        ax.plot(cx, cp, "-", marker=marker, ms=3.5, lw=1, markevery=at_nodes,
                markerfacecolor="none", label=f"FE, pair {k}: {d['body']} / {target}")
        for i, (x0, x1) in enumerate(d["zones"]):
            ax.axvspan(x0, x1, color="0.5", alpha=0.12, lw=0,
                       label="contact zone" if i == 0 and k == chosen[0] else None)
            zones_all.append((x0, x1))
        xs_all.append(d["x"])
    x_min = min((v.min() for v in xs_all if v.size), default=0.0)
    x_max = max((v.max() for v in xs_all if v.size), default=1.0)
    shown = (x_min, x_max)
    window = _zoom_range(zones_all, x_min, x_max)
    if zoom is None:
        zoom = window is not None and window[1] - window[0] < 2.0 * ZOOM_BELOW * (x_max - x_min)
    if zoom and window is not None:
        shown = window
        ax.set_xlim(*shown)
        # Pressures of the shown points set the height (the rest is zero or off-screen).
        visible = [d["pressure"][(d["x"] >= shown[0]) & (d["x"] <= shown[1])] for d in (arrays[k] for k in chosen)]
        top = max((v.max() for v in visible if v.size), default=0.0)
        if top > 0.0:
            ax.set_ylim(-0.05 * top, 1.4 * top)  # room for the legend above the peak
    if reference is not None and reference is not False:
        if reference is True or reference in ("closed_form", "hertz"):
            if request is None:
                raise ValueError("a closed-form reference needs request=<the request the reply answers>")
            p_ref, label = _closed_form(request, result, chosen[0])
            if reference == "hertz" and not label.startswith("Hertz"):
                raise ValueError(f"reference='hertz' on a scene whose closed form is {label.split(' (')[0]}")
        elif callable(reference):
            p_ref, label = reference, "reference"
        else:
            raise ValueError(f"reference must be True, 'closed_form', 'hertz' or a callable p(x), not {reference!r}")
        x = np.linspace(shown[0], shown[1], 801)
        ax.plot(x, [p_ref(v) for v in x], "k--", lw=1, label=label)
    xlabel = ("r" if axi else "x") + _unit(result, "length")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("contact pressure" + _unit(result, "stress"))
    if shear and shear_ax is not None:
        _shear_panel(shear_ax, arrays, frictional, shown if zoom else None)
        ax.set_xlabel("")
        shear_ax.set_xlabel(xlabel)
        shear_ax.set_ylabel("tangential traction" + _unit(result, "stress"))
    if title is None:
        title = (request or {}).get("description") or "Contact pressure"
    ax.set_title(textwrap.fill(title, 80), fontsize=8)
    # Zoomed, the upper corners are beside the zone, where the pressure is zero.
    ax.legend(fontsize=8, loc="upper right" if zoom else "best")
    return ax


def _shear_panel(ax, arrays: list[dict], frictional: list[int], window: tuple[float, float] | None) -> None:
    """The tangential traction of every pair in ``frictional`` with ±μp and its stick
    zones, on ``ax`` (x limited to ``window`` when zoomed)."""
    import numpy as np

    ax.axhline(0.0, color="0.6", lw=0.5)
    tops = []
    for n, k in enumerate(frictional):
        d = arrays[k]
        order = np.argsort(d["x"])
        x, t, bound = d["x"][order], d["tangential_traction"][order], d["mu"] * d["pressure"][order]
        marker = "osD^v"[k % 5]
        ax.plot(x, t, "-", marker=marker, ms=3.5, lw=1, markerfacecolor="none", label=f"t, pair {k}")
        ax.plot(x, bound, "k--", lw=0.8, label=f"±μp (μ = {d['mu']:g})" if n == 0 else None)
        ax.plot(x, -bound, "k--", lw=0.8)
        for i, (x0, x1) in enumerate(d["stick_zones"]):
            ax.axvspan(x0, x1, color="tab:blue", alpha=0.08, lw=0, label="stick" if i == 0 and n == 0 else None)
        inside = (x >= window[0]) & (x <= window[1]) if window else np.ones_like(x, dtype=bool)
        tops.append(np.nanmax(np.abs(np.concatenate([t[inside], bound[inside]])), initial=0.0))
    top = max(tops, default=0.0)
    if top > 0.0:
        ax.set_ylim(-1.15 * top, 1.7 * top)  # room for the legend above +μp
    ax.legend(fontsize=8, loc="upper right", ncol=3)


def save_vtu(result: dict, path: str) -> None:
    """Write the reply's ``vtu`` (requested with ``outputs: ["vtu"]``) to ``path`` for ParaView."""
    if "vtu" not in result:
        raise ValueError("the reply has no 'vtu': add \"vtu\" to the request's outputs")
    with open(path, "wb") as f:
        f.write(base64.b64decode(result["vtu"]))

