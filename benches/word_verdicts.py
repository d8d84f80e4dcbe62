#!/usr/bin/env python3
"""Verdicts and durations of every fold word of 1 to N letters in two models (issue 27).

    python3 benches/word_verdicts.py --letters 6 --s 0.3 --a engine --b coupled [--jobs 2] [--bin DIR]

Models: engine (fold-run's default), ja (--reference, the joint-angle model), coupled
(--reference --model coupled), fb (--reference --model free-body). Inertial defaults, thesis
design. A verdict is `result` and the sorted set of folded joints. Prints the counts of
verdicts differing, of same-verdict durations off by more than 0.5% and 1%, the largest
off, the kinds of change (a -> b) with examples, and one line a differing word with -v.
"""

import argparse
import collections
import itertools
import json
import os
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = {
    "engine": [],
    "ja": ["--reference"],
    "coupled": ["--reference", "--model", "coupled"],
    "fb": ["--reference", "--model", "free-body"],
}


def run(binary, word, s, model, out):
    cmd = [binary, word, "--s", str(s), "--json", "--quiet", "--frames", "1", "--out", out, *MODELS[model]]
    p = subprocess.run(cmd, capture_output=True, text=True)
    try:
        d = json.loads(p.stdout)
    except ValueError:
        return ("error " + p.stderr.strip()[-120:], (), float("nan"))
    return (d["result"], tuple(sorted(d["folds"])), d["duration_s"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--letters", type=int, default=6)
    ap.add_argument("--min-letters", type=int, default=1)
    ap.add_argument("--s", type=float, default=0.3)
    ap.add_argument("--a", default="engine")
    ap.add_argument("--b", default="coupled")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--bin", default=os.path.join(ROOT, "target/release"))
    ap.add_argument("-v", action="store_true")
    a = ap.parse_args()
    binary = os.path.join(a.bin, "fold-run")
    words = ["".join(w) for n in range(a.min_letters, a.letters + 1) for w in itertools.product("SLR", repeat=n)]
    tmp = tempfile.mkdtemp(prefix="wv-")

    def both(i_w):
        i, w = i_w
        return w, run(binary, w, a.s, a.a, f"{tmp}/a{i}"), run(binary, w, a.s, a.b, f"{tmp}/b{i}")

    with ThreadPoolExecutor(a.jobs) as ex:
        rows = list(ex.map(both, enumerate(words)))
    differ, off05, off1, largest = [], 0, 0, (0.0, "")
    kinds = collections.defaultdict(list)
    for w, ra, rb in rows:
        if ra[:2] != rb[:2]:
            differ.append(w)
            kind = f"{ra[0]}{'' if ra[1] == rb[1] else ' (other folds)'} -> {rb[0]}"
            kinds[kind].append(w)
            if a.v:
                print(f"  {w}: {a.a} {ra} {a.b} {rb}")
            continue
        off = abs(ra[2] / rb[2] - 1) if rb[2] else 0.0
        off05 += off > 0.005
        off1 += off > 0.01
        if off > largest[0]:
            largest = (off, w)
    print(f"s = {a.s} mm, {len(words)} words of {a.min_letters}-{a.letters} letters, {a.a} against {a.b}: "
          f"{len(differ)} verdicts differ; same verdict, duration off > 0.5%: {off05}, > 1%: {off1}; "
          f"largest {100 * largest[0]:.3f}% ({largest[1]})")
    for k, ws in sorted(kinds.items(), key=lambda kv: -len(kv[1])):
        print(f"  {len(ws):5}  {k}: {' '.join(ws[:6])}")


if __name__ == "__main__":
    main()
