#!/usr/bin/env python3
"""Validates the Kubernetes and Agones manifests of deploy/k8s/ (issue 22), offline.

Kubernetes kinds (Deployment, Service, ServiceAccount, Role, RoleBinding, …) are validated
strictly against the Kubernetes OpenAPI schemas bundled in the `kubernetes-validate` package
(version --k8s, 1.32 by default). Agones kinds have no schema there (they are CRDs, and
GameServerAllocation is an aggregated API), so their fields are checked here against Agones'
documented schema (agones.dev reference: Fleet / GameServer spec, FleetAutoscaler policy,
GameServerAllocation): required fields, enums and ranges; and the pod template a Fleet embeds
is wrapped in a PodTemplate and validated strictly against the Kubernetes schema. Then the
manifests are checked against each other and against the server's flags: the FleetAutoscaler's
fleet and Counter exist, the allocation selects an existing fleet and Counter, the game-server
container runs `--agones` with `--max-sessions` equal to the Counter's capacity, a health
interval below the health period, a drain grace below the pod's termination grace period, and
Guaranteed QoS (requests equal limits, whole CPUs) with CAP_SYS_NICE for SCHED_FIFO.

Usage: validate_manifests.py [--k8s 1.32.0] FILE.yaml...   (exit 1 naming each problem)
"""

import argparse
import re
import sys

import kubernetes_validate
import yaml

AGONES_GROUPS = ("agones.dev/", "autoscaling.agones.dev/", "allocation.agones.dev/")
DNS_LABEL = re.compile(r"^[a-z0-9]([-a-z0-9]*[a-z0-9])?$")


class Problems:
    def __init__(self):
        self.items = []

    def add(self, where, what):
        self.items.append(f"{where}: {what}")


def get(d, path, default=None):
    for k in path.split("."):
        if not isinstance(d, dict) or k not in d:
            return default
        d = d[k]
    return d


def need(p, where, d, path, kind=None):
    v = get(d, path)
    if v is None:
        p.add(where, f"missing {path}")
    elif kind is not None and not isinstance(v, kind):
        p.add(where, f"{path} must be {kind.__name__ if isinstance(kind, type) else kind}, found {v!r}")
    return v


def enum(p, where, d, path, allowed, required=False):
    v = get(d, path)
    if v is None:
        if required:
            p.add(where, f"missing {path}")
        return v
    if v not in allowed:
        p.add(where, f"{path} = {v!r}: one of {allowed}")
    return v


def int_range(p, where, d, path, lo, hi=2**31, required=False):
    v = get(d, path)
    if v is None:
        if required:
            p.add(where, f"missing {path}")
        return v
    if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= hi:
        p.add(where, f"{path} = {v!r}: an integer in [{lo}, {hi}]")
    return v


def flags(args):
    """`--name=value` and `--name value` arguments as a dict (`--flag` alone: True)."""
    out, i = {}, 0
    while i < len(args):
        a = str(args[i])
        if a.startswith("--"):
            if "=" in a:
                k, v = a[2:].split("=", 1)
                out[k] = v
            elif i + 1 < len(args) and not str(args[i + 1]).startswith("--"):
                out[a[2:]] = str(args[i + 1])
                i += 1
            else:
                out[a[2:]] = True
        i += 1
    return out


def quantity_cpu(v):
    s = str(v)
    return float(s[:-1]) / 1000 if s.endswith("m") else float(s)


def check_pod_template(p, where, template, k8s):
    doc = {"apiVersion": "v1", "kind": "PodTemplate", "metadata": {"name": "gameserver-template"}, "template": template}
    try:
        kubernetes_validate.validate(doc, k8s, strict=True)
    except kubernetes_validate.ValidationError as e:
        p.add(where, f"the pod template: {e.message} at {'.'.join(str(x) for x in e.path)}")
    except Exception as e:  # noqa: BLE001 - the validator's other errors name the problem too
        p.add(where, f"the pod template: {e}")


