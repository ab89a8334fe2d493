"""Composable request constructors: the parts of a solve request as plain dicts.

Every builder in ``scenes``, the tests and the examples put their requests
together from these, so the protocol's spelling lives in one place::

    from contact_client import request as rq

    req = rq.request(
        bodies=[rq.body("block", rq.material(200.0, 0.3),
                        rq.rectangle([-20, -20], 40, 20, size=1.0,
                                     grading=rq.grading(0.01, extent=1.2, focus=[0, 0])),
                        supports=[rq.support("bottom", ux=0.0, uy=0.0)])],
        obstacles=[rq.obstacle("cylinder", rq.circle([0.0, 7.88], 8.0))],
        contacts=[rq.contact("block", "top", obstacle="cylinder")],
    )

Units are the caller's, consistent (the reply uses the same). Arguments left
as ``None`` are left out of the request, so the service's defaults apply.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

PROTOCOL_VERSION = "1"

__all__ = [
    "PROTOCOL_VERSION",
    "request",
    "body",
    "accuracy",
    "material",
    "rectangle",
    "half_disk",
    "quarter_disk",
    "inline_mesh",
    "gmsh",
    "grading",
    "support",
    "pressure",
    "traction",
    "point_load",
    "obstacle",
    "line",
    "circle",
    "polyline",
    "profile",
    "punch",
    "coupling",
    "load",
    "displacement",
    "foundation",
    "winkler",
    "pasternak",
    "half_plane",
    "contact",
    "load_step",
]


def _given(**fields: Any) -> dict:
    """The fields that are not None, in the order given."""
    return {k: v for k, v in fields.items() if v is not None}


def request(
    bodies: Iterable[dict],
    obstacles: Iterable[dict] = (),
    contacts: Iterable[dict] = (),
    foundations: Iterable[dict] | None = None,
    *,
    analysis: str | None = "plane_strain",
    method: str | None = None,
    settings: dict | None = None,
    outputs: Iterable[str] | None = None,
    load_factors: Iterable[float] | None = None,
    time_limit: float | None = None,
    client_id: str | None = None,
    description: str | None = None,
    load_path: Iterable[dict] | None = None,
) -> dict:
    """A whole solve request. ``load_path``: steps ``{"loads": {pointer: factor}}``
    (see ``load_step``), exclusive with ``load_factors``."""
    req = _given(version=PROTOCOL_VERSION, description=description, analysis=analysis)
    req["bodies"] = list(bodies)
    obstacles = list(obstacles)
    if foundations is not None:
        req["foundations"] = list(foundations)
    if foundations is None or obstacles:
        req["obstacles"] = obstacles
    req["contacts"] = list(contacts)
    req.update(_given(method=method, settings=settings, time_limit=time_limit, client_id=client_id))
    if outputs:
        req["outputs"] = list(outputs)
    if load_factors is not None:
        req["load_factors"] = list(load_factors)
    if load_path is not None:
        req["load_path"] = list(load_path)
    return req


def accuracy(
    pressure_l2: float | None = None,
    zone_edge: float | None = None,
    *,
    max_rounds: int | None = None,
    max_dofs: int | None = None,
) -> dict:
    """``settings.accuracy``: refine the meshes round by round (generated ones
    near the zones and, less, away from them; given inline or Gmsh ones by
    splitting every triangle in four) until every pair's estimated relative L2
    error of the pressure is within 0.6 of ``pressure_l2`` and every zone end's
    estimated error within 0.6 of ``zone_edge`` [length] (the estimate is a best
    guess, not a bound: the margin keeps the true error under the target), or a
    limit stops the rounds (the reply then warns ``tolerance_not_reached``). Pass as
    ``settings={"accuracy": accuracy(...)}`` or the ``accuracy=`` of ``scenes.hertz_cylinder``
    and ``scenes.ball_on_flat``."""
    if pressure_l2 is None and zone_edge is None:
        raise ValueError("accuracy needs pressure_l2 and/or zone_edge")
    return _given(pressure_l2=pressure_l2, zone_edge=zone_edge, max_rounds=max_rounds, max_dofs=max_dofs)


def load_step(factors: dict[str, float] | None = None) -> dict:
    """One load path step: the factor of each named load or prescribed motion by its
    JSON pointer in the request (``"/bodies/0/supports/1"``,
    ``"/obstacles/0/punch/horizontal"``, a 3D solid's ``"/solid/body/tractions/0"``,
    ...); those not named keep factor 1."""
    return {"loads": dict(factors or {})}


def material(youngs_modulus: float, poisson_ratio: float) -> dict:
    """Linear elastic, isotropic: E [force/length^2] and nu (< 0.5)."""
    return {"youngs_modulus": youngs_modulus, "poisson_ratio": poisson_ratio}


def body(
    name: str,
    material: dict,
    mesh: dict,
    supports: Iterable[dict] = (),
    tractions: Iterable[dict] | None = None,
    body_force: list[float] | None = None,
    point_loads: Iterable[dict] | None = None,
    couplings: Iterable[dict] | None = None,
) -> dict:
    """A deformable body; ``supports``, ``tractions``, ``point_loads`` and
    ``couplings`` name the mesh's edge sets (generated meshes: rectangle "bottom",
    "right", "top", "left"; half-disk "flat", "arc"; quarter-disk "flat", "arc", "axis")."""
    b = {"name": name, "material": material, "mesh": mesh, "supports": list(supports)}
    if tractions is not None:
        b["tractions"] = list(tractions)
    if point_loads:
        b["point_loads"] = list(point_loads)
    if body_force is not None:
        b["body_force"] = list(body_force)
    if couplings:
        b["couplings"] = list(couplings)
    return b


def grading(h_min: float, ratio: float = 1.1, extent: float = 0.0, focus: list[float] | None = None) -> dict:
    """Elements of ``h_min`` within ``extent`` of ``focus`` (a disk's apex when
    omitted), growing by ``ratio`` per element beyond, up to the mesh's size."""
    return _given(focus=focus, h_min=h_min, ratio=ratio, extent=extent)


