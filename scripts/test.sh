#!/usr/bin/env bash
# All of wearsim's tests, each phase announced with the seconds elapsed:
#   formatting and lints (cargo fmt, clippy, ruff);
#   the Rust unit, validation and CLI tests (one release build, which also gives target/release/wearsim);
#   the Python package: one abi3 wheel built by maturin, installed into a fresh venv with cargo off the
#   PATH (a user without a Rust toolchain) and into .venv with the pinned test dependencies of
#   tests/python/requirements.txt; its type stubs (mypy stubtest), mypy, the pytest suite (API, studies on
#   a Dask LocalCluster, cross-checks against tamaas from PyPI); examples/python/quickstart.py runs in the
#   fresh venv; the pytest suite again in a venv holding the oldest versions pyproject.toml allows
#   (scripts/test-floors.sh); the API references (cargo doc and pdoc, warnings are errors); the
#   tutorials of examples/tutorials run and convert to notebooks.
# The Python dependencies are installed in the background while Rust compiles.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
phase() { printf '\n== [%4ds] %s\n' "$SECONDS" "$1"; }

phase "Python test environment: .venv with the pinned dependencies (in the background)"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
mkdir -p target
pip_log="$root/target/pip-install.log"
(
    .venv/bin/python -m pip install -q --upgrade pip &&
        .venv/bin/python -m pip install -q -r tests/python/requirements.txt
) >"$pip_log" 2>&1 &
pip_pid=$!
floors_log="$root/target/pip-install-floors.log"
scripts/test-floors.sh "" install >"$floors_log" 2>&1 &
floors_pid=$!

phase "Formatting: cargo fmt --check"
cargo fmt --all --check

phase "Lints: cargo clippy --workspace --all-targets -- -D warnings"
cargo clippy --workspace --all-targets --locked -q -- -D warnings

phase "Rust tests: unit, property, analytic validation, CLI (release build)"
cargo test --release --workspace --locked

phase "Rust API reference: cargo doc --no-deps, warnings are errors"
scripts/api-docs.sh rust

phase "Waiting for the Python test environment"
if ! wait "$pip_pid"; then
    cat "$pip_log" >&2
    echo "error: installing the pinned Python test dependencies failed (log above)" >&2
    exit 1
fi

phase "Python lints: ruff check, ruff format --check"
.venv/bin/ruff check
.venv/bin/ruff format --check

phase "Python wheel: maturin, release, abi3"
rm -rf target/wheels
.venv/bin/python -m pip wheel -q . --no-deps -w target/wheels
wheel=$(ls target/wheels/wearsim-*.whl)
echo "built $wheel"

phase "The wheel in a fresh venv, without cargo on the PATH: import, then the README's quickstart"
fresh="$(mktemp -d)/venv"
python3 -m venv "$fresh"
no_cargo_path=$(printf '%s' "$PATH" | tr ':' '\n' | grep -v -e cargo -e rustup | paste -sd: -)
(cd /tmp && env PATH="$no_cargo_path" "$fresh/bin/python" -m pip install -q "$root/$wheel[examples]")
(cd /tmp && env PATH="$no_cargo_path" "$fresh/bin/python" -c "import shutil, wearsim; assert shutil.which('cargo') is None; print('wearsim', wearsim.__version__, 'from the wheel, without cargo')")
env PATH="$no_cargo_path" MPLBACKEND=Agg "$fresh/bin/python" examples/python/quickstart.py --out "$(mktemp -d)/python-example"
rm -rf "$fresh"

phase "The wheel in .venv; type stubs against the compiled module; mypy"
.venv/bin/python -m pip install -q --force-reinstall --no-deps "$wheel"
(cd /tmp && "$root/.venv/bin/python" -c "import wearsim; print('wearsim', wearsim.__version__, 'imported from', wearsim.__file__)")
(cd /tmp && "$root/.venv/bin/python" -m mypy.stubtest wearsim._wearsim)
(cd python && ../.venv/bin/python -m mypy wearsim)

phase "Python API reference: pdoc from the docstrings, warnings are errors"
scripts/api-docs.sh python

phase "Tutorials: each examples/tutorials/*.py runs, and converts to a notebook"
for tutorial in examples/tutorials/*.py; do
    echo "$tutorial"
    (cd /tmp && env WEARSIM_BIN="$root/target/release/wearsim" MPLBACKEND=Agg "$root/.venv/bin/python" "$root/$tutorial" >/dev/null)
    .venv/bin/jupytext --quiet --to ipynb --output "$(mktemp -d)/tutorial.ipynb" "$tutorial"
done

phase "Python tests: pytest"
WEARSIM_BIN="$root/target/release/wearsim" .venv/bin/python -m pytest -rs tests/python

phase "Python tests on the oldest versions pyproject.toml allows"
if ! wait "$floors_pid"; then
    cat "$floors_log" >&2
    echo "error: installing the oldest allowed Python dependencies failed (log above)" >&2
    exit 1
fi
scripts/test-floors.sh "$wheel"

phase "All tests passed"
