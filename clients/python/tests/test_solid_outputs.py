"""The 3D solid through the service: the contact patch test of
``scenes.block_on_plane_3d`` and its VTU read back with meshio.

Tolerances: the patch test's state is exact in the discrete space, so its
pressures carry round-off only (about 1e-12 of p measured by
crates/contact/tests/solid.rs on the same scene); 1e-9 of p leaves room for
other meshes. The VTU's arrays are the reply's numbers written as
little-endian f64, so they are equal.
"""

from __future__ import annotations

import pytest

from contact_client import request as rq, save_vtu, scenes


@pytest.mark.parametrize("element", ["t4", "t10"])
def test_block_on_plane_3d_presses_uniformly(client, element):
    p = 2.0
    reply = client.solve(scenes.block_on_plane_3d(pressure=p, h_min=3.0, element=element))
    assert reply["status"] == "solved"
    solid = reply["solid"]
    worst = max(abs(q["pressure"] - p) for q in solid["points"]) / p
    assert worst < 1e-9, f"{element}: pressure off p by {worst:e} of p"
    assert all(q["in_contact"] for q in solid["points"])
    (patch,) = solid["patches"]
    # The whole 40 x 40 base carries the load: p times its area.
    assert abs(patch["force"] - p * 1600.0) < 1e-9 * p * 1600.0



def test_block_on_plane_3d_along_a_load_path(client):
    """A load path on a solid, built with ``request.load_step``: each step scales the
    top's pressure (``/solid/body/tractions/0``) and is the patch test at that
    pressure, to the same round-off; each step echoes its loads with factor 1."""
    p, factors = 2.0, [0.5, 2.0]
    req = scenes.block_on_plane_3d(pressure=p, h_min=3.0, element="t4")
    req["load_path"] = [rq.load_step({"/solid/body/tractions/0": k}) for k in factors]
    reply = client.solve(req)
    assert reply["status"] == "solved"
    assert len(reply["steps"]) == len(factors)
    for step, k in zip(reply["steps"], factors):
        assert step["factor"] == 1.0 and step["loads"] == {"/solid/body/tractions/0": k}
        worst = max(abs(q["pressure"] - k * p) for q in step["solid"]["points"]) / (k * p)
        assert worst < 1e-9, f"step {k}: pressure off k p by {worst:e}"
    # The top level answers the last step.
    assert reply["solid"]["resultant"] == reply["steps"][-1]["solid"]["resultant"]

def test_solid_vtu_opens_with_meshio(client, tmp_path):
    """meshio reads the T10 file as tetra10 (VTK type 24, VTK's node order): its
    points and displacement are the reply's, and each cell's node 8 is the
    midpoint of corners 1 and 3 (VTK's edge order; Gmsh's node 8 is on edge 3-2);
    its cell stress is the oedometer's."""
    meshio = pytest.importorskip("meshio")
    reply = client.solve(
        scenes.block_on_plane_3d(element="t10", size=20.0, outputs=["vtu", "mesh", "displacement"])
    )
    solid = reply["solid"]
    path = tmp_path / "block.vtu"
    save_vtu(reply, str(path))
    m = meshio.read(path)
    assert m.points.tolist() == solid["nodes"]
    assert m.point_data["displacement"].tolist() == solid["displacement"]
    (cells,) = m.cells
    assert cells.type == "tetra10" and len(cells.data) == len(solid["elements"])
    for cell in cells.data:
        mid = (m.points[cell[1]] + m.points[cell[3]]) / 2
        assert abs(m.points[cell[8]] - mid).max() < 1e-12
    # Oedometric stress in every cell: σzz = −p, σxx = σyy = ν/(1−ν) σzz, no shear
    # (XX, YY, ZZ, XY, YZ, XZ), a linear field the elements hold to round-off.
    p, nu = 2.0, 0.3
    want = [nu / (1 - nu) * -p, nu / (1 - nu) * -p, -p, 0.0, 0.0, 0.0]
    assert abs(m.cell_data["stress_tensor"][0] - want).max() < 1e-9 * p
