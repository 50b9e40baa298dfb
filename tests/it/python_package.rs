//! The Python package `needlesim` (client/pyneedlesim: PyO3, built by maturin and installed into
//! the test venv by tests/run) through its pytest suite, client/pyneedlesim/tests: stepping and
//! `Simulation.run` from Python against the real `needlesim-server simulate` binary's CSV to
//! 1e-12, the typed exceptions and their messages, 3D stepping on the shipped cube, `help()`;
//! planning under tissue uncertainty (test_robust.py): the planner from Python, scaled scenes,
//! a sweep on a Dask LocalCluster of 2 worker processes equal to the serial one bit for bit,
//! and the robust-planning example writing its PNG.

use std::process::Command;

use needlesim_tests::{TempDir, bin, python, repo_root, run, text};

#[test]
fn the_python_packages_pytest_suite_passes_against_the_simulate_binary() {
    let py = python();
    let probe = run(Command::new(&py).args(["-c", "import needlesim, pytest; print(needlesim.__file__)"]));
    let (o, e) = text(&probe);
    assert!(
        probe.status.success(),
        "the needlesim package or pytest is not installed in {} (tests/run builds the wheel with maturin and installs it):\n{o}\n{e}",
        py.display()
    );
    let dir = TempDir::new("pytest");
    let out = run(Command::new(&py)
        .args(["-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", "--basetemp"])
        .arg(dir.path())
        .arg(repo_root().join("client/pyneedlesim/tests"))
        .env("NEEDLESIM_SERVER", bin("needlesim-server"))
        .env("PYTHONDONTWRITEBYTECODE", "1"));
    let (o, e) = text(&out);
    assert!(out.status.success(), "the pytest suite of client/pyneedlesim failed ({}):\n{o}\n{e}", out.status);
    assert!(o.contains(" passed") && !o.contains("skipped"), "{o}");
}
