#!/usr/bin/env python3
"""A small Python client of the needlesim gRPC API (package needlesim.v1), as planning software
would integrate it.

Setup: generate the stubs once (they are not committed) and put them on the import path::

    python client/python/generate.py /tmp/needlesim-stubs
    PYTHONPATH=/tmp/needlesim-stubs python client/python/needlesim_client.py \\
        --address 127.0.0.1:50051 demo

(`--stubs DIR` does the same as PYTHONPATH and generates the stubs into DIR when they are
missing.) Needs grpcio, protobuf, grpcio-health-checking and grpcio-reflection; see tests/run for
the pinned versions.

Usage from Python::

    from needlesim_client import NeedlesimClient
    with NeedlesimClient("127.0.0.1:50051") as c:
        s = c.create_session_from_mesh(nodes, triangles, regions, fixed_nodes, needle, targets)
        for frame in c.watch(s.session_id, rate_hz=30, n_frames=10):
            print(frame.tick, frame.tip_m.x, frame.tip_m.y)
        c.close_session(s.session_id)

3D sessions (a 3D example such as "cube-phantom-3d", a scene TOML with `dim = 3`, or a TOML with
its Gmsh mesh: create_session_from_toml) are driven with 3D poses::

    s = c.create_session("cube-phantom-3d")
    responses = c.drive(s.session_id, "insert3d.csv")   # or an (N, 8) array t_s,x,y,z,qw,qx,qy,qz
    print(responses[-1].d3.force_n)
    for frame in c.watch(s.session_id, n_frames=10):
        print(frame.d3.tip_m, [t.distance_m for t in frame.d3.targets])

Conventions (see proto/needlesim/v1/needlesim.proto): SI units, 2D positions (x, y) in metres,
angles counter-clockwise in radians; 3D positions (x, y, z) in metres in the scene's world frame,
orientations as unit quaternions (w, x, y, z) taking the needle's body frame (shaft along +x) to
the world frame. Creating a session returns a controller token (to drive the
needle, record and close) and an observer token (to watch); the client keeps both per session
and sends the right one as `authorization: Bearer <token>` metadata.

Command line: `demo`, `demo3d`, `health [SERVICE]`, `services`, `record` and `hold` (see --help).
"""

from __future__ import annotations

import argparse
import dataclasses
import errno
import importlib
import json
import math
import os
import stat
import sys
import threading
import time
from typing import Callable, Iterable, Iterator, Optional, Sequence

import grpc

# The server's rule for local files (crate needlesim-localfile), and its bounds by file kind.
MAX_LOCAL_FILE_BYTES = 256 << 20  # a scene, a mesh, a trajectory
MAX_CERTIFICATE_BYTES = 1 << 20  # a PEM certificate (chain)


