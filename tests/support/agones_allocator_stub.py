#!/usr/bin/env python3
"""A local stand-in of the Agones allocator service's REST API, for tests (issue 22).

Written from Agones' documented API (agones.dev, "Allocator Service"; proto/allocation/
allocation.proto and its swagger, allocation.swagger.json; grpc-gateway's protojson mapping):

    POST /gameserverallocation   body: AllocationRequest   200: AllocationResponse

over HTTPS with a required client certificate (mTLS: --tls-cert/--tls-key for the server,
--client-ca for the certificates it accepts; a client without an accepted certificate fails the
TLS handshake, as the allocator's `RequireAnyClientCert` + verification does), or plain HTTP (an
allocator with TLS disabled) without those flags.

The request is checked as grpc-gateway's protojson unmarshalling would: an unknown field, a wrong
type or an unknown enum name is 400 with `{"code": 3, "message", "details": []}`
(InvalidArgument). Allocation follows the documented semantics over the game servers of
--game-servers (a JSON list of {name, namespace, address, nodeName, ports: [{name, port}],
labels, state: Ready|Allocated|…, counters: {name: {count, capacity}}}): the selectors
(`gameServerSelectors`, or the deprecated `requiredGameServerSelector` +
`preferredGameServerSelectors`) are tried in order; a game server matches when it is in the
request's namespace ("default" when empty), carries every `matchLabels` label, is in the
selector's `gameServerState` (READY by default, or ALLOCATED) and passes each Counter filter
(minCount ≤ count ≤ maxCount, minAvailable ≤ capacity − count ≤ maxAvailable; a max of 0 means
no maximum); among the matches of the first selector with any, `priorities` order them (Counter
by available capacity, Ascending or Descending), else file order. The chosen server becomes
Allocated, the request's Counter actions (Increment/Decrement by amount, capacity) and
`metadata` labels/annotations are applied, and the answer is its AllocationResponse (int64 as
strings, as protojson writes them). No match is the allocator's UnAllocated answer: HTTP 429
`{"code": 8, "message": "there is no available GameServer to allocate", "details": []}`
(ResourceExhausted, mapped by grpc-gateway).

Every request is appended to --log as one JSON line {"t", "path", "body", "status",
"game_server"}. The port is written to --port-file once listening.

Usage: agones_allocator_stub.py --game-servers servers.json --port-file port --log calls.jsonl
       [--tls-cert server.crt --tls-key server.key --client-ca clients-ca.crt]
"""

import argparse
import json
import os
import ssl
import sys
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

INT64_MAX = 2**63 - 1


class BadRequest(Exception):
    """A request grpc-gateway would refuse (InvalidArgument)."""


def check_fields(where, obj, allowed):
    if not isinstance(obj, dict):
        raise BadRequest(f"{where}: an object expected, found {json.dumps(obj)}")
    for k in obj:
        if k not in allowed:
            raise BadRequest(f'{where}: unknown field "{k}"')


def string_map(where, v):
    if v is None:
        return {}
    if not isinstance(v, dict) or not all(isinstance(k, str) and isinstance(x, str) for k, x in v.items()):
        raise BadRequest(f"{where}: a map of strings expected")
    return v


def int64(where, v, unsigned=False):
    """protojson int64/uint64: a JSON string or number holding an integer."""
    if v is None:
        return 0
    if isinstance(v, bool):
        raise BadRequest(f"{where}: an integer expected, found {v}")
    if isinstance(v, str):
        try:
            n = int(v)
        except ValueError:
            raise BadRequest(f"{where}: an integer expected, found {v!r}") from None
    elif isinstance(v, int):
        n = v
    elif isinstance(v, float) and v.is_integer():
        n = int(v)
    else:
        raise BadRequest(f"{where}: an integer expected, found {v!r}")
    if (unsigned and n < 0) or abs(n) > INT64_MAX:
        raise BadRequest(f"{where}: {n} out of range")
    return n


def enum(where, v, names, default):
    if v is None:
        return default
    if isinstance(v, int) and not isinstance(v, bool) and 0 <= v < len(names):
        return names[v]
    if v not in names:
        raise BadRequest(f"{where}: invalid value {v!r} (one of {names})")
    return v


