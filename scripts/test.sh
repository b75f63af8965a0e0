#!/usr/bin/env bash
# All of wearsim's tests, each phase announced with the seconds elapsed since the start:
#   formatting (cargo fmt) and lints (clippy's, in the build; ruff);
#   one Cargo build (the `ci` profile of Cargo.toml, linked for glibc 2.17 by scripts/build-env.sh)
#   that gives the Rust unit, validation and CLI tests, the `wearsim` program the other phases drive,
#   and, with the Python extension added, the wheel;
#   the Rust tests and API reference (cargo doc, warnings are errors);
#   what a cluster installs (scripts/build-dist.sh): the CLI and the extension checked for the glibc
#   they need, the manylinux2014 abi3 wheel (auditwheel) and the sdist (twine check);
#   a real Slurm (scripts/test-slurm.sh): examples/slurm/study.sbatch as a job array, a task stopped
#   by its time-limit signal part-way and requeued, the results equal to a local run;
#   the Python package: the wheel in a fresh venv without cargo on the PATH (import, then
#   examples/python/quickstart.py) and in .venv with the pinned test dependencies of
#   tests/python/requirements.txt: its type stubs (mypy stubtest), mypy, the API reference (pdoc),
#   the tutorials of examples/tutorials (run, and converted to notebooks), the pytest suite (API,
#   studies on a Dask LocalCluster, cross-checks against tamaas from PyPI); the pytest suite again
#   in a venv holding the oldest versions pyproject.toml allows (scripts/test-floors.sh).
# Phases that do not need each other run side by side: package installs while Rust compiles, the
# Slurm test and the Python checks beside the Rust tests. Their output is shown when they end
# (logs in target/test-logs/), with the seconds they started and ended at.
set -euo pipefail
cd "$(dirname "$0")/.."
# The commands the tests run skip the cost estimate printed before `slide` and `study run` (its
# calibration, about 10 s per thread count on a first run, would be repeated by every fresh test
# machine); the estimate's own tests calibrate and check it (the CLI's tests/cost.rs; the timing
# of crates/wearsim/tests/cost.rs is run on request, with --ignored).
export WEARSIM_NO_ESTIMATE=1
root="$PWD"
# The venvs are installed without bytecode (uv; pip --no-compile): the Python processes of the tests
# compile what they import and keep it, once, under target/pycache, even where the environment says
# not to write bytecode beside the sources.
unset PYTHONDONTWRITEBYTECODE
export PYTHONPYCACHEPREFIX="$root/target/pycache"
logs="$root/target/test-logs"
rm -rf "$logs"
mkdir -p "$logs"
# `cpu_seconds`: sets $cpu to the CPU seconds (user + system) of the processes this shell started
# that have ended. `times` is a builtin: run in this shell (not in $(...), a copy) it reads this
# shell's own counters.
cpu_seconds() {
    local file="$logs/.times.$BASHPID"
    times >"$file"
    cpu=$(awk 'NR == 2 {
        for (i = 1; i <= 2; i++) { split($i, t, /[ms]/); total += t[1] * 60 + t[2] }
        printf "%.1f", total
    }' "$file")
    rm -f "$file"
}
# The CPU of each phase. The main shell's own counters also take in each background step as soon as
# it ends, whenever that is, so they cannot be split by phase: instead a phase's commands are run by
# `run`, in a subshell that reports the CPU of what it started, and `phase` shows the sum when the
# next phase begins. The background steps show theirs when they finish; the end shows both lists.
phase_title="" phase_cpu=0
cpu_table=()
phase() {
    end_phase
    phase_title=$1
    printf '\n== [%4ds] %s\n' "$SECONDS" "$1"
}
end_phase() {
    if [ -n "$phase_title" ]; then
        printf '(%.1f s of CPU in this phase, the background steps not counted)\n' "$phase_cpu"
        cpu_table+=("$(printf '%7.1f s  %s' "$phase_cpu" "$phase_title")")
    fi
    phase_cpu=0
}
# `run COMMAND...`: runs it (a program or a shell function) and adds its CPU to the phase's.
run() {
    local file="$logs/.run.cpu"
    (
        "$@"
        cpu_seconds
        echo "$cpu" >"$file"
    )
    phase_cpu=$(awk -v a="$phase_cpu" -v b="$(cat "$file")" 'BEGIN { printf "%.1f", a + b }')
}

