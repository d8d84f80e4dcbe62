#!/usr/bin/env bash
# Compares two fold-run builds' summaries: result, duration, first collision and clearance
# (value, tiles, time, joint) on 200 random words of 2 to 14 letters (seed 27) and
# benches/serpentine-1k.txt, each under the inertial defaults and `--dynamics overdamped
# --s 0.1`. Prints each run that differs and the count; exits 1 if any differ.
#
#   bash benches/summary_diff.sh OLD_FOLD_RUN NEW_FOLD_RUN [WORDS]
#
# OLD_FOLD_RUN is typically main's build copied aside (cp target/release/fold-run
# /tmp/fold-run-main before building the branch), NEW_FOLD_RUN the branch's.
set -euo pipefail
old=${1:?usage: summary_diff.sh OLD_FOLD_RUN NEW_FOLD_RUN [WORDS]}
new=${2:?usage: summary_diff.sh OLD_FOLD_RUN NEW_FOLD_RUN [WORDS]}
count=${3:-200}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$count" >"$work/words" <<'EOF'
import random, sys
rng = random.Random(27)
for _ in range(int(sys.argv[1])):
    print("".join(rng.choice("SLR") for _ in range(rng.randint(2, 14))))
EOF
tr -s ' \n' ' ' <"$here/serpentine-1k.txt" >>"$work/words"
echo >>"$work/words"

# the fields compared, one line a run
fields() {
    python3 -c '
import json, sys
d = json.load(sys.stdin)
c = d.get("first_collision")
k = d.get("clearance")
print(json.dumps([d.get("result"), d.get("duration_s"), c,
                  k and [k.get("mm"), k.get("tiles"), k.get("time"), k.get("joint")]]))'
}

runs=0
differ=0
while IFS= read -r word; do
    [ -n "$word" ] || continue
    for dyn in inertial overdamped; do
        if [ "$dyn" = overdamped ]; then
            opts=(--dynamics overdamped --s 0.1)
        else
            opts=()
        fi
        # a run that collides exits non-zero: its summary is what is compared
        "$old" "$word" "${opts[@]}" --frames 1 --out "$work/a" --json --quiet >"$work/a.json" 2>/dev/null || true
        "$new" "$word" "${opts[@]}" --frames 1 --out "$work/b" --json --quiet >"$work/b.json" 2>/dev/null || true
        a=$(fields <"$work/a.json")
        b=$(fields <"$work/b.json")
        runs=$((runs + 1))
        if [ "$a" != "$b" ]; then
            differ=$((differ + 1))
            echo "differ: ${word:0:60} ($dyn)"
            echo "  old: $a"
            echo "  new: $b"
        fi
    done
done <"$work/words"
echo "$runs runs, $differ differ"
[ "$differ" -eq 0 ]
