"""The one table of expected error replies: case id -> (code, accepted JSON pointers).

Used by test_errors.py (one bad request per case) and test_cli.py.
Where the protocol leaves a choice (which code an unknown edge-set name gets,
whether an unknown field's path names the field or its container), the
accepted alternatives are listed explicitly; adjust them here, and nowhere
else, if the service's documented choice differs.
"""

from __future__ import annotations

# case id -> (code, accepted JSON pointers)
EXPECTED: dict[str, tuple[str, tuple[str, ...]]] = {
    "malformed_json":            ("malformed_json", ("",)),
    "not_utf8":                  ("malformed_json", ("",)),
    "empty_payload":             ("malformed_json", ("",)),
    "nan_literal":               ("malformed_json", ("",)),
    "top_level_array":           ("invalid_request", ("",)),
    "unknown_field_top":         ("invalid_request", ("", "/frobnicate")),
    "unknown_field_nested":      ("invalid_request", ("/bodies/0/material", "/bodies/0/material/colour")),
    "missing_bodies":            ("invalid_request", ("", "/bodies")),
    "string_for_number":         ("invalid_request", ("/bodies/0/material/youngs_modulus",)),
    "unknown_method":            ("invalid_request", ("/method",)),
    "version_99":                ("unsupported_version", ("/version",)),
    "youngs_modulus_zero":       ("invalid_material", ("/bodies/0/material/youngs_modulus",)),
    "youngs_modulus_negative":   ("invalid_material", ("/bodies/0/material/youngs_modulus",)),
    "poisson_ratio_half":        ("invalid_material", ("/bodies/0/material/poisson_ratio",)),
    "inverted_triangle":         ("invalid_mesh", ("/bodies/0/mesh/inline/elements/1",)),
    "element_index_out_of_range": ("invalid_mesh", ("/bodies/0/mesh/inline/elements/0",
                                                    "/bodies/0/mesh/inline/elements/0/2")),
    # A body held only by contact whose loads no contact pressure can balance
    # (Fichera's condition fails).
    "held_by_contact_pulled_off": ("incompatible_loads", ("/bodies/0/tractions/0",)),
    # A body whose supports leave rigid motions free and that no contact pair
    # involves: nothing can hold it.
    "unsupported_body_without_contact": ("no_support", ("/bodies/1", "/bodies/1/supports")),
    # Naming an edge set the body does not have is the same mistake wherever it is
    # made, so it is expected to get the same code as for a support (below).
    "unknown_contact_edge_set":  ("invalid_request", ("/contacts/0/edges",)),
    "unknown_support_edge_set":  ("invalid_request", ("/bodies/0/supports/0/edges",)),
    "contact_body_out_of_range": ("invalid_request", ("/contacts/0/body",)),
    "no_contacts":               ("no_contact_candidates", ("/contacts",)),
    # Every candidate's initial gap is far beyond what small strain can close.
    "obstacle_out_of_reach":     ("no_contact_candidates", ("/contacts/0", "/contacts/0/edges")),
    "circle_radius_negative":    ("invalid_geometry", ("/obstacles/0/shape/circle/radius",)),
}
