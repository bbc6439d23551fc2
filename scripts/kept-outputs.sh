#!/usr/bin/env bash
# Writes the kept results of every example anew (tests/reference/examples/: each
# example's recorded signals and summary, each structure's expansion and every
# fidelity on every section), then says what changed against the last commit.
# A change that means to alter a result runs this and says why in its commit;
# tests/tests/kept_outputs.rs compares against these files on every test run.
#
# Usage: ./scripts/kept-outputs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
# Over the workspace's test build, as test.sh runs it (a `-p` build rebuilds slender-fmu).
SLENDER_KEEP=1 cargo test --quiet --release --workspace --tests -- kept_outputs:: > /dev/null
kept=tests/reference/examples
if git diff --quiet -- "$kept" && [ -z "$(git ls-files --others --exclude-standard -- "$kept")" ]; then
    echo "kept results unchanged"
else
    echo "kept results that changed (git diff -- $kept shows each value):"
    git diff --stat -- "$kept"
    git ls-files --others --exclude-standard -- "$kept" | sed 's/^/ new: /'
fi
