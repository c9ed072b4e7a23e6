"""Shared fixtures: the repository's root, its examples and the CLI."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("*.qd"))


def qdot_bin() -> Path:
    """The CLI built by `cargo test --release` (or $QDOT_BIN)."""
    env = os.environ.get("QDOT_BIN")
    if env:
        return Path(env)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "qdot"


@pytest.fixture(scope="session")
def cli():
    path = qdot_bin()
    if not path.exists():
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    assert path.exists(), f"no qdot binary at {path}"

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(path), *args], cwd=ROOT, capture_output=True, text=True)

    return run
