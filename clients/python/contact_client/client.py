"""Calls to the ``contact`` service over zenoh.

The service declares three queryables:

``contact/solve``
    payload: a solve request (JSON, UTF-8). An ``ok`` reply carries the solve
    reply JSON; an ``err`` reply carries ``{"version", "code", "message", "path"}``
    where ``path`` is a JSON pointer into the request.
``contact/health``
    ``ok`` reply: ``{"version", "uptime_s", "solves_served", "queue_depth", "in_flight", ...}``.
``contact/schema``
    ``ok`` reply: ``{"request": ..., "reply": ..., "error": ...}`` (JSON Schemas).

Every solve reply and error reply carries ``request_id`` (``<instance>-<n>``, the
id the service logs it under) and echoes the request's ``client_id``.

Several service instances may serve the same keys behind a zenoh router. Their
queryables are *complete*, so zenoh's default query target routes each query to
exactly one instance (always the same one while it lives; the next one when it
goes). ``Client(spread=True)`` spreads the load instead: it lists the live
instances (zenoh liveliness tokens ``contact/instance/<zid>``) and takes turns
querying ``contact/instance/<zid>/solve``. ``solve(..., retries=n)`` retries what
may succeed on a second try: no answer (an instance that died mid-query) and
``busy``; solving is a pure function of the request, so a retry is safe.

Two failure kinds are kept apart:

* :class:`ContactError`: the service understood the query and answered with a
  structured error (bad request, no support, busy, ...). Retrying the same
  request gives the same answer, except for ``busy`` and ``timeout``.
* :class:`TransportError`: no usable answer came back: no session could be
  opened, nothing answered before the timeout, or the answer was not the
  service's JSON (zenoh reports its own query timeout as an error reply whose
  payload is the text ``Timeout``).

The zenoh configuration is always client mode with one explicit endpoint and
multicast scouting off, so nothing leaves the given address. ``tls={"ca", "cert",
"key"}`` (PEM paths) opens a ``tls/HOST:PORT`` endpoint with mutual TLS: the
router's access control (deploy/router-acl.json5) then lets only certificates
of solvers declare the service's keys, so that nothing else can answer.

Every answer is checked before it is returned: a solve reply must validate
against the reply schema and an error reply against the error schema (both
shipped in the package, the service's own, see ``proto/``), and a solve reply must
echo the request's ``client_id`` when the request has one (an error reply too,
unless it was sent unread: ``busy``, ``too_large``); an answer that does
not is a :class:`TransportError` (``verify=False`` skips the schema check,
whose cost grows with the reply: 14 ms for the 59 kB reply of the Hertz
example, against a 6 ms round trip of a small solve).

Length: this docstring (the service's keys, the failure kinds, what is checked) is a
tenth of the file; the rest is one transport: the zenoh configuration, the checks of
an answer, the query with its retries, :class:`Client` (a quarter of the file),
``solve_local`` and the module-level shortcuts, all sharing the private query,
decoding and progress helpers. The exceptions live in ``errors``, the reply in ``reply``.
"""

from __future__ import annotations

import contextlib
import functools
import json
import time
import uuid
from collections.abc import Mapping
from importlib import resources
from typing import Any, Callable, Union

import zenoh

from .errors import ContactError, NotSolved, TransportError
from .reply import Reply

__all__ = [
    "Reply",
    "DEFAULT_CONNECT",
    "KEY_INSTANCES",
    "KEY_SOLVE",
    "KEY_HEALTH",
    "KEY_SCHEMA",
    "KEY_PROGRESS",
    "STAGES",
    "work_fraction",
    "Client",
    "ContactError",
    "NotSolved",
    "TransportError",
    "make_config",
    "solve",
    "health",
    "schema",
]

DEFAULT_CONNECT = "tcp/127.0.0.1:7447"
KEY_SOLVE = "contact/solve"
KEY_HEALTH = "contact/health"
KEY_SCHEMA = "contact/schema"
#: Progress of a solve: ``contact/progress/<client_id>`` (see :meth:`Client.solve`).
KEY_PROGRESS = "contact/progress"
#: Liveliness tokens of the running instances, ``contact/instance/<zid>``.
KEY_INSTANCES = "contact/instance/*"

#: Timeout of the small queries (health, schema), seconds.
SMALL_QUERY_TIMEOUT = 10.0
#: With ``spread=True``, the list of instances is refreshed after this many seconds.
INSTANCE_REFRESH_S = 2.0
#: Pause before retrying a ``busy`` answer, seconds (doubled on each retry).
BUSY_BACKOFF_S = 0.05

