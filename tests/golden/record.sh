#!/usr/bin/env bash
# Records the outputs the refactor (issue 10) must not change: run once on the commit before
# the refactor, from the repository root, with the release binaries built
# (`cargo build --release --workspace`). `tests/golden.rs` in the CLI crate compares today's
# outputs with these files (numbers to 1e-12 relative; wall-clock fields excluded).
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${BIN:-target/release}
G=tests/golden
"$B/fold-enum" --max-tiles 12 --json > "$G/enum-12.json"
"$B/fold-enum" --max-tiles 9 --random --json > "$G/enum-9-random.json"
: > "$G/check-words.jsonl"
while read -r w; do
  code=0
  out=$("$B/fold-check" --json "$w" 2>/dev/null) || code=$?
  python3 -c 'import json,sys; print(json.dumps({"word": sys.argv[1], "exit": int(sys.argv[2]), "stdout": json.loads(sys.argv[3]) if sys.argv[3] else None}))' "$w" "$code" "$out" >> "$G/check-words.jsonl"
done < "$G/check-words.txt"
for s in shapes/*.svg; do
  n=$(basename "$s" .svg)
  # an unplannable shape is recorded as its exit code (issue 13: exit 1 with the reason)
  code=0
  "$B/fold-plan" "$s" --json --quiet > "$G/plan-$n.json" || code=$?
  if [ "$code" -ne 0 ]; then echo "{\"exit\": $code}" > "$G/plan-$n.json"; fi
done
"$B/fold-plan" shapes/square.svg --tiles 107 --turns tight --tiles-tolerance 0 --json > "$G/plan-square-107-tight.json"
"$B/fold-plan" shapes/square.svg --tiles 82 --turns loose --tiles-tolerance 0 --json > "$G/plan-square-82-loose.json"
i=0
while IFS='|' read -r chain opts; do
  i=$((i+1))
  tmp=$(mktemp -d)
  # shellcheck disable=SC2086
  code=0
  "$B/fold-run" "$chain" $opts --out "$tmp/run" --json > "$G/run-$i-summary.json" || code=$?
  echo "$code" > "$G/run-$i-exit.txt"
  cp "$tmp/run/timeline.json" "$G/run-$i-timeline.json"
  rm -rf "$tmp"
done < "$G/run-chains.txt"
"$B/fold-validate" --quick --json > "$G/validate-quick.json"
