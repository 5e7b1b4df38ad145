//! The generator's patches ([`Grid`]): height fields of each family whose
//! `x` and `y` are dyadic affine maps of the parameters (random degrees,
//! clamped or unclamped knot vectors with creases; heights full-precision,
//! coarse or nearly flat, sometimes with a flat edge), and the features on
//! them a ray can be aimed at ([`Target`]): corners, edges, knot lines,
//! creases, knot corners and the interior.

use super::exact::pow2;
use super::generate::Mix;
use rootclip::ray::PatchSpec;

/// A line in the domain a ray can run along.
#[derive(Clone, Copy, Debug)]
pub(super) enum Along {
    /// `u = c`, `v` varying.
    U(f64),
    /// `v = c`.
    V(f64),
    /// The hypotenuse `u + v = 1` of a triangle.
    Hyp,
}

/// A point on a feature of the domain.
#[derive(Clone, Debug)]
pub(super) struct Target {
    pub(super) name: String,
    pub(super) u: f64,
    pub(super) v: f64,
    pub(super) along: Option<Along>,
}

pub(super) fn target(name: impl Into<String>, u: f64, v: f64, along: Option<Along>) -> Target {
    Target {
        name: name.into(),
        u,
        v,
        along,
    }
}

/// A patch with its affine map, domain, and the features to aim at.
pub(super) struct Grid {
    pub(super) spec: PatchSpec,
    pub(super) affine: [f64; 4],
    pub(super) dom: [f64; 4],
    pub(super) targets: Vec<Target>,
    /// On the heights, for the label.
    pub(super) note: String,
    /// `Some(c)`: `∂z/∂u = 0` along the edge `u = c`.
    pub(super) flat_edge: Option<f64>,
}

/// `k/64` for a random `1 ≤ k ≤ 63`.
pub(super) fn dyadic01(rng: &mut Mix) -> f64 {
    rng.range(1, 63) as f64 / 64.0
}

/// Heights and a note on them: full-precision in `[−1, 1)` (most cases),
/// multiples of `1/256` (exact ties: hits exactly on edges), or nearly flat,
/// `c + ε·r` with `ε` down to `2^-50` (a ray at height `c` runs almost in the
/// surface: many hits, or a ridge of near-tangency).
fn heights(rng: &mut Mix, count: usize) -> (Vec<f64>, String) {
    match rng.range(0, 9) {
        0 | 1 => (
            (0..count).map(|_| rng.range(-256, 256) as f64 / 256.0).collect(),
            "coarse z".into(),
        ),
        2 | 3 => {
            let c = rng.signed();
            let e = rng.pick(&[-10, -20, -30, -40, -50]);
            let z = (0..count).map(|_| c + pow2(e) * rng.signed()).collect();
            (z, format!("flat z (2^{e})"))
        }
        _ => ((0..count).map(|_| rng.signed()).collect(), String::new()),
    }
}

/// `[hx, x0, hy, y0]`: grid steps and offsets, dyadic.
fn steps(rng: &mut Mix) -> [f64; 4] {
    let step = [0.25, 0.5, 0.75, 1.0, 1.5];
    let offset = [0.0, -0.5, 0.25, -3.0, 1024.5, 1048576.5, -196608.25];
    [rng.pick(&step), rng.pick(&offset), rng.pick(&step), rng.pick(&offset)]
}

/// The four corners and four edges of `[u0, u1] × [v0, v1]`, and the interior.
fn box_targets(rng: &mut Mix, [u0, u1, v0, v1]: [f64; 4]) -> Vec<Target> {
    let mut out = Vec::new();
    for (cu, cv) in [(u0, v0), (u0, v1), (u1, v0), (u1, v1)] {
        let along = if rng.chance(0.5) { Along::U(cu) } else { Along::V(cv) };
        out.push(target(format!("corner ({cu}, {cv})"), cu, cv, Some(along)));
    }
    let (su, sv) = (u0 + (u1 - u0) * dyadic01(rng), v0 + (v1 - v0) * dyadic01(rng));
    for cu in [u0, u1] {
        out.push(target(format!("edge u={cu}"), cu, sv, Some(Along::U(cu))));
    }
    for cv in [v0, v1] {
        out.push(target(format!("edge v={cv}"), su, cv, Some(Along::V(cv))));
    }
    out.push(target("interior", su, sv, None));
    out
}

