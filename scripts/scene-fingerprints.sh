#!/usr/bin/env bash
# Fingerprints of every example scene's outputs, to prove that a change which
# moves code does not change behaviour: for each scene, the SHA-256 of its
# timeseries.csv and of its summary.json without the wall-clock fields (status,
# counters, residuals, indicators, order, settings).
#
# Usage: ./scripts/scene-fingerprints.sh OUT.txt     (release build of `slender` first)
#        ./scripts/scene-fingerprints.sh --compare BEFORE.txt
#
# tests/reference/scene-fingerprints.txt holds the current fingerprints and
# ./scripts/test.sh compares against it. A change that means to alter a scene's
# results regenerates it (first form) and says why in its commit message.
set -euo pipefail
cd "$(dirname "$0")/.."
slender=target/release/slender
work=target/scene-fingerprints
compare=""
if [ "${1:-}" = "--compare" ]; then compare="$2"; out=$(mktemp); else out="${1:?usage: scene-fingerprints.sh OUT.txt | --compare BEFORE.txt}"; fi
rm -rf "$work"; mkdir -p "$work"
: > "$out"
for scene in examples/*.toml; do
    name=$(basename "$scene" .toml)
    "$slender" run "$scene" --quiet --out "$work/$name" > /dev/null 2>&1 || true
    csv=$(sha256sum < "$work/$name/timeseries.csv" | cut -d' ' -f1)
    # Drop the fields that measure wall-clock time; keep everything the run computed.
    summary=$(python3 - "$work/$name/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for k in ("wall_time_s", "cost_per_simulated_second", "scene"):
    s.pop(k, None)
for u in s.get("counters", {}).get("units", []):
    u.pop("step_time_s", None)
print(json.dumps(s, sort_keys=True))
PY
)
    echo "$name csv=$csv summary=$(printf '%s' "$summary" | sha256sum | cut -d' ' -f1)" >> "$out"
done
if [ -n "$compare" ]; then
    if diff "$compare" "$out"; then
        echo "bit-identical: $(wc -l < "$out") scenes"
    else
        echo "scene outputs differ from $compare: if the change means it, regenerate with ./scripts/scene-fingerprints.sh $compare" >&2
        exit 1
    fi
else
    cat "$out"
fi
