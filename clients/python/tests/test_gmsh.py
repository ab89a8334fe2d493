"""Gmsh meshes through the service: the checked-in Gmsh example, and (with the gmsh
package installed) quadratic meshes made on the spot, against Hertz."""

from __future__ import annotations

import pytest
from test_hertz import assert_hertz

from contact_client import scenes
from support import EXAMPLES, load_json


def test_the_gmsh_example_obeys_hertz(client):
    req = load_json(EXAMPLES / "signorini_hertz_cylinder_gmsh.json")
    assert_hertz(client.solve(req), 8.0, 200.0, 0.3)


def test_a_quadratic_gmsh_mesh_obeys_hertz(client):
    pytest.importorskip("gmsh")
    from contact_client import gmsh_meshes

    msh = gmsh_meshes.hertz_block(h_min=0.01, order=2)
    assert "\n9 " in msh.split("$Elements")[1] or " 9 " in msh.split("$Elements")[1]
    req = scenes.hertz_cylinder(mesh=scenes.gmsh_mesh(msh, ["block"]))
    assert_hertz(client.solve(req), 8.0, 200.0, 0.3)


def test_an_unsupported_element_is_named(client):
    from contact_client import ContactError

    req = load_json(EXAMPLES / "signorini_hertz_cylinder_gmsh.json")
    req["bodies"][0]["mesh"]["gmsh"]["msh"] = req["bodies"][0]["mesh"]["gmsh"]["msh"].replace("4.1 0 8", "2.2 0 8")
    with pytest.raises(ContactError) as e:
        client.solve(req)
    assert (e.value.code, e.value.path) == ("invalid_mesh", "/bodies/0/mesh/gmsh/msh")