/// `α_0 … α_m`: positive, random, in `[1/4, 2)` or (one time in four) over
/// `2^±6`.
fn alphas(rng: &mut Mix, m: usize) -> Vec<f64> {
    let extreme = rng.chance(0.25);
    (0..=m)
        .map(|_| {
            if extreme {
                pow2(rng.range(-6, 6)) * (1.0 + rng.unit())
            } else {
                0.25 + 1.75 * rng.unit()
            }
        })
        .collect()
}

/// Rational patches take rays with `dy = 0` only: no line `u = c` to run along.
fn only_rows(targets: &mut [Target]) {
    for t in targets {
        if matches!(t.along, Some(Along::U(_))) {
            t.along = Some(Along::V(t.v));
        }
    }
}

pub(super) fn tensor_grid(rng: &mut Mix, rational: bool) -> Grid {
    let (m, n) = (rng.range(1, 4) as usize, rng.range(1, 4) as usize);
    let [hx, x0, hy, y0] = steps(rng);
    let (mut z, mut note) = heights(rng, (m + 1) * (n + 1));
    let flat_edge = (m >= 2 && rng.chance(0.2)).then(|| {
        // Rows m and m − 1 equal: ∂z/∂u = 0 along u = 1.
        z.copy_within((m - 1) * (n + 1)..m * (n + 1), m * (n + 1));
        note += " flat edge";
        1.0
    });
    let points = (0..=m)
        .flat_map(|i| (0..=n).map(move |j| (i, j)))
        .map(|(i, j)| [x0 + hx * i as f64, y0 + hy * j as f64, z[i * (n + 1) + j]])
        .collect();
    let weights = rational.then(|| alphas(rng, m).into_iter().flat_map(|a| vec![a; n + 1]).collect());
    let mut targets = box_targets(rng, [0.0, 1.0, 0.0, 1.0]);
    if rational {
        only_rows(&mut targets);
    }
    Grid {
        spec: PatchSpec::Tensor {
            degree: [m, n],
            points,
            weights,
        },
        affine: [hx * m as f64, x0, hy * n as f64, y0],
        dom: [0.0, 1.0, 0.0, 1.0],
        targets,
        note,
        flat_edge,
    }
}

pub(super) fn triangle_grid(rng: &mut Mix) -> Grid {
    let n = rng.range(1, 4) as usize;
    let [hx, x0, hy, y0] = steps(rng);
    let (mut z, mut note) = heights(rng, (n + 1) * (n + 2) / 2);
    let flat_edge = (n >= 2 && rng.chance(0.2)).then(|| {
        // z(1, j) = z(0, j): ∂z/∂u = 0 along u = 0 (points (i, j) stored
        // j outer, i inner).
        let mut start = 0;
        for j in 0..n {
            z[start + 1] = z[start];
            start += n - j + 1;
        }
        note += " flat edge";
        0.0
    });
    let points = (0..=n)
        .flat_map(|j| (0..=n - j).map(move |i| (i, j)))
        .zip(&z)
        .map(|((i, j), &z)| [x0 + hx * i as f64, y0 + hy * j as f64, z])
        .collect();
    let r = dyadic01(rng);
    let targets = vec![
        target("corner (0, 0)", 0.0, 0.0, Some(Along::U(0.0))),
        target(
            "corner (1, 0)",
            1.0,
            0.0,
            Some(if rng.chance(0.5) { Along::V(0.0) } else { Along::Hyp }),
        ),
        target(
            "corner (0, 1)",
            0.0,
            1.0,
            Some(if rng.chance(0.5) { Along::U(0.0) } else { Along::Hyp }),
        ),
        target("edge u=0", 0.0, r, Some(Along::U(0.0))),
        target("edge v=0", r, 0.0, Some(Along::V(0.0))),
        target("hypotenuse", r, 1.0 - r, Some(Along::Hyp)),
        target("interior", r / 2.0, (1.0 - r) / 2.0, None),
    ];
    Grid {
        spec: PatchSpec::Triangle {
            degree: n,
            points,
            weights: None,
        },
        affine: [hx * n as f64, x0, hy * n as f64, y0],
        dom: [0.0, 1.0, 0.0, 1.0],
        targets,
        note,
        flat_edge,
    }
}

