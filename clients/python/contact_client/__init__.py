"""Python client of the ``contact`` 2D frictionless contact solve service.

    >>> from contact_client import solve, scenes
    >>> reply = solve(scenes.hertz_cylinder(), connect="tcp/127.0.0.1:7447")
    >>> reply["resultant"]["fy"]
"""

from .client import (
    DEFAULT_CONNECT,
    Client,
    ContactError,
    NotSolved,
    TransportError,
    health,
    make_config,
    schema,
    solve,
)
from . import scenes
from .results import plot_pressure, save_vtu, to_numpy

__version__ = "0.1.0"

__all__ = [
    "DEFAULT_CONNECT",
    "Client",
    "ContactError",
    "NotSolved",
    "TransportError",
    "health",
    "make_config",
    "schema",
    "scenes",
    "solve",
    "plot_pressure",
    "save_vtu",
    "to_numpy",
]
