"""The checked-in JSON Schemas (proto/*.schema.json) against examples, replies and the service."""

from __future__ import annotations

import copy

import jsonschema
import pytest

from contact_client import ContactError, scenes
from scenes_small import DELTA, NU, expected_pressure, square_block
from support import EXAMPLES, load_json, validator_for

DRAFT_2020_12 = "https://json-schema.org/draft/2020-12/schema"
EXAMPLE_FILES = sorted(EXAMPLES.glob("*.json"))


@pytest.fixture(scope="module")
def validators(proto_schemas):
    return {k: validator_for(v) for k, v in proto_schemas.items()}


@pytest.mark.parametrize("kind", ["request", "reply", "error"])
def test_schema_declares_draft_2020_12(proto_schemas, kind):
    schema = proto_schemas[kind]
    assert schema.get("$schema") == DRAFT_2020_12
    jsonschema.Draft202012Validator.check_schema(schema)


def test_examples_exist(hertz_example_path):
    assert EXAMPLE_FILES, "proto/examples/ holds no example"
    assert hertz_example_path in EXAMPLE_FILES


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=[p.name for p in EXAMPLE_FILES])
def test_example_request_validates(validators, path):
    validators["request"].validate(load_json(path))


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=[p.name for p in EXAMPLE_FILES])
def test_example_solves(client, validators, path):
    """Every example is a test: it solves through zenoh, the reply fits the schema,
    and the truths of every scene hold (VERIFICATION.md section 6)."""
    reply = client.solve(load_json(path))
    validators["reply"].validate(reply)
    assert reply["status"] == "solved"
    for k, v in reply["certificate"].items():
        # With friction, "friction" holds the Coulomb conditions' residuals.
        for name, r in (v.items() if isinstance(v, dict) else [(k, v)]):
            assert 0.0 <= r <= 1e-8, f"certificate {name} = {r}"  # solver tolerance 1e-10, two orders of margin
    for pair in reply["pairs"]:
        peak = max((p["pressure"] for p in pair["points"]), default=0.0)
        assert peak > 0.0, "every example presses something"
        assert min(p["pressure"] for p in pair["points"]) >= -1e-9 * peak


def test_builder_requests_validate(validators):
    for req in (scenes.hertz_cylinder(), scenes.hertz_cylinder(element="t6", method="interior_point",
                                                               client_id="x", outputs=["mesh"]),
                square_block()):
        validators["request"].validate(req)


def test_request_schema_rejects_what_serde_rejects(validators):
    """The schema is as strict as the service: unknown fields, missing bodies, wrong types."""
    v = validators["request"]
    good = square_block()
    v.validate(good)

    def mutated(change):
        r = copy.deepcopy(good)
        change(r)
        return r

    bad = [
        mutated(lambda r: r.update(frobnicate=1)),
        mutated(lambda r: r["bodies"][0]["material"].update(colour="red")),
        mutated(lambda r: r.pop("bodies")),
        mutated(lambda r: r["bodies"][0]["material"].update(youngs_modulus="200")),
        mutated(lambda r: r.update(method="simplex")),
    ]
    for r in bad:
        assert not v.is_valid(r), r


def test_hertz_reply_validates(validators, hertz_reply):
    validators["reply"].validate(hertz_reply)


def test_reply_with_all_outputs_validates_and_is_exact(client, validators):
    """Optional outputs appear when asked for, fit the schema, and are the exact
    uniform state of the small scene (T3 represents it exactly: round-off tolerances)."""
    req = square_block()
    req["outputs"] = ["displacement", "mesh", "stress"]
    req["client_id"] = "outputs-1"
    reply = client.solve(req)
    validators["reply"].validate(reply)
    assert reply["client_id"] == "outputs-1"
    (body,) = reply["bodies"]
    assert body["name"] == "square"
    assert body["nodes"] == req["bodies"][0]["mesh"]["inline"]["nodes"]
    assert body["elements"] == req["bodies"][0]["mesh"]["inline"]["elements"]
    # Top nodes (2, 3) move down by delta; bottom nodes do not move vertically.
    # Lateral expansion in plane strain with sigma_xx = 0: eps_xx = nu/(1-nu) * delta/H.
    eps_xx = NU / (1.0 - NU) * DELTA
    for i, (x, y) in enumerate(req["bodies"][0]["mesh"]["inline"]["nodes"]):
        ux, uy = body["displacement"][i]
        assert uy == pytest.approx(-DELTA if y == 0.0 else 0.0, abs=1e-12)
        assert ux == pytest.approx(eps_xx * x, abs=1e-12)
    for sxx, syy, sxy in body["stress"]:
        scale = expected_pressure()
        assert abs(sxx) <= 1e-9 * scale
        assert syy == pytest.approx(-scale, rel=1e-9)
        assert abs(sxy) <= 1e-9 * scale


def test_error_replies_validate(client, validators):
    bad = [b"{", {"version": "99"}, square_block() | {"frobnicate": 1}]
    r = square_block()
    r["bodies"][0]["material"]["poisson_ratio"] = 0.5
    bad.append(r)
    for payload in bad:
        with pytest.raises(ContactError) as ei:
            client.solve(payload)
        validators["error"].validate(ei.value.reply)


def test_service_schema_matches_checked_in_files(client, proto_schemas):
    served = client.schema()
    assert set(served) == {"request", "reply", "error", "progress"}
    for kind in ("request", "reply", "error", "progress"):
        assert served[kind] == proto_schemas[kind], f"contact/schema {kind} differs from proto/{kind}.schema.json"


@pytest.mark.parametrize("kind", ["reply", "error", "progress"])
def test_the_packaged_schemas_are_the_checked_in_ones(proto_schemas, kind):
    """The client checks answers against its own copies (contact_client/schemas/): they must not drift."""
    import json
    from importlib import resources

    packaged = json.loads(resources.files("contact_client").joinpath("schemas", f"{kind}.schema.json").read_text())
    assert packaged == proto_schemas[kind], f"copy proto/{kind}.schema.json to contact_client/schemas/"


def test_the_outcome_enums_are_the_schemas():
    """Every method, stop reason, estimate basis, warning code, note kind and status the
    reply's schema lists is a member of the client's enum of that name, and nothing else is."""
    import json
    from importlib import resources

    from contact_client import outcomes

    schema = json.loads(resources.files("contact_client").joinpath("schemas/reply.schema.json").read_text())
    defs = schema["$defs"]

    def values(name):
        d = defs[name]
        if "enum" in d:
            return set(d["enum"])
        out = set()
        for o in d["oneOf"]:
            out |= {o["const"]} if "const" in o else set(o.get("enum", []))
        return out

    for wire, cls in [("MethodRan", outcomes.Method), ("StopReason", outcomes.StopReason),
                      ("EstimateBasis", outcomes.EstimateBasis), ("WarningCode", outcomes.WarningCode),
                      ("NoteKind", outcomes.NoteKind),
                      ("SolveStatus", outcomes.Status)]:
        assert values(wire) == {m.value for m in cls}, wire


def test_the_progress_stages_are_the_schemas():
    """``client.STAGES``, the stages the progress bar knows, are the progress schema's
    ``ProgressStage`` values, in the order a solve runs them (issue 38.2)."""
    import json
    from importlib import resources

    from contact_client.client import STAGES

    schema = json.loads(resources.files("contact_client").joinpath("schemas/progress.schema.json").read_text())
    node = schema["$defs"]["ProgressStage"]
    values = node["enum"] if "enum" in node else [o["const"] for o in node["oneOf"]]
    assert list(STAGES) == values
