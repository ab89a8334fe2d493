"""The client's exceptions: :class:`ContactError`, :class:`NotSolved` and
:class:`TransportError` (the two failure kinds are described in ``client``).

A module of their own so that ``reply`` (``Reply.raise_for_status`` raises
:class:`NotSolved`) and ``client`` (which returns replies) both import them
without importing each other; ``client`` and the package re-export them.
"""

from __future__ import annotations

__all__ = ["ContactError", "NotSolved", "TransportError"]


class ContactError(Exception):
    """A structured error reply of the service.

    Attributes: ``code`` (e.g. ``"invalid_material"``), ``message``, ``path``
    (JSON pointer into the request, ``""`` for the whole request), ``version``,
    ``details`` (the refusal as data where there is more to it than a path, e.g.
    ``{"loads": [{"path", "value", "min", "max"}]}`` with ``incompatible_loads``;
    ``None`` otherwise) and ``reply`` (the whole decoded error JSON).
    """

    def __init__(self, code: str, message: str, path: str = "", *, version: str | None = None,
                 reply: dict | None = None):
        super().__init__(f"{code} at {path!r}: {message}" if path else f"{code}: {message}")
        self.code = code
        self.message = message
        self.path = path
        self.version = version
        self.reply = reply if reply is not None else {
            "version": version, "code": code, "message": message, "path": path}
        self.details = self.reply.get("details")


class TransportError(Exception):
    """No structured answer: session failure, zenoh timeout, no reply, or a payload that is not the service's JSON."""


class NotSolved(ContactError):
    """The service answered, but the solve did not certify (``status`` is not
    ``"solved"``: ``max_iterations`` or ``numerical_error``). ``code`` is the
    status and ``reply`` the whole solve reply: its numbers must not be used as
    an answer. Pass ``check=False`` to get such replies back instead."""

    def __init__(self, reply: dict):
        status = str(reply.get("status"))
        cert = reply.get("certificate", {})
        super().__init__(status, f"the solve ended '{status}' (method {reply.get('method')}, "
                         f"{reply.get('iterations')} iterations, certificate {cert}); its pressures are not an answer",
                         reply=reply)
