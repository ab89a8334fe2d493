"""The ``contact`` 2D elastic contact solver (frictionless or with Coulomb
friction) in Python: in this process (``solve_local``, ``Client(local=True)``)
or through a ``contact serve`` service over zenoh (``solve``,
``Client(connect)``), with the same replies.

    >>> from contact_client import solve_local, scenes
    >>> reply = solve_local(scenes.hertz_cylinder())
    >>> reply["resultant"]["fy"]
"""

from . import closed_forms, scenes
from .client import (
    DEFAULT_CONNECT,
    STAGES,
    Client,
    ContactError,
    NotSolved,
    Reply,
    TransportError,
    health,
    make_config,
    schema,
    solve,
    solve_local,
    work_fraction,
)
from .outcomes import EstimateBasis, Method, NoteKind, Status, StopReason, WarningCode
from .patch_map import plot_patch
from .results import described_pressure, plot_pressure, save_vtu, to_numpy

__version__ = "0.2.0"

__all__ = [
    "DEFAULT_CONNECT",
    "STAGES",
    "Client",
    "ContactError",
    "NotSolved",
    "Reply",
    "TransportError",
    "health",
    "make_config",
    "schema",
    "scenes",
    "closed_forms",
    "solve",
    "solve_local",
    "plot_pressure",
    "plot_patch",
    "save_vtu",
    "to_numpy",
    "described_pressure",
    "work_fraction",
    "Method",
    "StopReason",
    "EstimateBasis",
    "WarningCode",
    "NoteKind",
    "Status",
]