def rectangle(
    corner: list[float], width: float, height: float, size: float, element: str = "t3", grading: dict | None = None
) -> dict:
    """Generated rectangle from its lower-left ``corner``; edge sets bottom, right, top, left."""
    return {
        "rectangle": _given(
            corner=list(corner), width=width, height=height, size=size, element=element, grading=grading
        )
    }


def _disk(kind: str, center, radius, facing, size, element, grading) -> dict:
    return {
        kind: _given(center=list(center), radius=radius, facing=facing, size=size, element=element, grading=grading)
    }


def half_disk(
    center: list[float], radius: float, facing: str, size: float, element: str = "t3", grading: dict | None = None
) -> dict:
    """Generated half-disk with its arc ``facing`` "down" or "up"; edge sets arc and flat."""
    return _disk("half_disk", center, radius, facing, size, element, grading)


def quarter_disk(
    center: list[float], radius: float, facing: str, size: float, element: str = "t3", grading: dict | None = None
) -> dict:
    """Generated quarter-disk (the right half of ``half_disk``, for a symmetric
    scene); edge sets arc, flat and axis."""
    return _disk("quarter_disk", center, radius, facing, size, element, grading)


def inline_mesh(nodes: list[list[float]], elements: list[list[int]], edge_sets: dict[str, list[list[int]]]) -> dict:
    """A mesh given node by node: counter-clockwise triangles (3 or 6 nodes) and
    named edge sets of boundary edges."""
    return {
        "inline": {
            "nodes": [list(p) for p in nodes],
            "elements": [list(e) for e in elements],
            "edge_sets": {k: [list(e) for e in v] for k, v in edge_sets.items()},
        }
    }


def gmsh(msh: str, surfaces: list[str] | None = None) -> dict:
    """A mesh from Gmsh MSH 4.1 ASCII text (e.g. ``open("part.msh").read()``).

    Triangles (3- or 6-node) make the body, or only those of the physical surface
    groups named in ``surfaces``; each physical curve group becomes the edge set
    of its name."""
    g: dict = {"msh": msh}
    if surfaces:
        g["surfaces"] = list(surfaces)
    return {"gmsh": g}


def support(edges: str, ux: float | None = None, uy: float | None = None) -> dict:
    """Prescribed displacement components on an edge set (a missing one is free)."""
    return _given(edges=edges, ux=ux, uy=uy)


def pressure(edges: str, p: float, x_range: list[float] | None = None) -> dict:
    """Uniform pressure on an edge set, positive pushing into the body; with
    ``x_range=[x_min, x_max]`` only on the part of the set inside it."""
    return _given(edges=edges, pressure=p, x_range=None if x_range is None else list(x_range))


def traction(edges: str, t: list[float], x_range: list[float] | None = None) -> dict:
    """Uniform traction vector [tx, ty] on an edge set (or its part in ``x_range``)."""
    return _given(edges=edges, traction=list(t), x_range=None if x_range is None else list(x_range))


def point_load(edges: str, at: list[float], force: list[float]) -> dict:
    """A concentrated force [fx, fy] (per unit thickness) at the point ``at`` of an
    edge set, shared by the nodes of the edge it falls on as their shape functions say."""
    return {"edges": edges, "at": list(at), "force": list(force)}


def line(point: list[float], normal: list[float]) -> dict:
    """Rigid half-plane through ``point``; ``normal`` points out of the obstacle."""
    return {"line": {"point": list(point), "normal": list(normal)}}


def circle(center: list[float], radius: float) -> dict:
    """Rigid disk."""
    return {"circle": {"center": list(center), "radius": radius}}


