#!/usr/bin/env bash
# The API references, built from the code's own documentation, warnings are errors:
#   Rust:   target/doc/wearsim/index.html    (cargo doc: the library and the CLI crate)
#   Python: target/api-python/wearsim.html   (pdoc, from the installed package's docstrings)
#   scripts/api-docs.sh [rust|python|all] [PYTHON]
# PYTHON: an interpreter with wearsim and pdoc installed (default .venv/bin/python).
# WEARSIM_CARGO_PROFILE: the Cargo profile cargo doc builds under (default dev; scripts/test.sh sets
# ci, the profile of its build).
set -euo pipefail
cd "$(dirname "$0")/.."
which="${1:-all}"
if [ "$which" = rust ] || [ "$which" = all ]; then
    RUSTDOCFLAGS="-D warnings" cargo doc --profile "${WEARSIM_CARGO_PROFILE:-dev}" --no-deps --locked -q
    echo "Rust API reference: target/doc/wearsim/index.html"
fi
if [ "$which" = python ] || [ "$which" = all ]; then
    python=$(realpath -s "${2:-.venv/bin/python}") # -s: a venv's python is a link; keep its path
    out="$PWD/target/api-python"
    rm -rf "$out"
    # From /tmp, so that the installed package is documented, not the source folder.
    (cd /tmp && "$python" -W error -m pdoc --docformat restructuredtext -o "$out" wearsim)
    echo "Python API reference: target/api-python/wearsim.html"
fi
