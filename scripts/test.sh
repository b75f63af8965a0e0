#!/usr/bin/env bash
# All of wearsim's tests: Rust unit, validation and CLI tests, then the Python cross-checks against
# tamaas (installed into .venv from PyPI on first use).
set -euo pipefail
cd "$(dirname "$0")/.."

cargo test --workspace --locked

cargo build --release --locked -p wearsim-cli
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip >/dev/null 2>&1 || true
.venv/bin/python -m pip install -q numpy pytest
if ! .venv/bin/python -m pip install -q tamaas; then
    echo "WARNING: tamaas could not be installed from PyPI; the tamaas cross-checks will be skipped" >&2
fi
WEARSIM_BIN="$PWD/target/release/wearsim" .venv/bin/python -m pytest -rs tests/python
