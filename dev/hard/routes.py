#!/usr/bin/env python3
"""Routes against each other on random dense systems: whole-process seconds.

Usage: dev/hard/routes.py BINARY [--domain triangle|square] [--seeds N] [--degrees 2,3,4,...]

For each degree, N random dense systems (Bernstein coefficients, integers in
[-9, 9]; total degree n on the triangle, bidegree (n, n) on the square) are solved by
`BINARY solve --json` on both routes of the domain (triangle: `--triangle-route
triangle|rect`; square: `--square-route triangles|rect`). Prints the median
seconds per route and checks that both routes are complete with the same
certified roots (each root box of one route meets exactly one of the other's).
Needs only Python 3.
"""
import json, random, statistics, subprocess, sys, time

def dense(rng, n, domain):
    """Random Bernstein coefficients (integers in [-9, 9]) written out in u, v:
    curves that cross the domain, so that the systems have roots there."""
    from math import comb
    terms = []
    if domain == "triangle":
        for i in range(n + 1):
            for j in range(n + 1 - i):
                k = n - i - j
                c = rng.randint(-9, 9)
                if c:
                    w = comb(n, i) * comb(n - i, j)
                    terms.append(f"({c * w})*u^{i}*v^{j}*(1-u-v)^{k}")
    else:
        for i in range(n + 1):
            for j in range(n + 1):
                c = rng.randint(-9, 9)
                if c:
                    w = comb(n, i) * comb(n, j)
                    terms.append(f"({c * w})*u^{i}*(1-u)^{n - i}*v^{j}*(1-v)^{n - j}")
    return " + ".join(terms) or "1"

def run(binary, f, g, domain, flag, route):
    cmd = [binary, "solve", "--f", f, "--g", g, "--domain", domain, flag, route, "--json"]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        return dt, None
    return dt, json.loads(p.stdout)

def meets(a, b):
    return not (a["u"][1] < b["u"][0] or b["u"][1] < a["u"][0] or a["v"][1] < b["v"][0] or b["v"][1] < a["v"][0])

def main():
    args = sys.argv[1:]
    binary = args[0]
    domain, seeds, degrees = "triangle", 5, [2, 3, 4, 6, 8, 10, 12]
    i = 1
    while i < len(args):
        if args[i] == "--domain":
            domain = args[i + 1]
        elif args[i] == "--seeds":
            seeds = int(args[i + 1])
        elif args[i] == "--degrees":
            degrees = [int(x) for x in args[i + 1].split(",")]
        else:
            raise SystemExit(f"unknown argument {args[i]}")
        i += 2
    flag, routes = ("--triangle-route", ["triangle", "rect"]) if domain == "triangle" else ("--square-route", ["triangles", "rect"])
    print(f"{domain}: median whole-process seconds over {seeds} systems per degree")
    print("degree | " + " | ".join(routes) + " | roots | agree")
    for n in degrees:
        times = {r: [] for r in routes}
        roots, agree = 0, True
        for s in range(seeds):
            rng = random.Random(1000 * n + s)
            f, g = dense(rng, n, domain), dense(rng, n, domain)
            out = {}
            for r in routes:
                dt, js = run(binary, f, g, domain, flag, r)
                times[r].append(dt)
                out[r] = js
            a, b = out[routes[0]], out[routes[1]]
            if a is None or b is None or not (a["complete"] and b["complete"]):
                agree = False
                continue
            if a["clusters"] or b["clusters"] or len(a["roots"]) != len(b["roots"]):
                agree = False
            for r in a["roots"]:
                if sum(meets(r["box"], t["box"]) for t in b["roots"]) != 1:
                    agree = False
            roots += len(a["roots"])
        med = " | ".join(f"{statistics.median(times[r]):.3f}" for r in routes)
        print(f"{n} | {med} | {roots} | {'yes' if agree else 'NO'}")

if __name__ == "__main__":
    main()
