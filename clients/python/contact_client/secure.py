"""The production configuration on loopback, for the tests and the benchmarks:
throwaway certificates and a mutual-TLS router with the access control of
``deploy/router-acl.json5`` in front of one ``contact serve``.

Certificates are made by :class:`ThrowawayCA` with the ``cryptography`` package
(``pip install 'contact-client[test]'``); they live one day and are meant for
loopback tests only (see docs/howto/security.md, "TLS and access control", for
the production recipe with openssl).
"""

from __future__ import annotations

import datetime
import ipaddress
import subprocess
import time
from contextlib import contextmanager
from pathlib import Path

from .client import Client, ContactError, TransportError
from .local import free_loopback_port, stop

#: The common names the shipped ACL knows (deploy/router-acl.json5).
SOLVER_CN = "contact-solver"
CLIENT_CN = "contact-client"


class ThrowawayCA:
    """A certificate authority in ``directory`` issuing leaf certificates by common name."""

    def __init__(self, directory: Path, name: str = "contact-test-ca"):
        from cryptography import x509
        from cryptography.hazmat.primitives import hashes, serialization
        from cryptography.hazmat.primitives.asymmetric import ec
        from cryptography.x509.oid import NameOID

        self.dir = Path(directory)
        self.name = name
        self.key = ec.generate_private_key(ec.SECP256R1())
        subject = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, name)])
        now = datetime.datetime.now(datetime.timezone.utc)
        self.cert = (x509.CertificateBuilder().subject_name(subject).issuer_name(subject)
                     .public_key(self.key.public_key()).serial_number(x509.random_serial_number())
                     .not_valid_before(now - datetime.timedelta(minutes=5))
                     .not_valid_after(now + datetime.timedelta(days=1))
                     .add_extension(x509.BasicConstraints(ca=True, path_length=None), critical=True)
                     .add_extension(x509.KeyUsage(digital_signature=True, key_cert_sign=True, crl_sign=True,
                                                  content_commitment=False, key_encipherment=False,
                                                  data_encipherment=False, key_agreement=False,
                                                  encipher_only=False, decipher_only=False), critical=True)
                     .sign(self.key, hashes.SHA256()))
        self.pem = self.dir / f"{name}.pem"
        self.pem.write_bytes(self.cert.public_bytes(serialization.Encoding.PEM))

    def issue(self, common_name: str) -> dict:
        """``{"ca", "cert", "key"}`` PEM paths of a certificate for ``common_name``,
        valid for localhost and 127.0.0.1, as server and as client."""
        from cryptography import x509
        from cryptography.hazmat.primitives import hashes, serialization
        from cryptography.hazmat.primitives.asymmetric import ec
        from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

        key = ec.generate_private_key(ec.SECP256R1())
        now = datetime.datetime.now(datetime.timezone.utc)
        cert = (x509.CertificateBuilder()
                .subject_name(x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)]))
                .issuer_name(self.cert.subject).public_key(key.public_key())
                .serial_number(x509.random_serial_number())
                .not_valid_before(now - datetime.timedelta(minutes=5))
                .not_valid_after(now + datetime.timedelta(days=1))
                .add_extension(x509.SubjectAlternativeName([x509.DNSName("localhost"),
                                                            x509.IPAddress(ipaddress.ip_address("127.0.0.1"))]),
                               critical=False)
                .add_extension(x509.ExtendedKeyUsage([ExtendedKeyUsageOID.SERVER_AUTH,
                                                      ExtendedKeyUsageOID.CLIENT_AUTH]), critical=False)
                .sign(self.key, hashes.SHA256()))
        stem = self.dir / f"{self.name}-{common_name}"
        cert_path, key_path = stem.with_suffix(".pem"), stem.with_suffix(".key")
        cert_path.write_bytes(cert.public_bytes(serialization.Encoding.PEM))
        key_path.write_bytes(key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                               serialization.NoEncryption()))
        return {"ca": str(self.pem), "cert": str(cert_path), "key": str(key_path)}


def tls_args(tls: dict) -> list[str]:
    """The ``--tls-*`` arguments of ``contact serve``/``router`` for ``tls``."""
    return ["--tls-cert", tls["cert"], "--tls-key", tls["key"], "--tls-ca", tls["ca"]]


def default_acl() -> Path:
    """deploy/router-acl.json5 of the source tree this package runs from."""
    return Path(__file__).resolve().parents[3] / "deploy" / "router-acl.json5"


@contextmanager
def routed_service(binary, directory: Path, tls: bool = True, acl: Path | None = None, serve_args: tuple = (),
                   before_serve=None, startup_s: float = 30.0):
    """``binary router`` on a free loopback port and one ``binary serve`` connected to it, until the
    block ends. With ``tls`` the router listens on ``tls/`` with mutual TLS and the ACL (default
    :func:`default_acl`), the instance holds a solver certificate, and the block gets
    ``(endpoint, client_tls, ca)``; without, plain TCP everywhere and ``(endpoint, None, None)``.
    ``before_serve(endpoint, ca)`` runs once the router listens, before the instance starts.
    Logs go to ``directory``."""
    directory = Path(directory)
    endpoint = f"{'tls' if tls else 'tcp'}/127.0.0.1:{free_loopback_port()}"
    ca = client_tls = None
    router_tls: list[str] = []
    serve_tls: list[str] = []
    if tls:
        ca = ThrowawayCA(directory)
        client_tls = ca.issue(CLIENT_CN)
        router_tls = [*tls_args(ca.issue("contact-router")), "--acl", str(acl or default_acl())]
        serve_tls = tls_args(ca.issue(SOLVER_CN))
    procs, files = [], []

    def start(name: str, *args: str) -> subprocess.Popen:
        files.append(open(directory / f"{name}.log", "wb"))
        procs.append(subprocess.Popen([str(binary), *args], stdin=subprocess.DEVNULL,
                                      stdout=subprocess.DEVNULL, stderr=files[-1]))
        return procs[-1]

    def log(name: str) -> str:
        return (directory / f"{name}.log").read_text(errors="replace")[-4000:]

    try:
        router = start("router", "router", "--listen", endpoint, *router_tls)
        deadline = time.monotonic() + startup_s
        # The router listens once a client can open a session to it (it answers nothing yet).
        while True:
            try:
                Client(endpoint, timeout=2.0, tls=client_tls).close()
                break
            except TransportError as e:
                if router.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"the router did not come up:\n{log('router')}") from e
                time.sleep(0.1)
        if before_serve is not None:
            before_serve(endpoint, ca)
        serve = start("serve", "serve", "--connect", endpoint, *serve_tls, *serve_args)
        while True:
            try:
                with Client(endpoint, timeout=5.0, tls=client_tls) as c:
                    c.health(timeout=2.0)
                break
            except (TransportError, ContactError) as e:
                if serve.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"the service did not answer through the router:\n{log('serve')}") from e
                time.sleep(0.2)
        yield endpoint, client_tls, ca
    finally:
        for p in reversed(procs):
            stop(p)
        for f in files:
            f.close()
