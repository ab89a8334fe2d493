"""Builders of standard scenes: functions returning solve requests (dicts).

Each builder's docstring gives its scene's geometry, loads and mesh, and names the
closed-form reference its answer is compared with; those references live in
``contact_client.closed_forms`` (Hertz, Sadowsky, Boussinesq, Cattaneo–Mindlin, the
foundations, Lamé) and are re-exported here, so ``scenes.hertz_reference`` and
``from contact_client.scenes import sadowsky_pressure`` keep working.

Length: fourteen independent builders of about 50 lines each (a signature of
documented defaults, a docstring giving the scene, its sizes and its reference, and
the request), read and documented as one page (``contact_client.scenes``). The
closed forms moved out to ``closed_forms``; splitting the builders by kind would
add modules that this one would still have to re-export.
"""

from __future__ import annotations

import math

from . import request as rq

# Re-exported for compatibility: these closed forms were defined here until they moved
# to closed_forms; users and docs import them from contact_client.scenes.
from .closed_forms import (
    boussinesq_pressure,
    boussinesq_settlement,
    cattaneo_mindlin_stick,
    effective_modulus,
    hertz_measure,
    hertz_pressure,
    hertz_reference,
    hertz_sphere_reference,
    hertz_two_cylinders,
    lame_press_fit_pressure,
    pasternak_deflection,
    rigid_footing_pressure,
    sadowsky_pressure,
    stick_measure,
)

__all__ = [
    "gmsh_mesh",
    "roller_on_plate",
    "footing_with_eccentric_load",
    "rigid_footing_pressure",
    "punch_from_polyline",
    "roller_on_floor",
    "block_on_polyline",
    "block_held_by_contact",
    "footing_on_foundation",
    "pasternak_deflection",
    "two_cylinders",
    "hertz_two_cylinders",
    "punch_on_block",
    "sadowsky_pressure",
    "hertz_cylinder",
    "hertz_reference",
    "hertz_pressure",
    "hertz_measure",
    "effective_modulus",
    "ball_on_flat",
    "ball_on_flat_3d",
    "sphere_into_block_3d",
    "block_on_plane_3d",
    "hertz_sphere_reference",
    "flat_punch_of_revolution",
    "boussinesq_pressure",
    "boussinesq_settlement",
    "cattaneo_mindlin_stick",
    "stick_measure",
    "lame_press_fit_pressure",
]


def hertz_cylinder(
    radius: float = 8.0,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    depth: float | None = None,
    h_min: float = 0.01,
    element: str = "t3",
    *,
    load: float | None = None,
    width: float = 40.0,
    height: float = 20.0,
    size: float = 1.0,
    ratio: float = 1.1,
    extent: float | None = None,
    analysis: str = "plane_strain",
    method: str = "auto",
    client_id: str | None = None,
    outputs: list[str] | None = None,
    mesh: dict | None = None,
    accuracy: dict | None = None,
) -> dict:
    """Request: a rigid circle of ``radius`` pressed ``depth`` (default 0.12) into an
    elastic block, or with ``load`` instead: the block held only by contact and ``load``
    [force per unit thickness].

    With ``load``, the circle touches the top face at the origin and the block's bottom,
    clamped in the displacement version, carries the uniform pressure load / width
    upward instead, and keeps only ux = 0: the vertical translation is left to the
    contact, and the rotation about the bottom's centre that ux = 0 leaves free is
    resisted by the contact zone (the loads have no moment about it, so it carries
    none). Hertz's P is ``load`` exactly: the body's equilibrium makes the contact
    resultant equal to it.

    ``mesh`` replaces the generated rectangle, e.g. ``gmsh_mesh(text, ["block"])``
    with ``gmsh_meshes.hertz_block()``; it needs edge sets "top" and "bottom".
    ``accuracy`` (``request.accuracy(pressure_l2=...)``) refines until the
    reply's error estimate meets it.

    The block is [-width/2, width/2] x [-height, 0] (top face at y = 0, fixed
    bottom), meshed uniformly at ``h_min`` within ``extent`` of the origin and
    growing by ``ratio`` per element beyond, up to ``size``. ``extent`` defaults
    to the half-chord sqrt(depth (2 R - depth)) of the circle's overlap with the
    undeformed face, which bounds the contact half-width a from above (the face
    sinks under the load), so the whole contact is meshed at ``h_min``. The
    circle's centre is at (0, radius - depth), so its lowest point overlaps the
    top face by ``depth``; the contact pair is the block's "top" edge set
    against it.

    The defaults are the scene of proto/examples/signorini_hertz_cylinder.json
    except ``extent``, which the example sets by hand (the default half-chord is
    1.38; a is about 0.69).

    Sizes: with the defaults P is about 10 and a about 0.69, so a/R ~ 1/12 (the
    circle differs from Hertz's parabola by x^4/(8R^3), a relative change of the
    gap of (a/2R)^2 < 0.2 % at the contact edge), and the block is about 30 a
    deep and 60 a wide, so its finite size changes a and p0 by well under 1 %.
    The zone ends are node positions, so a is resolved to h_min/a ~ 1.5 %.
    About 37k nodes (73k DOFs); one solve takes about half a second on 2 cores.
    """
    if element not in ("t3", "t6"):
        raise ValueError("element must be 't3' or 't6'")
    if load is not None:
        depth = _load_or_motion(load, depth, "depth")
        if extent is None:
            # Twice Hertz's half-width for this load: the zone, and a margin for a
            # finite block's slightly wider one, is meshed at h_min.
            extent = 2.0 * hertz_reference(load, radius, youngs_modulus, poisson_ratio, analysis)[0]
    elif depth is None:
        depth = 0.12
    if not 0.0 <= depth < radius or (load is None and depth == 0.0):
        raise ValueError("need 0 < depth < radius")
    if extent is None:
        # Half-chord of the circle's overlap with the undeformed face: the surface
        # sinks under the load, so the contact half-width a is always smaller.
        extent = math.sqrt(depth * (2.0 * radius - depth))
    if mesh is None:
        mesh = rq.rectangle(
            [-width / 2.0, -height], width, height, size, element, rq.grading(h_min, ratio, extent, focus=[0.0, 0.0])
        )
    if load is None:
        held = {"supports": [rq.support("bottom", 0.0, 0.0)]}
        how = f"pressed {depth} into"
        bottom = "fixed bottom"
    else:
        held = {"supports": [rq.support("bottom", ux=0.0)], "tractions": [rq.pressure("bottom", load / width)]}
        how = f"pressed with P={load} onto"
        bottom = "bottom pushed up by P/width, held by contact"
    return rq.request(
        bodies=[rq.body("block", rq.material(youngs_modulus, poisson_ratio), mesh, **held)],
        obstacles=[rq.obstacle("cylinder", rq.circle([0.0, radius - depth], radius))],
        contacts=[rq.contact("block", "top", obstacle="cylinder")],
        analysis=analysis,
        method=method,
        settings=None if accuracy is None else {"accuracy": accuracy},
        client_id=client_id,
        outputs=outputs,
        description=(
            f"Hertz: rigid cylinder R={radius} {how} an elastic block "
            f"{width} x {height} (E={youngs_modulus}, nu={poisson_ratio}, {analysis}), {bottom}"
        ),
    )