def check_game_server_spec(p, where, spec, k8s):
    """A GameServer spec (alone or a Fleet's template.spec). Returns its counters and server flags."""
    pod = need(p, where, spec, "template", dict) or {}
    containers = get(pod, "spec.containers") or []
    if not containers:
        p.add(where, "template.spec.containers: at least one container")
    names = [c.get("name") for c in containers]
    for c in containers:
        if not c.get("image"):
            p.add(where, f"container {c.get('name')!r}: missing image")
    gs_container = spec.get("container")
    if gs_container is None and len(containers) > 1:
        p.add(where, "container: required with more than one container")
    if gs_container is not None and gs_container not in names:
        p.add(where, f"container = {gs_container!r} names no container of the template ({names})")
    main = next((c for c in containers if c.get("name") == (gs_container or (names[0] if names else None))), {})
    ports = need(p, where, spec, "ports", list) or []
    if not ports:
        p.add(where, "ports: at least one port")
    container_ports = {cp.get("containerPort") for cp in main.get("ports", [])}
    for i, port in enumerate(ports):
        w = f"{where} ports[{i}]"
        enum(p, w, port, "portPolicy", ["Dynamic", "Static", "Passthrough"])
        enum(p, w, port, "protocol", ["UDP", "TCP", "TCPUDP"])
        cp = int_range(p, w, port, "containerPort", 1, 65535, required=port.get("portPolicy") != "Passthrough")
        if port.get("portPolicy") == "Static":
            int_range(p, w, port, "hostPort", 1, 65535, required=True)
        if cp is not None and cp not in container_ports:
            p.add(w, f"containerPort {cp} is not a port of container {main.get('name')!r} ({sorted(x for x in container_ports if x)})")
    enum(p, where, spec, "scheduling", ["Packed", "Distributed"])
    health = spec.get("health") or {}
    if health.get("disabled"):
        p.add(where, "health.disabled: the server's health pings are what detect a stalled real-time thread")
    int_range(p, where, health, "initialDelaySeconds", 0)
    period = int_range(p, where, health, "periodSeconds", 0) or 5
    int_range(p, where, health, "failureThreshold", 1)
    enum(p, where, spec, "sdkServer.logLevel", ["Error", "Info", "Debug"])
    counters = spec.get("counters") or {}
    for name, c in counters.items():
        w = f"{where} counters.{name}"
        count = int_range(p, w, c, "count", 0) or 0
        cap = int_range(p, w, c, "capacity", 0)
        if cap is not None and count > cap:
            p.add(w, f"count {count} > capacity {cap}")
    check_pod_template(p, where, pod, k8s)
    # The server's own flags against the spec.
    args = main.get("args") or []
    f = flags(args[1:] if args and args[0] == "serve" else args)
    if "agones" not in f:
        p.add(where, "the game-server container runs without --agones")
    if "sessions" not in counters:
        p.add(where, "counters.sessions: the Counter the server publishes is not declared")
    elif str(counters["sessions"].get("capacity")) != str(f.get("max-sessions", 16)):
        p.add(where, f"counters.sessions.capacity {counters['sessions'].get('capacity')} != --max-sessions {f.get('max-sessions', 16)}")
    interval_ms = int(f.get("agones-health-interval-ms", 2000))
    if interval_ms >= period * 1000:
        p.add(where, f"--agones-health-interval-ms {interval_ms} is not below health.periodSeconds {period} s")
    listen = str(f.get("listen", "127.0.0.1:50051"))
    if not listen.startswith("0.0.0.0:") and not listen.startswith("[::]:"):
        p.add(where, f"--listen {listen}: a game server must listen on all interfaces")
    elif int(listen.rsplit(":", 1)[1]) not in container_ports:
        p.add(where, f"--listen {listen}: its port is not a container port")
    grace = get(pod, "spec.terminationGracePeriodSeconds", 30)
    drain = int(f.get("drain-grace-s", 1800))
    if drain >= grace:
        p.add(where, f"--drain-grace-s {drain} is not below terminationGracePeriodSeconds {grace}")
    res = main.get("resources") or {}
    req, lim = res.get("requests") or {}, res.get("limits") or {}
    for r in ("cpu", "memory"):
        if r not in lim or str(req.get(r, lim.get(r))) != str(lim[r]):
            p.add(where, f"resources: {r} requests must equal limits (Guaranteed QoS), found {req.get(r)!r} / {lim.get(r)!r}")
    if "cpu" in lim and not quantity_cpu(lim["cpu"]).is_integer():
        p.add(where, f"resources.limits.cpu {lim['cpu']!r}: whole CPUs, so the static CPU manager pins them")
    caps = get(main, "securityContext.capabilities.add") or []
    if "SYS_NICE" not in caps and "CAP_SYS_NICE" not in caps:
        p.add(where, "securityContext.capabilities.add: SYS_NICE is needed for SCHED_FIFO (--rt-priority)")
    return counters


