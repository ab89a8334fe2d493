"""Closed-form references of the standard scenes (``contact_client.scenes``).

The solver's answers are checked against these: the tests, ``plot_pressure``'s
reference curve (``results``) and the README's examples call them. Each is the
classical solution for the idealised problem (half-plane or half-space, small
strain, frictionless unless said); the scene builders' docstrings say how
closely their finite meshes and bodies approach it. ``scenes`` re-exports every
name here, so ``scenes.hertz_reference`` keeps working.

Hertz, cylinder on a flat (plane strain, frictionless, small strain), with
P the load per unit thickness and E* = E / (1 - nu^2) for an elastic body
against a rigid one (E* = E in plane stress):

    a  = sqrt(4 P R / (pi E*))          contact half-width
    p0 = 2 P / (pi a)                   peak pressure
    p(x) = p0 sqrt(1 - x^2 / a^2),  |x| <= a

The theory assumes a << R and a body large compared with a: see
``scenes.hertz_cylinder`` for the sizes the builder picks and why.

References:

- H. Hertz, Über die Berührung fester elastischer Körper, J. reine angew.
  Math. 92 (1882) 156–171: Hertz contact of cylinders and spheres.
- K. L. Johnson, Contact Mechanics, Cambridge University Press (1985):
  ch. 2 (the flat punch, §2.8), ch. 3 (point loading of a half-space,
  Boussinesq's punch), ch. 4 (Hertz theory), ch. 7 (tangential loading,
  Cattaneo–Mindlin).
- M. Sadowsky, Zweidimensionale Probleme der Elastizitätstheorie, ZAMM 8
  (1928) 107–121: the rigid flat punch on a half-plane.
- J. Boussinesq, Application des potentiels à l'étude de l'équilibre et du
  mouvement des solides élastiques, Gauthier-Villars, Paris (1885): the rigid
  flat cylindrical punch on a half-space.
- C. Cattaneo, Sul contatto di due corpi elastici: distribuzione locale degli
  sforzi, Rend. Accad. Naz. Lincei 27 (1938); R. D. Mindlin, Compliance of
  elastic bodies in contact, J. Appl. Mech. 16 (1949) 259–268: the stick zone
  under a tangential load.
- E. Winkler, Die Lehre von der Elasticität und Festigkeit, Prag (1867): the
  foundation of independent springs.
- P. L. Pasternak, On a new method of analysis of an elastic foundation by
  means of two foundation constants (in Russian), Moscow (1954): the layer
  with shear, p = k w - mu w''.
- G. Lamé, Leçons sur la théorie mathématique de l'élasticité des corps
  solides, Paris (1852): the thick-walled cylinder, hence the fit pressure.
"""

from __future__ import annotations

import math

__all__ = [
    "effective_modulus",
    "hertz_reference",
    "hertz_pressure",
    "hertz_two_cylinders",
    "hertz_measure",
    "sadowsky_pressure",
    "cattaneo_mindlin_stick",
    "stick_measure",
    "rigid_footing_pressure",
    "pasternak_deflection",
    "hertz_sphere_reference",
    "boussinesq_pressure",
    "boussinesq_settlement",
    "lame_press_fit_pressure",
]


# Hertz, plane (Hertz 1882; Johnson ch. 4).


def effective_modulus(youngs_modulus: float, poisson_ratio: float, analysis: str = "plane_strain") -> float:
    """E* of an elastic body against a rigid one."""
    if analysis in ("plane_strain", "axisymmetric"):
        return youngs_modulus / (1.0 - poisson_ratio ** 2)
    if analysis == "plane_stress":
        return youngs_modulus
    raise ValueError(f"analysis must be 'plane_strain', 'plane_stress' or 'axisymmetric', not {analysis!r}")


def hertz_reference(P: float, R: float, E: float, nu: float, analysis: str = "plane_strain") -> tuple[float, float]:
    """(a, p0) of a rigid cylinder of radius R pressed with P per unit thickness on an elastic half-plane.

    Hertz (1882); Johnson, Contact Mechanics, ch. 4."""
    if P < 0 or R <= 0 or E <= 0:
        raise ValueError("need P >= 0, R > 0, E > 0")
    e_star = effective_modulus(E, nu, analysis)
    a = math.sqrt(4.0 * P * R / (math.pi * e_star))
    p0 = 2.0 * P / (math.pi * a) if a > 0 else 0.0
    return a, p0