Request = Union[dict, str, bytes, bytearray]


#: Default time a solve may take, seconds: the service's own default limit
#: (``--max-solve-s 300``), so that neither side gives up before the other.
DEFAULT_TIMEOUT_S = 300.0

#: Attempts after the first on ``busy`` or a lost instance (a solve is a pure
#: function of the request: repeating it is safe).
DEFAULT_RETRIES = 2

#: What the client keeps of its timeout for transport: the request's
#: ``time_limit`` is the timeout less this fraction and ``TIME_LIMIT_MARGIN_S``,
#: so the service stops the solve (and answers ``timeout``) before the client
#: stops waiting, instead of solving on for nobody.
TIME_LIMIT_MARGIN = 0.1
TIME_LIMIT_MARGIN_S = 0.5


def _with_time_limit(request: Request, timeout: float) -> Request:
    """A dict request with ``time_limit`` no later than the client's timeout
    allows (a smaller one of the request's own is kept); others unchanged."""
    if not isinstance(request, dict):
        return request
    limit = timeout * (1.0 - TIME_LIMIT_MARGIN) - TIME_LIMIT_MARGIN_S
    if limit < 1.0:
        return request
    own = request.get("time_limit")
    if isinstance(own, (int, float)) and not isinstance(own, bool) and own <= limit:
        return request
    return {**request, "time_limit": limit}


#: The keys of ``tls``: PEM paths of the CA, this client's certificate and its private key.
TLS_KEYS = ("ca", "cert", "key")


def make_config(connect: str = DEFAULT_CONNECT, tls: Mapping[str, Any] | None = None) -> zenoh.Config:
    """Client-mode zenoh config with a single connect endpoint and multicast scouting off.

    ``tls``: ``{"ca": PEM, "cert": PEM, "key": PEM}`` paths for a ``tls/``
    endpoint; ``ca`` alone authenticates the router only, all three make the
    link mutual TLS (what a router with the ACL requires)."""
    if not isinstance(connect, str) or "/" not in connect:
        raise ValueError(f"connect must be a zenoh endpoint like 'tcp/127.0.0.1:7447', got {connect!r}")
    conf = zenoh.Config()
    conf.insert_json5("mode", '"client"')
    conf.insert_json5("connect/endpoints", json.dumps([connect]))
    conf.insert_json5("scouting/multicast/enabled", "false")
    if tls:
        unknown = set(tls) - set(TLS_KEYS)
        if unknown:
            raise ValueError(f"tls takes the keys {TLS_KEYS}, not {sorted(unknown)}")
        if ("cert" in tls) != ("key" in tls):
            raise ValueError("tls: 'cert' and 'key' go together")
        if not connect.startswith("tls/"):
            raise ValueError(f"tls= needs a tls/HOST:PORT endpoint, got {connect!r}")
        paths = {k: str(v) for k, v in tls.items()}
        for path in paths.values():
            # zenoh would report a missing file as an unexplained refused connection.
            with open(path, "rb"):
                pass
        if "ca" in paths:
            conf.insert_json5("transport/link/tls/root_ca_certificate", json.dumps(paths["ca"]))
        if "cert" in paths:
            conf.insert_json5("transport/link/tls/connect_certificate", json.dumps(paths["cert"]))
            conf.insert_json5("transport/link/tls/connect_private_key", json.dumps(paths["key"]))
            if "ca" in paths:
                conf.insert_json5("transport/link/tls/enable_mtls", "true")
    return conf


@functools.cache
def _validator(kind: str):
    """The jsonschema validator of the packaged ``<kind>.schema.json`` (built once)."""
    import jsonschema

    text = resources.files(__package__).joinpath("schemas", f"{kind}.schema.json").read_text(encoding="utf-8")
    schema = json.loads(text)
    return jsonschema.validators.validator_for(schema, default=jsonschema.Draft202012Validator)(schema)


