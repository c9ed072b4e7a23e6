"""conftest.py's CLI build: announced before the tests start, shown while it
runs, and only when a selected test needs the CLI. Run in a pytest of its
own on a copy of conftest.py, with a stub for cargo that writes a stub
binary (nothing is compiled)."""

import os
import shutil
import stat
import subprocess
import sys
import textwrap
from pathlib import Path

from conftest import BUILD_TIME, ROOT

TESTS = '''
def test_needs_the_cli(cli):
    assert cli("--version").stdout == "stub qdot\\n"

def test_without_the_cli():
    pass
'''

# cargo as conftest.py calls it: `$CARGO build --release` in the root, the
# binary into $CARGO_TARGET_DIR/release/qdot
CARGO = '''#!{python}
import os, pathlib, sys
assert sys.argv[1:] == ["build", "--release"], sys.argv
print("   Compiling qdot (stub)", file=sys.stderr)
with open(pathlib.Path(os.environ["STUB_LOG"]), "a") as log:
    log.write(os.getcwd() + "\\n")
out = pathlib.Path(os.environ["CARGO_TARGET_DIR"]) / "release" / "qdot"
out.parent.mkdir(parents=True, exist_ok=True)
out.write_text("#!/bin/sh\\necho stub qdot\\n")
out.chmod(0o755)
'''


def executable(path: Path, text: str) -> Path:
    path.write_text(text)
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


def session(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    """A pytest run of TESTS beside a copy of conftest.py (its ROOT is then
    tmp_path), the CLI missing and cargo the stub."""
    tests = tmp_path / "python" / "tests"
    if not tests.exists():
        tests.mkdir(parents=True)
        shutil.copy(ROOT / "python" / "tests" / "conftest.py", tests)
        (tests / "test_stub.py").write_text(TESTS)
        executable(tmp_path / "cargo", CARGO.format(python=sys.executable))
    env = {k: v for k, v in os.environ.items() if k not in ("QDOT_BIN", "PYTEST_ADDOPTS")}
    env.update(CARGO=str(tmp_path / "cargo"), CARGO_TARGET_DIR=str(tmp_path / "target"),
               STUB_LOG=str(tmp_path / "cargo.log"))
    return subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", *args],
                          cwd=tests, env=env, capture_output=True, text=True, timeout=120)


def test_a_missing_cli_is_announced_then_built_once(tmp_path):
    run = session(tmp_path, "-q")
    assert run.returncode == 0, run.stdout + run.stderr
    out = run.stdout
    # the first thing printed, before any test runs
    assert out.startswith(f"qdot: no CLI binary at {tmp_path / 'target' / 'release' / 'qdot'}; ")
    notice = 0
    assert f"build it first with `cargo build --release` ({BUILD_TIME}). " in out
    assert "QDOT_BIN=/path/to/qdot uses a built one instead." in out
    building = out.index(f"qdot: building the CLI: {tmp_path / 'cargo'} build --release")
    built = out.index("qdot: CLI built in ")
    assert notice < building < built < out.index("[100%]")
    # cargo's own progress is not captured
    assert "Compiling qdot (stub)" in run.stderr
    assert (tmp_path / "cargo.log").read_text() == f"{tmp_path}\n"
    assert "2 passed" in out


def test_no_build_when_no_selected_test_needs_the_cli(tmp_path):
    run = session(tmp_path, "-q", "-k", "without")
    assert run.returncode == 0, run.stdout + run.stderr
    assert "qdot:" not in run.stdout
    assert not (tmp_path / "cargo.log").exists()
    assert not (tmp_path / "target").exists()


def test_a_missing_qdot_bin_is_an_error_not_a_build(tmp_path):
    missing = tmp_path / "nowhere" / "qdot"
    tests = tmp_path / "python" / "tests"
    session(tmp_path, "--collect-only", "-q")  # lays out the files
    env = {k: v for k, v in os.environ.items() if k != "PYTEST_ADDOPTS"}
    env.update(QDOT_BIN=str(missing), CARGO=str(tmp_path / "cargo"),
               STUB_LOG=str(tmp_path / "cargo.log"))
    run = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-q"],
                         cwd=tests, env=env, capture_output=True, text=True, timeout=120)
    assert run.returncode == 1, run.stdout + run.stderr
    assert f"qdot: QDOT_BIN={missing}: no such file" in run.stdout
    assert f"QDOT_BIN={missing}: no such file (build the CLI with `cargo build --release`" in run.stdout
    assert not (tmp_path / "cargo.log").exists()