def check_agones(p, where, doc, k8s, fleets):
    kind, spec = doc.get("kind"), doc.get("spec") or {}
    name = get(doc, "metadata.name") or get(doc, "metadata.generateName")
    if not name:
        p.add(where, "missing metadata.name")
    if kind == "Fleet" and doc["apiVersion"] == "agones.dev/v1":
        int_range(p, where, spec, "replicas", 0)
        enum(p, where, spec, "scheduling", ["Packed", "Distributed"])
        enum(p, where, spec, "strategy.type", ["RollingUpdate", "Recreate"])
        gs = need(p, where, spec, "template.spec", dict) or {}
        fleets[name] = check_game_server_spec(p, where, gs, k8s)
    elif kind == "GameServer" and doc["apiVersion"] == "agones.dev/v1":
        check_game_server_spec(p, where, spec, k8s)
    elif kind == "FleetAutoscaler" and doc["apiVersion"] == "autoscaling.agones.dev/v1":
        fleet = need(p, where, spec, "fleetName", str)
        t = enum(p, where, spec, "policy.type", ["Buffer", "Webhook", "Counter", "List", "Chain"], required=True)
        if t == "Counter":
            c = need(p, where, spec, "policy.counter", dict) or {}
            key = need(p, where, c, "key", str)
            buf = need(p, where, c, "bufferSize")
            mx = int_range(p, where, c, "maxCapacity", 1, required=True)
            mn = int_range(p, where, c, "minCapacity", 0)
            if isinstance(buf, int) and mn is not None and mn < buf:
                p.add(where, f"policy.counter.minCapacity {mn} is below bufferSize {buf}")
            if mx is not None and mn is not None and mx < mn:
                p.add(where, f"policy.counter.maxCapacity {mx} is below minCapacity {mn}")
            if fleet in fleets and key not in fleets[fleet]:
                p.add(where, f"policy.counter.key {key!r}: Fleet {fleet!r} declares no such Counter")
        elif t == "Buffer":
            int_range(p, where, spec, "policy.buffer.maxReplicas", 1, required=True)
        if fleet is not None and fleet not in fleets:
            p.add(where, f"fleetName {fleet!r}: no such Fleet in these manifests")
        enum(p, where, spec, "sync.type", ["FixedInterval"])
        int_range(p, where, spec, "sync.fixedInterval.seconds", 1)
    elif kind == "GameServerAllocation" and doc["apiVersion"] == "allocation.agones.dev/v1":
        selectors = need(p, where, spec, "selectors", list) or []
        for i, s in enumerate(selectors):
            w = f"{where} selectors[{i}]"
            enum(p, w, s, "gameServerState", ["Ready", "Allocated"])
            fleet = (s.get("matchLabels") or {}).get("agones.dev/fleet")
            if fleet not in fleets:
                p.add(w, f"matchLabels agones.dev/fleet = {fleet!r}: no such Fleet in these manifests")
            for key, c in (s.get("counters") or {}).items():
                if fleet in fleets and key not in fleets[fleet]:
                    p.add(w, f"counters.{key}: Fleet {fleet!r} declares no such Counter")
                for bound in ("minCount", "maxCount", "minAvailable", "maxAvailable"):
                    int_range(p, f"{w} counters.{key}", c, bound, 0)
        enum(p, where, spec, "scheduling", ["Packed", "Distributed"])
        for i, pr in enumerate(spec.get("priorities") or []):
            enum(p, f"{where} priorities[{i}]", pr, "type", ["Counter", "List"], required=True)
            enum(p, f"{where} priorities[{i}]", pr, "order", ["Ascending", "Descending"])
            need(p, f"{where} priorities[{i}]", pr, "key", str)
        for key, c in (spec.get("counters") or {}).items():
            enum(p, f"{where} counters.{key}", c, "action", ["Increment", "Decrement"])
            int_range(p, f"{where} counters.{key}", c, "amount", 0)
    else:
        p.add(where, f"{doc.get('apiVersion')} {kind}: not an Agones kind this checker knows")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--k8s", default="1.32.0", help="Kubernetes version of the schemas")
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    p = Problems()
    docs = []
    for path in a.files:
        with open(path, encoding="utf-8") as f:
            try:
                for i, doc in enumerate(yaml.safe_load_all(f)):
                    if doc is not None:
                        docs.append((f"{path}#{i}", doc))
            except yaml.YAMLError as e:
                p.add(path, f"not YAML: {e}")
    # Fleets first, so that autoscalers and allocations can refer to them in any order.
    docs.sort(key=lambda d: d[1].get("kind") != "Fleet")
    fleets = {}
    n_k8s = n_agones = 0
    for where, doc in docs:
        where = f"{where} ({doc.get('kind')} {get(doc, 'metadata.name') or get(doc, 'metadata.generateName')})"
        if not isinstance(doc, dict) or "apiVersion" not in doc or "kind" not in doc:
            p.add(where, "missing apiVersion or kind")
            continue
        if doc["apiVersion"].startswith(AGONES_GROUPS):
            check_agones(p, where, doc, a.k8s, fleets)
            n_agones += 1
        else:
            try:
                kubernetes_validate.validate(doc, a.k8s, strict=True)
            except kubernetes_validate.ValidationError as e:
                p.add(where, f"{e.message} at {'.'.join(str(x) for x in e.path)}")
            except Exception as e:  # noqa: BLE001 - e.g. no schema for the kind: a problem too
                p.add(where, str(e))
            n_k8s += 1
    for item in p.items:
        print(f"error: {item}")
    print(f"{len(docs)} documents: {n_k8s} Kubernetes (schemas {a.k8s}), {n_agones} Agones; {len(p.items)} problems")
    return 1 if p.items else 0


if __name__ == "__main__":
    sys.exit(main())