def _load_or_motion(load: float, motion: float | None, name: str) -> float:
    """The body's initial position under load control: touching (0), after checks."""
    if motion is not None:
        raise ValueError(f"give either {name} (displacement control) or load (load control), not both")
    if not (isinstance(load, (int, float)) and math.isfinite(load) and load > 0.0):
        raise ValueError(f"load must be a positive number (force pressing the bodies together), not {load!r}")
    return 0.0


def _press_ramp(steps: int) -> list[float]:
    """The factors of the press in ``steps`` equal load path steps: k / steps for k = 1 .. steps.

    Why the frictional builders press in steps (issue 39): a node that closes during a step
    carries the tangential motion it made while open into that step's slip (the slip is the
    increment over the step), so a press in one step from rest locks a spurious shear into the
    zone. Measured on the Cattaneo-Mindlin roller (``roller_on_floor``, nu = 0.499, T6,
    h = 0.0075, mu = 0.5): its peak shear is +15.5, +8.3, +5.1 % against mu p0 sqrt(Q/(mu P))
    at Q/(mu P) = 0.29, 0.49, 0.67 pressed in one step, +4.2, +4.2, +4.0 % in ten."""
    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise ValueError(f"steps must be a whole number >= 1 (load path steps of the press), not {steps!r}")
    return [k / steps for k in range(1, steps + 1)]


def _pressed_then(press: str, shift: str, steps: int, shifts: list[float]) -> list[dict]:
    """A load path: the motion or load ``press`` ramped in ``steps`` steps with ``shift`` held
    at 0, then ``shift`` at each factor of ``shifts`` in turn (``press`` at its full value).
    With steps = 1 it is the one-step path the builders made before ``steps`` existed."""
    ramp = [rq.load_step({press: f, shift: 0.0} if f != 1.0 else {shift: 0.0}) for f in _press_ramp(steps)]
    return ramp + [rq.load_step({shift: s}) for s in shifts]


def punch_on_block(
    profile: dict,
    load: float = 10.0,
    moment: float = 0.0,
    horizontal_load: float = 0.0,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    width: float = 40.0,
    depth: float = 20.0,
    h_min: float = 0.01,
    extent: float = 1.2,
    element: str = "t3",
    method: str = "auto",
    *,
    friction: float | None = None,
    steps: int = 10,
) -> dict:
    """Request: a rigid punch pressed with ``load`` (force per unit thickness,
    downward) into the top face (y = 0) of an elastic block ``width`` x ``depth``
    with its bottom fixed, plane strain. The punch's reference point is the
    origin; its profile is one of the protocol's ``psi`` forms, e.g.
    ``{"flat": {"half_width": 1.0}}`` (Sadowsky) or ``{"circle": {"radius": 8.0}}``
    (Hertz); ``{"flat": {"half_width": 1.0, "corner_radius": 0.3}}`` rounds the flat's
    corners within the half-width (flat over |x| <= 0.7, see ``request.profile``), and
    the pressure stays bounded where the zone ends on the rounding. ``moment``
    (counter-clockwise, about the origin) and ``horizontal_load`` act on the punch;
    all three motions are load-controlled.
    The mesh is uniform at ``h_min`` within ``extent`` of the origin (cover the
    contact zone) and graded by 1.1 up to size 1 elsewhere.

    With ``friction`` (Coulomb μ on the punch's face), friction holds the punch
    sideways: it is pressed by ``load`` first, in ``steps`` equal load path steps
    (default 10), then pushed by ``horizontal_load`` in one more step (friction depends
    on the path). It presses in steps because a point that closes during a step carries
    the tangential motion it made while open into that step's slip: pressed in one step
    from rest, the zone keeps a shear the gradual press does not leave (on the
    Cattaneo-Mindlin roller, ``roller_on_floor``, the peak shear read +15.5 to +5.1 %
    against the closed form pressed in one step, +4.2 to +4.0 % in ten). ``steps=1``
    presses in one step, as before.
    It sticks while |horizontal_load| < μ load; beyond, it would slide and the service
    refuses the request (``incompatible_loads``, with the admissible range
    [-μ load, μ load]).
    """
    mesh = rq.rectangle([-0.5 * width, -depth], width, depth, 1.0, element, rq.grading(h_min, 1.1, extent, [0.0, 0.0]))
    controls = rq.punch(horizontal=rq.load(horizontal_load), vertical=rq.load(-load), rotation=rq.load(moment))
    path = None
    if friction is not None and horizontal_load != 0.0:
        path = _pressed_then("/obstacles/0/punch/vertical", "/obstacles/0/punch/horizontal", steps, [1.0])
    return rq.request(
        bodies=[
            rq.body("block", rq.material(youngs_modulus, poisson_ratio), mesh, [rq.support("bottom", 0.0, 0.0)])
        ],
        obstacles=[rq.obstacle("punch", rq.profile(profile), controls)],
        contacts=[rq.contact("block", "top", obstacle="punch", friction=friction)],
        method=method,
        load_path=path,
        description=f"rigid punch {profile} pressed with P = {load} into an elastic block {width} x {depth}"
        + ("" if friction is None else f", friction mu = {friction}, pushed sideways by Q = {horizontal_load}"),
    )


