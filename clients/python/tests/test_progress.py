"""Progress of a long solve on contact/progress/<client_id>."""

from __future__ import annotations

import pytest

from contact_client import scenes
from contact_client.client import STAGES, _validator, work_fraction


def _all_valid(messages: list[dict]) -> None:
    """Every message is a progress message of the packaged schema (proto/progress.schema.json)."""
    for m in messages:
        _validator("progress").validate(m)


def test_a_large_solve_reports_its_stages_in_order(client):
    # About 280k DOF: a solve of a few seconds, long enough to watch.
    req = scenes.hertz_cylinder(h_min=0.0028, extent=0.8)
    seen: list[dict] = []
    r = client.solve(req, progress=seen.append, timeout=120.0)
    assert r["status"] == "solved" and r["size"]["dofs"] > 250_000
    assert r["client_id"].startswith("progress-"), "the generated key comes back as the client id"
    stages = [m["stage"] for m in seen]
    order = [s for i, s in enumerate(stages) if i == 0 or stages[i - 1] != s]
    # A first solve of this mesh misses the cache, so every stage runs.
    assert order == list(STAGES), order
    assert all(m["request_id"] == r["request_id"] for m in seen)
    _all_valid(seen)
    assert [m["elapsed"] for m in seen] == sorted(m["elapsed"] for m in seen)
    iterations = [m for m in seen if "iteration" in m]
    assert iterations and all(m["stage"] == "contact_solve" and m["residual"] >= 0.0 for m in iterations)
    # Progress in predicted work: it only moves forward, the factorization (most
    # of the time at this size) is most of it, and the total predicted once its
    # symbolic analysis is known is within 2x of the solve's real time.
    work = [work_fraction(m) for m in seen]
    assert all(w is not None for w in work) and work == sorted(work), work
    at = {m["stage"]: work_fraction(m) for m in reversed(seen)}  # first report of each stage
    # Of the solve's own stages (the estimate, planned after them, begins where they end).
    assert (at["condensation"] - at["factorization"]) / at["estimate"] > 0.5, at
    revised = [m for m in seen if m["stage"] == "factorization"][-1]  # after the symbolic analysis
    assert 0.5 < revised["total"] / r["timings"]["total"] < 2.0


def test_progress_bar_and_a_client_id_of_ones_own(client):
    pytest.importorskip("tqdm")
    req = scenes.hertz_cylinder(h_min=0.04, client_id="my-run-1")
    seen: list[dict] = []
    r = client.solve(req, progress=seen.append)
    assert r["client_id"] == "my-run-1" and seen[0]["stage"] == "mesh"
    assert client.solve(req, progress=True)["status"] == "solved"
    with pytest.raises(ValueError):
        client.solve(scenes.hertz_cylinder(h_min=0.04, client_id="a/b"), progress=True)


def test_an_in_process_solve_reports_the_stages_as_the_service_does():
    from contact_client import solve_local

    # The Hertz example's mesh (about 75k DOF), solved once in this process: a new
    # mesh for this process's cache, so every stage runs.
    req = scenes.hertz_cylinder(h_min=0.0105, client_id="in-process")
    seen: list[dict] = []
    r = solve_local(req, progress=seen.append)
    _all_valid(seen)
    stages = [m["stage"] for m in seen]
    order = [s for i, s in enumerate(stages) if i == 0 or stages[i - 1] != s]
    assert order == list(STAGES), order
    assert [m["elapsed"] for m in seen] == sorted(m["elapsed"] for m in seen)
    assert all(m["elapsed"] <= r["timings"]["total"] + 0.05 for m in seen)
    # The same plan as the service's: predicted work that only moves forward.
    work = [work_fraction(m) for m in seen]
    assert all(w is not None for w in work) and work == sorted(work), work
    iterations = [m for m in seen if "iteration" in m]
    assert iterations and all(m["stage"] == "contact_solve" and m["residual"] >= 0.0 for m in iterations)


def test_an_in_process_progress_bar_and_a_failing_callback():
    from contact_client import solve_local

    pytest.importorskip("tqdm")
    req = scenes.hertz_cylinder(h_min=0.04)
    assert solve_local(req, progress=True)["status"] == "solved"

    calls = []

    def broken(msg):
        calls.append(msg)
        raise RuntimeError("a callback that fails")

    # Its exception stops the messages and comes out of the solve, as Python's would.
    with pytest.raises(RuntimeError, match="a callback that fails"):
        solve_local(req, progress=broken)
    assert len(calls) == 1


def test_the_bar_reads_the_stage_once_then_the_percentage():
    pytest.importorskip("tqdm")
    from contact_client.client import _ProgressBar

    bar = _ProgressBar()
    try:
        bar({"stage": "contact_solve", "done": 6.0, "total": 10.0, "iteration": 3, "residual": 1e-3})
        assert str(bar.bar).startswith("contact_solve:  60%|") and "iteration=3" in str(bar.bar)
        bar({"stage": "post", "done": 7.0, "total": 10.0})
        line = str(bar.bar)
        # Was "post: :  70%", the iteration of the stage before still shown.
        assert line.startswith("post:  70%|") and ": :" not in line and "iteration" not in line, line
    finally:
        bar.close()


def test_the_estimate_is_a_stage_of_its_own_share():
    from contact_client import STAGES as exported, solve_local, work_fraction as exported_fraction

    assert exported == STAGES and exported_fraction is work_fraction
    req = scenes.hertz_cylinder(h_min=0.02)
    seen: list[dict] = []
    solve_local(req, progress=seen.append)
    stages = [m["stage"] for m in seen]
    assert stages[-1] == "estimate" and stages.count("estimate") >= 1
    # The estimate's companion is planned at half the solve's time (its upper bound,
    # adapt::ESTIMATE_SHARE): the bar enters it at 2/3, not at the end of post (was 99 %).
    entered = next(m for m in seen if m["stage"] == "estimate")
    assert work_fraction(entered) == pytest.approx(1.0 / 1.5, rel=1e-12)
    during = [work_fraction(m) for m in seen if m["stage"] == "estimate"]
    assert during == sorted(during) and during[-1] <= 1.0, during
    # Without an estimate the plan has no share for it, and no stage.
    seen.clear()
    solve_local(req | {"settings": {"estimate": False}}, progress=seen.append)
    order = [s for i, s in enumerate(m["stage"] for m in seen) if i == 0 or seen[i - 1]["stage"] != s]
    assert order == list(STAGES[:-1]), order
    assert work_fraction(seen[-1]) < 1.0
