#!/usr/bin/env bash
# Interrupts `fold-run --out DIR --frames 3000` of a 1,000-tile serpentine, which replaces an
# earlier run in DIR (2,000 frames, and a user's file), with SIGINT and SIGKILL at random
# moments, and checks every time that DIR holds exactly one whole run: byte for byte the
# earlier one or the new one, the user's file kept (issue 29). Also: two runs into one DIR at
# once, one refused and the other whole.
#
# usage: tools/interrupt_check.sh [TRIALS_PER_SIGNAL (20)] [FOLD_RUN (target/release/fold-run)]
set -euo pipefail
trials=${1:-20}
bin=$(realpath "${2:-target/release/fold-run}")
work=$(mktemp -d /tmp/foldchain-interrupt.XXXXXX)
cd "$work"
python3 -c "print(('S*98 LL S*98 RR '*5).strip())" > chain.txt
"$bin" chain.txt --out A --frames 2000 --quiet > /dev/null
echo "a user's notes" > A/notes.txt
cp -a A B
start=$(date +%s.%N)
"$bin" chain.txt --out B --frames 3000 --quiet > /dev/null
full=$(echo "$(date +%s.%N) - $start" | bc)
echo "a whole run takes ${full} s; $trials interruptions per signal at uniform random moments in it"
same() { diff -rq "$1" "$2" > /dev/null 2>&1; }
fails=0
for sig in INT KILL; do
  for i in $(seq 1 "$trials"); do
    rm -rf DIR; cp -a A DIR
    at=$(python3 -c "import random; print(round(random.uniform(0, $full), 2))")
    "$bin" chain.txt --out DIR --frames 3000 --quiet > /dev/null 2>&1 &
    pid=$!
    sleep "$at"
    kill -s "$sig" "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null && code=0 || code=$?
    left=$(ls -a . | grep -c 'fold-staging' || true)
    if same DIR A; then held=earlier; elif same DIR B; then held=new; else held=MIXED; fails=$((fails+1)); fi
    echo "SIG$sig at ${at} s: exit $code, DIR holds the $held run ($(ls DIR | wc -l) files), staging dirs left beside it: $left"
  done
done
# two writers at once: one is refused at once, the other's run is whole
rm -rf DIR; cp -a A DIR
"$bin" chain.txt --out DIR --frames 3000 --quiet > one.out 2> one.err & p1=$!
sleep 1
"$bin" chain.txt --out DIR --frames 3000 --quiet > two.out 2> two.err && c2=0 || c2=$?
wait "$p1" && c1=0 || c1=$?
echo "concurrent: first exit $c1, second exit $c2: $(cat two.err)"
if same DIR B; then echo "concurrent: DIR holds the first run, whole"; else echo "concurrent: DIR MIXED"; fails=$((fails+1)); fi
rm -rf "$work"
echo "failures: $fails"
[ "$fails" -eq 0 ]