def _verify(kind: str, value: dict, key: str, client_id: Any, schema: bool) -> None:
    """Raises TransportError unless ``value`` is a ``kind`` answer (schema) to the request with ``client_id``."""
    if schema:
        error = next(iter(_validator(kind).iter_errors(value)), None)
        if error is not None:
            where = "/" + "/".join(str(p) for p in error.absolute_path)
            raise TransportError(f"the {kind} on {key!r} does not validate against the {kind} schema "
                                 f"at {where!r}: {error.message[:200]}")
    # A refusal sent unread (busy, too_large) cannot echo the id; one that names an id must name ours.
    echo_optional = kind == "error" and "client_id" not in value
    if client_id is not None and not echo_optional and value.get("client_id") != client_id:
        raise TransportError(f"the {kind} on {key!r} echoes client_id {value.get('client_id')!r}, "
                             f"not the request's {client_id!r}: it answers another request")


def _plain(value):
    """numpy scalars and arrays (anything with ``tolist``) as plain Python
    numbers and lists, so a request can be built from numpy results; numpy is
    not imported (nor required)."""
    tolist = getattr(value, "tolist", None)
    if callable(tolist):
        return tolist()
    raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")


def encode_request(request: Request) -> bytes:
    """The payload bytes of a request.

    A dict is serialised as strict JSON (NaN and infinities are refused here:
    strict JSON cannot carry them); numpy scalars and arrays anywhere in it
    become plain numbers and lists. A ``str`` or ``bytes`` is sent verbatim and
    not parsed locally, so the service alone judges it.
    """
    if isinstance(request, dict):
        try:
            return json.dumps(request, allow_nan=False, separators=(",", ":"), default=_plain).encode("utf-8")
        except ValueError as e:
            raise ValueError(f"request is not representable as strict JSON: {e}") from e
    if isinstance(request, str):
        return request.encode("utf-8")
    if isinstance(request, (bytes, bytearray)):
        return bytes(request)
    raise TypeError(f"request must be a dict, a JSON string or bytes, not {type(request).__name__}")


def _payload_text(zbytes: zenoh.ZBytes) -> str:
    raw = zbytes.to_bytes()
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("utf-8", errors="replace")


def _structured_error(obj: Any) -> bool:
    return (isinstance(obj, dict) and isinstance(obj.get("code"), str)
            and isinstance(obj.get("message"), str))


def _query(session: zenoh.Session, key: str, payload: bytes | None, timeout: float,
           verify: tuple[Any, bool] | None = None) -> dict:
    """One query; the first reply decoded, or an exception. ``verify``: the
    request's ``client_id`` (None: none) and whether to check schemas, for a solve."""
    try:
        if payload is None:
            replies = session.get(key, timeout=timeout)
        else:
            replies = session.get(key, payload=payload, timeout=timeout)
        first = None
        for reply in replies:  # ends when the query is finalised (all replies or timeout)
            if first is None:
                first = reply
    except zenoh.ZError as e:
        raise TransportError(f"query on {key!r} failed: {e}") from e
    if first is None:
        raise TransportError(f"no reply on {key!r} within {timeout} s: is `contact serve` running and reachable?")

    ok = first.ok
    if ok is not None:
        text = _payload_text(ok.payload)
        try:
            value = json.loads(text)
        except json.JSONDecodeError as e:
            raise TransportError(f"reply on {key!r} is not JSON: {text[:200]!r}") from e
        if not isinstance(value, dict):
            raise TransportError(f"reply on {key!r} is not a JSON object: {text[:200]!r}")
        if verify is not None:
            _verify("reply", value, key, *verify)
        return value

    err = first.err
    text = _payload_text(err.payload) if err is not None else ""
    try:
        value = json.loads(text)
    except json.JSONDecodeError:
        value = None
    if _structured_error(value):
        if verify is not None:
            _verify("error", value, key, *verify)
        raise ContactError(value["code"], value["message"], value.get("path", ""),
                           version=value.get("version"), reply=value)
    # e.g. zenoh's own query timeout, whose payload is the text "Timeout".
    raise TransportError(f"error reply on {key!r} that is not a service error: {text[:200]!r}")


def _open(connect: str, tls: Mapping[str, Any] | None = None) -> zenoh.Session:
    try:
        return zenoh.open(make_config(connect, tls))
    except zenoh.ZError as e:
        # zenoh's message ends with the Rust source location of the failure,
        # which tells a Python user nothing; the original stays chained.
        if "Unable to connect" in str(e):
            raise TransportError(f"no contact service answers at {connect}: is `contact serve` running?") from e
        raise TransportError(f"cannot open a zenoh session to {connect}: {str(e).split('  at ')[0]}") from e