def two_cylinders(
    R1: float = 8.0,
    R2: float = 12.0,
    E1: float = 200.0,
    nu1: float = 0.3,
    E2: float = 100.0,
    nu2: float = 0.25,
    approach: float = 0.08,
    h_min: float = 0.01,
    element: str = "t3",
    discretization: str = "mortar",
    *,
    friction: float | None = None,
    shifts: list[float] | None = None,
    steps: int = 10,
) -> dict:
    """Two elastic half-disks pressed together (plane strain).

    The upper one (radius R1, modulus E1 and Poisson ratio nu1, arc down,
    touching the lower one at the origin) has its flat top clamped and moved
    down by ``approach``; the lower one (R2, E2, nu2, arc up) is clamped on its
    flat bottom. Both meshes are graded toward the contact point, with element
    sizes ``h_min`` and 1.3 h_min there, so the two meshes do not match. The
    upper arc carries the pressure (slave side); ``discretization`` is
    "mortar" or "node_to_segment". Units are the caller's, consistent.
    Compare with ``hertz_two_cylinders`` using ``P = reply["pairs"][0]["resultant"]["fy"]``.

    ``friction``: Coulomb μ between the two surfaces. ``shifts``: after pressing,
    the upper one's clamped top is moved sideways by each of these displacements
    [length] in turn (a load path: pressed, then shifted, so that P stays about
    constant while Q = -resultant.fx grows). With ``shifts`` the approach is ramped
    in ``steps`` equal steps (default 10; the reply's ``steps`` holds those, then one
    per shift): a point closing during a step counts the tangential motion it made
    while open as that step's slip, so a press in one step leaves a shear in the zone
    that a gradual press does not (see ``roller_on_floor``). ``steps=1`` presses in one
    step, as before. With the same material on both sides
    (E1 = E2, nu1 = nu2: Dundurs beta = 0) the contact then sticks on
    |x| < a sqrt(1 - Q/(μP)), ``cattaneo_mindlin_stick`` with a from
    ``hertz_two_cylinders``.
    """

    def half_disk(center, radius, facing, h):
        return rq.half_disk(center, radius, facing, radius / 16.0, element, rq.grading(h, 1.1, 0.15 * min(R1, R2)))

    upper = [rq.support("flat", 0.0, -approach)]
    path = None
    if shifts is not None:
        shifts = [float(s) for s in shifts]
        if not shifts or not all(math.isfinite(s) for s in shifts):
            raise ValueError(f"shifts must be a non-empty list of finite displacements, not {shifts!r}")
        # The sideways motion as its own support on the top, scaled alone by the path.
        upper = [rq.support("flat", uy=-approach), rq.support("flat", ux=1.0)]
        path = _pressed_then("/bodies/0/supports/0", "/bodies/0/supports/1", steps, shifts)
    return rq.request(
        bodies=[
            rq.body("upper", rq.material(E1, nu1), half_disk([0.0, R1], R1, "down", h_min), upper),
            rq.body("lower", rq.material(E2, nu2), half_disk([0.0, -R2], R2, "up", 1.3 * h_min),
                    [rq.support("flat", 0.0, 0.0)]),
        ],
        contacts=[rq.contact("upper", "arc", against=("lower", "arc"), discretization=discretization,
                             friction=friction)],
        load_path=path,
    )


def footing_on_foundation(
    model: dict,
    width: float = 2.0,
    height: float = 0.5,
    pressure: float = 1.0,
    youngs_modulus: float = 1000.0,
    poisson_ratio: float = 0.25,
    size: float = 0.05,
    extent: float = 5.0,
    element: str = "t3",
) -> dict:
    """A rectangular footing ``width`` x ``height`` with no other support resting
    on a tensionless foundation along y = 0, x in [-extent, extent], under a
    uniform ``pressure`` on its top (P = pressure * width per unit thickness).

    ``model`` is the protocol's foundation model, e.g.
    ``{"winkler": {"stiffness": k}}`` (k: pressure per length),
    ``{"pasternak": {"stiffness": k, "shear": mu}}`` (mu: force per unit thickness),
    ``{"half_plane": {"youngs_modulus": E, "poisson_ratio": nu, "reference_distance": d}}``.
    The footing's horizontal translation is not resisted by a frictionless
    foundation; the reply says so in ``notes``.
    """
    return _footing(model, width, height, youngs_modulus, poisson_ratio, size, extent, element,
                    tractions=[rq.pressure("top", pressure)])


def _footing(model: dict, width: float, height: float, youngs_modulus: float, poisson_ratio: float, size: float,
             extent: float, element: str, description: str | None = None, **loads) -> dict:
    """An unsupported footing centred on x = 0 resting on the foundation ``soil``
    along y = 0, x in [-extent, extent], with ``loads`` (tractions=, point_loads=)."""
    footing = rq.body("footing", rq.material(youngs_modulus, poisson_ratio),
                      rq.rectangle([-0.5 * width, 0.0], width, height, size, element), **loads)
    return rq.request(
        bodies=[footing],
        foundations=[rq.foundation("soil", model, -extent, extent)],
        contacts=[rq.contact("footing", "bottom", foundation="soil")],
        description=description,
    )


