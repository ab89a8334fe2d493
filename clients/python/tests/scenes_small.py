"""A tiny scene with an exact answer, cheap enough to solve after every bad request.

A unit square block [0, 1] x [-1, 0] of two T3 triangles, bottom on rollers
(uy = 0), left side on rollers (ux = 0), pressed down by `delta` by a rigid
flat (a line obstacle through (0, -delta) whose normal points down, toward
the block). Frictionless top and rollers elsewhere leave a uniform uniaxial
stress state that linear elements represent exactly: in plane strain with
sigma_xx = 0, sigma_yy = -E / (1 - nu^2) * delta / H, so the contact pressure is
E / (1 - nu^2) * delta / H at every point and the total force is that times W.
"""

from __future__ import annotations

from contact_client import request as rq

E = 200.0
NU = 0.3
DELTA = 0.01
H = 1.0
W = 1.0

# Counter-clockwise triangles (0,1,2) and (0,2,3) of the square
# 0 (0,-1), 1 (1,-1), 2 (1,0), 3 (0,0).
NODES = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0], [0.0, 0.0]]
ELEMENTS_CCW = [[0, 1, 2], [0, 2, 3]]


def expected_pressure() -> float:
    return E / (1.0 - NU * NU) * DELTA / H


def square_block(elements=None) -> dict:
    mesh = rq.inline_mesh(NODES, elements or ELEMENTS_CCW,
                          {"bottom": [[0, 1]], "right": [[1, 2]], "top": [[2, 3]], "left": [[3, 0]]})
    square = rq.body("square", rq.material(E, NU), mesh, [rq.support("bottom", uy=0.0), rq.support("left", ux=0.0)])
    return rq.request(
        bodies=[square],
        obstacles=[rq.obstacle("flat", rq.line([0.0, -DELTA], [0.0, -1.0]))],
        contacts=[rq.contact(0, "top", obstacle=0)],
        analysis=None,
        description="unit square pressed 0.01 by a rigid flat; uniform stress",
    )
