#!/usr/bin/env python3
"""A needlesim server from the Agones allocator service, then a session on it (issue 22).

The allocator's REST API (agones.dev, "Allocator Service"; allocation.proto): ``POST
/gameserverallocation`` with an AllocationRequest over HTTPS with a client certificate (mTLS).
The request is the one of deploy/k8s/allocation.yaml and of ``needlesim allocate``: for each
label set, in order, a server already Allocated with a free place in its ``sessions`` Counter,
then a Ready one; the place reserved with the Counter's Increment (``counter=False``: labels
only). The answer's ``address`` and the port named ``port_name`` ("grpc", the Fleet's) are where
the session is created. Only the standard library is used for the allocation (http.client, ssl);
creating the session uses needlesim_client.py (grpcio and the generated stubs).

Usage from Python::

    from needlesim_allocate import allocate, create_allocated_session
    a = allocate("https://34.82.195.204", [{"agones.dev/fleet": "needlesim"}],
                 client_cert="client.crt", client_key="client.key", ca_cert="ca.crt")
    print(a.target)                      # "10.0.0.5:7463"
    client, session, a = create_allocated_session("https://34.82.195.204", [{"agones.dev/fleet": "needlesim"}],
                                                  "paper-phantom", client_cert=..., client_key=..., ca_cert=...)

Command line (prints one JSON object; ``--create EXAMPLE`` also creates a session there)::

    python needlesim_allocate.py --allocator https://HOST --selector agones.dev/fleet=needlesim \\
        --client-cert client.crt --client-key client.key --ca-cert ca.crt [--create paper-phantom --stubs DIR]

Errors are AllocationError subclasses, each saying what to fix: NoServerAvailable (the
allocator's UnAllocated answer, HTTP 429 / ResourceExhausted), AllocatorUnreachable,
CertificateError (the allocator's certificate not trusted, or the client certificate refused),
AllocatorRefused (any other error status, with the allocator's message).
"""

from __future__ import annotations

import argparse
import dataclasses
import http.client
import json
import os
import re
import socket
import ssl
import sys
import urllib.parse
from typing import Mapping, Optional, Sequence

SESSIONS_COUNTER = "sessions"
_NAME = re.compile(r"^[A-Za-z0-9]([-A-Za-z0-9_.]{0,61}[A-Za-z0-9])?$")
_PREFIX = re.compile(r"^[a-z0-9]([-a-z0-9]*[a-z0-9])?(\.[a-z0-9]([-a-z0-9]*[a-z0-9])?)*$")


class AllocationError(Exception):
    """Asking the allocator for a server failed; the message says what to fix."""


class NoServerAvailable(AllocationError):
    """No game server matches the selectors with a free place (the allocator's 429 UnAllocated)."""


class AllocatorUnreachable(AllocationError):
    """The allocator cannot be reached (refused, unresolved, timed out)."""


class CertificateError(AllocationError):
    """The allocator's certificate is not trusted, or it refused the client certificate."""


class AllocatorRefused(AllocationError):
    """Any other error answer (400 malformed request, 409 contention, 5xx), or an unusable answer."""


@dataclasses.dataclass
class Allocation:
    """An allocated game server."""

    game_server: str
    node_name: str
    address: str
    port: int
    ports: list  # [(name, port)]

    @property
    def target(self) -> str:
        """``address:port`` (an IPv6 address in brackets), what NeedlesimClient takes."""
        host = f"[{self.address}]" if ":" in self.address and not self.address.startswith("[") else self.address
        return f"{host}:{self.port}"


def parse_selector(text: str) -> dict:
    """``"k=v,k2=v2"`` as a label map, checked against the Kubernetes label syntax."""
    labels = {}
    for part in text.split(","):
        part = part.strip()
        if "=" not in part:
            raise ValueError(f"selector {text!r}: {part!r} is not KEY=VALUE")
        k, v = (x.strip() for x in part.split("=", 1))
        check_label(k, v)
        if k in labels:
            raise ValueError(f"selector {text!r}: {k!r} is given twice")
        labels[k] = v
    return labels


def check_label(key: str, value: str) -> None:
    prefix, _, name = key.rpartition("/")
    if (prefix and (len(prefix) > 253 or not _PREFIX.match(prefix))) or not _NAME.match(name):
        raise ValueError(f"{key!r} is not a Kubernetes label key ([prefix/]name, name ≤ 63 characters: letters, digits, -, _, .)")
    if value and not _NAME.match(value):
        raise ValueError(f"{value!r} (label {key}) is not a Kubernetes label value")