def gmsh_mesh(msh: str, surfaces: list[str] | None = None) -> dict:
    """A body's ``mesh`` from Gmsh MSH 4.1 ASCII text (e.g. ``open("part.msh").read()``).

    Triangles (3- or 6-node) make the body, or only those of the physical surface groups
    named in ``surfaces``; each physical curve group becomes the edge set of its name.
    """
    return rq.gmsh(msh, surfaces)


def roller_on_floor(
    radius: float = 8.0,
    approach: float | None = None,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    h_min: float = 0.01,
    size: float = 0.5,
    extent: float = 1.2,
    element: str = "t3",
    analysis: str = "plane_strain",
    *,
    load: float | None = None,
    friction: float | None = None,
    shifts: list[float] | None = None,
    steps: int = 10,
) -> dict:
    """An elastic roller on a rigid floor (proto/examples/signorini_roller_on_flat.json).

    A half-disk of ``radius`` [length], arc down, touching the rigid line y = 0 at the
    origin; its flat top face is clamped and moved down by ``approach`` [length]
    (default 0.05), or, with ``load`` [force per unit thickness] instead, pushed
    down by the uniform pressure load / (2 radius) and held only by the floor (see
    ``_held_by_contact``). Material ``youngs_modulus`` [force/length^2] and
    ``poisson_ratio``. The mesh is ``h_min`` [length] within ``extent`` of the apex,
    graded by 1.1 up to ``size``. Hertz (elastic cylinder on a rigid flat) with P =
    |resultant.fy|, which is ``load`` under load control: ``hertz_reference``.

    ``friction``: Coulomb μ between roller and floor. ``shifts``: after pressing,
    the clamped top is moved sideways by each of these displacements [length] in
    turn (a load path: pressed, then shifted, so that P stays about constant while
    the tangential load Q = -resultant.fx grows; the contact sticks on
    |x| < a sqrt(1 - Q/(μP)), ``cattaneo_mindlin_stick``). With ``shifts`` the
    approach is ramped in ``steps`` equal steps (default 10; the reply's ``steps``
    holds those, then one per shift), because friction depends on the path: a point
    closing during a step counts the tangential motion it made while open as that
    step's slip, so a press in one step from rest locks a shear into the zone that a
    gradual press does not. Measured (nu = 0.499, T6, h_min = 0.0075, μ = 0.5, shifts
    0.015, 0.025, 0.035, Q/(μP) = 0.29 to 0.67): the peak shear reads +15.5 to +5.1 %
    against Cattaneo-Mindlin's μ p0 sqrt(Q/(μP)) pressed in one step, +4.2 to +4.0 % in
    ten (20 steps change it by < 0.05 %; the 4 % left is the finite roller, a/R = 0.06).
    ``steps=1`` presses in one step, as before. The tangential load is
    applied by the motion of the top rather than as a force: with friction the
    solver does not yet take a body held sideways only by the floor, so ``shifts``
    needs displacement control (``approach``, not ``load``). A sideways load
    (force) on a rigid punch is ``punch_on_block(friction=..., horizontal_load=...)``.
    """
    mesh = rq.half_disk([0.0, radius], radius, "down", size, element, rq.grading(h_min, 1.1, extent))
    held, how = _held_by_contact("flat", 2.0 * radius, approach, load, 0.05)
    path = None
    if shifts is not None:
        if load is not None:
            raise ValueError("shifts move the roller's clamped top: give approach (displacement control), not load")
        shifts = [float(s) for s in shifts]
        if not shifts or not all(math.isfinite(s) for s in shifts):
            raise ValueError(f"shifts must be a non-empty list of finite displacements, not {shifts!r}")
        # The sideways motion as its own support on the top, scaled alone by the path.
        pressed = held["supports"][0]
        held["supports"] = [rq.support("flat", uy=pressed["uy"]), rq.support("flat", ux=1.0)]
        path = _pressed_then("/bodies/0/supports/0", "/bodies/0/supports/1", steps, shifts)
        how += f", then shifted sideways by {shifts}"
    return rq.request(
        bodies=[rq.body("roller", rq.material(youngs_modulus, poisson_ratio), mesh, **held)],
        obstacles=[rq.obstacle("floor", rq.line([0.0, 0.0], [0.0, 1.0]))],
        contacts=[rq.contact("roller", "arc", obstacle="floor", friction=friction)],
        analysis=analysis,
        load_path=path,
        description=f"elastic roller R={radius} {how} onto a rigid floor"
        + ("" if friction is None else f", friction mu = {friction}"),
    )


def _held_by_contact(face: str, face_width: float, approach: float | None, load: float | None,
                     default_approach: float, axisymmetric: bool = False) -> tuple[dict, str]:
    """The supports and loads of a body pressed down through its clamped top ``face``.

    Displacement control: ``face`` clamped and moved down by ``approach``.
    Load control: ``face`` carries the uniform pressure that sums to ``load`` (over
    ``face_width``, or over the disk of that radius in axisymmetry) and keeps only
    ux = 0: the vertical translation is left to the contact (Fichera: it balances
    ``load``), ux = 0 fixes the sideways slide that a frictionless contact cannot
    resist (a support that carries no net load: nothing pushes sideways), and the
    rotation about the face's centre that it leaves free is resisted by the contact
    zone and carries no load either (the loads have no moment about that point).
    In axisymmetry the face is free: u_r = 0 on the axis already, and the
    axial translation is the only rigid motion.
    """
    if load is None:
        approach = default_approach if approach is None else approach
        return ({"supports": [rq.support(face, None if axisymmetric else 0.0, -approach)]},
                f"pressed {approach}")
    _load_or_motion(load, approach, "approach")
    area = math.pi * face_width ** 2 if axisymmetric else face_width
    supports = [] if axisymmetric else [rq.support(face, ux=0.0)]
    return {"supports": supports, "tractions": [rq.pressure(face, load / area)]}, f"pressed with P={load}"


def _block(width: float, height: float, size: float, element: str) -> dict:
    """Rectangle [-width/2, width/2] x [0, height]; edge sets bottom, right, top, left."""
    return rq.rectangle([-0.5 * width, 0.0], width, height, size, element)


