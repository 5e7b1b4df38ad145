#!/usr/bin/env python3
"""Hard inputs of issue 20: time and certified counts, one process per input.

Usage: dev/hard/families.py BINARY [--timeout S] [--deadline S] [--route R] [--only SUBSTRING]...

--timeout kills a run after S seconds; --deadline passes `--timeout S` to
`rootclip solve` (the library's wall-clock budget); --route passes
`--square-route R` to the square's solves.

Each family runs `BINARY solve ... --json` or `BINARY ray ... --json` under a
wall-clock limit and prints one line: name, seconds, complete, certified
roots/hits, undecided regions, and the number of simple roots the input is
built to have where it is known (products of lines: every pairwise crossing
in the domain, counted in exact rationals here). Needs only Python 3.
"""
import json, os, subprocess, sys, tempfile, time
from fractions import Fraction as F

def lines_product(lines):
    """prod (a u + b v + c) as an expression string."""
    return "*".join(f"(({a})*u + ({b})*v + ({c}))" for a, b, c in lines)

def crossing_points(f_lines, g_lines, domain):
    """Distinct crossings (exact rationals) of a line of f with a line of g inside the closed domain."""
    pts = set()
    for a1, b1, c1 in f_lines:
        for a2, b2, c2 in g_lines:
            det = F(a1) * F(b2) - F(a2) * F(b1)
            if det == 0:
                continue
            u = (F(b1) * F(c2) - F(b2) * F(c1)) / det
            v = (F(c1) * F(a2) - F(c2) * F(a1)) / det
            if u < 0 or v < 0:
                continue
            if domain == "triangle" and u + v > 1:
                continue
            if domain == "square" and (u > 1 or v > 1):
                continue
            pts.add((u, v))
    return pts

def crossings(f_lines, g_lines, domain):
    """How many distinct crossings lie in the closed domain."""
    return len(crossing_points(f_lines, g_lines, domain))

def rng(seed):
    x = seed
    def nxt():
        nonlocal x
        x = (x * 6364136223846793005 + 1442695040888963407) % 2**64
        return x >> 11
    return nxt

def random_lines(n, seed):
    """Lines a u + b v + c with small random rationals, crossing the domain."""
    r = rng(seed)
    out = []
    for _ in range(n):
        a = F(int(r() % 199) - 99, 97)
        b = F(int(r() % 199) - 99, 89)
        if a == 0 and b == 0:
            b = F(1)
        # through a random point of the unit square
        pu, pv = F(int(r() % 1000), 1000), F(int(r() % 1000), 1000)
        out.append((a, b, -(a * pu + b * pv)))
    return out

def systems():
    out = []
    v20 = [(1, 0, F(-i, 22)) for i in range(1, 21)]
    h20 = [(0, 1, F(-j, 22)) for j in range(1, 21)]
    out.append(("grid20x20/22 triangle hc", "triangle", v20, h20, []))
    v25 = [(1, 0, F(-i, 26)) for i in range(1, 26)]
    h25 = [(0, 1, F(-j, 26)) for j in range(1, 26)]
    out.append(("grid25x25/26 triangle", "triangle", v25, h25, []))
    out.append(("grid25x25/26 square", "square", v25, h25, []))
    rl1, rl2 = random_lines(25, 1), random_lines(25, 2)
    out.append(("random25x25 triangle", "triangle", rl1, rl2, []))
    out.append(("random25x25 square", "square", rl1, rl2, []))
    v15 = [(1, 0, F(-i, 16)) for i in range(1, 16)]
    h15 = [(0, 1, F(-j, 16)) for j in range(1, 16)]
    out.append(("grid15x15/16 square", "square", v15, h15, []))
    # A pencil of 10 lines through (0, 1/2) on the edge u = 0.
    pencil = [(F(k - 5, 10) + F(1, 20), -1, F(1, 2)) for k in range(10)]
    out.append(("pencil10@(0,1/2) x 2 verticals, square", "square", pencil, [(1, 0, F(-1, 3)), (1, 0, F(-2, 3))], []))
    out.append(("pencil10@(0,1/2) x 2 verticals, triangle", "triangle", pencil, [(1, 0, F(-1, 5)), (1, 0, F(-2, 5))], []))
    pencil2 = [(F(k - 5, 10) + F(1, 20), -1, F(1, 2) - (F(k - 5, 10) + F(1, 20))) for k in range(10)]  # through (1, 1/2)
    out.append(("pencil10@(0,1/2) x pencil10@(1,1/2), square", "square", pencil, pencil2, []))
    # Two pencils of 20 lines through (0, 1/2) and (1/3, 0): each product
    # vanishes to order 20 at its pencil's point.
    p20a = [(F(4 * k - 39, 40), -1, F(1, 2)) for k in range(20)]
    p20b = [(1, F(4 * k - 39, 40), F(-1, 3)) for k in range(20)]
    out.append(("pencil20@(0,1/2) x pencil20@(1/3,0), square", "square", p20a, p20b, []))
    out.append(("pencil20@(0,1/2) x pencil20@(1/3,0), triangle", "triangle", p20a, p20b, []))
    v30 = [(1, 0, F(-i, 31)) for i in range(1, 31)]
    h30 = [(0, 1, F(-j, 31)) for j in range(1, 31)]
    out.append(("grid30x30/31 square", "square", v30, h30, []))
    out.append(("grid30x30/31 triangle", "triangle", v30, h30, []))
    rl3, rl4 = random_lines(30, 3), random_lines(30, 4)
    out.append(("random30x30 square", "square", rl3, rl4, []))
    out.append(("random30x30 triangle", "triangle", rl3, rl4, []))
    return out