def request_body(namespace: str, selectors: Sequence[Mapping[str, str]], counter: bool = True) -> dict:
    """The AllocationRequest (see the module docs); int64 fields as strings, as protojson writes them."""
    sets = [dict(s) for s in selectors] or [{}]
    if not counter:
        return {"namespace": namespace, "gameServerSelectors": [{"matchLabels": s} for s in sets]}
    free = {SESSIONS_COUNTER: {"minAvailable": "1"}}
    chosen = []
    for s in sets:
        chosen.append({"matchLabels": s, "gameServerState": "ALLOCATED", "counters": free})
        chosen.append({"matchLabels": s, "gameServerState": "READY", "counters": free})
    return {
        "namespace": namespace,
        "gameServerSelectors": chosen,
        "scheduling": "Packed",
        "counters": {SESSIONS_COUNTER: {"action": "Increment", "amount": "1"}},
        "priorities": [{"type": "Counter", "key": SESSIONS_COUNTER, "order": "Ascending"}],
    }


def _describe(selectors) -> str:
    if not selectors:
        return "any game server (no selector)"
    return " then ".join("[" + ",".join(f"{k}={v}" for k, v in s.items()) + "]" for s in selectors)


def allocate(
    allocator: str,
    selectors: Sequence[Mapping[str, str] | str] = (),
    namespace: str = "default",
    client_cert: Optional[str] = None,
    client_key: Optional[str] = None,
    ca_cert: Optional[str] = None,
    port_name: str = "grpc",
    counter: bool = True,
    timeout: float = 30.0,
) -> Allocation:
    """Asks the Agones allocator at ``allocator`` (https://HOST[:PORT], or http:// for one with TLS
    disabled) for a game server. ``selectors``: label maps (or "k=v,k2=v2" strings), tried in
    order. Raises an AllocationError subclass."""
    sels = [parse_selector(s) if isinstance(s, str) else dict(s) for s in selectors]
    for s in sels:
        for k, v in s.items():
            check_label(k, v)
    u = urllib.parse.urlsplit(allocator.strip())
    if u.scheme not in ("https", "http") or not u.hostname:
        raise ValueError(f"allocator {allocator!r}: write https://HOST[:PORT] (http:// for an allocator with TLS disabled)")
    path = u.path.rstrip("/")
    if not path.endswith("/gameserverallocation"):
        path += "/gameserverallocation"
    if (client_cert is None) != (client_key is None):
        raise ValueError("client_cert and client_key go together")
    if u.scheme == "https":
        try:
            ctx = ssl.create_default_context(cafile=ca_cert)
            if client_cert:
                ctx.load_cert_chain(client_cert, client_key)
        except (OSError, ssl.SSLError) as e:
            raise CertificateError(f"cannot load the certificates (ca_cert={ca_cert}, client_cert={client_cert}, client_key={client_key}): {e}") from e
        conn = http.client.HTTPSConnection(u.hostname, u.port or 443, timeout=timeout, context=ctx)
    else:
        if client_cert or ca_cert:
            raise ValueError(f"certificates need an https:// allocator, got {allocator}")
        conn = http.client.HTTPConnection(u.hostname, u.port or 80, timeout=timeout)
    body = json.dumps(request_body(namespace, sels, counter)).encode()
    try:
        conn.request("POST", path, body=body, headers={"Content-Type": "application/json", "Accept": "application/json"})
        resp = conn.getresponse()
        status, data = resp.status, resp.read(1 << 20)
    except ssl.SSLCertVerificationError as e:
        raise CertificateError(
            f"the allocator at {allocator} presented a certificate this client does not trust: {e.verify_message}; "
            "pass the allocator's CA as ca_cert (the secret allocator-tls-ca) and use the address its certificate names"
        ) from e
    except ssl.SSLError as e:
        what = "the client certificate" if client_cert else "the connection: it requires a client certificate, none was given"
        raise CertificateError(
            f"the allocator at {allocator} refused {what}: {e.reason or e}; pass an allow-listed client certificate "
            "(client_cert, client_key; Helm: the secret allocator-client.default)"
        ) from e
    except (ConnectionRefusedError, socket.gaierror, socket.timeout, TimeoutError) as e:
        raise AllocatorUnreachable(f"cannot reach the Agones allocator at {allocator}: {e}") from e
    except (ConnectionResetError, BrokenPipeError) as e:
        # TLS 1.3: a refused client certificate may surface as a reset on the first read.
        if u.scheme == "https":
            raise CertificateError(f"the allocator at {allocator} closed the connection ({e}): was the client certificate refused?") from e
        raise AllocatorUnreachable(f"the Agones allocator at {allocator} closed the connection: {e}") from e
    except OSError as e:
        raise AllocatorUnreachable(f"cannot reach the Agones allocator at {allocator}: {e}") from e
    finally:
        conn.close()
    try:
        answer = json.loads(data)
    except ValueError:
        answer = {"message": data.decode(errors="replace").strip()[:300]}
    if status != 200:
        message = answer.get("message", "") if isinstance(answer, dict) else str(answer)
        code = answer.get("code") if isinstance(answer, dict) else None
        if status == 429 or code == 8:
            raise NoServerAvailable(
                f"no needlesim server available in namespace '{namespace}' for {_describe(sels)}: the allocator answered "
                f"{status}: {message}. Every matching server is full or none carries these labels: retry once the fleet "
                f"has scaled up, or check the labels (kubectl get gameservers -n {namespace} --show-labels)"
            )
        raise AllocatorRefused(f"the Agones allocator at {allocator} answered {status}: {message}")
    ports = [(p.get("name", ""), int(p.get("port", 0))) for p in answer.get("ports") or []]
    if not answer.get("address") or not ports:
        raise AllocatorRefused(f"the allocator's answer has no address or port: {answer}")
    chosen = [p for n, p in ports if n == port_name] or ([ports[0][1]] if len(ports) == 1 else [])
    if not chosen:
        raise AllocatorRefused(f"the allocated game server {answer.get('gameServerName')} has no port named {port_name!r}: {ports}")
    return Allocation(answer.get("gameServerName", ""), answer.get("nodeName", ""), answer["address"], chosen[0], ports)