class Client:
    """One zenoh session for many calls::

        with Client("tcp/127.0.0.1:7447") as c:
            print(c.health()["solves_served"])
            reply = c.solve(request)
    """

    def __init__(self, connect: str = DEFAULT_CONNECT, timeout: float = DEFAULT_TIMEOUT_S, spread: bool = False,
                 local: bool = False, tls: Mapping[str, Any] | None = None, verify: bool = True):
        """``local=True`` solves in this process with the built-in solver
        (:func:`solve_local`) and opens no zenoh session. ``tls``: PEM paths
        ``{"ca", "cert", "key"}`` for a ``tls/`` endpoint (see :func:`make_config`).
        ``verify=False`` skips the schema check of solve replies (the
        ``client_id`` echo is always checked)."""
        self.connect = connect
        self.verify = verify
        self.timeout = float(timeout)
        self.spread = spread
        self.local = local
        self._instances: list[str] = []
        self._listed_at = float("-inf")
        self._turn = 0
        self._session: zenoh.Session | None = None if local else _open(connect, tls)

    @property
    def session(self) -> zenoh.Session:
        if self.local:
            raise TransportError("Client(local=True) solves in this process; health, schema and instances "
                                 "are the service's: use Client(connect) for them")
        if self._session is None:
            raise TransportError("client is closed")
        return self._session

    def solve(self, request: Request, timeout: float | None = None, retries: int = DEFAULT_RETRIES,
              progress: bool | Callable[[dict], Any] = False, check: bool = True) -> Reply:
        """Solve one request; returns the reply (a :class:`Reply`: the reply's
        dict, whose ``repr`` is its summary).

        Raises :class:`ContactError` for a structured error reply,
        :class:`NotSolved` (a ContactError) when the reply's status is not
        ``solved`` (unless ``check=False``), and :class:`TransportError` when no
        structured answer arrives. Up to ``retries`` more attempts (default 2,
        with backoff) follow a :class:`TransportError` or ``busy`` (with
        ``spread=True``, on another instance).

        ``timeout`` (default: the client's, 300 s like the service's own solve
        limit) also becomes the request's ``time_limit`` (less 10 % and 0.5 s
        for transport) when the request is a dict without a smaller one, so
        that the service stops a solve the client will no longer wait for.

        ``progress=True`` shows a tqdm bar over the solve's stages (mesh,
        assembly, factorization, condensation, contact_solve, post; needs
        ``pip install 'contact-client[progress]'``); a callable instead receives
        every progress message ``{stage, iteration?, residual?, elapsed,
        request_id}``. The service publishes them on
        ``contact/progress/<client_id>``: the request's ``client_id`` is used
        when it is a plain key chunk (no ``/ * $ ? #``), else one is generated
        (``progress-<uuid>``) and set in the request, so it comes back in the reply.
        """
        if self.local:
            return solve_local(request if timeout is None else _with_time_limit(request, float(timeout)),
                               check=check, progress=progress)
        if progress:
            request, key = _with_progress_key(request)
            sink = progress if callable(progress) else _ProgressBar()
            sub = self.session.declare_subscriber(f"{KEY_PROGRESS}/{key}", lambda s: sink(_decode(s.payload)))
            try:
                return self.solve(request, timeout, retries, check=check)
            finally:
                sub.undeclare()
                if isinstance(sink, _ProgressBar):
                    sink.close()
        timeout = self.timeout if timeout is None else float(timeout)
        payload = encode_request(_with_time_limit(request, timeout))
        as_dict = _as_dict(request)
        client_id = as_dict.get("client_id") if as_dict is not None else None
        backoff = BUSY_BACKOFF_S
        for attempt in range(retries + 1):
            key = self._solve_key()
            try:
                reply = Reply(_query(self.session, key, payload, timeout, (client_id, self.verify)), as_dict)
                if check:
                    reply.raise_for_status()
                return reply
            except TransportError:
                self._forget(key)
                if attempt == retries:
                    raise
                time.sleep(backoff)
                backoff *= 2
            except ContactError as e:
                if isinstance(e, NotSolved) or e.code != "busy" or attempt == retries:
                    raise
                time.sleep(backoff)
                backoff *= 2
        raise AssertionError("unreachable")

    def instances(self, timeout: float = SMALL_QUERY_TIMEOUT) -> list[str]:
        """The zenoh ids of the live service instances, sorted."""
        try:
            replies = self.session.liveliness().get(KEY_INSTANCES, timeout=timeout)
            return sorted(str(r.ok.key_expr).rsplit("/", 1)[1] for r in replies if r.ok is not None)
        except zenoh.ZError as e:
            raise TransportError(f"listing instances failed: {e}") from e

    def health_all(self, timeout: float = SMALL_QUERY_TIMEOUT) -> list[dict]:
        """The health record of every instance reachable (target ALL, no consolidation)."""
        try:
            replies = self.session.get(KEY_HEALTH, timeout=timeout, target=zenoh.QueryTarget.ALL,
                                       consolidation=zenoh.ConsolidationMode.NONE)
            return [json.loads(_payload_text(r.ok.payload)) for r in replies if r.ok is not None]
        except (zenoh.ZError, json.JSONDecodeError) as e:
            raise TransportError(f"health of all instances failed: {e}") from e

    def _solve_key(self) -> str:
        if not self.spread:
            return KEY_SOLVE
        if not self._instances or time.monotonic() - self._listed_at > INSTANCE_REFRESH_S:
            self._instances = self.instances()
            self._listed_at = time.monotonic()
        if not self._instances:
            return KEY_SOLVE
        self._turn += 1
        return f"contact/instance/{self._instances[self._turn % len(self._instances)]}/solve"

    def _forget(self, key: str) -> None:
        """After no answer from ``key``: drop that instance until the next listing."""
        self._instances = [z for z in self._instances if f"/{z}/" not in key]

    def health(self, timeout: float = SMALL_QUERY_TIMEOUT) -> dict:
        """The service's health record (version, uptime_s, solves_served, queue_depth, in_flight, ...)."""
        return _query(self.session, KEY_HEALTH, None, float(timeout))

    def schema(self, timeout: float = SMALL_QUERY_TIMEOUT) -> dict:
        """The JSON Schemas the service speaks: ``{"request", "reply", "error", "progress"}``."""
        return _query(self.session, KEY_SCHEMA, None, float(timeout))

    def close(self) -> None:
        if self._session is not None:
            session, self._session = self._session, None
            with contextlib.suppress(zenoh.ZError):
                session.close()

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def solve_local(request: Request, check: bool = True,
                progress: bool | Callable[[dict], Any] = False) -> Reply:
    """Solve one request in this process with the solver built into the
    package; the reply is the service's (same fields, same numbers; no
    ``request_id``, and the timings and ``cache`` of this run), as a
    :class:`Reply` (a dict whose ``repr`` is the ``--summary`` text).

    Raises :class:`ContactError` for a refusal (the service's error reply) and
    :class:`NotSolved` when the status is not ``solved`` (unless
    ``check=False``). The solve holds no lock on the interpreter: other threads
    go on while it runs.

    ``progress=True`` shows a tqdm bar over the solve's predicted work, as
    :meth:`Client.solve` does for a service (needs ``pip install
    'contact-client[progress]'``); a callable instead receives every progress
    message ``{stage, elapsed, done, total, iteration?, residual?}`` (the
    service's messages, without ``request_id``), called on the solving thread;
    an exception it raises stops the messages and is raised after the solve.
    """
    try:
        from ._contact import solve as _solve
    except ImportError as e:
        raise TransportError(
            "this install has no built-in solver (contact_client._contact): install the package from source "
            "with a Rust toolchain (`pip install ./clients/python`) or from a wheel made with "
            "`maturin build --release`, or use a service (Client(connect))"
        ) from e
    payload = encode_request(request)
    if progress:
        sink = progress if callable(progress) else _ProgressBar()
        try:
            ok, text = _solve(payload, sink)
        finally:
            if isinstance(sink, _ProgressBar):
                sink.close()
    else:
        ok, text = _solve(payload)
    value = json.loads(text)
    if not ok:
        raise ContactError(value["code"], value["message"], value.get("path", ""),
                           version=value.get("version"), reply=value)
    reply = Reply(value, _as_dict(request))
    if check:
        reply.raise_for_status()
    return reply


