#!/usr/bin/env bash
# Size check of the Rust sources (the project's standard: files under ~600 lines,
# functions under ~80). Fails on a file over 600 lines or a function over 80,
# naming each.
# Usage: ./scripts/check-sizes.sh
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files --cached --others --exclude-standard '*.rs')
status=0
for f in $files; do
    n=$(wc -l < "$f")
    if [ "$n" -gt 600 ]; then
        echo "file over 600 lines: $f ($n)"
        status=1
    fi
done
if python3 - $files <<'PY'
import re, sys
long = []
for path in sys.argv[1:]:
    lines = open(path, encoding="utf-8").read().split("\n")
    for i, line in enumerate(lines):
        m = re.match(r"^(\s*)(pub(\([a-z]+\))? )?(const )?(unsafe )?(extern \"C\" )?fn (\w+)", line)
        if not m:
            continue
        # A declaration (extern block, trait method without body) ends with `;`
        # before any `{`.
        k = i
        while k < len(lines) and "{" not in lines[k] and not lines[k].rstrip().endswith(";"):
            k += 1
        if k == len(lines) or "{" not in lines[k]:
            continue
        indent = m.group(1)
        for j in range(i + 1, len(lines)):
            if lines[j] == indent + "}":
                if j - i + 1 > 80:
                    long.append((j - i + 1, path, i + 1, m.group(7)))
                break
for n, path, line, name in sorted(long, reverse=True):
    print(f"function over 80 lines: {path}:{line} {name} ({n})")
print(f"{len(long)} functions over 80 lines")
sys.exit(1 if long else 0)
PY
then :; else status=1; fi
exit $status
