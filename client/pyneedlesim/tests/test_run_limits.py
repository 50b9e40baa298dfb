"""Issue 35 item 8: the length of a scripted run asked from Python is bounded. A ``max_ticks``
over ``needlesim.MAX_TICKS_LIMIT`` is refused with an exception naming it (it aborted the
interpreter: "memory allocation of 8000000000000008 bytes failed"), and a trajectory longer than
``max_ticks`` names its last line and its tick count, in 2D and 3D.

Run by tests/it/python_package.rs with the rest of the suite.
"""

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import needlesim

DOWN = -1.57
QUAT_DOWN = (0.7071067811865476, 0.0, 0.7071067811865476, 0.0)


def run_python(code):
    """Runs `code` in a fresh interpreter: a crash there is a return code, not a lost test run."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=600)


def test_issue_35_a_huge_max_ticks_raises_instead_of_aborting_the_interpreter():
    out = run_python(
        """
        import numpy as np
        from needlesim import Simulation, load_scene, NeedlesimError
        try:
            Simulation(load_scene("paper-phantom")).run(
                np.array([[0, .05, .21, -1.57], [1e12, .05, .2, -1.57]]), max_ticks=10**16)
        except NeedlesimError as e:
            print(type(e).__name__, e)
        """
    )
    assert out.returncode == 0, f"the interpreter died ({out.returncode}): {out.stderr}"
    assert out.stdout.startswith("TrajectoryError max_ticks = 10000000000000000 is over the limit of "), out.stdout
    assert f"over the limit of {needlesim.MAX_TICKS_LIMIT} ticks" in out.stdout, out.stdout


def test_issue_35_max_ticks_is_checked_by_every_call_that_takes_it():
    scene = needlesim.load_scene("paper-phantom")
    short = np.array([[0.0, 0.05, 0.21, DOWN], [0.01, 0.05, 0.2, DOWN]])
    over = needlesim.MAX_TICKS_LIMIT + 1
    with pytest.raises(needlesim.TrajectoryError, match=f"max_ticks = {over} is over the limit"):
        needlesim.Simulation(scene).run(short, max_ticks=over)
    with pytest.raises(needlesim.TrajectoryError, match=f"max_ticks = {over} is over the limit"):
        needlesim.tick_poses(scene, short, max_ticks=over)
    # At the limit, a short run runs; a long trajectory is refused naming its last line.
    sim = needlesim.Simulation(scene)
    assert sim.run(short, max_ticks=needlesim.MAX_TICKS_LIMIT).ticks == 11
    long = np.array([[0.0, 0.05, 0.21, DOWN], [1e12, 0.05, 0.2, DOWN]])
    for call in (lambda: sim.run(long, max_ticks=needlesim.MAX_TICKS_LIMIT), lambda: needlesim.tick_poses(scene, long)):
        with pytest.raises(needlesim.TrajectoryError, match=r"line 3: t_s = 1e12 .* 1e15 ticks at 1000 Hz: over the limit of"):
            call()


def test_issue_35_a_3d_trajectory_over_the_limit_names_its_line_and_its_ticks():
    out = run_python(
        f"""
        import numpy as np
        from needlesim import Simulation, load_scene, tick_poses, NeedlesimError
        scene = load_scene("cube-phantom-3d")
        q = {QUAT_DOWN!r}
        long = np.array([[0, .05, .05, .11, *q], [1e17, .05, .05, .1, *q]])
        for call in (lambda: Simulation(scene).run(long, max_ticks=10**16),
                     lambda: Simulation(scene).run(long),
                     lambda: tick_poses(scene, long)):
            try:
                call()
                print("no error")
            except NeedlesimError as e:
                print(type(e).__name__, e)
        """
    )
    assert out.returncode == 0, f"the interpreter died ({out.returncode}): {out.stderr}"
    lines = out.stdout.splitlines()
    assert len(lines) == 3, out.stdout
    assert lines[0].startswith("TrajectoryError max_ticks = 10000000000000000 is over the limit"), lines[0]
    for line in lines[1:]:
        assert line.startswith("TrajectoryError trajectory line 3: t_s = 1e17 ends 1e17 s after the first sample, 1e20 ticks at 1000 Hz"), line
        assert f"over the limit of {needlesim.DEFAULT_MAX_TICKS} ticks" in line, line


def test_issue_35_a_max_ticks_no_u64_holds_raises_the_packages_error_naming_it():
    scene = needlesim.load_scene("paper-phantom")
    short = np.array([[0.0, 0.05, 0.21, DOWN], [0.01, 0.05, 0.2, DOWN]])
    for call in (lambda m: needlesim.Simulation(scene).run(short, max_ticks=m), lambda m: needlesim.tick_poses(scene, short, max_ticks=m)):
        with pytest.raises(needlesim.TrajectoryError, match=r"^max_ticks = -1 must be ≥ 0"):
            call(-1)
        with pytest.raises(needlesim.TrajectoryError, match=r"^max_ticks = 18446744073709551616 is over the limit of"):
            call(2**64)
        # A long int is quoted clipped; one past Python's 4300-digit str() limit is described.
        # (Made by arithmetic: int("1" * 5000) is itself refused by Python.)
        with pytest.raises(needlesim.TrajectoryError, match=r"^max_ticks = 1{64}… is over the limit of"):
            call(10**1000 // 9)
        with pytest.raises(needlesim.TrajectoryError, match=r"^max_ticks = an int of more than 4300 digits is over the limit of"):
            call(10**5000 // 9)
        # Not an int at all: Python's TypeError naming the argument, as before.
        with pytest.raises(TypeError, match="max_ticks"):
            call("ten")
    assert needlesim.Simulation(scene).run(short, max_ticks=11).ticks == 11


def test_issue_35_step_refuses_the_poses_run_refuses():
    sim = needlesim.Simulation(needlesim.load_scene("paper-phantom"))
    with pytest.raises(needlesim.TrajectoryError, match=r"x_m = 1e308 is out of range \(at most 1e3 in magnitude\)"):
        sim.run(np.array([[0.0, 1e308, 0.2, DOWN], [0.01, 0.05, 0.2, DOWN]]))
    for pose, name in (((1e308, 0.2, DOWN), "x_m = 1e308"), ((0.05, -1001.0, DOWN), "y_m = -1001"), ((0.05, 0.2, 2e3), "theta_rad = 2000")):
        with pytest.raises(needlesim.PoseError, match=f"{name} is out of range \\(at most 1e3 in magnitude"):
            sim.step(pose)
    # The refused poses left the state alone: the first step taken is tick 0.
    assert sim.step((0.05, 0.205, DOWN)).tick == 0
    sim.step((1e3, 0.205, DOWN))  # at the bound: accepted (clamped to the per-tick step)
    sim3 = needlesim.Simulation(needlesim.load_scene("cube-phantom-3d"))
    with pytest.raises(needlesim.PoseError, match=r"z_m = -1e300 is out of range"):
        sim3.step((0.05, 0.05, -1e300) + QUAT_DOWN)