def hertz_pressure(x: float, a: float, p0: float) -> float:
    """Hertz pressure at abscissa x (0 outside the contact)."""
    return p0 * math.sqrt(1.0 - (x / a) ** 2) if abs(x) < a else 0.0


def hertz_two_cylinders(
    P: float,
    R1: float,
    R2: float,
    E1: float,
    nu1: float,
    E2: float,
    nu2: float,
    analysis: str = "plane_strain",
) -> tuple[float, float]:
    """(a, p0) of two elastic cylinders pressed together with P per unit thickness.

    Effective radius 1/R = 1/R1 + 1/R2 and modulus 1/E* = 1/E1* + 1/E2*, with
    Ei* = Ei / (1 - nui^2) in plane strain (Ei in plane stress).
    Hertz (1882); Johnson, Contact Mechanics, ch. 4."""
    R = 1.0 / (1.0 / R1 + 1.0 / R2)
    e_star = 1.0 / (1.0 / effective_modulus(E1, nu1, analysis) + 1.0 / effective_modulus(E2, nu2, analysis))
    a = math.sqrt(4.0 * P * R / (math.pi * e_star))
    return a, (2.0 * P / (math.pi * a) if a > 0 else 0.0)


def hertz_measure(reply: dict, pair: int = 0) -> dict:
    """Contact load and FE Hertz quantities of a solve reply.

    Returns ``P`` (= |resultant.fy|, the obstacle pushes the body down),
    ``a`` (half the length of the single zone), ``p0`` (largest candidate
    pressure), and the node spacing ``h_edge`` just outside each zone end
    (the resolution with which the zone ends can place the true edge).
    These are the quantities ``hertz_reference`` gives in closed form.
    """
    pr = reply["pairs"][pair]
    zones = pr["zones"]
    if len(zones) != 1:
        raise ValueError(f"expected one contact zone, got {len(zones)}: {zones}")
    x0, x1 = zones[0]
    xs = sorted(p["x"] for p in pr["points"])

    def spacing_beyond(x: float, outward: int) -> float:
        i = min(range(len(xs)), key=lambda k: abs(xs[k] - x))
        j = i + outward
        return abs(xs[j] - xs[i]) if 0 <= j < len(xs) else math.inf

    return {
        "P": abs(reply["resultant"]["fy"]),
        "a": 0.5 * (x1 - x0),
        "p0": max(p["pressure"] for p in pr["points"]),
        "zone": (x0, x1),
        "h_edge": max(spacing_beyond(x0, -1), spacing_beyond(x1, +1)),
    }


# The flat punch and friction.


def sadowsky_pressure(x: float, P: float, b: float) -> float:
    """Pressure under a rigid flat punch of half-width b with a centred load P (|x| < b).

    Sadowsky (1928); Johnson, Contact Mechanics, §2.8."""
    return P / (math.pi * math.sqrt(b * b - x * x)) if abs(x) < b else 0.0


def cattaneo_mindlin_stick(a: float, Q: float, mu: float, P: float) -> float:
    """Half-width c of the central stick zone of a cylinder (Hertz half-width ``a``)
    pressed by P and then loaded tangentially by |Q| < μP with P held
    (Cattaneo-Mindlin, elastically similar bodies): c = a sqrt(1 - |Q|/(μP)).

    Cattaneo (1938), Mindlin (1949); Johnson, Contact Mechanics, ch. 7."""
    if not abs(Q) < mu * P:
        raise ValueError(f"|Q| = {abs(Q)} must be below μP = {mu * P}: beyond, the contact slides")
    return a * math.sqrt(1.0 - abs(Q) / (mu * P))


