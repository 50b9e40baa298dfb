"""The Python package `needlesim` against the Rust binary: stepping from Python and
`Simulation.run` give the numbers of `needlesim-server simulate` (its CSV, to 1e-12), the
errors raise the right exception classes with the Rust messages, the 3D simulation steps the
shipped cube, `help()` shows the documentation, and a dumped state re-solves to the
simulation's own field.

Run by tests/it/python_package.rs (cargo test -p needlesim-tests --test it python_package::),
which sets NEEDLESIM_SERVER to the needlesim-server binary; by hand:
    NEEDLESIM_SERVER=target/debug/needlesim-server tests/.venv/bin/python -m pytest client/pyneedlesim/tests
"""

import os
import pydoc
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import needlesim

# Relative tolerance of Python against the binary: the same code on the same machine, so the
# numbers agree to round-off of the CSV's shortest round-trip printing (exact in practice).
TOL = 1e-12


def server():
    path = os.environ.get("NEEDLESIM_SERVER")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("NEEDLESIM_SERVER must name the needlesim-server binary (tests/it/python_package.rs sets it)")
    return path


def simulate_cli(tmp_path, scene, trajectory=None):
    """Runs `needlesim-server simulate` and returns its CSV as {column: array}."""
    out = tmp_path / "cli.csv"
    cmd = [server(), "simulate", "--scene", scene, "-o", str(out)]
    if trajectory is not None:
        cmd += ["--trajectory", str(trajectory)]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    header = out.read_text().splitlines()[0].split(",")
    data = np.loadtxt(out, delimiter=",", skiprows=1, ndmin=2)
    return {h: data[:, i] for i, h in enumerate(header)}


def cli_error(args):
    p = subprocess.run([server(), *args], capture_output=True, text=True, timeout=600)
    assert p.returncode != 0, p.stdout
    return p.stderr


def assert_close(name, ours, theirs, tol=TOL):
    ours = np.asarray(ours, dtype=float)
    theirs = np.asarray(theirs, dtype=float)
    assert ours.shape == theirs.shape, f"{name}: shape {ours.shape} against {theirs.shape}"
    err = np.abs(ours - theirs) / np.maximum(1.0, np.abs(theirs))
    k = int(np.argmax(err)) if err.size else 0
    assert err.size == 0 or err.max() <= tol, f"{name}: row {k}: {ours.flat[k]!r} against {theirs.flat[k]!r}"


def columns_2d(rows, target_names):
    """The CSV's columns from a list of StepResults."""
    c = {
        "x_m": [r.pose[0] for r in rows],
        "y_m": [r.pose[1] for r in rows],
        "theta_rad": [r.pose[2] for r in rows],
        "fx_n": [r.force_n[0] for r in rows],
        "fy_n": [r.force_n[1] for r in rows],
        "torque_nm": [r.torque_nm[0] for r in rows],
        "f_axial_n": [r.force_axial_n for r in rows],
        "f_lateral_n": [r.force_lateral_n for r in rows],
        "tip_x_m": [r.tip_m[0] for r in rows],
        "tip_y_m": [r.tip_m[1] for r in rows],
        "inserted_m": [r.inserted_length_m for r in rows],
        "n_stuck": [r.n_stuck for r in rows],
        "n_slipping": [r.n_slipping for r in rows],
        "n_tip": [r.n_tip for r in rows],
    }
    for j, n in enumerate(target_names):
        c[f"target_{n}_distance_m"] = [r.target_distances_m[j] for r in rows]
        c[f"target_{n}_x_m"] = [r.target_positions_m[j, 0] for r in rows]
        c[f"target_{n}_y_m"] = [r.target_positions_m[j, 1] for r in rows]
        c[f"target_{n}_hit"] = [float(r.target_hits[j]) for r in rows]
    return c