def block_on_polyline(
    points: list[list[float]] | None = None,
    push: float = 0.01,
    width: float = 2.0,
    height: float = 1.0,
    youngs_modulus: float = 1000.0,
    poisson_ratio: float = 0.25,
    size: float = 0.05,
    element: str = "t3",
    analysis: str = "plane_stress",
) -> dict:
    """An elastic block ``width`` x ``height`` [length], bottom face on y = 0, resting on a
    rigid polyline floor through ``points`` [[x, y], ...] given left to right (rigid below;
    default the vee (-2, 0.2), (0, 0), (2, 0.2) of
    proto/examples/signorini_inline_block_on_vee.json), its top clamped and moved down by
    ``push`` [length]. Material in force/length^2; uniform mesh of ``size``.
    """
    points = points if points is not None else [[-2.0, 0.2], [0.0, 0.0], [2.0, 0.2]]
    return rq.request(
        bodies=[rq.body("block", rq.material(youngs_modulus, poisson_ratio), _block(width, height, size, element),
                        [rq.support("top", 0.0, -push)])],
        obstacles=[rq.obstacle("floor", rq.polyline(points))],
        contacts=[rq.contact("block", "bottom", obstacle="floor")],
        analysis=analysis,
        description=f"elastic block {width} x {height} pushed {push} onto a rigid polyline floor",
    )


def block_held_by_contact(
    pressure: float = 1.0,
    width: float = 2.0,
    height: float = 1.0,
    youngs_modulus: float = 1000.0,
    poisson_ratio: float = 0.25,
    size: float = 0.05,
    element: str = "t3",
) -> dict:
    """A block ``width`` x ``height`` [length] with no support, held only by contact: a
    uniform ``pressure`` [force/length^2] on its top presses it onto the rigid floor y = 0.
    Its horizontal sliding is resisted by nothing (frictionless) and carries no load: the
    reply says so in ``notes``. Exact answer: uniform contact pressure equal to ``pressure``.
    """
    return rq.request(
        bodies=[rq.body("block", rq.material(youngs_modulus, poisson_ratio), _block(width, height, size, element),
                        tractions=[rq.pressure("top", pressure)])],
        obstacles=[rq.obstacle("floor", rq.line([0.0, 0.0], [0.0, 1.0]))],
        contacts=[rq.contact("block", "bottom", obstacle="floor")],
        description=f"unsupported block {width} x {height} pressed by {pressure} onto a rigid floor",
    )


def roller_on_plate(
    radius: float = 8.0,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    plate_modulus: float = 70.0,
    plate_poisson: float = 0.33,
    approach: float | None = None,
    plate_width: float = 40.0,
    plate_depth: float = 20.0,
    h_min: float = 0.01,
    extent: float = 1.2,
    element: str = "t3",
    discretization: str = "mortar",
    *,
    load: float | None = None,
    tangential: float | list[float] | None = None,
    friction: float | None = None,
    steps: int = 10,
) -> dict:
    """An elastic roller on an elastic plate (two deformable bodies, any materials).

    A half-disk of ``radius`` (arc down, touching the plate's top face y = 0 at
    the origin) with its flat top clamped and moved down by ``approach`` (default
    0.05), or, with ``load`` instead, pressed down by that force through its axle:
    the flat is coupled rigidly to the centre (0, radius) (``request.coupling``),
    which carries the vertical load, is held sideways and against rotation, and
    the roller is held only by the plate below it. The plate
    ``plate_width`` x ``plate_depth`` below it is fixed at its bottom.
    Both meshes are ``h_min`` within ``extent`` of the contact point (not
    matching: the plate's is 1.3 h_min), graded by 1.1 elsewhere. The softer
    body carries the pressure (the service turns the pair round when needed).
    Reference: ``hertz_two_cylinders(P, radius, math.inf, E, nu, E_plate,
    nu_plate)`` with P = |resultant.fy| of the pair (a flat is a cylinder of
    infinite radius), while a is small against the radius and the plate.

    ``friction``: Coulomb μ between roller and plate. ``tangential``: a sideways
    force Q [force per unit thickness] pushed through the axle after the press, its
    rotation still held (or a list of forces, applied in turn); it needs ``friction``
    and is carried by it while |Q| < μP. The axle is coupled with ``tangential``
    whether the press is a ``load`` or an ``approach``. With friction the press is
    ramped in ``steps`` equal load path steps (default 10; the reply's ``steps`` holds
    those, then one per tangential force), since friction depends on the path (see
    ``roller_on_floor``); ``steps=1`` presses in one step. With the same material on
    both sides (plate_modulus = youngs_modulus, plate_poisson = poisson_ratio: Dundurs
    beta = 0) the contact then sticks on |x| < a sqrt(1 - Q/(μP)),
    ``cattaneo_mindlin_stick`` with a from ``hertz_two_cylinders``; each coupling's
    motion and the force through it are in the reply's ``couplings`` (per step too).
    A free axle (its rotation a load of 0, ``request.coupling``) would roll under Q:
    the reply warns ``rolling``.
    """
    press = "/bodies/0/couplings/0/vertical"
    push = "/bodies/0/couplings/0/horizontal"
    forces = None
    if tangential is not None:
        forces = [float(q) for q in (tangential if isinstance(tangential, (list, tuple)) else [tangential])]
        if not forces or not all(math.isfinite(q) for q in forces):
            raise ValueError(f"tangential must be a finite force or a non-empty list of them, not {tangential!r}")
        if not friction:
            raise ValueError("a tangential load needs friction: a frictionless contact cannot carry it")
    if load is not None:
        _load_or_motion(load, approach, "approach")
        vertical, how = rq.load(-load), f"pressed through its axle with P={load}"
    elif forces is not None:
        approach = 0.05 if approach is None else approach
        vertical, how = rq.displacement(-approach), f"its axle pressed {approach}"
    else:
        vertical = None
    if vertical is None:
        held, how = _held_by_contact("flat", 2.0 * radius, approach, None, 0.05)
    else:
        # Q enters the horizontal load at factor 1, each step naming its force.
        horizontal = rq.load(1.0) if forces is not None else None
        held = {"couplings": [rq.coupling("flat", [0.0, radius], horizontal=horizontal, vertical=vertical)]}
    path = None
    if friction and "supports" in held:
        path = [rq.load_step({"/bodies/0/supports/0": f}) for f in _press_ramp(steps)]
    if friction and "couplings" in held:
        if forces is None:
            path = [rq.load_step({press: f}) for f in _press_ramp(steps)]
        else:
            path = _pressed_then(press, push, steps, forces)
            how += f", then pushed sideways by {forces}"
    roller = rq.body("roller", rq.material(youngs_modulus, poisson_ratio),
                     rq.half_disk([0.0, radius], radius, "down", radius / 16.0, element,
                                  rq.grading(h_min, 1.1, extent)),
                     **held)
    plate = rq.body("plate", rq.material(plate_modulus, plate_poisson),
                    rq.rectangle([-0.5 * plate_width, -plate_depth], plate_width, plate_depth, plate_depth / 16.0,
                                 element, rq.grading(1.3 * h_min, 1.1, extent, focus=[0.0, 0.0])),
                    [rq.support("bottom", 0.0, 0.0)])
    return rq.request(
        bodies=[roller, plate],
        contacts=[rq.contact("roller", "arc", against=("plate", "top"), discretization=discretization,
                             friction=friction)],
        load_path=path,
        description=f"elastic roller R={radius} (E={youngs_modulus}) {how} onto an elastic plate "
                    f"(E={plate_modulus})" + ("" if friction is None else f", friction mu = {friction}"),
    )