def _as_dict(request: Request) -> dict | None:
    """The request as a dict, for the reply to keep (a JSON text is parsed; None
    when it is not a JSON object)."""
    if isinstance(request, dict):
        return request
    try:
        value = json.loads(request)
    except (TypeError, ValueError):
        return None
    return value if isinstance(value, dict) else None


def solve(request: Request, connect: str = DEFAULT_CONNECT, timeout: float = DEFAULT_TIMEOUT_S,
          progress: bool | Callable[[dict], Any] = False, retries: int = DEFAULT_RETRIES,
          check: bool = True, tls: Mapping[str, Any] | None = None) -> Reply:
    """Solve one request on a session opened for this call. See :meth:`Client.solve`."""
    with Client(connect, timeout, tls=tls) as c:
        return c.solve(request, progress=progress, retries=retries, check=check)


_UNSAFE_KEY_CHARS = set("/*$?#")


def _plain_chunk(s: Any) -> bool:
    """Whether ``s`` can be one chunk of a key expression (as the service checks it)."""
    return (isinstance(s, str) and 0 < len(s.encode()) <= 128 and not _UNSAFE_KEY_CHARS & set(s)
            and all(c.isprintable() for c in s))


def _with_progress_key(request: Request) -> tuple[Request, str]:
    """The request with a ``client_id`` usable as the progress key, and that key."""
    obj = request if isinstance(request, dict) else json.loads(request)
    if not isinstance(obj, dict):
        raise ValueError("progress needs a JSON object request")
    cid = obj.get("client_id")
    if _plain_chunk(cid):
        return request, cid
    if cid is not None:
        raise ValueError(f"client_id {cid!r} cannot be a zenoh key chunk (it has one of / * $ ? #): "
                         "drop it or pick a plain one to see progress")
    key = f"progress-{uuid.uuid4().hex}"
    return {**obj, "client_id": key}, key


