"""The closed sets a reply answers in, as :class:`enum.Enum` classes a caller can match on.

Each member's value is the reply's JSON string, and each class is a ``str`` enum, so
``reply["method"] == Method.ACTIVE_SET`` and ``Method(reply["method"])`` both work. The
reply's JSON Schema lists the same values (a test checks the two agree).
"""

from __future__ import annotations

import enum

__all__ = ["Method", "StopReason", "EstimateBasis", "WarningCode", "NoteKind", "Status"]


class Method(str, enum.Enum):
    """The contact method that produced the answer (``reply["method"]``)."""

    ACTIVE_SET = "active_set"
    INTERIOR_POINT = "interior_point"
    PENALTY = "penalty"
    AUGMENTED_LAGRANGIAN = "augmented_lagrangian"
    BARRIER = "barrier"
    ACTIVE_SET_FULL = "active_set_full"
    INTERIOR_POINT_FULL = "interior_point_full"


class StopReason(str, enum.Enum):
    """Why tolerance-driven refinement stopped (``reply["refinement"]["stopped"]``)."""

    REACHED = "reached"
    NO_CONTACT = "no_contact"
    NOT_SOLVED = "not_solved"
    MAX_ROUNDS = "max_rounds"
    MAX_DOFS = "max_dofs"
    TIME_LIMIT = "time_limit"
    SIZE_LIMIT = "size_limit"
    ROUND_FAILED = "round_failed"
    NOT_CONVERGING = "not_converging"


class EstimateBasis(str, enum.Enum):
    """What an error estimate is based on (``pair["accuracy"]["basis"]``, ``reply["solid"]["accuracy"]["basis"]``)."""

    TWO_LEVEL = "two_level"
    TWO_LEVEL_FINER = "two_level_finer"
    ZONE_EDGES = "zone_edges"
    NONE = "none"


class WarningCode(str, enum.Enum):
    """What a warning is about (``reply["warnings"][i]["code"]``)."""

    LARGE_STRAIN = "large_strain"
    LARGE_ROTATION = "large_rotation"
    LARGE_DISPLACEMENT = "large_displacement"
    ROLLING = "rolling"
    COARSE_CONTACT_ZONE = "coarse_contact_zone"
    LARGE_CONTACT_ZONE = "large_contact_zone"
    GAP_LINEARIZATION = "gap_linearization"
    TOLERANCE_NOT_REACHED = "tolerance_not_reached"
    PRESCRIBED_SLIP = "prescribed_slip"


class NoteKind(str, enum.Enum):
    """What a note is about: ``reply["note_kinds"][i]`` is the kind of ``reply["notes"][i]``
    (the two lists are as long; ``Reply.notes_of(kind)`` gives one kind's texts). A note
    explains the answer; a warning questions it."""

    PAIR_SWAPPED = "pair_swapped"
    NEARLY_INCOMPRESSIBLE = "nearly_incompressible"
    P2_P0_ELEMENT = "p2_p0_element"
    UNDETERMINED_MOTION = "undetermined_motion"
    METHOD_FALLBACK = "method_fallback"
    FULL_SYSTEM = "full_system"
    NON_FINITE = "non_finite"
    UNBOUNDED_FORCES = "unbounded_forces"
    ESTIMATE_LIMITED = "estimate_limited"
    NOT_REFINED = "not_refined"
    SLIDING_PUNCH = "sliding_punch"
    UNSETTLED_BODY = "unsettled_body"


class Status(str, enum.Enum):
    """A solve reply's ``status``."""

    SOLVED = "solved"
    MAX_ITERATIONS = "max_iterations"
    NUMERICAL_ERROR = "numerical_error"
