#!/usr/bin/env bash
# Sets up and runs every check of slender: formatting, lints, the whole test suite
# (release build: the verification runs need the speed), and the example scenes
# through the CLI. Usage: ./scripts/test.sh   (CI runs exactly this.)
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n== %s\n' "$*"; }

step "toolchain"
cargo --version
rustc --version

# Python side of the test suite (FMU cross-checks with FMPy and pythonfmu): a
# local virtual environment, created on first use.
step "python test environment (.venv)"
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r scripts/requirements-test.txt
# The Python reader of results (python/, `import slender`), as a user installs it.
.venv/bin/python -m pip install --quiet --disable-pip-version-check ./python
export SLENDER_PYTHON="$PWD/.venv/bin/python"

step "format"
cargo fmt --all -- --check

step "sizes (no file over 600 lines, no function over 80)"
./scripts/check-sizes.sh

step "lints"
cargo clippy --workspace --all-targets --release -- -D warnings

step "build (CLI and the FMU library libslender_fmu.so, used by the FMI tests)"
cargo build --workspace --release

step "tests"
log=$(mktemp)
cargo test --workspace --release 2>&1 | tee "$log"
count() { awk -v what="$1" '/^test result:/ { for (i = 1; i <= NF; i++) if ($i ~ "^" what) n += $(i - 1) } END { print n + 0 }' "$log"; }
passed=$(count passed)
failed=$(count failed)
ignored=$(count ignored)

# The ignored tests below run by module filters over the whole workspace's
# test binaries: the build the test step made, reused as it is (`-p` on one
# package builds slender-fmu, a cdylib and an rlib, again: 70 s each time).
step "cross-checks with FMPy, pythonfmu, libcosim, chaospy, MoorPy and the Python reader (ignored above: they need .venv)"
cargo test --release --workspace --tests -- --ignored fmi_python:: uq_python:: ssp:: python_reader:: moorpy:: body_pythonfmu:: 2>&1 | tee "$log"
python_passed=$(count passed)
passed=$((passed + python_passed))
ignored=$((ignored - python_passed))

step "portable FMU library: built against glibc 2.17 with zig (ignored above)"
./scripts/portable-fmu.sh
cargo test --release --workspace --tests -- --ignored fmi_portable:: 2>&1 | tee "$log"
portable_passed=$(count passed)
passed=$((passed + portable_passed))
ignored=$((ignored - portable_passed))

step "cluster tests: a UQ study and a load-case matrix through a local single-node Slurm (ignored above)"
if [ "$(id -u)" = 0 ]; then
    ./scripts/slurm-up.sh
    cargo test --release --workspace --tests -- --ignored uq_slurm:: cases_cli:: 2>&1 | tee "$log"
    slurm_passed=$(count passed)
    passed=$((passed + slurm_passed))
    ignored=$((ignored - slurm_passed))
else
    echo "skipped: starting Slurm needs root (it installs slurm-wlm and munge and starts their daemons)"
fi
rm -f "$log"

step "HTML reports in a headless browser (Debian's chromium; ignored above)"
if [ ! -x /usr/bin/chromium ] && [ "$(id -u)" = 0 ]; then
    apt-get install -y --no-install-recommends chromium >/dev/null 2>&1 \
        || { apt-get update >/dev/null && apt-get install -y --no-install-recommends chromium >/dev/null; }
fi
if [ -x /usr/bin/chromium ]; then
    cargo test --release --workspace --tests -- --ignored report_browser:: 2>&1 | tee "$log"
    browser_passed=$(count passed)
    passed=$((passed + browser_passed))
    ignored=$((ignored - browser_passed))
else
    echo "skipped: installing chromium needs root (apt-get install chromium)"
fi
rm -f "$log"

step "user guide (docs/, an mdBook; its tutorials ran with the tests above)"
if ! command -v mdbook > /dev/null; then
    cargo install --quiet --locked mdbook --version 0.4.52 --no-default-features --features search
fi
mdbook build docs > "$log" 2>&1 || { cat "$log"; exit 1; }
test -s target/book/tutorials/first-scene.html
echo "built target/book ($(find target/book -name '*.html' | wc -l) pages)"
rm -f "$log"

step "example scenes (their results are compared with tests/reference/examples/ by the kept_outputs test above)"
for scene in examples/*.toml; do
    cargo run --quiet --release -- check "$scene" > /dev/null
done
cargo run --quiet --release -- run examples/truncation_signal_loss.toml --quiet --out target/example-results/truncation_signal_loss

# Last: maturin links the command again without its debug information.
step "the slender wheel (maturin): installed into a fresh venv and run from outside the repository"
./scripts/wheel.sh
rm -rf target/wheel-venv
python3 -m venv target/wheel-venv
target/wheel-venv/bin/python -m pip install --quiet --disable-pip-version-check target/wheels/slender-*.whl
root="$PWD"
(cd "$(mktemp -d)" && env -u SLENDER_BINARY PATH=/usr/bin:/bin \
    "$root/target/wheel-venv/bin/python" "$root/tests/python/wheel_check.py" "$root")

step "all checks passed"
echo "tests: ${passed} passed, ${failed} failed, ${ignored} skipped"
