#!/usr/bin/env bash
# Builds the FMU library against glibc 2.17 (RHEL 7 and later, Ubuntu 14.04 and
# later), so an exported FMU loads on the hosts many masters run on, not only
# where it was built. Zig links it (`ziglang` from PyPI into .venv; zig is
# self-contained) through cargo-zigbuild (from crates.io, installed once with
# `cargo install` beside cargo itself, as the test script installs mdbook: a
# fresh clone then does not build it again, a minute of every CI run).
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
zigbuild=0.24.1
if ! cargo zigbuild --version 2>/dev/null | grep -qF "$zigbuild"; then
    cargo install --quiet --locked "cargo-zigbuild@$zigbuild"
fi
# cargo-zigbuild runs zig through `python3 -m ziglang` when no zig is on PATH.
# The library ships stripped (the workspace's profile for slender-fmu), so its
# dependencies are built without the release profile's line tables too.
PATH="$PWD/.venv/bin:$PATH" CARGO_PROFILE_RELEASE_DEBUG=false \
    cargo zigbuild --quiet --release -p slender-fmu --target "$target.$glibc" >&2
echo "$PWD/target/$target/release/libslender_fmu.so"
