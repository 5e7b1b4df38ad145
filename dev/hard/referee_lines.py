#!/usr/bin/env python3
"""Referee for many simple roots: random products of n lines against n lines
(n = 12..30), on the square and the triangle, checked against the crossings
computed in exact rationals here.

Usage: dev/hard/referee_lines.py BINARY [--seeds A B]

Every crossing in the closed domain must lie in exactly one certified root
box, every root box must hold a crossing, and the answer must be complete
with no undecided region (crossings of lines are simple; a cluster where two
nearly coincide would be honest, but is flagged for a look). Prints one line
per system and the number flagged. Needs only Python 3.
"""
import json, os, subprocess, sys, time
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(__file__))
import families as fm  # noqa: E402


def main():
    args = sys.argv[1:]
    binary = args[0]
    lo, hi = 20, 32
    if "--seeds" in args:
        i = args.index("--seeds")
        lo, hi = int(args[i + 1]), int(args[i + 2])
    flagged = total = 0
    for seed in range(lo, hi):
        n = 12 + (seed * 7) % 19
        fl, gl = fm.random_lines(n, seed * 2 + 101), fm.random_lines(n, seed * 2 + 102)
        for dom in ["square", "triangle"]:
            pts = fm.crossing_points(fl, gl, dom)
            t0 = time.perf_counter()
            p = subprocess.run([binary, "solve", "--f", fm.lines_product(fl), "--g", fm.lines_product(gl),
                                "--domain", dom, "--json", "--timeout", "60"], capture_output=True, text=True)
            dt = time.perf_counter() - t0
            total += 1
            if p.returncode != 0:
                flagged += 1
                print(f"seed {seed} n {n} {dom}: exit {p.returncode}: {p.stderr.strip()[:200]}")
                continue
            js = json.loads(p.stdout)
            boxes = [tuple(F(x) for x in (r["box"]["u"] + r["box"]["v"])) for r in js["roots"]]
            inside = lambda b, q: b[0] <= q[0] <= b[1] and b[2] <= q[1] <= b[3]
            counts = [sum(1 for b in boxes if inside(b, q)) for q in pts]
            miss, multi = counts.count(0), sum(1 for k in counts if k > 1)
            false = sum(1 for b in boxes if not any(inside(b, q) for q in pts))
            ok = miss == 0 and false == 0 and multi == 0 and js["complete"] and not js["clusters"]
            flagged += not ok
            print(f"seed {seed} n {n} {dom:8s} {dt:6.2f} s roots {len(boxes)}/{len(pts)} missed {miss} "
                  f"false {false} twice {multi} clusters {len(js['clusters'])} complete {js['complete']} "
                  f"restarts {js['stats']['exact_restarts']}{'' if ok else '  <-- flagged'}", flush=True)
    print(f"flagged {flagged} of {total}")


if __name__ == "__main__":
    main()
