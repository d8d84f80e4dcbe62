#!/usr/bin/env python3
"""Issue 27's must-show lines, run on a release build (BENCHMARKS.md "Issue 27's must-shows").

    python3 benches/issue27_must_show.py [PART ...]   # parts: fold scale head serp scenes srl drag knife ref1999 s100k

Runs target/release/fold-run (and fold-validate) under /usr/bin/time and prints one line a
measurement: what was asked, what was measured, the user+system CPU seconds. Long parts
(ref1999, s100k) only when named.
"""

import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN = os.path.join(ROOT, "target/release/fold-run")
VALIDATE = os.path.join(ROOT, "target/release/fold-validate")
TMP = tempfile.mkdtemp(prefix="ms27-")


def run(chain, *args, timeout=3600):
    """fold-run CHAIN ARGS: (summary, timeline events, cpu s, wall s)."""
    out = os.path.join(TMP, str(abs(hash((chain,) + args))))
    tf = os.path.join(TMP, "time")
    cmd = ["/usr/bin/time", "-f", "%U %S %e", "-o", tf, RUN, chain, "--json", "--quiet",
           "--frames", "1", "--out", out, *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    u, s, e = open(tf).read().split()[-3:]
    try:
        summary = json.loads(p.stdout)
        summary["exit"] = p.returncode
    except ValueError:
        return {"exit": p.returncode, "stderr": p.stderr.strip()[-300:]}, [], float(u) + float(s), float(e)
    try:
        events = json.load(open(os.path.join(out, "timeline.json")))["events"]
    except (OSError, KeyError, ValueError):
        events = []
    return summary, events, float(u) + float(s), float(e)


def folds(events):
    """joint -> (start, end) from the timeline."""
    st, en = {}, {}
    for t, kind, j in events:
        if kind == "fold_starts":
            st.setdefault(j, t)
        elif kind == "fold_ends":
            en[j] = t
    return {j: (st[j], en.get(j)) for j in st}


def fold_scale():
    print("## S*n L S*n: fold duration, ratio at 2n (asked >= 4)")
    for dyn in ["inertial", "overdamped"]:
        for model in [[], ["--reference"], ["--reference", "--model", "free-body"]]:
            prev = None
            for n in [10, 20, 40, 80, 160, 320]:
                s, ev, cpu, wall = run(f"S*{n} L S*{n}", "--dynamics", dyn, *model)
                f = folds(ev).get(n)
                d = (f[1] - f[0]) if f and f[1] is not None else None
                ratio = (d / prev) if (d and prev) else None
                print(f"{dyn:10} {' '.join(model) or 'engine':30} n={n:4} {s.get('result')} "
                      f"fold {d} ratio {ratio} cpu {cpu:.2f}", flush=True)
                prev = d


def head():
    print("## S*2 L S*200: last tile's turn (asked < 10 deg)")
    for dyn in ["inertial", "overdamped"]:
        for model in [[], ["--reference"], ["--reference", "--model", "free-body"]]:
            s, _, cpu, _ = run("S*2 L S*200", "--dynamics", dyn, *model)
            fm = s.get("free_motion") or {}
            print(f"{dyn:10} {' '.join(model) or 'engine':30} {s.get('result')} last {fm.get('last_tile_turn_deg')} "
                  f"first {fm.get('first_tile_turn_deg')} cpu {cpu:.2f}", flush=True)


def serp():
    print("## 2,019-tile serpentine, rows of 20, s = 0.3: max_tile_speed_m_s (asked < 0.5)")
    word = " ".join(["S*18 LL S*18 RR"] * 50) + " S*18"
    for model in [[]]:
        s, _, cpu, wall = run(word, "--s", "0.3", *model)
        fm = s.get("free_motion") or {}
        print(f"{' '.join(model) or 'engine':30} tiles {s.get('tiles')} {s.get('result')} "
              f"max {fm.get('max_tile_speed_m_s')} tile {fm.get('fastest_tile')} cpu {cpu:.2f} wall {wall:.2f}", flush=True)


SCENES = ["SS", "SL", "LS", "LL", "SLSRSL", "S*19", "SLS", "S*2LS*2", "S*5LS*5", "S*10LS*10",
          "S*24LS*24", "S*2LS*20", "SLLS", "SLLLS", "SLSLS", "SLRS", "SLSRS", "S*2LS*2RS*2",
          "S*4LLS*4RRS*4", "S*8LLS*8RRS*8", "S*4LS*4LS*4RS*4R", "S*7LLS*7RRS*7LLS*7"]


def scenes():
    print("## free body against the reduced models (asked within 1%), s = 0.3, inertial")
    for w in SCENES:
        fb, _, _, _ = run(w, "--s", "0.3", "--reference", "--model", "free-body")
        row = [f"{w:22} fb {fb.get('result'):9} {fb.get('duration_s'):.4f}"]
        for name, args in [("ja", ["--reference"]), ("cp", ["--reference", "--model", "coupled"]), ("en", [])]:
            s, _, _, _ = run(w, "--s", "0.3", *args)
            off = 100 * (s["duration_s"] / fb["duration_s"] - 1)
            same = "" if (s.get("result"), s.get("folds")) == (fb.get("result"), fb.get("folds")) else " VERDICT"
            row.append(f"{name} {s['duration_s']:.4f} ({off:+.2f}%){same}")
        print(" | ".join(row), flush=True)
    t = os.path.join(TMP, "vt")
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S", "-o", t, VALIDATE, "--experiments", "--quiet",
                        "--out", os.path.join(TMP, "val")], capture_output=True, text=True)
    print("fold-validate --experiments exit", p.returncode, p.stdout.strip().splitlines()[-1:] if p.stdout else p.stderr[-300:])


