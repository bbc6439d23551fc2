#!/usr/bin/env bash
# Builds the `slender` wheel (issue 49): the `slender` command for this
# machine's platform (its manylinux tag from the glibc it links), the FMU
# library it exports units with (libslender_fmu.so built against glibc 2.17
# by ./scripts/portable-fmu.sh, so the FMUs a wheel's user exports load on
# older hosts too; installed beside the command, where `slender fmu export`
# looks for it) and the Python reader (python/). Needs a Rust toolchain and
# maturin (`pip install maturin`; the test venv has it).
#
# Usage: ./scripts/wheel.sh [TARGET]   -> target/wheels/slender-*.whl
#   No TARGET: this machine's platform. TARGET (a Rust target triple, e.g.
#   aarch64-unknown-linux-gnu after `rustup target add` it): the command too
#   is linked by zig against glibc 2.17 (manylinux2014), a full release
#   build for that target; built here, not run (no such host in CI).
#   PYTHON names an interpreter with maturin (default .venv/bin/python).
set -euo pipefail
cd "$(dirname "$0")/.."
python="${PYTHON:-.venv/bin/python}"
target="${1:-}"

# The wheel's data folder, installed into the environment's scripts (bin)
# folder: the portable FMU library (stripped by its release profile).
rm -rf target/wheel-data target/wheels
mkdir -p target/wheel-data/scripts
if [ -z "$target" ]; then
    cp "$(./scripts/portable-fmu.sh | tail -1)" target/wheel-data/scripts/libslender_fmu.so
    "$python" -m maturin build --quiet --release --out target/wheels
else
    cp "$(./scripts/portable-fmu.sh "$target" | tail -1)" target/wheel-data/scripts/libslender_fmu.so
    PATH="$PWD/.venv/bin:$PATH" "$python" -m maturin build --quiet --release --out target/wheels \
        --target "$target" --zig --compatibility manylinux2014
fi
ls target/wheels/slender-*.whl