def run_columns_2d(run, target_names):
    c = {
        "x_m": run.pose[:, 0],
        "y_m": run.pose[:, 1],
        "theta_rad": run.pose[:, 2],
        "fx_n": run.force_n[:, 0],
        "fy_n": run.force_n[:, 1],
        "torque_nm": run.torque_nm[:, 0],
        "f_axial_n": run.force_axial_n,
        "f_lateral_n": run.force_lateral_n,
        "tip_x_m": run.tip_m[:, 0],
        "tip_y_m": run.tip_m[:, 1],
        "inserted_m": run.inserted_length_m,
        "n_stuck": run.contact_counts[:, 0],
        "n_slipping": run.contact_counts[:, 1],
        "n_tip": run.contact_counts[:, 2],
    }
    for j, n in enumerate(target_names):
        c[f"target_{n}_distance_m"] = run.target_distances_m[:, j]
        c[f"target_{n}_x_m"] = run.target_positions_m[:, j, 0]
        c[f"target_{n}_y_m"] = run.target_positions_m[:, j, 1]
        c[f"target_{n}_hit"] = run.target_hits[:, j].astype(float)
    return c


def oblique_trajectory(path):
    """An oblique insertion into the paper phantom that turns the needle while it is in the
    tissue, then withdraws it: stick, slip, puncture, rotation and release."""
    path.write_text(
        "t_s,x_m,y_m,theta_rad\n"
        "0,0.03,0.205,-1.3\n"
        "3,0.045,0.13,-1.3\n"
        "4,0.045,0.13,-1.4\n"
        "5,0.045,0.125,-1.4\n"
        "7,0.035,0.2,-1.35\n"
    )
    return path


@pytest.mark.parametrize("scene_name,custom", [("fig3-target", False), ("paper-phantom", True)])
def test_stepping_and_run_equal_the_simulate_command(tmp_path, scene_name, custom):
    traj = oblique_trajectory(tmp_path / "oblique.csv") if custom else None
    cli = simulate_cli(tmp_path, scene_name, traj)
    scene = needlesim.load_scene(scene_name)
    names = [t.name for t in scene.targets]
    assert names, "the scene has targets, so their columns are compared too"

    t_s, poses = needlesim.tick_poses(scene, traj)
    assert poses.shape == (len(cli["t_s"]), 3)
    assert_close("t_s", t_s, cli["t_s"], tol=1e-6)  # the CSV prints t_s with 6 decimals
    sim = needlesim.Simulation(scene, initial_pose=poses[0])
    rows = [sim.step(p) for p in poses]
    assert [r.tick for r in rows] == list(range(len(rows)))
    stepped = columns_2d(rows, names)
    for name, values in stepped.items():
        assert_close(f"step {name}", values, cli[name])

    reports = []
    run = needlesim.Simulation(scene).run(traj, progress=lambda done, total: reports.append((done, total)), progress_every=1000)
    assert run.ticks == len(cli["t_s"]) and not run.stopped_early
    assert_close("run t_s", run.t_s, cli["t_s"], tol=1e-6)
    for name, values in run_columns_2d(run, names).items():
        assert_close(f"run {name}", values, cli[name])
        # run() and the Python loop run the same code: identical, not merely close.
        assert np.array_equal(np.asarray(values, dtype=float), np.asarray(stepped[name], dtype=float)), name
    total = len(cli["t_s"])
    assert reports == [(k, total) for k in range(1000, total + 1, 1000)] + ([(total, total)] if total % 1000 else [])
    # The motion is not trivial: the needle went in, held contacts and felt force.
    assert cli["inserted_m"].max() > 0.02 and np.abs(cli["fy_n"]).max() > 0.05