def srl():
    print("## SRLSLLSR --s 0.05: engine and reference")
    for args in [[], ["--reference"]]:
        s, _, cpu, _ = run("SRLSLLSR", "--s", "0.05", *args)
        print(f"{' '.join(args) or 'engine':12} {s.get('result')} clearance {s.get('clearance')} cpu {cpu:.2f}", flush=True)


def drag():
    print("## SL overdamped --drag 10: engine vs reference; --drag, --magnet-mass on inertial runs")
    a, _, _, _ = run("SL", "--dynamics", "overdamped", "--drag", "10")
    b, _, _, _ = run("SL", "--dynamics", "overdamped", "--drag", "10", "--reference")
    print(f"engine {a.get('duration_s')} reference {b.get('duration_s')} off {100 * (a['duration_s'] / b['duration_s'] - 1):+.5f}%")
    for args in [[], ["--drag", "0.5"], ["--magnet-mass", "5"], ["--magnet-mass", "0.001"]]:
        for m in [[], ["--reference"], ["--reference", "--model", "free-body"]]:
            s, _, _, _ = run("SL", *args, *m)
            print(f"inertial {' '.join(args) or 'defaults':20} {' '.join(m) or 'engine':28} {s.get('duration_s', s)}", flush=True)


def knife():
    print("## knife edge: SL --design {wall: 1.2715684370696545} (asked < 2 s CPU)")
    d = os.path.join(TMP, "knife.json")
    json.dump({"wall": 1.2715684370696545}, open(d, "w"))
    for m in [[], ["--reference"], ["--reference", "--model", "free-body"]]:
        s, _, cpu, _ = run("SL", "--design", d, *m)
        print(f"{' '.join(m) or 'engine':28} exit {s.get('exit')} {s.get('result')} {str(s.get('reason') or s.get('stderr'))[:200]} cpu {cpu:.2f}", flush=True)


def ref1999():
    print("## S*1999 --reference (asked < 60 s CPU)")
    for m in [["--reference"], ["--reference", "--model", "free-body"]]:
        s, _, cpu, wall = run("S*1999", *m)
        print(f"{' '.join(m):28} {s.get('result')} {s.get('duration_s')} cpu {cpu:.2f} wall {wall:.2f}", flush=True)


def s100k():
    print("## benches/serpentine-100k.txt --s 0.1 (asked < 5 s wall on 2 cores)")
    f = os.path.join(ROOT, "benches/serpentine-100k.txt")
    for dyn in ["overdamped", "inertial"]:
        s, _, cpu, wall = run(f, "--s", "0.1", "--dynamics", dyn)
        print(f"{dyn:10} {s.get('result')} {s.get('duration_s')} cpu {cpu:.2f} wall {wall:.2f}", flush=True)


PARTS = {"fold": fold_scale, "head": head, "serp": serp, "scenes": scenes, "srl": srl,
         "drag": drag, "knife": knife, "ref1999": ref1999, "s100k": s100k}

if __name__ == "__main__":
    for name in sys.argv[1:] or ["head", "srl", "drag", "knife", "scenes", "serp", "fold"]:
        PARTS[name]()