def parse_selector(where, s):
    check_fields(where, s, {"matchLabels", "gameServerState", "players", "counters", "lists"})
    counters = {}
    for name, c in (s.get("counters") or {}).items():
        w = f"{where}.counters.{name}"
        check_fields(w, c, {"minCount", "maxCount", "minAvailable", "maxAvailable"})
        counters[name] = {k: int64(f"{w}.{k}", c.get(k)) for k in ("minCount", "maxCount", "minAvailable", "maxAvailable")}
    if s.get("players") is not None:
        check_fields(f"{where}.players", s["players"], {"minAvailable", "maxAvailable"})
    return {
        "labels": string_map(f"{where}.matchLabels", s.get("matchLabels")),
        "state": {"READY": "Ready", "ALLOCATED": "Allocated"}[enum(f"{where}.gameServerState", s.get("gameServerState"), ["READY", "ALLOCATED"], "READY")],
        "counters": counters,
    }


def parse_request(body):
    check_fields(
        "AllocationRequest",
        body,
        {
            "namespace", "multiClusterSetting", "requiredGameServerSelector", "preferredGameServerSelectors",
            "scheduling", "metaPatch", "metadata", "gameServerSelectors", "priorities", "counters", "lists",
        },
    )
    ns = body.get("namespace") or "default"
    if not isinstance(ns, str):
        raise BadRequest("namespace: a string expected")
    enum("scheduling", body.get("scheduling"), ["Packed", "Distributed"], "Packed")
    if body.get("gameServerSelectors"):
        if not isinstance(body["gameServerSelectors"], list):
            raise BadRequest("gameServerSelectors: a list expected")
        selectors = [parse_selector(f"gameServerSelectors[{i}]", s) for i, s in enumerate(body["gameServerSelectors"])]
    else:
        preferred = body.get("preferredGameServerSelectors") or []
        selectors = [parse_selector(f"preferredGameServerSelectors[{i}]", s) for i, s in enumerate(preferred)]
        selectors.append(parse_selector("requiredGameServerSelector", body.get("requiredGameServerSelector") or {}))
    priorities = []
    for i, p in enumerate(body.get("priorities") or []):
        w = f"priorities[{i}]"
        check_fields(w, p, {"type", "key", "order"})
        t = enum(f"{w}.type", p.get("type"), ["Counter", "List"], "Counter")
        o = enum(f"{w}.order", p.get("order"), ["Ascending", "Descending"], "Ascending")
        if not isinstance(p.get("key", ""), str):
            raise BadRequest(f"{w}.key: a string expected")
        priorities.append((t, p.get("key", ""), o))
    actions = {}
    for name, a in (body.get("counters") or {}).items():
        w = f"counters.{name}"
        check_fields(w, a, {"action", "amount", "capacity"})
        action = a.get("action")
        if action not in (None, "Increment", "Decrement"):
            raise BadRequest(f'{w}.action: "{action}": Increment or Decrement')
        amount = int64(f"{w}.amount", a.get("amount"))
        if action is not None and amount <= 0:
            raise BadRequest(f"{w}.amount: a positive integer with an action")
        actions[name] = (action, amount, None if a.get("capacity") is None else int64(f"{w}.capacity", a.get("capacity")))
    meta = body.get("metadata") or body.get("metaPatch") or {}
    check_fields("metadata", meta, {"labels", "annotations"})
    return {
        "namespace": ns,
        "selectors": selectors,
        "priorities": priorities,
        "actions": actions,
        "labels": string_map("metadata.labels", meta.get("labels")),
        "annotations": string_map("metadata.annotations", meta.get("annotations")),
    }


