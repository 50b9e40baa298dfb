#!/usr/bin/env python3
"""A local stand-in of the Agones SDK server's REST gateway, for tests (issue 22).

Written from Agones' documented REST API (agones.dev, "REST Game Server Client API", and the
SDK protos sdk.proto / beta.proto, whose google.api.http options define the paths): the stable
lifecycle calls POST /ready, /health, /allocate, /shutdown (body `{}`), PUT /metadata/label and
/metadata/annotation (`{"key", "value"}`), GET /gameserver and the newline-delimited JSON stream
GET /watch/gameserver (`{"result": GameServer}` per update), and the beta Counters
GET/PATCH /v1beta1/counters/{name} (CounterUpdateRequest: `count`, `capacity` as int64 — JSON
strings or numbers, as protojson accepts — and `countDiff`). Like grpc-gateway, an unknown field
or a malformed body is 400, a Counter the GameServer does not declare is 404, a count outside
[0, capacity] is 400 (OUT_OF_RANGE).

Every call is appended to the --log file as one JSON line: {"t": UNIX seconds (time.time(), the
clock the test reads too), "method", "path", "body"}. The state follows the calls as the real SDK
server's does (Ready, Allocated, Shutdown), and a test may set it with POST /__test/state
{"state": "Allocated"} (not part of the Agones API; not logged).

With --watch-no-newline (issue 35), GET /watch/gameserver streams bytes without a newline, as
fast as the client reads them, and logs {"method": "WATCH_END", "body": {"bytes": n}} when the
client drops the stream.

With --endless-health (issue 35), POST /health answers 200 with a body that never ends (no length,
sent as fast as the client reads it) and logs {"method": "HEALTH_END", "body": {"bytes": n}} when
the client drops it.

Usage: agones_sdk_stub.py --log calls.jsonl --port-file port [--counter sessions=0] [--watch-no-newline]
       [--endless-health]
"""

import argparse
import json
import os
import re
import sys
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

LABEL_KEY = re.compile(r"^[A-Za-z0-9]([-A-Za-z0-9_.]{0,61}[A-Za-z0-9])?$")
LABEL_VALUE = re.compile(r"^([A-Za-z0-9]([-A-Za-z0-9_.]{0,61}[A-Za-z0-9])?)?$")


class Sdk:
    """The GameServer as the SDK server sees it, and the call log."""

    def __init__(self, log_path, counters, watch_no_newline=False, endless_health=False):
        self.lock = threading.Condition()
        self.watch_no_newline = watch_no_newline
        self.endless_health = endless_health
        self.log_path = log_path
        self.state = "Scheduled"
        self.labels = {}
        self.annotations = {}
        self.counters = counters  # name -> {"count": int, "capacity": int}
        self.version = 0

    def record(self, method, path, body):
        line = json.dumps({"t": time.time(), "method": method, "path": path, "body": body})
        with self.lock:
            with open(self.log_path, "a", encoding="utf-8") as f:
                f.write(line + "\n")

    def game_server(self):
        return {
            "object_meta": {
                "name": "local",
                "namespace": "default",
                "uid": "1234",
                "resource_version": str(self.version),
                "labels": {"agones.dev/sdk-" + k: v for k, v in self.labels.items()},
                "annotations": {"agones.dev/sdk-" + k: v for k, v in self.annotations.items()},
            },
            "status": {
                "state": self.state,
                "address": "127.0.0.1",
                "ports": [{"name": "grpc", "port": 7777}],
                "counters": {k: {"count": str(v["count"]), "capacity": str(v["capacity"])} for k, v in self.counters.items()},
            },
        }

    def set_state(self, state):
        with self.lock:
            if self.state != state:
                self.state = state
                self.version += 1
                self.lock.notify_all()

    def changed(self):
        with self.lock:
            self.version += 1
            self.lock.notify_all()


def int64(v, field):
    """An int64 as protojson reads it: a JSON number or a decimal string."""
    if isinstance(v, bool) or not isinstance(v, (int, str)):
        raise ValueError(f"{field}: not an int64: {v!r}")
    if isinstance(v, str) and not re.fullmatch(r"-?[0-9]+", v):
        raise ValueError(f"{field}: not an int64: {v!r}")
    return int(v)