def _file_kind(mode: int) -> str:
    for test, kind in ((stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a directory")):
        if test(mode):
            return kind
    return "not a file"


# The kernel's pseudo file systems by statfs magic (linux/magic.h), as in needlesim-localfile:
# their files are made up as they are read (/proc/self/environ), none is a scene or certificate.
_PSEUDO_FILE_SYSTEMS = {
    0x00009FA0: "proc",
    0x62656572: "sysfs",
    0x64626720: "debugfs",
    0x74726163: "tracefs",
    0x73636673: "securityfs",
    0x0027E0EB: "cgroup",
    0x63677270: "cgroup2",
    0x62656570: "configfs",
    0xDE5E81E4: "efivarfs",
    0xCAFE4A11: "bpf",
    0x6165676C: "pstore",
}


def _pseudo_file_system(fd: int) -> Optional[str]:
    """The name of the kernel pseudo file system the open descriptor fd is on (fstatfs), or None
    (also off Linux). struct statfs begins with f_type, a C long, on every Linux target."""
    if not sys.platform.startswith("linux"):
        return None
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    buf = ctypes.create_string_buffer(512)  # sizeof(struct statfs) is 120 on 64-bit Linux
    if libc.fstatfs(fd, buf) != 0:
        e = ctypes.get_errno()
        raise OSError(e, os.strerror(e))
    return _PSEUDO_FILE_SYSTEMS.get(ctypes.c_long.from_buffer(buf).value & 0xFFFFFFFF)


def read_local_file(path, max_bytes: int = MAX_LOCAL_FILE_BYTES) -> bytes:
    """Reads a local file the way the server and the needlesim CLI do: refused (ValueError naming
    the path and the problem) when it is a symbolic link, not a regular file (a directory, a
    device such as /dev/zero, a FIFO, a socket) or larger than max_bytes. It is opened without
    following a link and without blocking (a FIFO swapped in after the check cannot block the
    open), checked again on the open descriptor, then made blocking again, and at most
    max_bytes + 1 bytes are read (a file that grows). A file on the kernel's pseudo file systems
    (/proc, /sys, …: fstatfs on the descriptor) is refused too. Errors never quote the file's contents;
    a missing or unreadable file raises OSError naming the path."""
    st = os.lstat(path)
    if stat.S_ISLNK(st.st_mode):
        raise ValueError(f"{path}: is a symbolic link; name the file it points to")
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{path}: not a regular file ({_file_kind(st.st_mode)})")
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as e:
        if e.errno == errno.ELOOP:
            raise ValueError(f"{path}: is a symbolic link; name the file it points to") from None
        raise
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{path}: not a regular file ({_file_kind(st.st_mode)})")
        fs = _pseudo_file_system(fd)
        if fs is not None:
            raise ValueError(
                f"{path}: on the kernel's {fs} file system, whose files are made up as they are read; "
                "local files on /proc, /sys and their kin are refused (copy it to a regular file)"
            )
        if st.st_size > max_bytes:
            raise ValueError(f"{path}: {st.st_size} bytes, over the limit of {max_bytes} bytes")
        os.set_blocking(fd, True)
        data = f.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise ValueError(f"{path}: {len(data)} bytes, over the limit of {max_bytes} bytes")
    return data


def read_local_text(path, max_bytes: int = MAX_LOCAL_FILE_BYTES) -> str:
    """read_local_file, as UTF-8 text (refused naming the offset of the first invalid byte)."""
    data = read_local_file(path, max_bytes)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError(f"{path}: not UTF-8 text (invalid byte at offset {e.start})") from None


pb = None  # needlesim.v1.needlesim_pb2, loaded by load_stubs()
pb_grpc = None  # needlesim.v1.needlesim_pb2_grpc


def load_stubs(stubs_dir: Optional[str] = None) -> None:
    """Imports the generated stubs, from stubs_dir if given (generating them there when missing),
    else from the import path."""
    global pb, pb_grpc
    if stubs_dir is not None:
        stubs_dir = os.path.abspath(stubs_dir)
        if not os.path.isfile(os.path.join(stubs_dir, "needlesim", "v1", "needlesim_pb2.py")):
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            from generate import generate

            generate(stubs_dir)
        if stubs_dir not in sys.path:
            sys.path.insert(0, stubs_dir)
    try:
        pb = importlib.import_module("needlesim.v1.needlesim_pb2")
        pb_grpc = importlib.import_module("needlesim.v1.needlesim_pb2_grpc")
    except ImportError as e:
        raise ImportError(
            "the needlesim.v1 stubs are not importable: run client/python/generate.py OUT_DIR and put "
            f"OUT_DIR on PYTHONPATH, or pass --stubs OUT_DIR ({e})"
        ) from e


class SessionFaultedError(RuntimeError):
    """The session driven faulted (its simulation failed: SessionStats.faulted); `responses`
    holds the ControlResponses received, the faulted tick last."""

    def __init__(self, message: str, responses: list):
        super().__init__(message)
        self.responses = responses


@dataclasses.dataclass
class Session:
    """A session created by this client, with its tokens."""

    session_id: str
    controller_token: str
    observer_token: str
    info: object  # needlesim.v1.SessionInfo


class NeedlesimClient:
    """A connection to a needlesim server.

    address: "host:port". root_cert: PEM bytes, or the path of a PEM file, of the CA that signed the
    server's certificate; with it the channel uses TLS, without it plain text. Use as a context
    manager or call close().
    """

    def __init__(self, address: str, root_cert: Optional[bytes | str] = None, max_message_bytes: int = 64 << 20):
        if pb is None:
            load_stubs()
        options = [
            ("grpc.max_receive_message_length", max_message_bytes),
            ("grpc.max_send_message_length", max_message_bytes),
        ]
        if root_cert is not None:
            if isinstance(root_cert, str):
                root_cert = read_local_file(root_cert, MAX_CERTIFICATE_BYTES)
            self.channel = grpc.secure_channel(address, grpc.ssl_channel_credentials(root_certificates=root_cert), options)
        else:
            self.channel = grpc.insecure_channel(address, options)
        self.sessions = pb_grpc.SessionServiceStub(self.channel)
        self.control = pb_grpc.ControlServiceStub(self.channel)
        self.observe = pb_grpc.ObserveServiceStub(self.channel)
        self.simulation = pb_grpc.SimulationServiceStub(self.channel)
        self.recordings = pb_grpc.RecordingServiceStub(self.channel)
        # session id -> Session (tokens), for sessions created by this client or added with add_tokens.
        self.tokens: dict[str, Session] = {}

    def close(self) -> None:
        self.channel.close()

    def __enter__(self) -> "NeedlesimClient":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # -- tokens -----------------------------------------------------------------------------

    def add_tokens(self, session_id: str, controller_token: str = "", observer_token: str = "") -> None:
        """Registers the tokens of a session this client did not create."""
        self.tokens[session_id] = Session(session_id, controller_token, observer_token, None)

    def _md(self, session_id: str, role: str, token: Optional[str] = None) -> list[tuple[str, str]]:
        if token is None:
            s = self.tokens.get(session_id)
            if s is None:
                raise KeyError(f"no tokens for session {session_id}: pass one or call add_tokens")
            token = s.controller_token if role == "controller" else (s.observer_token or s.controller_token)
        return [("authorization", f"Bearer {token}")]

    # -- scenes and sessions ----------------------------------------------------------------

    @staticmethod
    def uploaded_scene(
        nodes: Sequence[Sequence[float]],
        triangles: Sequence[Sequence[int]],
        regions: Sequence[dict],
        fixed_nodes: Iterable[int],
        needle: dict,
        targets: Sequence[dict] = (),
        triangle_regions: Optional[Sequence[int]] = None,
        name: str = "uploaded",
        plane: str = "stress",
        thickness_m: float = 0.0,
        tick_rate_hz: float = 0.0,
    ):
        """Builds a needlesim.v1.UploadedScene.

        nodes: [(x, y), ...] in metres. triangles: [(a, b, c), ...] 0-based node indices.
        regions: [{"name", "young_modulus_pa", "poisson_ratio", optional friction_n_per_m,
        static_friction_ratio, tip_peak_ratio, tip_peak_width_m, puncture_force_n,
        cutting_force_n}]; triangle_regions: the region index of each triangle (default: all 0).
        fixed_nodes: node indices held in place. needle: {"base": (x, y, theta_rad),
        optional "length_m", "capture_radius_m"}. targets: [{"name", "center": (x, y), "radius_m"}].
        """
        mesh = pb.Mesh(
            node_xy_m=[float(v) for p in nodes for v in (p[0], p[1])],
            triangle_nodes=[int(i) for t in triangles for i in t[:3]],
            triangle_region=list(triangle_regions) if triangle_regions is not None else [],
        )
        base = needle["base"]
        return pb.UploadedScene(
            name=name,
            mesh=mesh,
            regions=[pb.Region(**r) for r in regions],
            fixed_nodes=[int(n) for n in fixed_nodes],
            plane=plane,
            thickness_m=thickness_m,
            needle_length_m=float(needle.get("length_m", 0.0)),
            needle_base=pb.Pose2(x_m=base[0], y_m=base[1], theta_rad=base[2]),
            capture_radius_m=float(needle.get("capture_radius_m", 0.0)),
            targets=[
                pb.Target(name=t["name"], center_m=pb.Vec2(x=t["center"][0], y=t["center"][1]), radius_m=t["radius_m"])
                for t in targets
            ],
            tick_rate_hz=tick_rate_hz,
        )

    def create_session_from_mesh(
        self,
        nodes,
        triangles,
        regions,
        fixed_nodes,
        needle,
        targets=(),
        *,
        triangle_regions=None,
        name: str = "uploaded",
        tick_rate_hz: float = 0.0,
        record: bool = False,
        timeout: float = 60.0,
    ) -> Session:
        """Creates a live session from a mesh given as data (see uploaded_scene for the arguments);
        record=True records every tick to an MCAP file from the start. Returns the Session with
        its tokens, which the client also keeps."""
        scene = self.uploaded_scene(nodes, triangles, regions, fixed_nodes, needle, targets, triangle_regions, name)
        return self.create_session(pb.SceneSource(uploaded=scene), tick_rate_hz=tick_rate_hz, record=record, timeout=timeout)

    def create_session(self, scene, tick_rate_hz: float = 0.0, record: bool = False, timeout: float = 60.0) -> Session:
        """Creates a session from a SceneSource, an UploadedScene or a shipped example's name."""
        scene = _scene_source(scene)
        r = self.sessions.CreateSession(pb.CreateSessionRequest(scene=scene, tick_rate_hz=tick_rate_hz, record=record), timeout=timeout)
        s = Session(r.session.session_id, r.controller_token, r.observer_token, r.session)
        self.tokens[s.session_id] = s
        return s

    def create_session_from_toml(
        self, scene_toml: str, mesh_path: Optional[str] = None, tick_rate_hz: float = 0.0, record: bool = False, timeout: float = 120.0
    ) -> Session:
        """Creates a session from a scene TOML (the text, or the path of a .toml file): 2D, or 3D
        with `dim = 3`. mesh_path: the Gmsh .msh file a 3D TOML names in `[mesh] file`, uploaded
        with it (its file name must be the one the TOML names)."""
        if os.path.lexists(scene_toml) and not os.path.isdir(scene_toml):
            scene_toml = read_local_text(scene_toml)
        if mesh_path is None:
            return self.create_session(pb.SceneSource(scene_toml=scene_toml), tick_rate_hz=tick_rate_hz, record=record, timeout=timeout)
        mesh_text = read_local_text(mesh_path)
        scene = pb.UploadedScene3d(scene_toml=scene_toml, mesh_file_name=os.path.basename(mesh_path), mesh_text=mesh_text)
        return self.create_session(pb.SceneSource(uploaded3d=scene), tick_rate_hz=tick_rate_hz, record=record, timeout=timeout)

    def get_session(self, session_id: str):
        return self.sessions.GetSession(pb.GetSessionRequest(session_id=session_id), timeout=10)

    def dimension(self, session_id: str) -> int:
        """2 or 3: the dimension of a session (3: driven with 3D poses, frames carry d3)."""
        return max(2, self.get_session(session_id).dimension)

    def surface(self, session_id: str, token: Optional[str] = None):
        """The boundary surface of a 3D session's tissue (Surface: node_ids, node_xyz_m, triangles)."""
        return self.sessions.GetSurface(pb.GetSessionRequest(session_id=session_id), metadata=self._md(session_id, "observer", token), timeout=30)

    def stats(self, session_id: str, token: Optional[str] = None):
        """The tick statistics (SessionStats) of a session."""
        return self.sessions.GetStats(pb.GetSessionRequest(session_id=session_id), metadata=self._md(session_id, "observer", token), timeout=10)

    def close_session(self, session_id: str, token: Optional[str] = None) -> None:
        self.sessions.CloseSession(pb.CloseSessionRequest(session_id=session_id), metadata=self._md(session_id, "controller", token), timeout=30)
        self.tokens.pop(session_id, None)

    # -- driving and watching ---------------------------------------------------------------

    def set_pose(self, session_id: str, x_m: float, y_m: float, theta_rad: float, token: Optional[str] = None):
        """Moves the needle base (one pose; answered with the latest ControlResponse)."""
        req = pb.SetPoseRequest(session_id=session_id, base=pb.Pose2(x_m=x_m, y_m=y_m, theta_rad=theta_rad))
        return self.control.SetPose(req, metadata=self._md(session_id, "controller", token), timeout=10)

    def control_stream(self, session_id: str, poses: Iterable[tuple[float, float, float]], token: Optional[str] = None):
        """Opens the bidirectional Control stream: poses (x, y, theta) in, one ControlResponse per
        tick out (an iterator; cancel() it to stop)."""

        def requests():
            for seq, (x, y, th) in enumerate(poses, start=1):
                yield pb.ControlRequest(
                    session_id=session_id if seq == 1 else "",
                    base=pb.Pose2(x_m=x, y_m=y, theta_rad=th),
                    client_time_ns=time.monotonic_ns(),
                    seq=seq,
                )

        return self.control.Control(requests(), metadata=self._md(session_id, "controller", token))

    def set_pose3(self, session_id: str, position_m: Sequence[float], quat_wxyz: Sequence[float], token: Optional[str] = None):
        """Moves the needle base of a 3D session (position m, unit quaternion w, x, y, z)."""
        req = pb.SetPoseRequest3(session_id=session_id, base3=pose3(position_m, quat_wxyz))
        return self.control.SetPose3(req, metadata=self._md(session_id, "controller", token), timeout=10)

    def control_stream3(self, session_id: str, poses: Iterable[tuple[Sequence[float], Sequence[float]]], token: Optional[str] = None):
        """Opens the Control3 stream of a 3D session: poses (position_m, quat_wxyz) in, one
        ControlResponse per tick out (with d3; an iterator; cancel() it to stop)."""

        def requests():
            for seq, (p, q) in enumerate(poses, start=1):
                yield pb.ControlRequest3(
                    session_id=session_id if seq == 1 else "",
                    base3=pose3(p, q),
                    client_time_ns=time.monotonic_ns(),
                    seq=seq,
                )

        return self.control.Control3(requests(), metadata=self._md(session_id, "controller", token))

    def drive(self, session_id: str, trajectory, rate_hz: float = 1000.0, token: Optional[str] = None, grace_s: float = 0.05) -> list:
        """Plays a base trajectory in real time through the Control stream of a 2D session or
        the Control3 stream of a 3D one, a pose every 1/rate_hz s, and returns the ControlResponses
        (one per tick: the pose the tick applied, force, torque; d3 in 3D).

        trajectory: a CSV file (t_s,x_m,y_m,theta_rad or t_s,x_m,y_m,z_m,qw,qx,qy,qz) or an
        array-like of rows, (N, 4) for 2D, (N, 8) for 3D (a NumPy array works). A trajectory of the
        other dimension than the session's raises ValueError naming both."""
        if isinstance(trajectory, (str, os.PathLike)):
            traj = read_trajectory_csv(trajectory)
        else:
            traj = Trajectory(trajectory)
        dim = self.dimension(session_id)
        if traj.dimension != dim:
            raise ValueError(
                f"session {session_id} is {dim}D and takes a {dim}D trajectory ({HEADERS[dim]}), "
                f"but the trajectory is {traj.dimension}D ({HEADERS[traj.dimension]})"
            )
        t0, t1 = traj.span_s()
        stop = threading.Event()
        # The seq of the last pose sent, and the newest pose seq a response says a tick used.
        seqs = {"sent": 0, "used": 0}

        def poses():
            start = time.monotonic()
            period = 1.0 / rate_hz
            k = 0
            while not stop.is_set():
                el = time.monotonic() - start
                if el > t1 - t0:
                    break
                seqs["sent"] += 1
                yield traj.pose_at(t0 + el)
                k += 1
                delay = start + k * period - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
            # The last pose; then until a tick has used it (at most 2 s), and a little longer.
            seqs["sent"] += 1
            yield traj.pose_at(t1)
            deadline = time.monotonic() + 2.0
            while seqs["used"] < seqs["sent"] and time.monotonic() < deadline and not stop.is_set():
                time.sleep(0.005)
            time.sleep(grace_s)

        if dim == 3:
            call = self.control_stream3(session_id, poses(), token)
        else:
            call = self.control_stream(session_id, poses(), token)
        out = []
        try:
            for r in call:
                seqs["used"] = max(seqs["used"], r.pose_seq)
                out.append(r)
                if r.faulted:
                    # The session's last tick: its force is zero and it steps no more.
                    raise SessionFaultedError(
                        f"session {session_id} faulted at tick {r.tick} (t {r.time_s:.3f} s): {r.fault}; "
                        "its force is zero and it steps no more (close it and start a new one)",
                        out,
                    )
        except grpc.RpcError as e:
            if e.code() != grpc.StatusCode.CANCELLED:
                raise
        finally:
            stop.set()
            call.cancel()
        return out

    def watch(
        self,
        session_id: str,
        observer_token: Optional[str] = None,
        rate_hz: float = 30.0,
        n_frames: Optional[int] = None,
        duration_s: Optional[float] = None,
        include_displacements: bool = False,
    ) -> Iterator[object]:
        """Yields the Frames of a live session at rate_hz (30..120, or 0 for every tick) until
        n_frames frames have arrived or duration_s has passed (whichever comes first). A 3D
        session's frames carry d3 (pose, force, torque, tip, contacts, target spheres) and, with
        include_displacements, surface_displacement_m (in the order of surface().node_ids)."""
        req = pb.ObserveRequest(session_id=session_id, rate_hz=rate_hz, include_displacements=include_displacements)
        call = self.observe.Observe(req, metadata=self._md(session_id, "observer", observer_token), timeout=duration_s)
        n = 0
        try:
            for frame in call:
                yield frame
                n += 1
                if n_frames is not None and n >= n_frames:
                    break
        except grpc.RpcError as e:
            if not (duration_s is not None and e.code() == grpc.StatusCode.DEADLINE_EXCEEDED):
                raise
        finally:
            call.cancel()

    # -- offline simulation -----------------------------------------------------------------

    def simulate(
        self,
        scene,
        trajectory: Sequence[tuple[float, float, float, float]] = (),
        decimate: int = 1,
        on_progress: Optional[Callable[[int, int], None]] = None,
        timeout: Optional[float] = 600.0,
    ):
        """Runs an offline insertion (faster than real time on the server's workers).

        scene: an UploadedScene, a SceneSource or a shipped example's name. trajectory:
        [(t_s, x_m, y_m, theta_rad), ...] of the needle base, or for a 3D scene
        [(t_s, x_m, y_m, z_m, qw, qx, qy, qz), ...] (an (N, 4) or (N, 8) NumPy array works; rows
        then carry d3); empty: the example's own. Calls
        on_progress(ticks_done, ticks_total) as progress arrives; returns the SimulateResult
        (.rows: one SeriesRow every `decimate` ticks, gathered from the `series` chunks the
        server streams before the result)."""
        samples = []
        for row in trajectory:
            row = [float(v) for v in row]
            if len(row) == 8:
                samples.append(pb.TrajectorySample(t_s=row[0], base3=pose3(row[1:4], row[4:8])))
            elif len(row) == 4:
                samples.append(pb.TrajectorySample(t_s=row[0], base=pb.Pose2(x_m=row[1], y_m=row[2], theta_rad=row[3])))
            else:
                raise ValueError(f"trajectory row {len(samples)}: {len(row)} values; 4 (t_s, x_m, y_m, theta_rad) or 8 (t_s, x_m, y_m, z_m, qw, qx, qy, qz)")
        req = pb.SimulateRequest(scene=_scene_source(scene), trajectory=samples, decimate=decimate)
        result = None
        rows = []
        for ev in self.simulation.Simulate(req, timeout=timeout):
            kind = ev.WhichOneof("event")
            if kind == "progress" and on_progress is not None:
                on_progress(ev.progress.ticks_done, ev.progress.ticks_total)
            elif kind == "series":
                rows.extend(ev.series.rows)
            elif kind == "result":
                result = ev.result
        if result is None:
            raise RuntimeError("the Simulate stream ended without a result")
        rows.extend(result.rows)
        del result.rows[:]
        result.rows.extend(rows)
        return result

    # -- recordings -------------------------------------------------------------------------

    def start_recording(self, session_id: str, token: Optional[str] = None):
        return self.recordings.StartRecording(pb.StartRecordingRequest(session_id=session_id), metadata=self._md(session_id, "controller", token), timeout=10)

    def stop_recording(self, session_id: str, token: Optional[str] = None):
        """Finishes the recording of a session; returns its RecordingInfo (name, messages, ...)."""
        return self.recordings.StopRecording(pb.StopRecordingRequest(session_id=session_id), metadata=self._md(session_id, "controller", token), timeout=60)

    def list_recordings(self, session_id: str, token: Optional[str] = None):
        """The recordings of a session (which may have closed since): its observer or controller
        token, or `token` (the server's admin token lists them all)."""
        md = self._md(session_id, "observer", token)
        return list(self.recordings.ListRecordings(pb.ListRecordingsRequest(), metadata=md, timeout=10).recordings)

    def download_recording(self, name: str, path: str, session_id: str, token: Optional[str] = None) -> int:
        """Downloads the MCAP file `name` of session `session_id` into path (with that session's
        observer or controller token, or `token`); returns its size in bytes."""
        md = self._md(session_id, "observer", token)
        size = 0
        with open(path, "wb") as f:
            for chunk in self.recordings.DownloadRecording(pb.DownloadRecordingRequest(name=name), metadata=md, timeout=120):
                if chunk.offset != size:
                    raise RuntimeError(f"recording chunk at offset {chunk.offset}, expected {size}")
                f.write(chunk.data)
                size += len(chunk.data)
        return size

    # -- health and reflection --------------------------------------------------------------

    def health(self, service: str = "") -> str:
        """The grpc.health.v1 status of `service` ("" = the whole server): "SERVING",
        "NOT_SERVING", ..., or "NOT_FOUND" when the server does not know the service."""
        from grpc_health.v1 import health_pb2, health_pb2_grpc

        stub = health_pb2_grpc.HealthStub(self.channel)
        try:
            r = stub.Check(health_pb2.HealthCheckRequest(service=service), timeout=10)
        except grpc.RpcError as e:
            if e.code() == grpc.StatusCode.NOT_FOUND:
                return "NOT_FOUND"
            raise
        return health_pb2.HealthCheckResponse.ServingStatus.Name(r.status)

    def list_services(self) -> list[str]:
        """The services the server lists through gRPC server reflection (grpc.reflection.v1,
        falling back to v1alpha). The v1 and v1alpha messages are identical on the wire, so the
        v1alpha message classes of grpcio-reflection serve both."""
        from grpc_reflection.v1alpha import reflection_pb2 as rpb

        last = None
        for version in ("v1", "v1alpha"):
            method = self.channel.stream_stream(
                f"/grpc.reflection.{version}.ServerReflection/ServerReflectionInfo",
                request_serializer=rpb.ServerReflectionRequest.SerializeToString,
                response_deserializer=rpb.ServerReflectionResponse.FromString,
            )
            try:
                for resp in method(iter([rpb.ServerReflectionRequest(list_services="")]), timeout=10):
                    if resp.HasField("error_response"):
                        raise RuntimeError(f"reflection error {resp.error_response.error_code}: {resp.error_response.error_message}")
                    return sorted(s.name for s in resp.list_services_response.service)
            except grpc.RpcError as e:
                if e.code() != grpc.StatusCode.UNIMPLEMENTED:
                    raise
                last = e
        raise RuntimeError(f"the server has no reflection service: {last}")


def _scene_source(scene):
    if isinstance(scene, str):
        return pb.SceneSource(example=scene)
    if isinstance(scene, pb.UploadedScene):
        return pb.SceneSource(uploaded=scene)
    if isinstance(scene, pb.UploadedScene3d):
        return pb.SceneSource(uploaded3d=scene)
    return scene


# -- 3D poses and trajectories ------------------------------------------------------------------

HEADERS = {2: "t_s,x_m,y_m,theta_rad", 3: "t_s,x_m,y_m,z_m,qw,qx,qy,qz"}


def pose3(position_m: Sequence[float], quat_wxyz: Sequence[float]):
    """A needlesim.v1.Pose3 from a position (m) and a unit quaternion (w, x, y, z)."""
    x, y, z = (float(v) for v in position_m)
    w, qx, qy, qz = (float(v) for v in quat_wxyz)
    return pb.Pose3(position_m=pb.Vec3(x=x, y=y, z=z), orientation=pb.Quaternion(w=w, x=qx, y=qy, z=qz))


def _slerp(a: Sequence[float], b: Sequence[float], w: float) -> list[float]:
    """Spherical interpolation of unit quaternions (the shorter arc), as the server's trajectories."""
    dot = sum(x * y for x, y in zip(a, b))
    if dot < 0.0:
        b, dot = [-v for v in b], -dot
    if dot > 0.9995:
        q = [x + w * (y - x) for x, y in zip(a, b)]
    else:
        th = math.acos(min(1.0, dot))
        sa, sb = math.sin((1.0 - w) * th) / math.sin(th), math.sin(w * th) / math.sin(th)
        q = [sa * x + sb * y for x, y in zip(a, b)]
    n = math.sqrt(sum(v * v for v in q))
    return [v / n for v in q]


class Trajectory:
    """A base trajectory: rows (t_s, x_m, y_m, theta_rad) in 2D or (t_s, x_m, y_m, z_m, qw, qx,
    qy, qz) in 3D, times strictly increasing, values finite, quaternions of unit norm (within
    1e-6, then normalised). pose_at(t) interpolates (linear; slerp for the orientation) and holds
    the ends. Bad rows raise ValueError naming the row (`line` for rows read from a file)."""

    def __init__(self, rows, lines: Optional[Sequence[int]] = None):
        rows = [[float(v) for v in r] for r in rows]
        where = (lambda k: f"line {lines[k]}") if lines is not None else (lambda k: f"row {k}")
        if not rows:
            raise ValueError("the trajectory has no samples")
        width = len(rows[0])
        if width not in (4, 8):
            raise ValueError(f"{where(0)}: {width} values; a trajectory row has 4 ({HEADERS[2]}) or 8 ({HEADERS[3]})")
        self.dimension = 2 if width == 4 else 3
        for k, r in enumerate(rows):
            if len(r) != width:
                raise ValueError(f"{where(k)}: {len(r)} values, expected {width} ({HEADERS[self.dimension]})")
            if not all(math.isfinite(v) for v in r):
                raise ValueError(f"{where(k)}: a value is not a finite number: {r}")
            if k > 0 and not r[0] > rows[k - 1][0]:
                raise ValueError(f"{where(k)}: t_s = {r[0]} does not increase (previous {rows[k - 1][0]})")
            if self.dimension == 3:
                n = math.sqrt(sum(v * v for v in r[4:8]))
                if abs(n - 1.0) > 1e-6:
                    raise ValueError(f"{where(k)}: the quaternion qw,qx,qy,qz must have unit norm (its norm is {n})")
                r[4:8] = [v / n for v in r[4:8]]
        self.rows = rows

    def span_s(self) -> tuple[float, float]:
        return self.rows[0][0], self.rows[-1][0]

    def pose_at(self, t_s: float):
        """(x, y, theta) in 2D; (position, quaternion) in 3D."""
        rows = self.rows
        if t_s <= rows[0][0]:
            a = b = rows[0]
            w = 0.0
        elif t_s >= rows[-1][0]:
            a = b = rows[-1]
            w = 0.0
        else:
            import bisect

            k = bisect.bisect_right([r[0] for r in rows], t_s)
            a, b = rows[k - 1], rows[k]
            w = (t_s - a[0]) / (b[0] - a[0])
        if self.dimension == 2:
            return tuple(a[i] + w * (b[i] - a[i]) for i in (1, 2, 3))
        p = [a[i] + w * (b[i] - a[i]) for i in (1, 2, 3)]
        return p, _slerp(a[4:8], b[4:8], w)


def read_trajectory_csv(path) -> Trajectory:
    """Reads a trajectory CSV: the header (t_s,x_m,y_m,theta_rad or t_s,x_m,y_m,z_m,qw,qx,qy,qz)
    decides the dimension; `#` lines and blank lines are skipped; errors name the file and line."""
    rows, lines, header = [], [], None
    # Read whole, by the rule for local files (bounded; no FIFO, device or link).
    for n, line in enumerate(read_local_text(path).split("\n"), start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        cells = [c.strip() for c in text.split(",")]
        if header is None:
            header = ",".join(cells)
            if header not in (HEADERS[2], HEADERS[3]):
                raise ValueError(f"{path}: line {n}: the header must be {HEADERS[2]} (2D) or {HEADERS[3]} (3D), found another header of {len(cells)} columns")
            width = len(cells)
            continue
        if len(cells) != width:
            raise ValueError(f"{path}: line {n}: {len(cells)} fields, expected {width} ({header})")
        try:
            rows.append([float(c) for c in cells])
        except ValueError:
            bad = next(c for c in cells if not _is_float(c))
            raise ValueError(f"{path}: line {n}: `{bad[:32]}` is not a number") from None
        lines.append(n)
    if header is None:
        raise ValueError(f"{path}: empty: no header")
    try:
        return Trajectory(rows, lines)
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None


def _is_float(c: str) -> bool:
    try:
        float(c)
        return True
    except ValueError:
        return False


# -- the demo -----------------------------------------------------------------------------------


def grid_mesh(width_m: float = 0.1, height_m: float = 0.06, nx: int = 21, ny: int = 13):
    """A structured triangle mesh of [0, width] x [0, height]: nx * ny nodes (row-major from the
    bottom-left), two triangles per cell. Returns (nodes, triangles, bottom_nodes)."""
    nodes = [(width_m * i / (nx - 1), height_m * j / (ny - 1)) for j in range(ny) for i in range(nx)]
    tris = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a, b, c, d = j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i
            tris += [(a, b, c), (a, c, d)]
    return nodes, tris, list(range(nx))


DOWN = -math.pi / 2


def demo(client: NeedlesimClient) -> int:
    nodes, tris, bottom = grid_mesh()
    regions = [{"name": "tissue", "young_modulus_pa": 20e3, "poisson_ratio": 0.45}]
    length = 0.05
    # The needle points down; its tip starts 5 mm above the top surface (y = 0.06 m).
    x0, tip0 = 0.05, 0.065
    needle = {"base": (x0, tip0 + length, DOWN), "length_m": length}
    targets = [{"name": "lesion", "center": (0.05, 0.03), "radius_m": 0.003}]
    s = client.create_session_from_mesh(nodes, tris, regions, bottom, needle, targets, name="demo-grid")
    print(f"session created: {s.session_id} ({s.info.n_nodes} nodes, {s.info.n_triangles} triangles, {s.info.tick_rate_hz:g} Hz)", flush=True)

    # Offline: a straight insertion of the tip from 5 mm above the surface to 32 mm deep in 2 s.
    scene = client.uploaded_scene(nodes, tris, regions, bottom, needle, targets, name="demo-grid")
    depth, secs = 0.037, 2.0
    traj = [(t, x0, tip0 + length - depth * t / secs, DOWN) for t in (secs * k / 20 for k in range(21))]

    def progress(done, total):
        print(f"simulate progress: {done}/{total}", flush=True)

    t = time.monotonic()
    result = client.simulate(scene, traj, decimate=10, on_progress=progress)
    first, last = result.rows[0], result.rows[-1]
    print(f"simulate result: {len(result.rows)} rows, {result.ticks} ticks in {time.monotonic() - t:.2f} s (step p50 {result.step_p50_us:.0f} us)")
    print(f"tip: ({last.tip_m.x:.4f}, {last.tip_m.y:.4f}) m, inserted {last.inserted_length_m * 1e3:.1f} mm, axial force {last.force_axial_n:.3f} N")
    for t0, t1 in zip(first.targets, last.targets):
        print(f"tip-target distance: {t1.name} start {t0.distance_m:.6f} m end {t1.distance_m:.6f} m hit {t1.hit}")

    # Live: watch the session for 1 s at 30 Hz.
    frames = list(client.watch(s.session_id, rate_hz=30.0, duration_s=1.0))
    ticks = [f.tick for f in frames]
    span = f"ticks {ticks[0]}..{ticks[-1]}" if ticks else "no ticks"
    print(f"watched: {len(frames)} frames in 1 s at 30 Hz ({span})", flush=True)

    client.close_session(s.session_id)
    print(f"session closed: {s.session_id}", flush=True)
    return 0


# The cube's needle points straight down: a quarter turn about +y takes the body's +x to -z.
DOWN3 = (math.sqrt(0.5), 0.0, math.sqrt(0.5), 0.0)

LOG_HEADER3 = "tick,t_s,x_m,y_m,z_m,qw,qx,qy,qz,fx_n,fy_n,fz_n,torque_x_nm,torque_y_nm,torque_z_nm,f_axial_n,inserted_m,n_points,pose_seq"


def log_row3(r) -> str:
    """A ControlResponse of a 3D session as a CSV row (LOG_HEADER3; repr: exact round trip)."""
    d = r.d3
    p, q, f, m = d.base.position_m, d.base.orientation, d.force_n, d.torque_nm
    vals = [r.tick, r.time_s, p.x, p.y, p.z, q.w, q.x, q.y, q.z, f.x, f.y, f.z, m.x, m.y, m.z, d.axial_force_n, r.inserted_length_m, len(d.contacts), r.pose_seq]
    return ",".join(repr(v) for v in vals)


def demo3d(client: NeedlesimClient, seconds: float = 1.5, log: Optional[str] = None, out: Optional[str] = None) -> int:
    """A 3D run: a session of the shipped cube (cube-phantom-3d), its surface, an insertion driven
    through Control3 from a NumPy trajectory while an observer watches frames with d3 (and the
    session records, with `out`), then the same applied poses offline through Simulate: the final
    forces agree when the session admitted every contact on time (column_deferrals = 0)."""
    import numpy as np

    s = client.create_session("cube-phantom-3d")
    info = s.info
    print(f"session created: {s.session_id} (3D: {info.n_nodes} nodes, {info.n_tetrahedra} tetrahedra, {info.tick_rate_hz:g} Hz, dimension {info.dimension})", flush=True)
    surface = client.surface(s.session_id)
    print(f"surface: {len(surface.node_ids)} nodes, {len(surface.triangles) // 3} triangles", flush=True)
    if out is not None:
        client.start_recording(s.session_id)

    frames = []

    def watcher():
        for f in client.watch(s.session_id, rate_hz=30.0, duration_s=seconds + 0.5):
            frames.append(f)

    th = threading.Thread(target=watcher, daemon=True)
    th.start()
    time.sleep(0.2)
    # The tip from 5 mm above the top face (z = 0.1 m) to 20 mm deep, straight down.
    traj = np.array([[0.0, 0.05, 0.05, 0.205, *DOWN3], [seconds, 0.05, 0.05, 0.18, *DOWN3]])
    responses = client.drive(s.session_id, traj)
    th.join()
    rec = client.stop_recording(s.session_id) if out is not None else None
    stats = client.stats(s.session_id)
    last = responses[-1].d3
    f, tip = last.force_n, last.tip_m
    print(
        f"drive3d: {len(responses)} responses, final depth {responses[-1].inserted_length_m * 1e3:.3f} mm, "
        f"tip ({tip.x * 1e3:.3f}, {tip.y * 1e3:.3f}, {tip.z * 1e3:.3f}) mm, contacts {len(last.contacts)}, "
        f"final force ({f.x:.6f}, {f.y:.6f}, {f.z:.6f}) N, axial {last.axial_force_n:.6f} N",
        flush=True,
    )
    with_d3 = sum(1 for fr in frames if fr.HasField("d3"))
    targets = ", ".join(f"{t.name} {t.distance_m * 1e3:.3f} mm" for t in frames[-1].d3.targets) if frames else "-"
    print(f"watched3d: {len(frames)} frames, {with_d3} with d3; targets {targets}", flush=True)
    if log is not None:
        with open(log, "w", encoding="utf-8") as fh:
            fh.write(LOG_HEADER3 + "\n")
            for r in responses:
                fh.write(log_row3(r) + "\n")

    # The poses the ticks applied, one per tick from the first response (a gap ends the span),
    # offline through Simulate: the same step function, so the same forces.
    n = next((k + 1 for k in range(len(responses) - 1) if responses[k + 1].tick != responses[k].tick + 1), len(responses))
    rate = info.tick_rate_hz
    rows = []
    for j, r in enumerate(responses[:n]):
        b = r.d3.base
        rows.append((j / rate, b.position_m.x, b.position_m.y, b.position_m.z, b.orientation.w, b.orientation.x, b.orientation.y, b.orientation.z))
    result = client.simulate("cube-phantom-3d", np.array(rows))
    sim_f = np.array([[row.d3.force_n.x, row.d3.force_n.y, row.d3.force_n.z] for row in result.rows])
    live_f = np.array([[r.d3.force_n.x, r.d3.force_n.y, r.d3.force_n.z] for r in responses[:n]])
    peak = float(np.abs(sim_f).max()) if len(sim_f) else 0.0
    worst = float(np.abs(sim_f - live_f).max()) if len(sim_f) == len(live_f) else float("inf")
    print(
        f"simulate3d: {len(result.rows)} rows of {n} compared ticks, worst force difference {worst:.3e} N, peak {peak:.6f} N, "
        f"final fz session {live_f[-1][2]:.9f} N simulate {sim_f[-1][2]:.9f} N, column_deferrals {stats.column_deferrals}",
        flush=True,
    )
    if rec is not None:
        size = client.download_recording(rec.name, out, s.session_id)
        print(f"recording3d: {rec.name}, {rec.messages} messages, {size} bytes to {out}", flush=True)
    client.close_session(s.session_id)
    print(f"session closed: {s.session_id}", flush=True)
    return 0


def record(client: NeedlesimClient, seconds: float, out: str) -> int:
    """Records a session driven by SetPose for `seconds`, downloads the MCAP file into `out` and
    prints a JSON summary."""
    nodes, tris, bottom = grid_mesh()
    regions = [{"name": "tissue", "young_modulus_pa": 20e3, "poisson_ratio": 0.45}]
    length = 0.05
    needle = {"base": (0.05, 0.065 + length, DOWN), "length_m": length}
    s = client.create_session_from_mesh(nodes, tris, regions, bottom, needle, [], name="record-grid", record=True, tick_rate_hz=1000.0)
    t0 = time.monotonic()
    n_poses = 0
    while (t := time.monotonic() - t0) < seconds:
        client.set_pose(s.session_id, 0.05, 0.065 + length - 0.02 * t / seconds, DOWN)
        n_poses += 1
        time.sleep(0.005)
    info = client.stop_recording(s.session_id)
    stats = client.stats(s.session_id)
    size = client.download_recording(info.name, out, s.session_id)
    client.close_session(s.session_id)
    print(
        json.dumps(
            {
                "name": info.name,
                "messages": info.messages,
                "size_bytes": info.size_bytes,
                "finished": info.finished,
                "downloaded_bytes": size,
                "poses": n_poses,
                "ticks": stats.ticks,
                "dropped_records": stats.dropped_records,
            }
        ),
        flush=True,
    )
    return 0


def hold(client: NeedlesimClient, session_id: str, token: str) -> int:
    """Opens a full-rate Observe stream and a Control stream and keeps them open (until killed),
    printing `holding` once both deliver."""
    client.add_tokens(session_id, controller_token=token)
    stop = threading.Event()

    def poses():
        while not stop.is_set():
            yield (0.05, 0.115, DOWN)
            time.sleep(0.001)

    ctl = client.control_stream(session_id, poses())
    obs = client.observe.Observe(pb.ObserveRequest(session_id=session_id, rate_hz=0.0), metadata=client._md(session_id, "observer"))
    counts = {"frames": 0, "responses": 0}

    def drain(it, key):
        for _ in it:
            counts[key] += 1

    threads = [threading.Thread(target=drain, args=(ctl, "responses"), daemon=True), threading.Thread(target=drain, args=(obs, "frames"), daemon=True)]
    for th in threads:
        th.start()
    deadline = time.monotonic() + 30.0
    while counts["frames"] == 0 or counts["responses"] == 0:
        if time.monotonic() > deadline:
            print(f"no frames or responses within 30 s: {counts}", file=sys.stderr, flush=True)
            return 1
        time.sleep(0.01)
    print(f"holding: {counts['frames']} frames, {counts['responses']} responses", flush=True)
    while True:
        time.sleep(1)


def main(argv: Optional[Sequence[str]] = None) -> int:
    p = argparse.ArgumentParser(description="needlesim gRPC client")
    p.add_argument("--address", default="127.0.0.1:50051", help="host:port of the server")
    p.add_argument("--root-cert", help="PEM file of the CA of the server's certificate (enables TLS)")
    p.add_argument("--stubs", help="directory of the generated stubs (generated there if missing)")
    sub = p.add_subparsers(dest="command", required=True)
    sub.add_parser("demo", help="upload a grid mesh, simulate an insertion offline, watch the live session")
    d3 = sub.add_parser("demo3d", help="a 3D run: drive the cube phantom through Control3, watch, compare with Simulate")
    d3.add_argument("--seconds", type=float, default=1.5, help="the insertion's duration")
    d3.add_argument("--log", help="write every control response (the applied pose and the forces) as CSV")
    d3.add_argument("--out", help="record the session and download the MCAP file here")
    h = sub.add_parser("health", help="grpc.health.v1 status of a service ('' = the server)")
    h.add_argument("service", nargs="?", default="")
    sub.add_parser("services", help="the services listed by server reflection")
    r = sub.add_parser("record", help="record a session driven by SetPose and download the MCAP file")
    r.add_argument("--seconds", type=float, default=2.0)
    r.add_argument("--out", required=True)
    k = sub.add_parser("hold", help="keep a full-rate Observe and a Control stream open until killed")
    k.add_argument("--session", required=True)
    k.add_argument("--token", required=True, help="the controller token")
    args = p.parse_args(argv)

    load_stubs(args.stubs)
    with NeedlesimClient(args.address, root_cert=args.root_cert) as client:
        if args.command == "demo":
            return demo(client)
        if args.command == "demo3d":
            return demo3d(client, args.seconds, args.log, args.out)
        if args.command == "health":
            print(client.health(args.service))
            return 0
        if args.command == "services":
            for name in client.list_services():
                print(name)
            return 0
        if args.command == "record":
            return record(client, args.seconds, args.out)
        if args.command == "hold":
            return hold(client, args.session, args.token)
    return 2


if __name__ == "__main__":
    sys.exit(main())