def _decode(payload: zenoh.ZBytes) -> dict:
    try:
        value = json.loads(_payload_text(payload))
    except json.JSONDecodeError:
        value = None
    return value if isinstance(value, dict) else {"stage": "?", "raw": _payload_text(payload)}


#: The stages a solve reports, in order (factorization and condensation are skipped on a cache hit;
#: ``estimate``, the error estimate's companion solve, runs with ``settings.estimate``, the default).
STAGES = ("mesh", "assembly", "factorization", "condensation", "contact_solve", "post", "estimate")


def work_fraction(msg: dict) -> float | None:
    """The fraction of the solve's predicted work behind a progress message
    (``done / total``: predicted seconds, so a factorization that is most of the
    time is most of the bar), or None when the service sent no plan."""
    total = msg.get("total") or 0.0
    return min(1.0, max(0.0, msg.get("done", 0.0) / total)) if total > 0 else None


class _ProgressBar:
    """A tqdm bar over the solve's predicted work (percent), so its rate and
    remaining-time estimate follow the real work; the description is the stage,
    the postfix the contact iteration and residual."""

    def __init__(self):
        try:
            from tqdm.auto import tqdm  # optional dependency: pip install 'contact-client[progress]'
        except ImportError as e:
            raise ImportError("progress=True draws a tqdm bar: pip install tqdm (or 'contact-client[progress]'); "
                              "progress=<callable> needs nothing") from e

        self.bar = tqdm(total=100.0, unit="%", desc="solve", bar_format="{desc}: {percentage:3.0f}%|{bar}| "
                        "[{elapsed}<{remaining}{postfix}]")
        self.stage = None

    def __call__(self, msg: dict) -> None:
        stage = msg.get("stage")
        if stage in STAGES and stage != self.stage:
            self.stage = stage
            # set_description would add its own ": " to the format's: "assembly: :".
            self.bar.set_description_str(stage, refresh=False)
            # The contact iterations belong to contact_solve, not to the stages after it.
            self.bar.set_postfix_str("", refresh=False)
        f = work_fraction(msg)
        if f is not None and 100.0 * f > self.bar.n:
            self.bar.update(100.0 * f - self.bar.n)
        if msg.get("iteration") is not None:
            self.bar.set_postfix(iteration=msg["iteration"], residual=f"{msg.get('residual', 0.0):.2e}")

    def close(self) -> None:
        self.bar.update(100.0 - self.bar.n)
        self.bar.close()


def health(connect: str = DEFAULT_CONNECT, timeout: float = SMALL_QUERY_TIMEOUT,
           tls: Mapping[str, Any] | None = None) -> dict:
    """Query ``contact/health`` on a session opened for this call."""
    with Client(connect, tls=tls) as c:
        return c.health(timeout)


def schema(connect: str = DEFAULT_CONNECT, timeout: float = SMALL_QUERY_TIMEOUT,
           tls: Mapping[str, Any] | None = None) -> dict:
    """Query ``contact/schema`` on a session opened for this call."""
    with Client(connect, tls=tls) as c:
        return c.schema(timeout)
