"""A solve reply as a dict that reads well: :class:`Reply`.

``repr(reply)`` (what ``print`` and a notebook show) is the ``contact solve
--summary`` text: status, method, sizes, the contact load, per pair the zones and
the peak pressure, punches, foundations, certificate, times, warnings and notes.
The text is made by the solver built into the package (the CLI's own code, so the
two never drift apart, and whatever the summary learns to show, e.g. an error
estimate, shows here too); a reply this build cannot read (from a service of
another version) gets a shorter summary made here.

Everything else is the reply's JSON as a dict: ``reply["pairs"][0]["zones"]``,
``json.dumps(reply)`` and ``isinstance(reply, dict)`` work as before.
"""

from __future__ import annotations

import json
from typing import Any

from .errors import NotSolved

__all__ = ["Reply", "POINT_COLUMNS", "FRICTION_COLUMNS"]

#: The columns of :meth:`Reply.points` and :meth:`Reply.to_dataframe`, one row per
#: candidate point: the pair's index, body and target, then the point's fields, and
#: on a pair with friction its ``tangential_traction``, ``slip`` (in the last load
#: step) and ``state`` (``"stick"``, ``"slip"``, ``"open"`` or ``"prescribed"``: no free
#: motion along the surface there, so the slip is the supports' and the model applies
#: no friction force at that point; the supports take it).
POINT_COLUMNS = ("pair", "body", "target", "x", "y", "gap", "pressure", "force", "weight", "node", "nx", "ny",
                 "tangential_traction", "slip", "state")

#: The friction columns: None in :meth:`Reply.points` on a pair without friction
#: (NaN in a DataFrame's float columns).
FRICTION_COLUMNS = ("tangential_traction", "slip", "state")


def _num(v: float) -> str:
    """Six significant digits, no trailing noise (as the CLI's summary)."""
    if v == 0.0:
        return "0"
    if 1e-3 <= abs(v) < 1e6:
        return f"{v:.6f}".rstrip("0").rstrip(".")
    mantissa, exponent = f"{v:.5e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def _target(pair: dict) -> str:
    for key, what in (("obstacle", "obstacle"), ("against", "body"), ("foundation", "foundation")):
        if pair.get(key) is not None:
            return f"{what} '{pair[key]}'"
    return ""


def _fallback_summary(r: dict) -> str:
    """The summary's main lines for a reply the built-in solver cannot read."""
    units = r.get("units") or {}
    length, force, stress = (f" {units[k]}" if units.get(k) else "" for k in ("length", "force", "stress"))
    lines = [f"status       {r.get('status')}", f"method       {r.get('method')} ({r.get('iterations')} iterations)"]
    res = r.get("resultant") or {}
    if res:
        moment = f" {units['force']}·{units['length']}" if units.get("force") and units.get("length") else ""
        lines.append(f"contact load fx {_num(res.get('fx', 0.0))}{force}, fy {_num(res.get('fy', 0.0))}{force}, "
                     f"m {_num(res.get('m', 0.0))}{moment} (on the bodies, moment about the origin)")
    for k, p in enumerate(r.get("pairs", [])):
        zones = " ".join(f"[{_num(a)}, {_num(b)}]" for a, b in p.get("zones", []))
        zones = zones + length if zones else "none"
        pts = p.get("points", [])
        peak = max(pts, key=lambda q: q["pressure"]) if pts else None
        at = f"{_num(peak['pressure'])}{stress} at x = {_num(peak['x'])}{length}" if peak else "-"
        lines.append(f"pair {k}       body '{p.get('body')}' against {_target(p)}: zones {zones}; peak pressure {at}")
        shear = [q for q in pts if q.get("tangential_traction") is not None]
        if shear:
            q = max(shear, key=lambda q: abs(q["tangential_traction"]))
            peak = _num(abs(q["tangential_traction"]))
            lines.append(f"  shear      peak |t| {peak}{stress} at x = {_num(q['x'])}{length}")
    for w in r.get("warnings", []):
        lines.append(f"WARNING      {w.get('code')} at {w.get('location')}: {w.get('message')}")
    for n in r.get("notes", []):
        lines.append(f"note         {n}")
    return "\n".join(lines)