def footing_with_eccentric_load(
    model: dict,
    load: float = 10.0,
    eccentricity: float = 0.0,
    moment: float = 0.0,
    width: float = 2.0,
    height: float = 0.5,
    youngs_modulus: float = 1e5,
    poisson_ratio: float = 0.2,
    size: float = 0.05,
    extent: float = 5.0,
    element: str = "t3",
) -> dict:
    """A footing ``width`` x ``height`` with no support on a tensionless
    foundation (``model``: ``request.winkler(k)``, ``request.pasternak(k, mu)``
    or ``request.half_plane(E, nu, d)``) along y = 0, loaded on its top by a
    vertical point load ``load`` (per unit thickness, downward) at x =
    ``eccentricity`` and by a ``moment`` (counter-clockwise), the moment
    applied as a pair of opposite vertical point loads at the top corners.

    Reference for a stiff footing (the default modulus is 1e5 against the
    foundation): ``rigid_footing_pressure`` with the resultant's eccentricity
    ``eccentricity - moment / load``: the linear pressure of a rigid footing,
    valid while that stays within the kern (|e| <= width/6: no uplift; exact
    for Winkler). Equilibrium holds whatever the model: the foundation carries
    ``load`` and the moment load * eccentricity - moment about the origin.
    """
    half = 0.5 * width
    points = [rq.point_load("top", [eccentricity, height], [0.0, -load])]
    if moment:
        # M = couple of ±M/width at the corners (counter-clockwise positive).
        f = moment / width
        points += [rq.point_load("top", [half, height], [0.0, f]),
                   rq.point_load("top", [-half, height], [0.0, -f])]
    return _footing(model, width, height, youngs_modulus, poisson_ratio, size, extent, element,
                    description=f"footing {width} x {height} on a tensionless foundation, load {load} at "
                                f"x = {eccentricity}, moment {moment}",
                    point_loads=points)


def punch_from_polyline(points: list[list[float]], load: float = 10.0, **block) -> dict:
    """A rigid punch whose face is a drawing's polyline ``points`` [[x, y], ...]
    (left to right, y up; the rigid material above it), pressed with ``load``
    into the block of ``punch_on_block`` (keyword arguments as there). x is
    measured from the punch's reference point (the load acts there); the
    drawing is moved up or down so its lowest point touches the block's top
    face. A straight face from -b to b is the flat punch of ``sadowsky_pressure``."""
    if len(points) < 2 or any(b[0] <= a[0] for a, b in zip(points, points[1:])):
        raise ValueError("points must be at least two [x, y] with increasing x")
    low = min(y for _, y in points)
    shifted = [[float(x), float(y) - low] for x, y in points]
    return punch_on_block({"polyline": {"points": shifted}}, load=load, **block)


# Bodies of revolution (analysis "axisymmetric"): the r-z half-section, x = r >= 0,
# y the axis; forces are totals over the circumference.


def ball_on_flat(
    radius: float = 10.0,
    approach: float | None = None,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    h_min: float = 0.015,
    extent: float = 1.5,
    element: str = "t3",
    method: str = "auto",
    *,
    load: float | None = None,
    accuracy: dict | None = None,
) -> dict:
    """An elastic ball on a rigid flat (proto/examples/axisymmetric_ball_on_flat.json).

    The lower quarter of the ball's section (centre (0, ``radius``), the axis x = 0)
    touches the flat y = 0 at the origin; its equator plane is moved down by
    ``approach`` (default 0.04), or, with ``load`` (a total over the circumference)
    instead, pushed down by the pressure load / (pi radius^2) on the equator plane
    and held only by the flat (no support: the axial translation is the ball's only
    rigid motion). The mesh is ``h_min`` within ``extent`` of the contact point,
    graded by 1.1 up to ``radius`` / 8. Reference: ``hertz_sphere_reference`` with
    P = resultant.fy (``load`` under load control); the contact zone is [0, a] on
    the section. ``accuracy`` (``request.accuracy(pressure_l2=...)``) refines until
    the reply's error estimate meets it.
    """
    mesh = rq.quarter_disk([0.0, radius], radius, "down", radius / 8.0, element, rq.grading(h_min, 1.1, extent))
    held, how = _held_by_contact("flat", radius, approach, load, 0.04, axisymmetric=True)
    return rq.request(
        bodies=[rq.body("ball", rq.material(youngs_modulus, poisson_ratio), mesh, **held)],
        obstacles=[rq.obstacle("floor", rq.line([0.0, 0.0], [0.0, 1.0]))],
        contacts=[rq.contact("ball", "arc", obstacle="floor")],
        analysis="axisymmetric",
        method=method,
        settings=None if accuracy is None else {"accuracy": accuracy},
        description=f"elastic ball R={radius} {how} onto a rigid flat (axisymmetric)",
    )