def test_run_leaves_the_final_state_and_dump_state_resolves_to_the_simulations_field():
    scene = needlesim.load_scene("paper-phantom")
    t_s, poses = needlesim.tick_poses(scene)
    half = poses[: len(poses) // 2 + 1]  # stop mid-insertion, contacts in place
    sim = needlesim.Simulation(scene)
    run = sim.run(np.column_stack([t_s[: len(half)], half]))
    assert run.ticks == len(half)
    assert sim.last.tick == len(half) - 1
    np.testing.assert_array_equal(sim.last.force_n, run.force_n[-1])
    state = sim.dump_state()
    assert state["needle_nodes"], "contacts in the dumped state"
    result = needlesim.solve(state)
    ours = np.asarray(state["solver_displacements"])
    theirs = np.asarray(result["displacements"])
    rel = np.linalg.norm(ours - theirs) / np.linalg.norm(theirs)
    assert np.linalg.norm(theirs) > 1e-4 and rel < 1e-9, rel
    snap = sim.snapshot()
    assert len(snap["needle_states"]) == len(state["needle_nodes"])


def test_errors_raise_typed_exceptions_with_the_commands_messages(tmp_path):
    for cls in (needlesim.SceneError, needlesim.TrajectoryError, needlesim.PoseError, needlesim.SimulationError, needlesim.ScenarioError):
        assert issubclass(cls, needlesim.NeedlesimError)

    with pytest.raises(needlesim.SceneError, match="no-such-scene.toml' is neither a file nor a shipped example"):
        needlesim.load_scene(str(tmp_path / "no-such-scene.toml"))
    bad = tmp_path / "bad.toml"
    bad.write_text(needlesim_example_toml().replace("[needle]", "[needle]\nwobble = 3", 1))
    with pytest.raises(needlesim.SceneError) as e:
        needlesim.load_scene(bad)
    assert f"error: {e.value}" in cli_error(["simulate", "--scene", str(bad)]), "the message is the CLI's"

    scene = needlesim.load_scene("paper-phantom")
    sim = needlesim.Simulation(scene)
    before = sim.step(scene.initial_pose)
    for pose in [(np.nan, 0.2, -1.5), (0.05, np.inf, -1.5)]:
        with pytest.raises(needlesim.PoseError, match="is not finite"):
            sim.step(pose)
    with pytest.raises(needlesim.PoseError, match="3 numbers, not 2"):
        sim.step((0.05, 0.2))
    after = sim.step(scene.initial_pose)  # the refused poses changed nothing
    assert after.tick == before.tick + 1
    np.testing.assert_array_equal(after.tip_m, before.tip_m)

    backwards = np.array([[0.0, 0.05, 0.2, -1.5], [1.0, 0.05, 0.19, -1.5], [0.5, 0.05, 0.18, -1.5]])
    with pytest.raises(needlesim.TrajectoryError, match="line 4"):
        sim.run(backwards)
    with pytest.raises(needlesim.TrajectoryError, match="over the limit of 100 ticks"):
        sim.run(max_ticks=100)
    with pytest.raises(needlesim.TrajectoryError, match="shape"):
        sim.run(np.zeros((3, 3)))
    with pytest.raises(needlesim.TrajectoryError, match="cannot read"):
        sim.run(tmp_path / "missing.csv")
    with pytest.raises(needlesim.ScenarioError, match="is not a valid scenario"):
        needlesim.solve({"nodes": "nonsense"})

    class Stop(Exception):
        pass

    def stop_at_2000(done, total):
        if done >= 2000:
            raise Stop(done)

    with pytest.raises(Stop):
        sim.run(progress=stop_at_2000)
    assert sim.last.tick == 1999, "the simulation holds the state of the last tick run"


def test_issue_35_devices_fifos_and_links_are_refused_unread(tmp_path):
    # /dev/zero would be read without end, a FIFO would block: both are refused at once, as
    # scene, as mesh file, as trajectory and as scenario, naming the path and the problem.
    fifo = tmp_path / "pipe.toml"
    os.mkfifo(fifo)
    link = tmp_path / "link.toml"
    link.symlink_to("/dev/zero")
    for path, problem in [("/dev/zero", "not a regular file (a character device)"), (fifo, "not a regular file (a FIFO)"), (link, "is a symbolic link")]:
        with pytest.raises(needlesim.SceneError, match=re.escape(f"{path}: {problem}")):
            needlesim.load_scene(path)
        with pytest.raises(needlesim.SceneError, match=re.escape(f"{path}: {problem}")):
            needlesim.load_scene(path, scale={"young_modulus_pa": 2.0})
    with_mesh = tmp_path / "mesh.toml"
    grid = '[mesh]\ntype = "grid"\nnx = 19\nny = 19\nwidth_m = 0.1\nheight_m = 0.1\n'
    assert grid in needlesim_example_toml()
    with_mesh.write_text(needlesim_example_toml().replace(grid, '[mesh]\ntype = "msh"\nfile = "/dev/zero"\n'))
    with pytest.raises(needlesim.SceneError, match=re.escape('mesh.file = "/dev/zero"') + ".*not a regular file"):
        needlesim.load_scene(with_mesh)
    sim = needlesim.Simulation(needlesim.load_scene("paper-phantom"))
    with pytest.raises(needlesim.TrajectoryError, match="/dev/zero: not a regular file"):
        sim.run("/dev/zero")
    with pytest.raises(needlesim.ScenarioError, match="/dev/zero: not a regular file"):
        needlesim.solve("/dev/zero")


def needlesim_example_toml():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "..", "..", "..", "server", "scenes", "paper-phantom.toml")) as f:
        return f.read()


