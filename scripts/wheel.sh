#!/usr/bin/env bash
# Builds the `slender` wheel (issue 49): the `slender` command for this
# machine's platform (its manylinux tag from the glibc it links), the FMU
# library it exports units with (libslender_fmu.so built against glibc 2.17
# by ./scripts/portable-fmu.sh, so the FMUs a wheel's user exports load on
# older hosts too; installed beside the command, where `slender fmu export`
# looks for it) and the Python reader (python/). Needs a Rust toolchain and
# maturin (`pip install maturin`; the test venv has it).
#
# Usage: ./scripts/wheel.sh [PYTHON]   (PYTHON: an interpreter with maturin;
#        default .venv/bin/python)      -> target/wheels/slender-*.whl
#
# Other platforms (not built or tested here): maturin builds them the same
# way with `--target aarch64-unknown-linux-gnu --zig --compatibility
# manylinux2014`, or inside the manylinux containers.
set -euo pipefail
cd "$(dirname "$0")/.."
python="${1:-.venv/bin/python}"

# The wheel's data folder, installed into the environment's scripts (bin)
# folder: the portable FMU library without its debug information.
rm -rf target/wheel-data target/wheels
mkdir -p target/wheel-data/scripts
strip --strip-debug -o target/wheel-data/scripts/libslender_fmu.so "$(./scripts/portable-fmu.sh | tail -1)"
"$python" -m maturin build --quiet --release --out target/wheels
ls target/wheels/slender-*.whl
