#!/usr/bin/env bash
# What a lab installs on its cluster nodes, built to start on glibc 2.17 or newer (RHEL/CentOS 7,
# Rocky/Alma 8 and 9, Debian ≥ 8, Ubuntu ≥ 14.04), whatever glibc this machine has:
#   target/dist/wearsim                     the command-line program (x86_64 Linux)
#   target/dist/wearsim-*-manylinux*.whl    the Python package: abi3, any CPython ≥ 3.11, manylinux2014
#   target/dist/wearsim-*.tar.gz            the source distribution
# and checks them: the highest GLIBC symbol version the program and the extension need (at most
# 2.17), the wheel's manylinux tag (auditwheel), both packages' metadata (twine check).
#   scripts/build-dist.sh [PROFILE]   # Cargo profile: release (default); scripts/test.sh passes ci
# Tools: scripts/build-requirements.txt, installed into target/build-venv on first use (PyPI).
set -euo pipefail
cd "$(dirname "$0")/.."
profile=${1:-release}
source scripts/build-env.sh
build_env_install
build_env_export
dist=target/dist
rm -rf "$dist"
mkdir -p "$dist"

# --workspace: the features the whole workspace selects, as `cargo test --workspace` builds them, so
# that scripts/test.sh finds the program already built; --bins: the program only.
cargo build --profile "$profile" --locked --workspace --bins
cp "target/$profile/wearsim" "$dist/wearsim"
"$build_venv/bin/maturin" build --profile "$profile" --compatibility manylinux2014 --out "$dist"
"$build_venv/bin/maturin" sdist --out "$dist"
wheel=$(ls "$dist"/wearsim-*.whl)
sdist=$(ls "$dist"/wearsim-*.tar.gz)

# The symbol versions of the program and of the extension inside the wheel.
unpacked=$(mktemp -d)
"$build_venv/bin/python" -m zipfile -e "$wheel" "$unpacked"
"$build_venv/bin/python" scripts/glibc-needs.py "$glibc_floor" "$dist/wearsim" "$unpacked"/wearsim/_wearsim*.so
rm -rf "$unpacked"
# auditwheel: the external libraries and symbol versions allow the manylinux_2_17 tag the wheel carries.
tag="manylinux_2_${glibc_floor#2.}_x86_64"
audit=$("$build_venv/bin/auditwheel" show "$wheel")
if ! tr -s ' \n' ' ' <<<"$audit" | grep -q "consistent with the following platform tag: \"$tag\""; then
    echo "$audit" >&2
    echo "error: auditwheel does not find $wheel consistent with $tag" >&2
    exit 1
fi
case "$wheel" in
*"$tag"*) ;;
*)
    echo "error: $wheel does not carry the $tag tag" >&2
    exit 1
    ;;
esac
echo "auditwheel: $(basename "$wheel") is consistent with $tag"
"$build_venv/bin/twine" check --strict "$wheel" "$sdist"
ls -l "$dist"
