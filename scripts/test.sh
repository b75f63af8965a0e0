#!/usr/bin/env bash
# All of wearsim's tests: Rust unit, validation and CLI tests; then the Python package built from
# this checkout (`pip install .` into .venv, with numpy, pandas, dask, matplotlib, pytest, mypy and
# tamaas from PyPI), its type stubs checked against the compiled module (mypy stubtest), its pytest
# suite (API, studies on a Dask LocalCluster, tamaas cross-checks of the CLI and of the Python API)
# and the example script.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo test --workspace --locked

cargo build --release --locked -p wearsim-cli
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install -q --upgrade pip >/dev/null 2>&1 || true
.venv/bin/python -m pip install -q numpy pandas "dask[distributed]" matplotlib pytest mypy pandas-stubs
if ! .venv/bin/python -m pip install -q tamaas; then
    echo "WARNING: tamaas could not be installed from PyPI; the tamaas cross-checks will be skipped" >&2
fi
# The Python package, built by maturin from this checkout, as a user installs it: first into a
# fresh venv with nothing else (its dependencies come from PyPI), then into the test venv.
fresh_venv="$(mktemp -d)/venv"
python3 -m venv "$fresh_venv"
"$fresh_venv/bin/python" -m pip install -q .
(cd /tmp && "$fresh_venv/bin/python" -c "import wearsim")
rm -rf "$fresh_venv"
.venv/bin/python -m pip install -q .
(cd /tmp && "$OLDPWD/.venv/bin/python" -c "import wearsim; print('wearsim', wearsim.__version__, 'imported from', wearsim.__file__)")
# The type stubs match the compiled module, and the package type-checks against them.
(cd /tmp && "$OLDPWD/.venv/bin/python" -m mypy.stubtest wearsim._wearsim)
(cd python && ../.venv/bin/python -m mypy wearsim)

WEARSIM_BIN="$PWD/target/release/wearsim" .venv/bin/python -m pytest -rs tests/python
MPLBACKEND=Agg .venv/bin/python examples/python/quickstart.py --out "$(mktemp -d)/python-example"