def make_handler(sdk):
    class Handler(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.0"  # close-delimited bodies, so the watch stream can stream

        def log_message(self, fmt, *args):  # quiet
            pass

        def reply(self, code, obj):
            data = json.dumps(obj).encode()
            self.send_response(code)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        def error(self, code, grpc_code, message):
            self.reply(code, {"code": grpc_code, "message": message, "details": []})

        def body(self):
            n = int(self.headers.get("Content-Length") or 0)
            raw = self.rfile.read(n) if n else b""
            if not raw.strip():
                return {}
            return json.loads(raw)

        def handle_any(self, method):
            path = self.path
            try:
                body = self.body()
            except ValueError as e:
                sdk.record(method, path, None)
                return self.error(400, 3, f"invalid JSON body: {e}")
            if path == "/__test/state" and method == "POST":
                sdk.set_state(body.get("state", ""))
                return self.reply(200, {})
            sdk.record(method, path, body)
            if not isinstance(body, dict):
                return self.error(400, 3, "the body is not a JSON object")
            if method == "POST" and path == "/health" and sdk.endless_health:
                return self.endless()
            if method == "POST" and path in ("/ready", "/health", "/allocate", "/shutdown"):
                if body:
                    return self.error(400, 3, f"unknown fields {sorted(body)} for Empty")
                new = {"/ready": "Ready", "/allocate": "Allocated", "/shutdown": "Shutdown"}.get(path)
                if new:
                    sdk.set_state(new)
                return self.reply(200, {})
            if method == "PUT" and path in ("/metadata/label", "/metadata/annotation"):
                if set(body) - {"key", "value"} or not isinstance(body.get("key"), str):
                    return self.error(400, 3, "KeyValue takes `key` and `value` strings")
                key, value = body["key"], str(body.get("value", ""))
                if path == "/metadata/label":
                    if not LABEL_KEY.match(key) or not LABEL_VALUE.match(value):
                        return self.error(400, 3, f"invalid label {key}={value}")
                    sdk.labels[key] = value
                else:
                    sdk.annotations[key] = value
                sdk.changed()
                return self.reply(200, {})
            m = re.fullmatch(r"/v1beta1/counters/([^/:]+)", path)
            if m:
                name = m.group(1)
                if name not in sdk.counters:
                    return self.error(404, 5, f"counter not found: {name}")
                c = sdk.counters[name]
                if method == "GET":
                    return self.reply(200, {"name": name, "count": str(c["count"]), "capacity": str(c["capacity"])})
                if method == "PATCH":
                    unknown = set(body) - {"name", "count", "capacity", "countDiff"}
                    if unknown:
                        return self.error(400, 3, f"unknown fields {sorted(unknown)} for CounterUpdateRequest")
                    try:
                        capacity = int64(body["capacity"], "capacity") if "capacity" in body else c["capacity"]
                        count = int64(body["count"], "count") if "count" in body else c["count"]
                        count += int64(body.get("countDiff", 0), "countDiff")
                    except ValueError as e:
                        return self.error(400, 3, str(e))
                    if capacity < 0 or not 0 <= count <= capacity:
                        return self.error(400, 11, f"count {count} out of range [0, {capacity}]")
                    c["count"], c["capacity"] = count, capacity
                    sdk.changed()
                    return self.reply(200, {"name": name, "count": str(count), "capacity": str(capacity)})
            if method == "GET" and path == "/gameserver":
                return self.reply(200, sdk.game_server())
            if method == "GET" and path == "/watch/gameserver":
                return self.watch()
            return self.error(404, 5, f"no such method: {method} {path}")

        def watch(self):
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.end_headers()
            if sdk.watch_no_newline:
                return self.watch_without_newlines()
            seen = -1
            try:
                while True:
                    with sdk.lock:
                        while sdk.version == seen:
                            sdk.lock.wait(timeout=1.0)
                        seen = sdk.version
                        line = json.dumps({"result": sdk.game_server()}) + "\n"
                    self.wfile.write(line.encode())
                    self.wfile.flush()
            except (BrokenPipeError, ConnectionResetError):
                return

        def write_forever(self, event):
            """Writes 64 kB chunks without a newline until the client leaves; records `event`
            with the bytes sent."""
            chunk = b"x" * 65536
            sent = 0
            try:
                while True:
                    self.wfile.write(chunk)
                    sent += len(chunk)
            except (BrokenPipeError, ConnectionResetError):
                sdk.record(event, self.path, {"bytes": sent})

        def watch_without_newlines(self):
            self.write_forever("WATCH_END")

        def endless(self):
            self.send_response(200)
            self.send_header("Content-Type", "application/json")
            self.send_header("Connection", "close")
            self.end_headers()
            self.write_forever("HEALTH_END")
            self.close_connection = True

        def do_GET(self):
            self.handle_any("GET")

        def do_POST(self):
            self.handle_any("POST")

        def do_PUT(self):
            self.handle_any("PUT")

        def do_PATCH(self):
            self.handle_any("PATCH")

    return Handler


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--log", required=True, help="append every call here, one JSON line each")
    ap.add_argument("--port-file", required=True, help="write the port listened on here")
    ap.add_argument("--counter", action="append", default=[], metavar="NAME=CAPACITY",
                    help="a Counter the GameServer's spec declares (count 0)")
    ap.add_argument("--watch-no-newline", action="store_true",
                    help="the watch stream sends bytes without a newline, without end")
    ap.add_argument("--endless-health", action="store_true",
                    help="POST /health answers 200 with a body without end")
    a = ap.parse_args()
    counters = {}
    for c in a.counter:
        name, _, cap = c.partition("=")
        counters[name] = {"count": 0, "capacity": int(cap or 0)}
    sdk = Sdk(a.log, counters, a.watch_no_newline, a.endless_health)
    server = ThreadingHTTPServer(("127.0.0.1", 0), make_handler(sdk))
    server.daemon_threads = True
    tmp = a.port_file + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(str(server.server_address[1]))
    os.replace(tmp, a.port_file)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