# A step in the background: `background NAME COMMAND...` starts it with its output in
# target/test-logs/NAME.log and its exit status, once it ends, in NAME.status; `finish NAME` waits
# for it, shows its output and stops the run if it failed; `await NAME`, for a step that needs
# another, waits for that one's status (a background step cannot wait for its sibling).
declare -A pids
background() {
    local name=$1
    shift
    (
        start=$SECONDS
        status=0
        # Run as its own process and wait for it: a shell function on the left of `||` would run
        # with `set -e` off, so a failing command inside it (a lint) would not fail the phase.
        "$@" &
        wait $! || status=$?
        cpu_seconds
        printf '(%s: from %ds to %ds, %s s of CPU, exit status %d)\n' "$name" "$start" "$SECONDS" "$cpu" "$status"
        echo "$cpu" >"$logs/$name.cpu"
        echo "$status" >"$logs/$name.status"
        exit "$status"
    ) >"$logs/$name.log" 2>&1 &
    pids[$name]=$!
}
finish() {
    local name=$1 status=0
    wait "${pids[$name]}" || status=$?
    cat "$logs/$name.log"
    if [ "$status" != 0 ]; then
        echo "error: $name failed (exit status $status; log above, also in target/test-logs/$name.log)" >&2
        exit 1
    fi
}
await() {
    until [ -f "$logs/$1.status" ]; do sleep 0.2; done
    if [ "$(cat "$logs/$1.status")" != 0 ]; then
        echo "error: $1 failed: see target/test-logs/$1.log" >&2
        return 1
    fi
}

phase "Build tools for glibc 2.17: target/build-venv (maturin, zig, cargo-zigbuild, auditwheel, twine)"
# First, on their own: the builds need them (the linker), the other installs can wait.
background slurm-packages scripts/test-slurm.sh install
background cargo-fetch cargo fetch --locked
source scripts/build-env.sh
run build_env_install
build_env_export
echo "linker: $CARGO_TARGET_X86_64_UNKNOWN_LINUX_GNU_LINKER"
# The workspace's crates compile through clippy-driver, which lints them as `cargo clippy
# --all-targets -- -D warnings` does while the build compiles them, and the test harnesses compile
# unoptimised (scripts/rustc-test-harness.sh says why). Set for every Cargo command of the build
# (the wrapper and its lint options are part of what Cargo compares before reusing a build).
export RUSTC_WORKSPACE_WRAPPER="$root/scripts/rustc-test-harness.sh"
export WEARSIM_LINT=1
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"

phase "In the background: .venv with the pinned test dependencies, the floors venv"
setup_venv() {
    [ -x .venv/bin/python ] || venv_create .venv
    venv_install .venv/bin/python -r tests/python/requirements.txt
}
background venv setup_venv
background floors-venv scripts/test-floors.sh "" install

phase "Formatting: cargo fmt --check"
finish cargo-fetch
run cargo fmt --all --check

phase "Rust build and lints: the tests and the wearsim program (profile ci, linked for glibc 2.17), clippy's lints with -D warnings"
run cargo test --profile ci --workspace --locked --no-run -q

phase "Rust API reference: cargo doc --no-deps, warnings are errors"
run env WEARSIM_CARGO_PROFILE=ci scripts/api-docs.sh rust

phase "For cluster nodes: the CLI, the manylinux wheel and the sdist (scripts/build-dist.sh ci)"
run scripts/build-dist.sh ci
wheel=$(ls "$root"/target/dist/wearsim-*.whl)
# What ships is what the Python tests, the tutorials and Slurm drive (the same build as the Rust
# tests' program).
bin="$root/target/dist/wearsim"

