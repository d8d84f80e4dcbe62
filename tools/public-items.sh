#!/usr/bin/env bash
# Counts the public items of the foldchain library crate: every struct, enum, union, trait,
# function, constant, static, type alias and macro a user can name by a public path
# (re-exports counted once, at the item; modules, enum variants, fields and methods not
# counted). Reads rustdoc's JSON (unstable on stable Rust, hence RUSTC_BOOTSTRAP=1).
# Usage: tools/public-items.sh [--list] [CRATE]   (default crate: foldchain)
set -euo pipefail
cd "$(dirname "$0")/.."
list=0
if [ "${1:-}" = "--list" ]; then list=1; shift; fi
crate=${1:-foldchain}
target=${CARGO_TARGET_DIR:-target}/public-items
RUSTC_BOOTSTRAP=1 cargo rustdoc -q -p "$crate" --lib --target-dir "$target" -- \
  -Z unstable-options --output-format json 2>/dev/null
python3 - "$target/doc/${crate//-/_}.json" "$list" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
index = doc["index"]
items = sorted(
    "::".join(p["path"])
    for id_, p in doc["paths"].items()
    if p["crate_id"] == 0
    and p["kind"] not in ("module", "variant", "struct_field", "assoc_type", "assoc_const")
    and id_ in index and index[id_]["visibility"] == "public"
)
if sys.argv[2] == "1":
    print("\n".join(items))
print(len(items))
PY