def polyline(points: list[list[float]]) -> dict:
    """Rigid material to the right of the direction of travel through ``points``."""
    return {"polyline": {"points": [list(p) for p in points]}}


def profile(psi: dict, reference: list[float] = (0.0, 0.0)) -> dict:
    """Punch surface y = y_r + psi(x - x_r), rigid above; ``psi`` is e.g.
    ``{"flat": {"half_width": 1.0}}`` or ``{"circle": {"radius": 8.0}}``.

    ``{"flat": {"half_width": b, "corner_radius": r}}`` rounds the flat's corners
    (r = 0, the default: sharp; 0 <= r <= b, else ``invalid_geometry``). ``half_width``
    includes the rounding: the face is flat (psi = 0) for |t| <= b - r, then each
    corner is a quarter circle of radius r (centre at t = ±(b - r), r above the flat)
    rising to psi = r at |t| = b, where it turns vertical and the punch ends. The gap
    is the distance to these arcs themselves; a zone running more than 0.3 r onto an
    arc is warned about (``large_contact_zone``)."""
    return {"profile": {"reference": list(reference), "psi": psi}}


def load(value: float) -> dict:
    """A punch or coupling motion left free, with this load on it."""
    return {"load": value}


def displacement(value: float) -> dict:
    """A prescribed punch or coupling motion."""
    return {"displacement": value}


def punch(
    reference: list[float] = (0.0, 0.0),
    horizontal: dict | None = None,
    vertical: dict | None = None,
    rotation: dict | None = None,
) -> dict:
    """Rigid-motion controls of an obstacle about ``reference``: each of
    (alpha1, P1), (alpha2, P2), (theta, M) as ``load(v)`` or ``displacement(v)``."""
    return _given(reference=list(reference), horizontal=horizontal, vertical=vertical, rotation=rotation)


def coupling(
    edges: str,
    reference: list[float],
    horizontal: dict | None = None,
    vertical: dict | None = None,
    rotation: dict | None = None,
) -> dict:
    """An edge set tied rigidly to the point ``reference`` (an axle): its nodes move as
    (ux, uy) + theta e3 x (x - reference), each of (ux, Fx), (uy, Fy), (theta, M about
    ``reference``) as ``load(v)`` or ``displacement(v)``, left out: held at 0. A body with
    a loaded coupling takes no supports (contact holds it); load path pointers
    ``/bodies/<i>/couplings/0/<horizontal|vertical|rotation>``."""
    return _given(edges=edges, reference=list(reference), horizontal=horizontal, vertical=vertical,
                  rotation=rotation)


def obstacle(name: str, shape: dict, punch: dict | None = None) -> dict:
    """A rigid obstacle (a punch when ``punch`` is given)."""
    return _given(name=name, shape=shape, punch=punch)


def winkler(stiffness: float) -> dict:
    """p = k w; k in pressure per length."""
    return {"winkler": {"stiffness": stiffness}}


def pasternak(stiffness: float, shear: float) -> dict:
    """p = k w - (mu w')'; mu in force per unit thickness."""
    return {"pasternak": {"stiffness": stiffness, "shear": shear}}


def half_plane(youngs_modulus: float, poisson_ratio: float, reference_distance: float) -> dict:
    """Elastic half-plane (Flamant), deflection zero at ``reference_distance`` from a load."""
    return {
        "half_plane": {
            "youngs_modulus": youngs_modulus,
            "poisson_ratio": poisson_ratio,
            "reference_distance": reference_distance,
        }
    }


def foundation(name: str, model: dict, x_min: float, x_max: float, y: float = 0.0) -> dict:
    """A tensionless foundation along y, x in [x_min, x_max]."""
    return {"name": name, "y": y, "x_min": x_min, "x_max": x_max, "model": model}


def contact(
    body: str | int,
    edges: str,
    *,
    obstacle: str | int | None = None,
    against: tuple[str | int, str] | None = None,
    foundation: str | int | None = None,
    discretization: str | None = None,
    friction: float | None = None,
) -> dict:
    """A contact pair: the body's edge set against exactly one of a rigid
    ``obstacle``, another body's edge set ``against=(body, edges)``, or a
    ``foundation``. ``friction``: the Coulomb coefficient μ (against a rigid
    obstacle, a punch or another body; frictionless without it)."""
    if sum(x is not None for x in (obstacle, against, foundation)) != 1:
        raise ValueError("a contact pair names exactly one of obstacle, against or foundation")
    c: dict = {"body": body, "edges": edges}
    if obstacle is not None:
        c["obstacle"] = obstacle
    if foundation is not None:
        c["foundation"] = foundation
    if against is not None:
        c["against"] = {"body": against[0], "edges": against[1]}
    if discretization is not None:
        c["discretization"] = discretization
    if friction is not None:
        c["friction"] = {"coefficient": friction}
    return c