def test_3d_run_equals_the_simulate_command_and_misses_the_fig3_target(tmp_path):
    cli = simulate_cli(tmp_path, "fig3-target-3d")
    scene = needlesim.load_scene("fig3-target-3d")
    names = [t.name for t in scene.targets]
    assert names, "the 3D Fig. 3 scene has a target"
    run = needlesim.Simulation(scene).run()
    assert run.ticks == len(cli["t_s"]) and not run.stopped_early
    for c, axis in enumerate("xyz"):
        assert_close(f"f{axis}_n", run.force_n[:, c], cli[f"f{axis}_n"])
        assert_close(f"tip_{axis}_m", run.tip_m[:, c], cli[f"tip_{axis}_m"])
    for j, n in enumerate(names):
        assert_close(f"target {n} distance", run.target_distances_m[:, j], cli[f"target_{n}_distance_m"])
        for c, axis in enumerate("xyz"):
            assert_close(f"target {n} {axis}", run.target_positions_m[:, j, c], cli[f"target_{n}_{axis}_m"])
        assert_close(f"target {n} hit", run.target_hits[:, j].astype(float), cli[f"target_{n}_hit"])
        # Aimed straight at it, the needle misses: the tissue carried the target away.
        assert not run.target_hits[-1, j]
        assert run.target_distances_m[:, j].min() > scene.targets[j].radius_m


