//! Referee run: random dense systems (degrees 2–6, random rational
//! coefficients) on the triangle and the square, solved by rootclip, checked
//! against Newton's method from a grid of starts (an independent heuristic):
//! every Newton root inside the domain (and 1e-9 away from its boundary) must
//! lie in a returned root or cluster box, and certified boxes must be
//! pairwise disjoint. `fuzz_dense [count] [seed]`.
use rootclip::num_rational::BigRational;
use rootclip::solve::{solve, Domain, SolveOptions};
use rootclip::Polynomial;
use std::time::Instant;

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next() % (hi - lo + 1) as u64) as i64
    }
}

fn random_poly(rng: &mut Lcg, deg: u32) -> Polynomial {
    let mut p = Polynomial::zero();
    for a in 0..=deg {
        for b in 0..=deg - a {
            let c = BigRational::new(rng.int(-20, 20).into(), rng.int(1, 9).into());
            p = p.add(&Polynomial::monomial(c, a, b));
        }
    }
    p
}

fn eval(p: &Polynomial, u: f64, v: f64) -> (f64, f64, f64) {
    let (mut val, mut du, mut dv) = (0.0, 0.0, 0.0);
    for (&(a, b), c) in p.terms() {
        let c = rootclip::scalar::rational_to_f64(c);
        val += c * u.powi(a as i32) * v.powi(b as i32);
        if a > 0 {
            du += c * a as f64 * u.powi(a as i32 - 1) * v.powi(b as i32);
        }
        if b > 0 {
            dv += c * b as f64 * u.powi(a as i32) * v.powi(b as i32 - 1);
        }
    }
    (val, du, dv)
}

fn newton_roots(f: &Polynomial, g: &Polynomial) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = Vec::new();
    for i in 0..=20 {
        for j in 0..=20 {
            let (mut u, mut v) = (i as f64 / 20.0, j as f64 / 20.0);
            for _ in 0..60 {
                let (fv, fu, fw) = eval(f, u, v);
                let (gv, gu, gw) = eval(g, u, v);
                let det = fu * gw - fw * gu;
                if det.abs() < 1e-300 {
                    break;
                }
                let du = (fv * gw - fw * gv) / det;
                let dv = (fu * gv - fv * gu) / det;
                u -= du;
                v -= dv;
                if !(u.is_finite() && v.is_finite()) || u.abs() > 10.0 || v.abs() > 10.0 {
                    break;
                }
                if du.abs() + dv.abs() < 1e-15 {
                    break;
                }
            }
            let (fv, _, _) = eval(f, u, v);
            let (gv, _, _) = eval(g, u, v);
            if fv.abs() < 1e-11 && gv.abs() < 1e-11 && !out.iter().any(|r| (r[0] - u).abs() + (r[1] - v).abs() < 1e-8) {
                out.push([u, v]);
            }
        }
    }
    out
}

fn main() {
    let count: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let seed: u64 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut rng = Lcg(seed);
    let (mut misses, mut overlaps, mut incomplete, mut errors, mut roots, mut clusters) = (0, 0, 0, 0, 0, 0);
    let t0 = Instant::now();
    for k in 0..count {
        let domain = if k % 2 == 0 { Domain::Triangle } else { Domain::Square };
        let (df, dg) = (rng.int(2, 6) as u32, rng.int(2, 6) as u32);
        let (f, g) = (random_poly(&mut rng, df), random_poly(&mut rng, dg));
        let sol = match solve(&f, &g, domain, &SolveOptions::default()) {
            Ok(s) => s,
            Err(e) => {
                errors += 1;
                println!("system {k}: error {e}");
                continue;
            }
        };
        if !sol.complete {
            incomplete += 1;
        }
        roots += sol.roots.len();
        clusters += sol.clusters.len();
        for c in &sol.clusters {
            println!("system {k} ({domain:?}): cluster {:?}\n  f = {f}\n  g = {g}", c.bx);
        }
        for (i, a) in sol.roots.iter().enumerate() {
            for b in &sol.roots[i + 1..] {
                if a.bx.u[0] <= b.bx.u[1] && b.bx.u[0] <= a.bx.u[1] && a.bx.v[0] <= b.bx.v[1] && b.bx.v[0] <= a.bx.v[1]
                {
                    overlaps += 1;
                }
            }
        }
        let inside = |u: f64, v: f64| match domain {
            Domain::Triangle => u > 1e-9 && v > 1e-9 && u + v < 1.0 - 1e-9,
            Domain::Square => u > 1e-9 && v > 1e-9 && u < 1.0 - 1e-9 && v < 1.0 - 1e-9,
        };
        for r in newton_roots(&f, &g) {
            if !inside(r[0], r[1]) {
                continue;
            }
            let near = |b: &rootclip::solve::Box2| {
                b.u[0] - 1e-9 <= r[0] && r[0] <= b.u[1] + 1e-9 && b.v[0] - 1e-9 <= r[1] && r[1] <= b.v[1] + 1e-9
            };
            if !sol.roots.iter().any(|x| near(&x.bx)) && !sol.clusters.iter().any(|c| near(&c.bx)) && sol.complete {
                misses += 1;
                println!("system {k} ({domain:?}): MISSED Newton root {r:?}\n  f = {f}\n  g = {g}");
            }
        }
    }
    println!(
        "{count} systems in {:.2} s: {roots} certified roots, {clusters} clusters, {misses} misses, {overlaps} overlapping certified boxes, {incomplete} incomplete, {errors} errors",
        t0.elapsed().as_secs_f64()
    );
}