phase "Rust tests: unit, property, analytic validation, CLI; beside them, Slurm and the Python checks"
slurm_test() {
    await slurm-packages
    scripts/test-slurm.sh "$bin"
}
background slurm slurm_test
fresh_venv() {
    # A user without a Rust toolchain: the wheel in a fresh venv, cargo off the PATH.
    local fresh no_cargo_path
    fresh="$(mktemp -d)/venv"
    python3 -m venv "$fresh"
    no_cargo_path=$(printf '%s' "$PATH" | tr ':' '\n' | grep -v -e cargo -e rustup | paste -sd: -)
    (cd /tmp && env PATH="$no_cargo_path" "$fresh/bin/python" -m pip install -q --no-compile "$wheel[examples]")
    (cd /tmp && env PATH="$no_cargo_path" "$fresh/bin/python" -c "import shutil, wearsim; assert shutil.which('cargo') is None; print('wearsim', wearsim.__version__, 'from the wheel, without cargo')")
    env PATH="$no_cargo_path" MPLBACKEND=Agg "$fresh/bin/python" examples/python/quickstart.py --out "$(mktemp -d)/python-example"
    rm -rf "$(dirname "$fresh")"
}
background fresh-venv fresh_venv
python_checks() {
    await venv
    echo "-- ruff check, ruff format --check"
    .venv/bin/ruff check
    .venv/bin/ruff format --check
    echo "-- the wheel in .venv; type stubs against the compiled module (stubtest); mypy"
    venv_install .venv/bin/python --reinstall --no-deps "$wheel"
    (cd /tmp && "$root/.venv/bin/python" -c "import wearsim; print('wearsim', wearsim.__version__, 'imported from', wearsim.__file__)")
    (cd /tmp && "$root/.venv/bin/python" -m mypy.stubtest wearsim._wearsim)
    (cd python && ../.venv/bin/python -m mypy wearsim)
    echo "-- Python API reference: pdoc from the docstrings, warnings are errors"
    scripts/api-docs.sh python
    echo "-- tutorials: each examples/tutorials/*.py runs, and converts to a notebook"
    for tutorial in examples/tutorials/*.py; do
        echo "$tutorial"
        (cd /tmp && env WEARSIM_BIN="$bin" MPLBACKEND=Agg "$root/.venv/bin/python" "$root/$tutorial" >/dev/null)
        .venv/bin/jupytext --quiet --to ipynb --output "$(mktemp -d)/tutorial.ipynb" "$tutorial"
    done
}
background python-checks python_checks
run cargo test --profile ci --workspace --locked

phase "Python lints, the wheel in .venv, stubtest, mypy, pdoc, tutorials (began beside the Rust tests)"
finish venv
finish python-checks

phase "Python tests: pytest; beside them, the pytest suite on the oldest versions pyproject.toml allows"
floors_test() {
    await floors-venv
    # Its own temporary folder: the main suite runs at the same time.
    WEARSIM_BIN="$bin" PYTEST_ADDOPTS="--basetemp=$root/target/floors-pytest" scripts/test-floors.sh "$wheel"
}
background floors floors_test
run env WEARSIM_BIN="$bin" .venv/bin/python -m pytest -rs tests/python

phase "Python tests on the oldest allowed versions (scripts/test-floors.sh)"
finish floors-venv
finish floors

phase "The wheel in a fresh venv, without cargo on the PATH: import, then the README's quickstart"
finish fresh-venv

phase "Slurm: examples/slurm/study.sbatch as a job array, a task stopped part-way and requeued (scripts/test-slurm.sh)"
finish slurm-packages
finish slurm

phase "All tests passed"
echo "CPU seconds (user + system) of each phase's own commands:"
printf '%s\n' "${cpu_table[@]}"
echo "and of each background step:"
for file in "$logs"/*.cpu; do
    printf '%7s s  %s\n' "$(cat "$file")" "$(basename "$file" .cpu)"
done
cpu_seconds
echo "CPU time of all phases: $cpu s (user + system; the Slurm daemons and jobs not counted)"
# The budget of the whole command on a 2-core machine, said out loud (a busy machine can exceed
# it without anything being wrong, so it is not a failure).
if awk -v c="$cpu" 'BEGIN { exit !(c > 1000) }'; then
    echo "NOTE: over the 1,000 s CPU budget of this command: look for a test that grew"
else
    echo "within the 1,000 s CPU budget of this command"
fi
