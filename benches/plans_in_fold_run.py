#!/usr/bin/env python3
"""Do the planner's plans fold in fold-run? Plans every one-piece drawing of the planner's
corpus (planner/corpus) at the given tile counts with `fold-plan --out`, then runs each plan in
`fold-run --plan` (the event engine, defaults: inertial, the thesis design) and, with
`--coupled`, in the coupled joint-angle reference too (`--reference --model coupled`, up to
2,000 tiles). Prints one line per plan and a summary per count: how many complete, collide,
stall. fold-plan checks every plan with the sequential fold check (one joint at a time);
fold-run folds the chain as its magnets drive it, several joints at once (docs/verifying.md).

    python3 benches/plans_in_fold_run.py --tiles 100,300 [--coupled] [--s MM] [--bin target/release]
"""
import argparse
import glob
import json
import os
import re
import resource
import subprocess
import sys
import tempfile


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd):
    before = cpu_of_children()
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p, cpu_of_children() - before


def summary_of(run_dir):
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def rows_before(plan_path, reason):
    """For a run that stalled at magnet N: the straight joints between the last U-turns
    before N's tile (the rows' lengths), from the plan's tile list; '' otherwise."""
    m = re.search(r"magnet (\d+)", reason or "")
    if not m:
        return ""
    with open(plan_path) as f:
        plan = json.load(f)
    tiles = []
    for t in plan["tile_list"].split():
        name, _, count = t.partition("*")
        tiles += [name] * (int(count) if count else 1)
    word = "".join(t[1] for t in tiles[:-1])
    tile = int(m.group(1)) // 2
    runs = [len(r) for r in re.split("[LR]+", word[:tile])][-4:]
    return f" rows before {runs}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tiles", default="100,300")
    ap.add_argument("--bin", default="target/release")
    ap.add_argument("--corpus", default="planner/corpus")
    ap.add_argument("--coupled", action="store_true")
    ap.add_argument("--filter", default="")
    ap.add_argument("--s", default=None, help="fold-run --s for every run (default: the design's)")
    a = ap.parse_args()
    files = sorted(set(glob.glob(os.path.join(a.corpus, "*", "*.svg"))))
    files = [f for f in files if a.filter in f]
    work = tempfile.mkdtemp(prefix="plans-in-fold-run-")
    for n in [int(t) for t in a.tiles.split(",")]:
        counts = {}
        for f in files:
            name = os.path.splitext(os.path.basename(f))[0]
            plan = os.path.join(work, f"{name}-{n}.json")
            p, _ = run([os.path.join(a.bin, "fold-plan"), f, "--tiles", str(n), "--quiet", "--out", plan])
            if p.returncode != 0:
                continue  # refused: separate parts, or no plan (the corpus bench counts these)
            models = [("engine", [])]
            if a.coupled:
                models.append(("coupled", ["--reference", "--model", "coupled"]))
            line = [f"{n:5d} {name:28s}"]
            for model, extra in models:
                out = os.path.join(work, f"{name}-{n}-{model}")
                p, cpu = run([os.path.join(a.bin, "fold-run"), "--plan", plan, "--out", out,
                              "--quiet", "--frames", "1", *extra,
                              *(["--s", a.s] if a.s is not None else [])])
                summary = summary_of(out)
                o = str(summary.get("result", "no-summary")) if p.returncode in (0, 1) else f"exit-{p.returncode}"
                counts.setdefault(model, {}).setdefault(o, 0)
                counts[model][o] += 1
                rows = rows_before(plan, summary.get("reason")) if o == "stalled" else ""
                line.append(f"{model} {o:10s} {cpu:6.2f} s{rows}")
            print("  ".join(line), flush=True)
        for model, c in counts.items():
            total = sum(c.values())
            parts = ", ".join(f"{k} {v}" for k, v in sorted(c.items()))
            print(f"{n} tiles, {model}: {total} plans: {parts}", flush=True)


if __name__ == "__main__":
    sys.exit(main())
