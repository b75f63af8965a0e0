#!/usr/bin/env bash
# RUSTC_WORKSPACE_WRAPPER of the test command's build (scripts/test.sh): compiles the workspace's
# crates through clippy-driver, so that the one build both lints them (cargo clippy's lints, with the
# options of $CLIPPY_ARGS, `-D warnings` there) and compiles them, and compiles the workspace's test
# harnesses (rustc --test: the library's unit tests, the integration test binaries, the CLI's unit
# tests) without optimisation, everything else as the Cargo profile says.
#
# Why clippy-driver: `cargo clippy` checks every dependency again (metadata only, no reuse by the
# build that follows) and the workspace's crates a second time, about 150 s of processor time on
# two cores; clippy-driver is rustc with clippy's lints added (cargo clippy itself runs it as the
# workspace wrapper of `cargo check`), so the build lints what it compiles for the lints' cost
# alone. Dependencies are compiled by rustc as before (Cargo wraps only the workspace's crates).
#
# Why: a test harness is a second full copy of its crate, and optimising the library's copy at
# opt-level 3 costs as much processor time as the library itself (about 70 s on two cores) for
# tests that run in seconds. Unoptimised, it compiles in a quarter of that and its tests run longer
# (about 30 s more), a net saving of about a minute on every CI run. What the tests drive stays
# optimised: the integration tests call the library as built for users (its rlib, opt-level 3) and
# the CLI tests run the `wearsim` program. Results do not depend on the opt-level: rustc does the same
# IEEE operations in the same order at every level (no fast-math), and overflow checks and debug
# assertions follow the profile, not this.
#
# Usage (Cargo calls it): rustc-test-harness.sh RUSTC ARGS...; with $WEARSIM_LINT set, through
# clippy-driver (in its wrapper mode: `clippy-driver RUSTC ARGS...`).
rustc=$1
shift
harness=0
for arg in "$@"; do
    if [ "$arg" = --test ]; then
        harness=1
        break
    fi
done
driver=()
if [ -n "${WEARSIM_LINT:-}" ]; then
    driver=(clippy-driver)
fi
if [ "$harness" = 0 ]; then
    exec "${driver[@]}" "$rustc" "$@"
fi
args=()
for arg in "$@"; do
    case "$arg" in
    opt-level=*) args+=("opt-level=0") ;;
    *) args+=("$arg") ;;
    esac
done
exec "${driver[@]}" "$rustc" "${args[@]}"