def ball_on_flat_3d(
    load: float = 6153.846153846154,
    radius: float = 50.0,
    youngs_modulus: float = 210000.0,
    poisson_ratio: float = 0.3,
    side: float = 10.0,
    h_min: float = 0.2,
    extent: float = 1.2,
    element: str = "t10",
) -> dict:
    """A ball of ``radius`` pressed on a rigid flat by the total ``load``, in 3D as Hertz
    poses it (proto/examples/solid_ball_on_flat.json, its defaults).

    The ball is a quarter of a cube of ``side`` (rollers on the symmetry planes x = 0
    and y = 0) whose flat face z = 0 carries the ball's gap r^2 / (2 ``radius``) to the
    flat (``initial_gap.paraboloid``); the quarter's top carries load / 4 as a uniform
    pressure. Cells of ``h_min`` within ``extent`` of the apex, graded by 2 up to
    ``side`` / 2. Reference: ``hertz_sphere_reference(load, radius, ...)``; the reply's
    ``solid.resultant.force[2]`` is load / 4.
    """
    return {
        "version": "1",
        "description": f"ball R={radius} pressed by {load} on a rigid flat (3D, quarter model)",
        "analysis": "solid",
        "solid": {
            "body": _quarter_cube_3d("ball", 0.0, "z_max", load, youngs_modulus, poisson_ratio, side, h_min, extent,
                                     element),
            "obstacle": {"name": "flat", "shape": {"plane": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}}},
            "contact": {
                "faces": "z_min",
                "initial_gap": {"paraboloid": {"apex": [0.0, 0.0, 0.0], "radius": radius}},
            },
        },
    }


def _quarter_cube_3d(name: str, z0: float, loaded: str, load: float, youngs_modulus: float, poisson_ratio: float,
                     side: float, h_min: float, extent: float, element: str) -> dict:
    """The body of the 3D Hertz quarter models: a cube of ``side`` from z = ``z0`` with
    rollers on x = 0 and y = 0, graded by 2 from ``h_min`` within ``extent`` of the
    origin up to ``side`` / 2, its face ``loaded`` pressed by load / 4."""
    return {
        "name": name,
        "material": {"youngs_modulus": youngs_modulus, "poisson_ratio": poisson_ratio},
        "mesh": {"box": {
            "corner": [0.0, 0.0, z0], "lengths": [side, side, side], "size": side / 2.0,
            "element": element,
            "grading": {"focus": [0.0, 0.0, 0.0], "h_min": h_min, "ratio": 2.0, "extent": extent},
        }},
        "supports": [{"faces": "x_min", "ux": 0.0}, {"faces": "y_min", "uy": 0.0}],
        "tractions": [{"faces": loaded, "pressure": load / 4.0 / (side * side)}],
    }


def sphere_into_block_3d(
    load: float = 6153.846153846154,
    radius: float = 50.0,
    youngs_modulus: float = 210000.0,
    poisson_ratio: float = 0.3,
    side: float = 10.0,
    h_min: float = 0.2,
    extent: float = 1.2,
    element: str = "t10",
) -> dict:
    """A rigid sphere of ``radius`` pressed into an elastic block by the total ``load``, in
    3D (proto/examples/solid_sphere_into_block.json, its defaults).

    The block is a quarter of a cube of ``side`` below z = 0 (rollers on the symmetry
    planes x = 0 and y = 0), touched at the origin by the sphere (``obstacle.shape.sphere``,
    its own distance as the gap); the quarter's bottom carries load / 4 as a uniform
    pressure pushing it up. Cells of ``h_min`` within ``extent`` of the apex, graded by 2
    up to ``side`` / 2. Reference: ``hertz_sphere_reference(load, radius, ...)``; the
    reply's ``solid.resultant.force[2]`` is -load / 4 (the sphere pushes down).
    """
    return {
        "version": "1",
        "description": f"rigid sphere R={radius} pressed by {load} into a block (3D, quarter model)",
        "analysis": "solid",
        "solid": {
            "body": _quarter_cube_3d("block", -side, "z_min", load, youngs_modulus, poisson_ratio, side, h_min, extent,
                                     element),
            "obstacle": {"name": "sphere", "shape": {"sphere": {"centre": [0.0, 0.0, radius], "radius": radius}}},
            "contact": {"faces": "z_max"},
        },
    }


