#!/usr/bin/env bash
# Times README's two commands on a fresh clone (a new target directory; crates already in
# ~/.cargo/registry are not downloaded again). Usage: tools/fresh_clone_times.sh [DIR]
# Prints wall and CPU seconds for each, with the load average before and after: on a shared
# machine the wall time is an upper bound, the CPU time the better guide.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
dir="${1:-$(mktemp -d)/foldchain}"
git clone -q "$src" "$dir"
cd "$dir"
echo "clone of $(git rev-parse --short HEAD) in $dir; $(nproc) cores; $(uptime)"
/usr/bin/time -f "cargo build --release: %e s wall, %U s user, %S s sys" cargo build --release 2>&1 | tail -1
echo "$(uptime)"
/usr/bin/time -f "cargo test --workspace --release: %e s wall, %U s user, %S s sys" cargo test --workspace --release 2>&1 | grep -E "^test result: FAILED|cargo test --workspace" || true
echo "$(uptime)"