class Fleet:
    def __init__(self, servers):
        self.lock = threading.Lock()
        self.servers = servers
        for gs in servers:
            gs.setdefault("namespace", "default")
            gs.setdefault("state", "Ready")
            gs.setdefault("labels", {})
            gs.setdefault("annotations", {})
            gs.setdefault("counters", {})
            gs.setdefault("nodeName", "node-1")

    @staticmethod
    def matches(gs, ns, sel):
        if gs["namespace"] != ns or gs["state"] != sel["state"]:
            return False
        if any(gs["labels"].get(k) != v for k, v in sel["labels"].items()):
            return False
        for name, f in sel["counters"].items():
            c = gs["counters"].get(name)
            if c is None:
                return False
            count, available = c["count"], c["capacity"] - c["count"]
            if count < f["minCount"] or (f["maxCount"] and count > f["maxCount"]):
                return False
            if available < f["minAvailable"] or (f["maxAvailable"] and available > f["maxAvailable"]):
                return False
        return True

    def allocate(self, req):
        with self.lock:
            for sel in req["selectors"]:
                found = [gs for gs in self.servers if self.matches(gs, req["namespace"], sel)]
                if not found:
                    continue
                for t, key, order in reversed(req["priorities"]):
                    if t == "Counter":
                        # Stable sorts, last priority first: the first priority decides.
                        avail = lambda gs, key=key: gs["counters"].get(key, {"capacity": 0, "count": 0})
                        found.sort(key=lambda gs: avail(gs)["capacity"] - avail(gs)["count"], reverse=order == "Descending")
                gs = found[0]
                gs["state"] = "Allocated"
                for name, (action, amount, capacity) in req["actions"].items():
                    c = gs["counters"].get(name)
                    if c is None:
                        continue
                    if capacity is not None:
                        c["capacity"] = capacity
                    if action == "Increment":
                        c["count"] = min(c["capacity"], c["count"] + amount)
                    elif action == "Decrement":
                        c["count"] = max(0, c["count"] - amount)
                gs["labels"].update(req["labels"])
                gs["annotations"].update(req["annotations"])
                return gs["name"], {
                    "gameServerName": gs["name"],
                    "ports": [{"name": p["name"], "port": p["port"]} for p in gs["ports"]],
                    "address": gs["address"],
                    "addresses": [{"type": "InternalIP", "address": gs["address"]}],
                    "nodeName": gs["nodeName"],
                    "source": "local",
                    "metadata": {"labels": gs["labels"], "annotations": gs["annotations"]},
                    "counters": {k: {"count": str(c["count"]), "capacity": str(c["capacity"])} for k, c in gs["counters"].items()},
                }
            return None, None


class Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"
    server_version = "agones-allocator-stub"

    def log_message(self, fmt, *args):  # quiet: the test reads the JSON log
        pass

    def answer(self, status, obj):
        data = json.dumps(obj).encode()
        self.send_response(status)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def log_call(self, body, status, game_server):
        line = json.dumps({"t": time.time(), "path": self.path, "body": body, "status": status, "game_server": game_server})
        with self.server.log_lock:
            with open(self.server.log_path, "a", encoding="utf-8") as f:
                f.write(line + "\n")

    def do_POST(self):
        length = int(self.headers.get("Content-Length") or 0)
        raw = self.rfile.read(length)
        if self.path != "/gameserverallocation":
            self.log_call(None, 404, None)
            return self.answer(404, {"code": 5, "message": "Not Found", "details": []})
        try:
            body = json.loads(raw or b"{}")
        except ValueError as e:
            self.log_call(raw.decode(errors="replace"), 400, None)
            return self.answer(400, {"code": 3, "message": f"invalid JSON: {e}", "details": []})
        try:
            req = parse_request(body)
        except BadRequest as e:
            self.log_call(body, 400, None)
            return self.answer(400, {"code": 3, "message": str(e), "details": []})
        name, resp = self.server.fleet.allocate(req)
        if resp is None:
            self.log_call(body, 429, None)
            return self.answer(429, {"code": 8, "message": "there is no available GameServer to allocate", "details": []})
        self.log_call(body, 200, name)
        return self.answer(200, resp)

    def do_GET(self):
        self.answer(405, {"code": 12, "message": "Method Not Allowed", "details": []})


class TlsServer(ThreadingHTTPServer):
    """Wraps each accepted connection in TLS in its own thread (a failed handshake ends only it)."""

    daemon_threads = True
    context = None

    def process_request_thread(self, request, client_address):
        if self.context is not None:
            try:
                request = self.context.wrap_socket(request, server_side=True)
            except (ssl.SSLError, OSError):
                request.close()
                return
        super().process_request_thread(request, client_address)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--game-servers", required=True)
    ap.add_argument("--port-file", required=True)
    ap.add_argument("--log", required=True)
    ap.add_argument("--tls-cert")
    ap.add_argument("--tls-key")
    ap.add_argument("--client-ca")
    a = ap.parse_args()
    with open(a.game_servers, encoding="utf-8") as f:
        servers = json.load(f)
    httpd = TlsServer(("127.0.0.1", 0), Handler)
    if a.tls_cert:
        ctx = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
        ctx.load_cert_chain(a.tls_cert, a.tls_key)
        if a.client_ca:
            ctx.verify_mode = ssl.CERT_REQUIRED
            ctx.load_verify_locations(a.client_ca)
        httpd.context = ctx
    httpd.fleet = Fleet(servers)
    httpd.log_path = a.log
    httpd.log_lock = threading.Lock()
    tmp = a.port_file + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(str(httpd.server_address[1]))
    os.replace(tmp, a.port_file)
    try:
        httpd.serve_forever()
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