def block_on_plane_3d(
    pressure: float = 2.0,
    lengths: tuple[float, float, float] = (40.0, 40.0, 20.0),
    size: float = 10.0,
    h_min: float | None = None,
    youngs_modulus: float = 210000.0,
    poisson_ratio: float = 0.3,
    element: str = "t4",
    outputs: list[str] | None = None,
) -> dict:
    """A box of ``lengths`` resting on a rigid plane z = 0 under a uniform ``pressure`` on
    its top, its four sides on rollers: the 3D contact patch test. The state is
    oedometric (a strain in T4's space), so every contact point's pressure is
    ``pressure`` on any mesh, T4 (nodal rows) or T10 (dual mortar rows).

    Cells of ``size``; with ``h_min``, graded from ``h_min`` at the corner (0.3, 0.6, 0)
    of the base's unit square by 1.5 up to ``size`` (a mesh with no symmetry, to show the
    answer does not depend on it). ``outputs`` (e.g. ``["vtu"]``) is the request's.
    """
    box = {"corner": [0.0, 0.0, 0.0], "lengths": list(lengths), "size": size, "element": element}
    if h_min is not None:
        box["grading"] = {"focus": [0.3, 0.6, 0.0], "h_min": h_min, "ratio": 1.5, "extent": 0.0}
    request = {
        "version": "1",
        "description": f"box {lengths} pressed by {pressure} on a rigid plane (3D patch test)",
        "analysis": "solid",
        "solid": {
            "body": {
                "name": "block",
                "material": {"youngs_modulus": youngs_modulus, "poisson_ratio": poisson_ratio},
                "mesh": {"box": box},
                "supports": [
                    {"faces": "x_min", "ux": 0.0}, {"faces": "x_max", "ux": 0.0},
                    {"faces": "y_min", "uy": 0.0}, {"faces": "y_max", "uy": 0.0},
                ],
                "tractions": [{"faces": "z_max", "pressure": pressure}],
            },
            "obstacle": {"name": "plane", "shape": {"plane": {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}}},
            "contact": {"faces": "z_min"},
        },
    }
    if outputs:
        request["outputs"] = list(outputs)
    return request


def flat_punch_of_revolution(
    load: float = 100.0,
    punch_radius: float = 1.0,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    body_radius: float = 80.0,
    h_min: float = 0.01,
    extent: float = 1.2,
    element: str = "t3",
    method: str = "auto",
) -> dict:
    """A rigid flat cylindrical punch of radius ``punch_radius`` pressed with the total
    ``load`` into an elastic cylinder of radius and height ``body_radius``, bottom
    fixed (proto/examples/axisymmetric_flat_punch.json). A punch of revolution moves
    along the axis only. References: ``boussinesq_pressure`` and
    ``boussinesq_settlement`` (half-space; the finite cylinder settles about
    a / body_radius less).
    """
    mesh = rq.rectangle([0.0, -body_radius], body_radius, body_radius, body_radius / 20.0, element,
                        rq.grading(h_min, 1.1, extent, [0.0, 0.0]))
    controls = rq.punch(vertical=rq.load(-load))
    return rq.request(
        bodies=[rq.body("block", rq.material(youngs_modulus, poisson_ratio), mesh, [rq.support("bottom", 0.0, 0.0)])],
        obstacles=[rq.obstacle("punch", rq.profile({"flat": {"half_width": punch_radius}}), controls)],
        contacts=[rq.contact("block", "top", obstacle="punch")],
        analysis="axisymmetric",
        method=method,
        description=f"rigid flat punch of radius {punch_radius} pressed with P = {load} (axisymmetric)",
    )


def press_fit(
    shaft_radius: float = 1.0,
    outer_radius: float = 2.0,
    height: float = 1.0,
    interference: float = 0.001,
    youngs_modulus: float = 200.0,
    poisson_ratio: float = 0.3,
    size: float = 0.05,
    element: str = "t3",
    *,
    friction: float | None = None,
    push: float | None = None,
    shaft_end: str = "top",
) -> dict:
    """A shaft of radius ``shaft_radius`` fitted into a ring of outer radius
    ``outer_radius`` with the radial ``interference`` (a negative initial gap), both of
    ``height``, the same material, the ring's bottom and the shaft's ``shaft_end`` held
    axially (axisymmetric; the ring's bore carries the pressure, mortar rows).
    Frictionless, the pressure is ``lame_press_fit_pressure`` over the whole bore (free
    ends: plane stress).

    ``friction``: Coulomb μ on the bore. ``push``: after the fit closes (first load
    path step), the shaft's held end is moved along the axis by ``push``; pushed beyond
    the elastic slip (about interference / radius × height), the whole bore slides and
    the push-out force, the friction resultant's axial part, is μ times the normal
    ring force Σ force, about μ p 2π b L (Lamé's p, b the bore radius, L the height).

    ``shaft_end``: ``"top"`` (the default), the shaft held and moved by its far end
    from the ring's held bottom, has a bounded answer at any μ (a large μ is the stick
    limit); ``"bottom"``, both bottoms held, puts the bore's bottom node on two held
    faces, so that moving the shaft prescribes its slip: it slides with the friction
    force μ λ, without bound as μ grows (``max_iterations`` from μ = 100), and the reply
    warns ``prescribed_slip``. At a real μ both answer alike (the push-out force is μ
    times the normal ring force either way). Up to 0.2.0 the shaft was held by its bottom.
    Unlike the other frictional builders it has no ``steps``: the fit is pressed by its
    interference, an initial gap, which load path factors do not scale (they scale loads
    and prescribed displacements, gaps unchanged), so it closes in the first step.
    """
    bore = shaft_radius - interference
    if shaft_end not in ("top", "bottom"):
        raise ValueError(f"shaft_end must be 'top' or 'bottom', not {shaft_end!r}")

    def body(name: str, corner: float, width: float, uy: float, held: str) -> dict:
        mesh = rq.rectangle([corner, 0.0], width, height, size, element)
        return rq.body(name, rq.material(youngs_modulus, poisson_ratio), mesh, [rq.support(held, uy=uy)])

    path = None
    if push is not None:
        if not math.isfinite(push):
            raise ValueError(f"push must be a finite displacement, not {push!r}")
        path = [rq.load_step({"/bodies/0/supports/0": 0.0}), rq.load_step({"/bodies/0/supports/0": 1.0})]
    return rq.request(
        bodies=[
            body("shaft", 0.0, shaft_radius, push if push is not None else 0.0, shaft_end),
            body("ring", bore, outer_radius - bore, 0.0, "bottom"),
        ],
        contacts=[rq.contact("ring", "left", against=("shaft", "right"), friction=friction)],
        analysis="axisymmetric",
        load_path=path,
        description=f"press fit, shaft radius {shaft_radius} in a ring to {outer_radius}, interference {interference}"
        + ("" if friction is None else f", friction mu = {friction}")
        + ("" if push is None else f", pushed {push} along the axis by the shaft's {shaft_end}"),
    )
