#!/usr/bin/env bash
# The Python tests on the oldest versions pyproject.toml allows (scripts/floors.py lists them), so that
# a floor is a tested promise: a venv with exactly those versions (wheels only, as users get them),
# the wheel given as $1 installed into it, and the pytest suite. The cross-checks against tamaas and
# the SurfaceTopography reader are not installed here; their tests skip and say so.
#   scripts/test-floors.sh target/dist/wearsim-*.whl [install]
# WEARSIM_BIN: the wearsim program the tests drive (default target/release/wearsim).
# With "install" as the second argument only the venv is made (scripts/test.sh does that while Rust
# compiles).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/floors-venv
# venv_create, venv_install (uv from target/build-venv).
source scripts/build-env.sh
if [ "${2:-}" = install ]; then
    build_env_install
    rm -rf "$venv"
    venv_create "$venv"
    python3 scripts/floors.py >target/floors.txt
    venv_install "$venv/bin/python" --only-binary :all: -r target/floors.txt
    exit 0
fi
wheel="$1"
venv_install "$venv/bin/python" --reinstall --no-deps "$wheel"
# The venv must hold the floors, not whatever pip resolved the wheel's dependencies to.
"$venv/bin/python" - target/floors.txt <<'PY'
import sys
from importlib.metadata import version

wrong = []
for line in open(sys.argv[1]).read().split():
    name, floor = line.split("==")
    name = name.split("[")[0]
    if tuple(map(int, version(name).split(".")[:3])) != tuple(map(int, floor.split("."))) + (0,) * (
        3 - len(floor.split("."))
    ):
        wrong.append(f"{name} {version(name)} (floor {floor})")
if wrong:
    sys.exit("the floors venv does not hold the floors: " + ", ".join(wrong))
print("floors:", ", ".join(f"{line.split('==')[0]} {version(line.split('==')[0].split('[')[0])}" for line in open(sys.argv[1]).read().split()))
PY
WEARSIM_BIN="${WEARSIM_BIN:-$PWD/target/release/wearsim}" "$venv/bin/python" -m pytest -q -rs -p no:cacheprovider tests/python