def stick_measure(answer: dict, pair: int = 0) -> dict:
    """The stick zone of a frictional answer (a reply, or one of its ``steps``), measured
    as ``cattaneo_mindlin_stick`` gives it.

    Returns ``P`` (= resultant.fy) and ``Q`` (= -resultant.fx: the force the contact takes
    from the body sideways, so a body pushed toward +x has Q > 0), ``c`` (half the length of
    the one run of sticking points, its ends midway between the run's end points and their
    outer neighbours, where the true transition lies to half a spacing; the reply's
    ``stick_zones`` end at the last sticking points, half a spacing short) and ``centre``.
    """
    res = answer["resultant"]
    pts = sorted(answer["pairs"][pair]["points"], key=lambda p: p["x"])
    idx = [i for i, p in enumerate(pts) if p.get("state") == "stick"]
    if not idx or idx != list(range(idx[0], idx[-1] + 1)):
        raise ValueError("expected one contiguous run of sticking points")
    lo, hi = idx[0], idx[-1]
    left = 0.5 * (pts[lo]["x"] + pts[lo - 1]["x"]) if lo > 0 else pts[lo]["x"]
    right = 0.5 * (pts[hi]["x"] + pts[hi + 1]["x"]) if hi + 1 < len(pts) else pts[hi]["x"]
    return {"P": res["fy"], "Q": -res["fx"], "c": 0.5 * (right - left), "centre": 0.5 * (left + right)}


# Footings on foundations.


def rigid_footing_pressure(x: float, load: float, eccentricity: float, width: float) -> float:
    """Pressure under a rigid footing of ``width`` centred at 0 on a Winkler
    foundation, carrying ``load`` whose resultant acts at x = ``eccentricity``:
    P/B (1 + 12 e x / B^2), valid while it stays >= 0 (|e| <= B/6, no uplift).

    The springs of a Winkler (1867) foundation under a rigid footing give a linear
    pressure; this one is that line's balance of ``load`` and its moment."""
    if abs(x) > 0.5 * width:
        return 0.0
    return load / width * (1.0 + 12.0 * eccentricity * x / width ** 2)


def pasternak_deflection(x: float, P: float, a: float, k: float, mu: float) -> float:
    """Deflection of a Pasternak layer (p = k w - mu w'') under a rigid footing of
    half-width a carrying P per unit thickness: w0 = P / (2 (k a + sqrt(k mu)))
    under it, w0 exp(-(|x| - a) / sqrt(mu/k)) outside.

    The layer of Pasternak (1954), solved for a rigid footing: uniform under it,
    decaying outside, the footing's load balancing k w0 2a and the shear at its ends."""
    w0 = P / (2.0 * (k * a + math.sqrt(k * mu)))
    return w0 if abs(x) <= a else w0 * math.exp(-(abs(x) - a) / math.sqrt(mu / k))


# Bodies of revolution (analysis "axisymmetric"): r >= 0 from the axis, forces are
# totals over the circumference.


def hertz_sphere_reference(P: float, R: float, E: float, nu: float) -> tuple[float, float]:
    """(a, p0) of an elastic sphere of radius R on a rigid flat under the total load P
    (3D Hertz): a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2), E* = E / (1 - nu^2);
    p(r) = p0 sqrt(1 - r^2 / a^2) (``hertz_pressure``).

    Hertz (1882); Johnson, Contact Mechanics, ch. 4."""
    if P < 0 or R <= 0 or E <= 0:
        raise ValueError("need P >= 0, R > 0, E > 0")
    a = (3.0 * P * R / (4.0 * E / (1.0 - nu * nu))) ** (1.0 / 3.0)
    return a, (3.0 * P / (2.0 * math.pi * a * a) if a > 0 else 0.0)


def boussinesq_pressure(r: float, P: float, a: float) -> float:
    """Pressure under a rigid flat cylindrical punch of radius a with the total load P (r < a).

    Boussinesq (1885); Johnson, Contact Mechanics, ch. 3."""
    return P / (2.0 * math.pi * a * math.sqrt(a * a - r * r)) if abs(r) < a else 0.0


def boussinesq_settlement(P: float, a: float, E: float, nu: float) -> float:
    """Settlement of that punch on an elastic half-space: P (1 - nu^2) / (2 a E).

    Boussinesq (1885); Johnson, Contact Mechanics, ch. 3."""
    return P * (1.0 - nu * nu) / (2.0 * a * E)


def lame_press_fit_pressure(shaft_radius: float, outer_radius: float, interference: float,
                            youngs_modulus: float) -> float:
    """Lame's fit pressure of a solid shaft in a ring of the same material (plane
    stress): E delta (c^2 - b^2) / (2 b c^2).

    From Lamé's (1852) thick-walled cylinder: the ring's bore and the shaft's surface
    together take up the interference delta."""
    b, c = shaft_radius, outer_radius
    return youngs_modulus * interference * (c * c - b * b) / (2.0 * b * c * c)