POLYS = [
    ("square (u+v)^100-1/2, u-v", "square", "(u+v)^100 - 1/2", "u - v", 1),
    ("square u^60-1/2, v^60-1/3", "square", "u^60 - 1/2", "v^60 - 1/3", 1),
    ("square u^200-1/2, v-1/3", "square", "u^200 - 1/2", "v - 1/3", 1),
    ("square u^20+v^20-2^-50, u-v", "square", "u^20 + v^20 - 1/1125899906842624", "u - v", 1),
    ("triangle (u+v)^30-1/2, u-v", "triangle", "(u+v)^30 - 1/2", "u - v", 1),
    ("triangle u^25-1/2, v^25-1/3", "triangle", "u^25 - 1/3", "v^25 - 1/3", 0),
    ("square u^25+v^25-1/2, (u-1/3)^2+(v-1/2)^2-1/16", "square", "u^25 + v^25 - 1/2", "(u-1/3)^2 + (v-1/2)^2 - 1/16", None),
]

BICUBIC = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "data", "seed000_bicubic.json")
RAYS = [
    ("ray bicubic, origin on it (t = 0)", BICUBIC, None, "1.5,2.25,0", "0,-1,0", 1),
    ("ray bicubic, origin on it, oblique", BICUBIC, None, "1.5,2.25,0", "0.25,-1,0.125", 1),
    ("ray bicubic, origin 1 ulp off", BICUBIC, None, "1.5,2.2500000000000004,0", "0,-1,0", 1),
    ("ray bilinear flat, origin on it", None, {"type": "tensor", "degree": [1, 1], "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]}, "0.3,0.4,0", "0.1,0.2,1", 1),
    ("ray quadratic triangle, origin on it", None, {"type": "triangle", "degree": 2, "points": [[0, 0, 0], [0.5, 0, 0.5], [1, 0, 0], [0, 0.5, 0.5], [0.5, 0.5, 1], [0, 1, 0]]}, None, "0.3,-0.2,1", 1),
]

EXTRA = []
EXTRA_SOLVE = []

def run(cmd, timeout):
    if cmd[1] == "solve" and "square" in cmd:
        cmd = cmd + EXTRA
    if cmd[1] == "solve":
        cmd = cmd + EXTRA_SOLVE
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return time.perf_counter() - t0, None, "timeout"
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        return dt, None, (p.stderr.strip() or p.stdout.strip())[:200]
    try:
        return dt, json.loads(p.stdout), ""
    except json.JSONDecodeError as e:
        return dt, None, f"bad json: {e}: {p.stdout[:200]}"

def main():
    args = sys.argv[1:]
    binary = args[0]
    timeout, only = 60.0, []
    i = 1
    while i < len(args):
        if args[i] == "--timeout":
            timeout = float(args[i + 1]); i += 2
        elif args[i] == "--deadline":
            EXTRA_SOLVE.extend(["--timeout", args[i + 1]]); i += 2
        elif args[i] == "--route":
            EXTRA.extend(["--square-route", args[i + 1]]); i += 2
        elif args[i] == "--only":
            only.append(args[i + 1]); i += 2
        else:
            raise SystemExit(f"unknown argument {args[i]}")
    want = lambda name: not only or any(o in name for o in only)
    tmp = tempfile.mkdtemp()
    rows = []
    for name, dom, fl, gl, _ in systems():
        if not want(name):
            continue
        expect = crossings(fl, gl, dom)
        dt, js, err = run([binary, "solve", "--f", lines_product(fl), "--g", lines_product(gl), "--domain", dom, "--json"], timeout)
        rows.append((name, dt, js, err, expect, "roots"))
    for name, dom, f, g, expect in POLYS:
        if not want(name):
            continue
        dt, js, err = run([binary, "solve", "--f", f, "--g", g, "--domain", dom, "--json"], timeout)
        rows.append((name, dt, js, err, expect, "roots"))
    for name, path, spec, origin, d, expect in RAYS:
        if not want(name):
            continue
        if spec is not None:
            path = os.path.join(tmp, "patch.json")
            with open(path, "w") as fh:
                json.dump(spec, fh)
        if origin is None:
            origin = "0.25,0.25,0.375"  # S(1/4, 1/4) of the quadratic triangle (z = uw + vw + 2uv), exact
        dt, js, err = run([binary, "ray", "--patch", path, "--origin", origin, "--dir", d, "--json"], timeout)
        rows.append((name, dt, js, err, expect, "hits"))
    for name, dt, js, err, expect, kind in rows:
        if js is None:
            print(f"{name:55s} {dt:8.3f} s  {err}")
            continue
        if kind == "roots":
            cert = sum(1 for r in js["roots"]) ; und = len(js["clusters"]); complete = js["complete"]
            extra = f"leftovers {len(js['leftovers'])}" if js["leftovers"] else ""
        else:
            ray = js["rays"][0] if "rays" in js else js
            hits = ray.get("hits", [])
            cert = sum(1 for h in hits if h.get("status") == "certified"); und = len(hits) - cert
            complete = ray.get("complete"); extra = ray.get("outcome", "") if "outcome" in ray else ""
            extra += " t=" + ",".join(str(h.get("t")) for h in hits)
        print(f"{name:55s} {dt:8.3f} s  complete={complete!s:5s} certified {cert:4d}/{expect if expect is not None else '?'}  undecided {und}  {extra}")

if __name__ == "__main__":
    main()