class Reply(dict):
    """A solve reply: the reply's JSON as a dict, whose ``repr`` is its summary.

    ``raise_for_status()`` raises :class:`~contact_client.NotSolved` unless the
    status is ``solved``; ``points()`` and ``to_dataframe()`` give the pressure
    points of every pair as a table.
    """

    __slots__ = ("request",)

    def __init__(self, reply: dict = (), request: dict | None = None):
        super().__init__(reply)
        #: The request this reply answers, when it was a dict or JSON (``plot_pressure``
        #: reads the analysis and the closed form's scene from it); None otherwise.
        self.request = request

    def summary(self) -> str:
        """The ``contact solve --summary`` text of this reply."""
        try:
            from ._contact import summary as _summary
        except ImportError:
            _summary = None
        if _summary is not None:
            text = _summary(json.dumps(self, allow_nan=True))
            if text is not None:
                return text
        return _fallback_summary(self)

    def __repr__(self) -> str:
        return self.summary()

    def _repr_pretty_(self, p, cycle: bool) -> None:
        """IPython and Jupyter show the summary too, not the 100k-character dict."""
        p.text("Reply(...)" if cycle else self.summary())

    @property
    def ok(self) -> bool:
        """Whether the solve certified its answer (``status`` is ``solved``)."""
        return self.get("status", "solved") == "solved"

    def raise_for_status(self) -> Reply:
        """This reply if its status is ``solved``; else raises :class:`NotSolved`
        (its numbers are then not an answer). Returns the reply, so
        ``solve_local(req, check=False).raise_for_status()`` chains."""
        if not self.ok:
            raise NotSolved(self)
        return self

    def notes_of(self, kind: str) -> list[str]:
        """The texts of this reply's notes of ``kind`` (a :class:`~contact_client.NoteKind`
        or its string), in order: ``reply.notes_of(NoteKind.UNDETERMINED_MOTION)``. A
        reply from a service older than ``note_kinds`` has none of any kind."""
        kinds = self.get("note_kinds", [])
        return [text for k, text in zip(kinds, self.get("notes", [])) if k == kind]

    def points(self) -> dict[str, list]:
        """Every pair's candidate points as columns (plain lists, no dependency):
        ``{"pair": [...], "body": [...], "target": [...], "x": [...], ...}``, one
        entry per point in pair order, columns ``POINT_COLUMNS`` (``target`` is the
        obstacle, other body or foundation; ``nx``, ``ny`` the row's normal). On a
        pair with friction, ``tangential_traction`` (along the point's tangent,
        (−ny, nx) unless the reply gives one), ``slip`` (in the last load step,
        along the same tangent) and ``state`` (``"stick"``, ``"slip"``, ``"open"``,
        ``"prescribed"``: the supports fix the slip and take the friction force);
        None on a pair without. Units are the request's."""
        cols: dict[str, list] = {c: [] for c in POINT_COLUMNS}
        for k, pair in enumerate(self.get("pairs", [])):
            target = pair.get("obstacle") or pair.get("against") or pair.get("foundation")
            for q in pair.get("points", []):
                cols["pair"].append(k)
                cols["body"].append(pair.get("body"))
                cols["target"].append(target)
                for c in ("x", "y", "gap", "pressure", "force", "weight", "node"):
                    cols[c].append(q[c])
                nx, ny = q.get("normal", (float("nan"), float("nan")))
                cols["nx"].append(nx)
                cols["ny"].append(ny)
                for c in FRICTION_COLUMNS:
                    cols[c].append(q.get(c))
        return cols

    def to_dataframe(self):
        """The pressure points as a pandas DataFrame, columns ``POINT_COLUMNS``
        (see :meth:`points`; ``tangential_traction`` and ``slip`` are NaN, ``state``
        None, on a pair without friction). Needs pandas, which the package does not
        install."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("Reply.to_dataframe needs pandas (`pip install pandas`); "
                              "Reply.points() gives the same table as plain lists") from e
        df = pd.DataFrame(self.points(), columns=list(POINT_COLUMNS))
        for c in ("tangential_traction", "slip"):
            df[c] = df[c].astype(float)
        return df

    def __reduce__(self) -> tuple[Any, ...]:
        return (Reply, (dict(self), self.request))
