"""Meshes made with the ``gmsh`` Python package (``pip install gmsh``), as MSH 4.1 ASCII text.

The service reads the text inline, ``{"gmsh": {"msh": text}}`` (or, with
``contact solve FILE``, ``{"gmsh": {"file": "mesh.msh"}}`` next to the request):
triangles make the body, the line elements of each physical curve group the edge
set of that name.
"""

from __future__ import annotations

import os
import tempfile


def hertz_block(width: float = 40.0, height: float = 20.0, h_min: float = 0.01, size: float = 1.0,
                fine: float = 0.8, growth: float = 0.1, order: int = 1) -> str:
    """MSH text of the block [-width/2, width/2] x [-height, 0] (lengths in the caller's unit).

    Element size ``h_min`` along the top face for |x| <= ``fine`` (cover the contact zone),
    growing with the distance d from that segment as h_min + ``growth`` d (neighbouring elements
    about 1 + growth times larger, like the generated meshes' ratio) up to ``size``. Physical
    curve groups "bottom", "right", "top", "left" (the edge sets of a generated rectangle) and
    the physical surface "block". ``order`` 1 gives 3-node triangles, 2 gives 6-node ones.
    """
    import gmsh  # optional dependency: pip install 'contact-client[gmsh]'

    w, h = 0.5 * width, height
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("hertz_block")
        g = gmsh.model.geo
        pts = [g.addPoint(x, y, 0.0) for x, y in [(-w, -h), (w, -h), (w, 0.0), (fine, 0.0), (-fine, 0.0), (-w, 0.0)]]
        bottom = g.addLine(pts[0], pts[1])
        right = g.addLine(pts[1], pts[2])
        top = [g.addLine(pts[2], pts[3]), g.addLine(pts[3], pts[4]), g.addLine(pts[4], pts[5])]
        left = g.addLine(pts[5], pts[0])
        loop = g.addCurveLoop([bottom, right, *top, left])
        surface = g.addPlaneSurface([loop])
        g.synchronize()
        for name, curves in (("bottom", [bottom]), ("right", [right]), ("top", top), ("left", [left])):
            gmsh.model.setPhysicalName(1, gmsh.model.addPhysicalGroup(1, curves), name)
        gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, [surface]), "block")
        f = gmsh.model.mesh.field
        dist = f.add("Distance")
        f.setNumbers(dist, "CurvesList", [top[1]])
        f.setNumber(dist, "Sampling", max(100, int(2 * fine / h_min)))
        grow = f.add("MathEval")
        f.setString(grow, "F", f"Min({size}, {h_min} + {growth} * F{dist})")
        f.setAsBackgroundMesh(grow)
        for opt in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(opt, 0)
        gmsh.model.mesh.generate(2)
        if order == 2:
            gmsh.model.mesh.setOrder(2)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        fd, path = tempfile.mkstemp(suffix=".msh")
        os.close(fd)
        try:
            gmsh.write(path)
            with open(path, encoding="ascii") as fh:
                return fh.read()
        finally:
            os.unlink(path)
    finally:
        gmsh.finalize()
