"""Shared fixtures: the repository's root, its examples and the CLI.

The tests that compare with the command line (the `cli` fixture) need the
`qdot` binary: $QDOT_BIN, or target/release/qdot. When it is missing, the
first such test builds it with `cargo build --release` (several minutes on
a fresh clone); the session says so before the tests start, and cargo's
progress is shown, not captured. Tests that do not use `cli` never build.
"""

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.qd"))

#: How long `cargo build --release` of the CLI takes from a fresh clone
#: (crates already downloaded), measured on 2026-11-28: 5 min of CPU time
#: (user + sys) on 2 cores, 23½ min of wall time while other builds loaded
#: them (load average 10–12); README.md says the same.
BUILD_TIME = "2–5 min on 2 idle cores, 20+ min on a loaded machine"


def qdot_bin() -> Path:
    """The CLI built by `cargo build --release` (or $QDOT_BIN)."""
    env = os.environ.get("QDOT_BIN")
    if env:
        return Path(env)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "qdot"


def _build_notice(path: Path) -> str:
    return (
        f"qdot: no CLI binary at {path}; the tests that compare with the command line "
        f"build it first with `cargo build --release` ({BUILD_TIME}). "
        "QDOT_BIN=/path/to/qdot uses a built one instead."
    )


def _say(config: pytest.Config, text: str) -> None:
    """A line on the terminal, even while pytest captures the output."""
    reporter = config.pluginmanager.getplugin("terminalreporter")
    capture = config.pluginmanager.getplugin("capturemanager")
    if reporter is None:
        sys.__stderr__.write(text + "\n")
        return
    if capture is None:
        reporter.write_line(text)
        return
    with capture.global_and_fixture_disabled():
        reporter.ensure_newline()
        reporter.write_line(text)


def pytest_collection_finish(session: pytest.Session) -> None:
    """Before the tests start: say that the CLI will be built, when a
    selected test needs it and it is missing."""
    path = qdot_bin()
    if path.exists() or not any("cli" in getattr(i, "fixturenames", ()) for i in session.items):
        return
    if os.environ.get("QDOT_BIN"):
        _say(session.config, f"qdot: QDOT_BIN={path}: no such file; the tests that compare "
                             "with the command line will fail")
    else:
        _say(session.config, _build_notice(path))


def _build(config: pytest.Config, path: Path) -> None:
    cargo = os.environ.get("CARGO", "cargo")
    _say(config, f"qdot: building the CLI: {cargo} build --release ({BUILD_TIME})")
    start = time.monotonic()
    capture = config.pluginmanager.getplugin("capturemanager")
    try:
        # cargo's progress goes to the terminal: a long build is seen working
        if capture is not None:
            with capture.global_and_fixture_disabled():
                done = subprocess.run([cargo, "build", "--release"], cwd=ROOT)
        else:
            done = subprocess.run([cargo, "build", "--release"], cwd=ROOT)
    except FileNotFoundError:
        pytest.fail(f"no qdot binary at {path}, and no `{cargo}` to build it: "
                    "install Rust (cargo), or set QDOT_BIN=/path/to/qdot", pytrace=False)
    if done.returncode != 0:
        pytest.fail(f"`{cargo} build --release` failed (exit {done.returncode}); "
                    "QDOT_BIN=/path/to/qdot uses a built CLI instead", pytrace=False)
    _say(config, f"qdot: CLI built in {time.monotonic() - start:.0f} s")


@pytest.fixture(scope="session")
def cli(request):
    path = qdot_bin()
    if os.environ.get("QDOT_BIN") and not path.exists():
        pytest.fail(f"QDOT_BIN={path}: no such file (build the CLI with "
                    "`cargo build --release`, or unset QDOT_BIN)", pytrace=False)
    if not path.exists():
        _build(request.config, path)
    assert path.exists(), f"no qdot binary at {path} (set QDOT_BIN=/path/to/qdot)"

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(path), *args], cwd=ROOT, capture_output=True, text=True)

    return run