/// A knot vector of degree `p` on the domain `[0, K]` with dyadic interior
/// knots, often one of multiplicity `p` (a crease); clamped, or (one time in
/// four) unclamped (`p` knots below 0 and above `K`: the domain's edges do
/// not interpolate). And the interior values, the crease's flagged, and
/// whether the vector is clamped.
fn knot_vector(rng: &mut Mix, p: usize) -> (Vec<f64>, Vec<(f64, bool)>, bool) {
    let count = rng.range(1, 3) as usize;
    let crease = rng.chance(0.6).then(|| rng.range(0, count as i64 - 1) as usize);
    let clamped = rng.chance(0.75);
    let end_step = |rng: &mut Mix| if clamped { 0.0 } else { rng.pick(&[0.5, 1.0]) };
    let h0 = end_step(rng);
    // h0·k − h0·p, not −h0·(p − k): no −0.0 in the vector.
    let mut knots: Vec<f64> = (0..=p).map(|k| h0 * k as f64 - h0 * p as f64).collect();
    let (mut at, mut interior) = (0.0, Vec::new());
    for k in 0..count {
        at += rng.pick(&[0.5, 0.75, 1.0, 1.5, 2.0]);
        let mult = if crease == Some(k) {
            p
        } else if p >= 3 && rng.chance(0.2) {
            2
        } else {
            1
        };
        knots.extend(std::iter::repeat_n(at, mult));
        interior.push((at, crease == Some(k)));
    }
    at += rng.pick(&[0.5, 1.0, 1.5]);
    let h1 = end_step(rng);
    knots.extend((0..=p).map(|k| at + h1 * k as f64));
    (knots, interior, clamped)
}

pub(super) fn bspline_grid(rng: &mut Mix, rational: bool) -> Grid {
    let (p, q) = (rng.range(2, 4) as usize, rng.range(2, 4) as usize);
    let (ku, iu, clamped_u) = knot_vector(rng, p);
    let (kv, iv, clamped_v) = knot_vector(rng, q);
    let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
    let [hx, x0, hy, y0] = steps(rng);
    // x = p·hx·u + x0: the points sit at p·hx·(Greville) = hx·(sum of p knots).
    let sum = |k: &[f64], i: usize, p: usize| k[i + 1..=i + p].iter().sum::<f64>();
    let (mut z, mut note) = heights(rng, nu * nv);
    if !(clamped_u && clamped_v) {
        note += " unclamped";
    }
    let flat_edge = (clamped_u && rng.chance(0.2)).then(|| {
        // The last two rows equal: ∂z/∂u = 0 along u = U1.
        z.copy_within((nu - 2) * nv..(nu - 1) * nv, (nu - 1) * nv);
        note += " flat edge";
        ku[nu]
    });
    let points = (0..nu)
        .flat_map(|i| (0..nv).map(move |j| (i, j)))
        .map(|(i, j)| [x0 + hx * sum(&ku, i, p), y0 + hy * sum(&kv, j, q), z[i * nv + j]])
        .collect();
    let weights = rational.then(|| alphas(rng, nu - 1).into_iter().flat_map(|a| vec![a; nv]).collect());
    let dom = [ku[p], ku[nu], kv[q], kv[nv]];
    let mut targets = box_targets(rng, dom);
    let crease = |c: bool| if c { " (crease)" } else { "" };
    let (su, sv) = (dom[1] * dyadic01(rng), dom[3] * dyadic01(rng));
    for &(k, c) in &iu {
        targets.push(target(format!("knot u={k}{}", crease(c)), k, sv, Some(Along::U(k))));
        targets.push(target(
            format!("knot u={k}{} at v=0", crease(c)),
            k,
            0.0,
            Some(Along::V(0.0)),
        ));
    }
    for &(k, c) in &iv {
        targets.push(target(format!("knot v={k}{}", crease(c)), su, k, Some(Along::V(k))));
    }
    for &(a, ca) in &iu {
        for &(b, cb) in &iv {
            let along = if rng.chance(0.5) { Along::U(a) } else { Along::V(b) };
            targets.push(target(
                format!("knot corner ({a}{}, {b}{})", crease(ca), crease(cb)),
                a,
                b,
                Some(along),
            ));
        }
    }
    if rational {
        only_rows(&mut targets);
    }
    Grid {
        spec: PatchSpec::Bspline {
            degree: [p, q],
            knots_u: ku,
            knots_v: kv,
            points,
            weights,
        },
        affine: [hx * p as f64, x0, hy * q as f64, y0],
        dom,
        targets,
        note,
        flat_edge,
    }
}
