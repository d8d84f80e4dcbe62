#!/usr/bin/env python3
"""Byte-compare two fold-plan builds over the corpus.

Usage: plan_diff.py OLD_BIN NEW_BIN CORPUS_DIR TILES[,TILES...] [--timeout S] [--out F.json]

For every SVG under CORPUS_DIR and every count, runs `BIN FILE --tiles N --json --quiet`
with both builds back to back and compares stdout, stderr and the exit status. Prints one
line per difference, then the user+system CPU of each build per count (median, sum) and
exits 1 if anything differs. A run over the timeout counts as a difference.
"""
import json
import os
import resource
import statistics
import subprocess
import sys
import time


def run(binary, svg, n, timeout):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    try:
        p = subprocess.run([binary, svg, "--tiles", str(n), "--json", "--quiet"],
                           capture_output=True, timeout=timeout)
        out = (p.stdout, p.stderr, p.returncode)
    except subprocess.TimeoutExpired:
        out = (b"", b"timeout", -1)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return out, cpu, time.monotonic() - t0


def main():
    args = sys.argv[1:]
    timeout = 120.0
    out_json = None
    if "--timeout" in args:
        i = args.index("--timeout")
        timeout = float(args[i + 1])
        del args[i:i + 2]
    if "--out" in args:
        i = args.index("--out")
        out_json = args[i + 1]
        del args[i:i + 2]
    old, new, corpus, tiles = args
    counts = [int(t) for t in tiles.split(",")]
    svgs = sorted(os.path.join(d, f) for d, _, fs in os.walk(corpus)
                  for f in fs if f.endswith(".svg"))
    rows = []
    differ = 0
    for n in counts:
        for svg in svgs:
            a, ca, _ = run(old, svg, n, timeout)
            b, cb, _ = run(new, svg, n, timeout)
            same = a == b and a[2] != -1
            if not same:
                differ += 1
                what = [k for k, x, y in zip(("stdout", "stderr", "exit"), a, b) if x != y]
                print(f"DIFF {svg} {n}: {','.join(what) or 'timeout'}", flush=True)
            rows.append({"file": svg, "tiles": n, "same": same, "cpu_old": ca, "cpu_new": cb})
    for n in counts:
        r = [x for x in rows if x["tiles"] == n]
        o = [x["cpu_old"] for x in r]
        w = [x["cpu_new"] for x in r]
        print(f"{n:>5} tiles, {len(r)} drawings: CPU median {statistics.median(o):.3f} -> "
              f"{statistics.median(w):.3f} s, sum {sum(o):.1f} -> {sum(w):.1f} s, "
              f"max {max(o):.2f} -> {max(w):.2f} s, "
              f"differ {sum(not x['same'] for x in r)}", flush=True)
    print(f"load average {open('/proc/loadavg').read().split()[:3]}")
    if out_json:
        with open(out_json, "w") as f:
            json.dump(rows, f, indent=1)
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