def create_allocated_session(allocator: str, selectors, scene, root_cert=None, tick_rate_hz: float = 0.0, **allocate_args):
    """Allocates a server, then creates a session there from ``scene`` (an example's name, a
    SceneSource or an UploadedScene). Returns (NeedlesimClient, Session, Allocation); close the
    client when done. ``root_cert``: the needlesim servers' CA, when they use TLS."""
    from needlesim_client import NeedlesimClient

    a = allocate(allocator, selectors, **allocate_args)
    client = NeedlesimClient(a.target, root_cert=root_cert)
    try:
        session = client.create_session(scene, tick_rate_hz=tick_rate_hz)
    except BaseException:
        client.close()
        raise
    return client, session, a


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--allocator", default=os.environ.get("NEEDLESIM_ALLOCATOR"), help="https://HOST[:PORT] (NEEDLESIM_ALLOCATOR)")
    ap.add_argument("--selector", action="append", default=[], help="KEY=VALUE[,KEY=VALUE...]; repeat for fallbacks tried in order")
    ap.add_argument("--namespace", default="default")
    ap.add_argument("--client-cert")
    ap.add_argument("--client-key")
    ap.add_argument("--ca-cert")
    ap.add_argument("--port-name", default="grpc")
    ap.add_argument("--no-counter", action="store_true", help="select on labels only (no sessions Counter)")
    ap.add_argument("--create", metavar="EXAMPLE", help="then create a session from this shipped example there")
    ap.add_argument("--stubs", help="the generated needlesim.v1 stubs (generated here when missing)")
    a = ap.parse_args(argv)
    if not a.allocator:
        ap.error("--allocator URL (or NEEDLESIM_ALLOCATOR) is required")
    kw = dict(namespace=a.namespace, client_cert=a.client_cert, client_key=a.client_key, ca_cert=a.ca_cert, port_name=a.port_name, counter=not a.no_counter)
    try:
        if a.create:
            import needlesim_client

            needlesim_client.load_stubs(a.stubs)
            client, session, alloc = create_allocated_session(a.allocator, a.selector, a.create, **kw)
            client.close()
            out = {"session_id": session.session_id, "controller_token": session.controller_token, "observer_token": session.observer_token}
        else:
            alloc, out = allocate(a.allocator, a.selector, **kw), {}
    except (AllocationError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except Exception as e:  # noqa: BLE001 - grpc.RpcError from CreateSession, named with its code
        code = getattr(e, "code", None)
        if code is None or not callable(code):
            raise
        print(f"error: creating the session on the allocated server: {code().name}: {e.details()}", file=sys.stderr)
        return 1
    out.update(
        address=alloc.address, port=alloc.port, target=alloc.target, game_server=alloc.game_server, node_name=alloc.node_name,
        ports=[{"name": n, "port": p} for n, p in alloc.ports],
    )
    print(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