def test_3d_stepping_on_the_cube_force_grows_with_depth():
    scene = needlesim.load_scene("cube-phantom-3d")
    assert scene.dim == 3 and scene.nodes_m.shape[1] == 3 and scene.elements.shape[1] == 4
    t_s, poses = needlesim.tick_poses(scene)
    assert poses.shape[1] == 7
    n = 700  # 20 mm/s from 5 mm above the top face: 9 mm deep at the end
    sim = needlesim.Simulation(scene, initial_pose=poses[0])
    rows = [sim.step(p) for p in poses[:n]]
    depth = np.array([r.inserted_length_m for r in rows])
    axial = np.array([r.force_axial_n for r in rows])
    assert rows[-1].tick == n - 1
    assert depth[-1] > 0.005, depth[-1]
    inside = depth > 0.002
    assert inside.sum() > 100
    # The resistance grows as the needle goes deeper (friction over more shaft): compare the
    # mean axial force over successive thirds of the time inside.
    thirds = np.array_split(axial[inside], 3)
    means = [t.mean() for t in thirds]
    assert 0 < means[0] < means[1] < means[2], means
    assert rows[-1].force_n.shape == (3,) and rows[-1].torque_nm.shape == (3,)
    assert rows[-1].contact_positions_m.shape == (len(rows[-1].contact_states), 3)
    snap = sim.snapshot()
    assert snap["x_m"].shape[0] == len(rows[-1].contact_states)
    # The 3D dump re-solves to the simulation's own answer (its point reactions).
    state = sim.dump_state()
    assert state["dim"] == 3 and state["points"], "points in the dumped 3D state"
    result = needlesim.solve(state)
    ours = np.asarray([[p["rx"], p["ry"], p["rz"]] for p in state["simulation_result"]["point_reactions"]], dtype=float)
    theirs = np.asarray([[p["rx"], p["ry"], p["rz"]] for p in result["point_reactions"]], dtype=float)
    assert np.abs(theirs).max() > 1e-3
    assert np.abs(ours - theirs).max() <= 1e-8 * np.abs(theirs).max(), (ours, theirs)

    # run() over the same poses gives the same numbers.
    run = needlesim.Simulation(scene).run(np.column_stack([t_s[:n], poses[:n]]))
    np.testing.assert_array_equal(run.force_axial_n, axial)
    np.testing.assert_array_equal(run.inserted_length_m, depth)

    for pose, what in [
        ((0.05, 0.05, 0.2, 0.9, 0.0, 0.7071067811865475, 0.0), "norm"),
        ((0.05, np.nan, 0.2, 0.7071067811865475, 0.0, 0.7071067811865475, 0.0), "non-finite"),
        ((0.05, 0.05, 0.2), "7 numbers"),
    ]:
        with pytest.raises(needlesim.PoseError, match=what):
            sim.step(pose)


def test_help_shows_the_documentation():
    text = pydoc.render_doc(needlesim.Simulation, renderer=pydoc.plaintext)
    for expected in ["Simulation(scene, initial_pose=None)", "step(", "Raises PoseError", "run(", "progress", "dump_state", "snapshot"]:
        assert expected in text, expected
    assert "GIL" in needlesim.Simulation.run.__doc__
    assert "shipped example" in needlesim.load_scene.__doc__
    assert "exchange format" in needlesim.solve.__doc__
    assert "stuck" in needlesim.StepResult.contact_states.__doc__
    assert needlesim.CONTACT_STATES == ["stuck", "slipping", "tip"]


def test_issue_35_scene_errors_quote_no_line_and_proc_files_are_refused(tmp_path):
    # A scene's parse error quoted the line it failed on (the TOML parser's snippet), and
    # /proc/self/environ, a regular file of size 0, was parsed: its error printed the environment.
    # The error now names the file, line and column only; /proc and /sys files are refused unread,
    # as scene, as scaled scene and in the pure-Python client's copy of the rule.
    secret = "SECRET_sk_live_0123456789abcdef"
    bad = tmp_path / "secret.toml"
    bad.write_text(f'name = "x"\n{secret} = = broken\n')
    for kwargs in [{}, {"scale": {"young_modulus_pa": 2.0}}]:
        with pytest.raises(needlesim.SceneError) as e:
            needlesim.load_scene(bad, **kwargs)
        assert "TOML parse error at line 2, column " in str(e.value), str(e.value)
        assert secret not in str(e.value) and "broken" not in str(e.value), str(e.value)
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
    import needlesim_client as nc

    for path in ["/proc/self/environ", "/proc/self/pagemap", "/sys/kernel/mm/transparent_hugepage/enabled"]:
        if not os.path.lexists(path):
            continue
        for kwargs in [{}, {"scale": {"young_modulus_pa": 2.0}}]:
            with pytest.raises(needlesim.SceneError, match=re.escape(f"{path}: on the kernel's ")) as e:
                needlesim.load_scene(path, **kwargs)
            assert "PATH=" not in str(e.value) and "HOME=" not in str(e.value), str(e.value)
        with pytest.raises(ValueError, match=re.escape(f"{path}: on the kernel's ")):
            nc.read_local_file(path)
