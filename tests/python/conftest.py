"""Shared fixtures of the Python tests: the CLI binary and the installed `wearsim` package."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
WEARSIM_BIN = os.environ.get("WEARSIM_BIN", str(ROOT / "target" / "release" / "wearsim"))


@pytest.fixture(scope="session")
def wearsim_bin():
    if not Path(WEARSIM_BIN).is_file():
        pytest.fail(f"{WEARSIM_BIN} not found: build it with `cargo build --release -p wearsim-cli`")
    return WEARSIM_BIN


@pytest.fixture(scope="session")
def root():
    return ROOT
