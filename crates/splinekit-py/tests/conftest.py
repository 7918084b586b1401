"""Shared fixtures: the repository's data files and the `splinekit` command line, if built."""

import os
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def cli():
    """The `splinekit` binary: $SPLINEKIT_CLI, else one built in the repository's target/, else
    on PATH; the tests that compare with it are skipped without one."""
    candidates = [os.environ.get("SPLINEKIT_CLI")]
    candidates += [str(REPO / "target" / p / "splinekit") for p in ("release", "debug")]
    candidates.append(shutil.which("splinekit"))
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    pytest.skip("no splinekit command line built (cargo build -p splinekit-cli --no-default-features)")
