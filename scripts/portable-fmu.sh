#!/usr/bin/env bash
# Builds the FMU library against glibc 2.17 (RHEL 7 and later, Ubuntu 14.04 and
# later), so an exported FMU loads on the hosts many masters run on, not only
# where it was built. Zig links it (`ziglang` from PyPI into .venv; zig is
# self-contained) through cargo-zigbuild (from crates.io, into target/tools).
# Prints the library's path; export with it:
#   slender fmu export SCENE --unit NAME --binary "$(./scripts/portable-fmu.sh | tail -1)"
# Usage: ./scripts/portable-fmu.sh [TARGET]  (default x86_64-unknown-linux-gnu;
#        aarch64-unknown-linux-gnu for ARM hosts, after `rustup target add`)
set -euo pipefail
cd "$(dirname "$0")/.."

glibc=2.17
target="${1:-x86_64-unknown-linux-gnu}"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check ziglang==0.17.1
if [ ! -x target/tools/bin/cargo-zigbuild ]; then
    cargo install --quiet --locked cargo-zigbuild@0.24.1 --root target/tools
fi
# cargo-zigbuild runs zig through `python3 -m ziglang` when no zig is on PATH.
PATH="$PWD/.venv/bin:$PWD/target/tools/bin:$PATH" \
    cargo zigbuild --quiet --release -p slender-fmu --target "$target.$glibc" >&2
echo "$PWD/target/$target/release/libslender_fmu.so"
