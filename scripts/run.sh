#!/bin/sh
# Installs what the build needs on a fresh Debian machine (run as root), then runs
#   sh scripts/run.sh main   the main job
#   sh scripts/run.sh test   the test suite
set -eu
cd "$(dirname "$0")/.."

need_packages=""
command -v m4 >/dev/null 2>&1 || need_packages="$need_packages m4"
command -v cc >/dev/null 2>&1 || need_packages="$need_packages gcc libc6-dev"
command -v make >/dev/null 2>&1 || need_packages="$need_packages make"
# FLINT (the `certified` feature, on by default) compiles one C file of its build with clang.
command -v clang >/dev/null 2>&1 || need_packages="$need_packages clang"
command -v cargo >/dev/null 2>&1 || [ -x "$HOME/.cargo/bin/cargo" ] || need_packages="$need_packages curl ca-certificates"
if [ -n "$need_packages" ]; then
    echo "installing:$need_packages" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $need_packages >/dev/null
fi
if ! command -v cargo >/dev/null 2>&1; then
    if [ ! -x "$HOME/.cargo/bin/cargo" ]; then
        curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal --component clippy,rustfmt
    fi
    PATH="$HOME/.cargo/bin:$PATH"
    export PATH
fi

# The Python package (python/): built by pip (maturin, reusing target/ and the caches of
# the compiled GMP, MPFR and FLINT) into a virtual environment of its own, then its tests
# against the command line built above.
python_package_tests() {
    if ! python3 -c 'import ensurepip, venv' >/dev/null 2>&1; then
        echo "installing: python3 python3-venv" >&2
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3 python3-venv >/dev/null
    fi
    venv=target/python-venv
    rm -rf "$venv"
    python3 -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --disable-pip-version-check ./python pytest hypothesis numpy mpmath python-flint
    "$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests
}

case "${1:-}" in
    main)
        cargo run --release --quiet -- verify
        ;;
    test)
        cargo test --release
        cargo run --release --quiet -- verify --quick
        # The library alone, without the command line's dependencies.
        cargo build --release --quiet --lib --no-default-features
        cargo build --release --quiet --bin microslip
        python_package_tests
        ;;
    *)
        echo "usage: sh scripts/run.sh main|test" >&2
        exit 2
        ;;
esac
