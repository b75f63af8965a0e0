# Sourced by scripts/test.sh and scripts/build-dist.sh: every Cargo build of the workspace links
# against glibc 2.17 (manylinux2014), so that the `wearsim` binary and the Python extension start on
# cluster nodes as old as RHEL/CentOS 7, whatever glibc the build machine has. The linker is zig's
# clang (PyPI `ziglang`) with its glibc 2.17 stubs, through cargo-zigbuild's `zig cc` wrapper, set
# for the host target so that the tests, the CLI and the wheel share one build of each crate.
#   build_env_install   the tools of scripts/build-requirements.txt into target/build-venv (once)
#   build_env_export    the linker for this shell's Cargo builds (CARGO_TARGET_..._LINKER)
#   venv_create DIR, venv_install PYTHON ARGS...
#                       a venv of the test scripts, and packages installed into it, by uv (from
#                       target/build-venv): pip's work at a tenth of its CPU time, and without
#                       compiling every installed module to bytecode (scripts/test.sh keeps the
#                       bytecode of what its processes import instead)
# x86_64 Linux only (the wrapper names x86_64-linux-gnu).

build_venv="$PWD/target/build-venv"
# The oldest glibc the binaries need; scripts/build-dist.sh checks their symbol versions against it.
glibc_floor=2.17

build_env_install() {
    if [ ! -x "$build_venv/bin/cargo-zigbuild" ] ||
        ! cmp -s scripts/build-requirements.txt "$build_venv/requirements.txt"; then
        rm -rf "$build_venv"
        python3 -m venv "$build_venv"
        "$build_venv/bin/python" -m pip install -q --upgrade pip
        "$build_venv/bin/python" -m pip install -q -r scripts/build-requirements.txt
        cp scripts/build-requirements.txt "$build_venv/requirements.txt"
    fi
}

venv_create() {
    "$build_venv/bin/uv" venv -q "$1"
}

venv_install() {
    local python=$1
    shift
    "$build_venv/bin/uv" pip install -q --python "$python" "$@"
}

build_env_export() {
    if [ "$(uname -sm)" != "Linux x86_64" ]; then
        echo "error: the builds for older glibc are set up for x86_64 Linux; this is $(uname -sm)" >&2
        return 1
    fi
    local cc="$PWD/target/zig/cc-x86_64-linux-gnu.$glibc_floor"
    mkdir -p "$(dirname "$cc")"
    # cargo-zigbuild finds zig as `python3 -m ziglang`: the build venv's python3, first on its PATH.
    cat >"$cc.tmp" <<WRAPPER
#!/bin/sh
PATH="$build_venv/bin:\$PATH" exec cargo-zigbuild zig cc -- -target x86_64-linux-gnu.$glibc_floor "\$@"
WRAPPER
    chmod +x "$cc.tmp"
    if cmp -s "$cc.tmp" "$cc"; then rm "$cc.tmp"; else mv "$cc.tmp" "$cc"; fi
    export CARGO_TARGET_X86_64_UNKNOWN_LINUX_GNU_LINKER="$cc"
}
