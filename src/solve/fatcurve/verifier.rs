//! The sliver proofs of a verified float clip: [`Verifier::sliver_free`]
//! (whose docs carry the soundness argument), the exit pieces ([`Piece`])
//! its sweeps reduce to, and the budgets that bound their work.

use super::curves::{Fat, Linear, Quadratic};
use crate::scalar::geo::Geo;
use std::cell::Cell;

/// The data of [`Verifier::sliver_free`] shared by the three slivers of one
/// clip: the fat line `|L| ≤ δ_a`, `L = l0 + l1 s + l2 t`, and the other fat
/// curve `|P| ≤ δ_b` as a quadratic `P` (a line has zero second-order terms),
/// with the products of `∇²P / 2` its proofs use.
pub(super) struct Verifier<G> {
    l: [G; 3],
    da: f64,
    /// `[−δ_a, δ_a]`.
    lambda: G,
    /// `P` (a line as a quadratic with zero second-order terms).
    q: Quadratic<G>,
    db: f64,
    /// The strip's direction `v = (l2, −l1)`.
    v: (G, G),
    /// `(∇²P / 2) v`.
    hv: (G, G),
    /// `vᵀ (∇²P / 2) v`.
    vhv: G,
    /// `wᵀ (∇²P / 2) w` for the directions `w` along `u = const`
    /// (`(0, 1)`), `v = const` (`(1, 0)`) and `w = const` (`(1, −1)`).
    hw: [G; 3],
    /// What is left of [`CLEAR_BUDGET`] in the current proof.
    budget: Cell<u32>,
}

impl<G: Geo> Verifier<G> {
    /// The verifier of a fat-curve pair whose first curve is a line.
    pub(super) fn of(fats: &[Fat<G>]) -> Option<Self> {
        match fats {
            [Fat::Line(line, da), other] => Some(Self::new(line, *da, other)),
            _ => None,
        }
    }

    fn new(line: &Linear<G>, da: f64, other: &Fat<G>) -> Self {
        let zero = G::pt(0.0);
        let (q, db) = match other {
            Fat::Line(l, db) => ([l.c[0], l.c[1], l.c[2], zero, zero, zero], *db),
            Fat::Conic(q, db) => (q.c, *db),
        };
        let quadratic = Quadratic { c: q };
        let [_, l1, l2] = line.c;
        let v = (l2, -l1);
        let c4h = q[4] * G::pt(0.5);
        let hv = (q[3] * v.0 + c4h * v.1, c4h * v.0 + q[5] * v.1);
        Verifier {
            l: line.c,
            da,
            lambda: G::pt(-da).hull(G::pt(da)),
            q: quadratic,
            db,
            v,
            hv,
            vhv: v.0 * hv.0 + v.1 * hv.1,
            hw: [q[5], q[3], q[3] - q[4] + q[5]],
            budget: Cell::new(CLEAR_BUDGET),
        }
    }

    /// `P` and `∇P` at `(s, t)`, sharing the products: with `a = c3 s`,
    /// `b = c4 t`, `c = c5 t`, `d = c4 s`, `i = c1 + a + b` and `j = c2 + c`,
    /// `P = c0 + s i + t j`, `∂P/∂s = i + a`, `∂P/∂t = j + c + d` (six
    /// products and eight sums; value and gradient apart take ten products).
    fn jet(&self, (s, t): (G, G)) -> (G, G, G) {
        let c = &self.q.c;
        let (a, b, cc, d) = (c[3] * s, c[4] * t, c[5] * t, c[4] * s);
        let i = c[1] + a + b;
        let j = c[2] + cc;
        (c[0] + s * i + t * j, i + a, j + cc + d)
    }

    /// `aᵀ (∇²P / 2) b`.
    fn half_hessian(&self, a: (G, G), b: (G, G)) -> G {
        let c = &self.q.c;
        c[3] * a.0 * b.0 + c[4] * G::pt(0.5) * (a.0 * b.1 + a.1 * b.0) + c[5] * a.1 * b.1
    }

    /// Proves (`true`) that no point of the tri-box with barycentric
    /// coordinate `σ = (u, v, w)[k] ≤ m` lies both in the fat line and in the
    /// other fat curve; `false` means "not proven".
    ///
    /// # The argument
    /// In coordinates `(σ, τ)` (`τ = v` for `k = 0`, else `u`) the tri-box
    /// is `T = {σ, τ ≥ 0, σ + τ ≤ 1}` and `L = l0' + lσ σ + lτ τ`. Either
    /// `L`'s values at the four corners of the (convex) sliver
    /// `Ω0 = T ∩ {σ ≤ m}` lie beyond `δ_a` on one side, and the strip misses
    /// it; or, with `lτ ≠ 0` proven, the strip is swept by the parallel lines
    /// `L = λ`, `|λ| ≤ δ_a`, which run along `d = ±v / lτ` (`dσ/dh = 1`). From
    /// a point `p` of `Ω = Ω0 ∩ strip` follow `p + h d`, `h ≥ 0`: it stays on
    /// its line, so it leaves `Ω` through an *exit piece*: the end segment
    /// `σ = m` (within `T`), or the part of edge `τ = 0` or `σ + τ = 1` in
    /// the strip with `σ ≤ m` (an exit only if the lines cross it outward).
    /// So `p = x − h d` for an exit point `x` and `0 ≤ h ≤ σ(x)`, and since
    /// `P` has degree ≤ 2, `P(x − h d) = E − D h + C h²` exactly, with
    /// `E = P(x)`, `D = ∇P(x)·d`, `C = dᵀ(∇²P/2)d`. Each piece is a segment
    /// `x0 + μ f`; `E` and `D` are enclosed over it by their (exact) Taylor
    /// expansions at `x0`, and [`bounded_away`] proves `E − D h + C h² > δ_b`
    /// (or `< −δ_b`) on `[0, σ_max]`. Then no point of `Ω` has `|P| ≤ δ_b`.
    /// The sweep is tried first over the *slab* `{0 ≤ σ ≤ m}` of the strip,
    /// a superset of `Ω` that ignores the tri-box's edges: every path then
    /// runs `h ≤ m` from the end line, and one piece is the proof, with no
    /// exit lengths and no edge pieces. Where `L` takes all of
    /// `[−δ_a, δ_a]` on both sides `σ = 0` and `σ = m` of the sliver
    /// ([`Verifier::strip_spans`], the usual case) the slab is `Ω` itself;
    /// elsewhere the sweep with exits follows a failed try. (Together about
    /// 10% of a certified solve of Example 3.)
    /// A strip (nearly) parallel to the end segment, `lτ` not proven
    /// non-zero, is swept across instead ([`Verifier::swept_across`]), and,
    /// where that fails, along its lines with `dτ/dh = 1`
    /// ([`Verifier::swept_along_tau`]); both need `lσ ≠ 0`.
    pub(super) fn sliver_free(&self, k: usize, m: f64) -> bool {
        let line = self.sliver_line(k, m);
        let da = self.da;
        let corners = [line.l0, line.top, line.base, line.far];
        if corners.iter().all(|x| x.lower() > da) || corners.iter().all(|x| x.upper() < -da) {
            return true;
        }
        self.budget.set(CLEAR_BUDGET);
        if line.lt.nonzero() {
            self.swept_along_sigma(k, m, line)
        } else {
            self.swept_across(k, m, line) || (line.ls.nonzero() && self.swept_along_tau(k, m, line))
        }
    }

    /// `L` in the frame of sliver `k` ([`Verifier::frame_line`]) with its
    /// values at the corners of the sliver `{σ ≤ m}`, computed once for
    /// the corner test and the sweeps.
    fn sliver_line(&self, k: usize, m: f64) -> SliverLine<G> {
        let (l0, ls, lt) = self.frame_line(k);
        let sig_m = G::pt(m);
        let base = l0 + ls * sig_m;
        SliverLine {
            l0,
            ls,
            lt,
            top: l0 + lt,
            base,
            far: base + lt * (G::pt(1.0) - sig_m),
        }
    }

    /// `L = l0' + lσ σ + lτ τ` in the frame of sliver `k` (see
    /// [`frame_point`]): `(l0', lσ, lτ)`.
    fn frame_line(&self, k: usize) -> (G, G, G) {
        let [a0, a1, a2] = self.l;
        match k {
            0 => (a0, a1, a2),
            1 => (a0, a2, a1),
            _ => (a0 + a2, -a2, a1 - a2),
        }
    }

    /// [`Verifier::sliver_free`] with `lτ ≠ 0`: the strip's lines run along
    /// `d` with `dσ/dh = 1`, so `h ≤ σ(x)`.
    fn swept_along_sigma(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            l0,
            ls,
            lt,
            top,
            base,
            far,
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let r = one / lt;
        let r2 = square(r);
        // d = v / σ(v) with σ(v) = lτ, except −lτ for k = 1.
        let sign = |x: G| if k == 1 { -x } else { x };
        let c = self.vhv * r2;
        let slope = -ls * r;
        // The end line σ = m, where L = λ at τ = (λ − base) / lτ; along it
        // x = x0 + μ w r, w = (0, 1), (1, 0) or (1, −1), expanded at λc
        // (τ0 = (λc − base) / lτ).
        let end_piece = |lc: G| {
            let tau0 = (lc - base) * r;
            let (p, gs, gt) = self.jet(frame_point(k, sig_m, tau0));
            let (gw, hwv) = match k {
                0 => (gt, self.hv.1),
                1 => (gs, self.hv.0),
                _ => (gs - gt, self.hv.0 - self.hv.1),
            };
            let gv = gs * self.v.0 + gt * self.v.1;
            let piece = Piece {
                p,
                b: gw * r,
                a: self.hw[k] * r2,
                d0: sign(gv * r),
                d1: sign(G::pt(2.0) * hwv * r2),
                c,
                db: self.db,
            };
            (piece, tau0)
        };
        // The slab: a point x of `Ω` lies on the level line `L = L(x)`,
        // which meets the end line after `h = m − σ(x) ∈ [0, m]`, and
        // `L(x)` lies in the hull Λ' of `L` at the sliver's four corners
        // (the sliver is convex, `L` linear), within `[−δ_a, δ_a]`: one piece
        // over Λ' with `h ≤ m`, exits ignored, covers `Ω` (with the slab of
        // the strip beyond the tri-box's edges, where the lines leave it).
        // Where `L` spans `[−δ_a, δ_a]` on both sides `σ = 0` and `σ = m`
        // within the tri-box ([`Verifier::strip_spans`], the usual case), the
        // strip crosses the slab inside the tri-box (convex, so the level
        // lines between stay in it): Λ' is all of `[−δ_a, δ_a]`, the slab is
        // `Ω` itself, no edge is an exit and this piece is the whole proof.
        // Elsewhere the slab may reach beyond an edge, where `P` may vanish:
        // it gets [`SLAB_TRY_BUDGET`] halvings, then the sweep with exits.
        let both = self.strip_spans((l0, top)) && self.strip_spans((base, far));
        let lam = if both {
            Some(self.lambda)
        } else {
            clamp_hull(l0.hull(top).hull(base).hull(far), self.lambda)
        };
        let Some(lam) = lam else { return true };
        let lc = if both {
            zero
        } else {
            G::pt(0.5 * (lam.lower() + lam.upper()))
        };
        let (piece, _) = end_piece(lc);
        if !both {
            self.budget.set(SLAB_TRY_BUDGET);
        }
        if piece.clear(lam - lc, &|_: G| sig_m, SPLITS, &self.budget) {
            return true;
        }
        if both {
            return false;
        }
        self.budget.set(CLEAR_BUDGET);
        // The end segment: σ = m, L = λ between `base` and `far` (τ from 0
        // to 1 − m), |λ| ≤ δ_a, expanded at the middle λc of that range.
        if let Some(lam) = clamp_hull(base.hull(far), self.lambda) {
            let lc = G::pt(0.5 * (lam.lower() + lam.upper()));
            let (piece, tau0) = end_piece(lc);
            // Back along d from x, σ falls by h and τ by slope·h: the path
            // leaves the tri-box (and never returns) at τ = 0 or σ + τ = 1.
            let h_max = |mu: G| {
                let tau = tau0 + mu * r;
                let mut h = m;
                if slope.lower() > 0.0 {
                    h = h.min((G::pt(tau.upper()) / G::pt(slope.lower())).upper());
                }
                let grow = -(one + slope);
                if grow.lower() > 0.0 {
                    h = h.min(((one - sig_m - G::pt(tau.lower())) / G::pt(grow.lower())).upper());
                }
                path_bound(h, m)
            };
            if !piece.clear(lam - lc, &h_max, SPLITS, &self.budget) {
                return false;
            }
        }
        // The edges τ = 0 (an exit where τ falls along d: lσ/lτ > 0) and
        // σ + τ = 1 (where σ + τ grows: 1 − lσ/lτ > 0), parametrized by σ
        // ∈ [0, m], which bounds h.
        let dir = (sign(self.v.0 * r), sign(self.v.1 * r));
        let by_sigma = |sig: G| path_bound(sig.upper(), m);
        let range = zero.hull(sig_m);
        (slope.lower() >= 0.0 || self.edge_clear(k, ((zero, zero), (one, zero)), (l0, ls), range, dir, c, &by_sigma))
            && ((one + slope).upper() <= 0.0
                || self.edge_clear(k, ((zero, one), (one, -one)), (top, ls - lt), range, dir, c, &by_sigma))
    }

    /// Whether `L` takes every value of `[−δ_a, δ_a]` on a side of the slab
    /// `0 ≤ σ ≤ m` within the tri-box, given `L` at the side's ends: `l0'`
    /// and `l0' + lτ` (`σ = 0`, `τ ∈ [0, 1]`) or `base` and `far` (`σ = m`,
    /// `τ ∈ [0, 1 − m]`), for every member of the enclosures.
    fn strip_spans(&self, (a, b): (G, G)) -> bool {
        let da = self.da;
        a.upper().min(b.upper()) <= -da && a.lower().max(b.lower()) >= da
    }

    /// [`Verifier::sliver_free`] with `lσ ≠ 0` (for a strip parallel, or
    /// nearly, to the end segment, where `lτ` is not proven non-zero): the
    /// strip's lines run along `d = (e, 1)` in `(σ, τ)`, `e = −lτ/lσ`, so
    /// `h ≤ τ(x)`. The exits are the edge `σ + τ = 1` (where `1 + e > 0`),
    /// `σ = 0` (where `e < 0`) and the end segment `σ = m` (where `e > 0`);
    /// `τ` grows along `d`, so `τ = 0` is never one.
    fn swept_along_tau(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            lt, ls, top, base, l0, ..
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let e = -lt / ls;
        let dir = frame_dir(k, e, one);
        let c = self.half_hessian(dir, dir);
        let by_tau = |tau: G| path_bound(tau.upper(), 1.0);
        let by_sigma = |sig: G| path_bound((one - sig).upper(), 1.0);
        let up = (zero, one);
        ((one + e).upper() <= 0.0
            || self.edge_clear(
                k,
                ((zero, one), (one, -one)),
                (top, ls - lt),
                zero.hull(sig_m),
                dir,
                c,
                &by_sigma,
            ))
            && (e.lower() >= 0.0 || self.edge_clear(k, ((zero, zero), up), (l0, lt), zero.hull(one), dir, c, &by_tau))
            && (e.upper() <= 0.0
                || self.edge_clear(
                    k,
                    ((sig_m, zero), up),
                    (base, lt),
                    zero.hull(one - sig_m),
                    dir,
                    c,
                    &by_tau,
                ))
    }

    /// [`Verifier::sliver_free`] across the strip, for one (nearly) parallel
    /// to the end segment (`lτ` not proven non-zero), where the strip's own
    /// lines run along the end segment and `P`'s extremum on them lies
    /// inside the sliver: `d = (1, 0)` in `(σ, τ)`, so `h ≤ σ(x)`. The path
    /// now leaves the strip too: the exits are the end segment, the edge
    /// `σ + τ = 1` and the strip's side `L = ±δ_a` where `±lσ > 0`, taken
    /// (for `lσ ≠ 0`) as `σ = (±δ_a − l0' − lτ τ) / lσ`, `τ ∈ [0, 1 − σ]`
    /// (a superset: points beyond the sliver only add checks); with `lσ`
    /// not proven non-zero, no proof.
    fn swept_across(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            lt, ls, top, base, l0, ..
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let dir = frame_dir(k, one, zero);
        let c = self.half_hessian(dir, dir);
        let by_sigma = |sig: G| path_bound(sig.upper(), m);
        let by_m = |_: G| sig_m;
        let up = (zero, one);
        if !ls.nonzero()
            || !self.edge_clear(
                k,
                ((sig_m, zero), up),
                (base, lt),
                zero.hull(one - sig_m),
                dir,
                c,
                &by_m,
            )
            || !self.edge_clear(
                k,
                ((zero, one), (one, -one)),
                (top, ls - lt),
                zero.hull(sig_m),
                dir,
                c,
                &by_sigma,
            )
        {
            return false;
        }
        let r = one / ls;
        let f = (-lt * r, one);
        for lam in [self.da, -self.da] {
            // The side's outward normal is ±∇L: an exit where ±lσ > 0.
            let exit = if lam > 0.0 { ls.upper() > 0.0 } else { ls.lower() < 0.0 };
            if !exit {
                continue;
            }
            // σ at τ = 0, and its range over τ ∈ [0, 1].
            let s0 = (G::pt(lam) - l0) * r;
            let sig = s0.hull(s0 + f.0);
            if sig.lower() > m || sig.upper() < 0.0 {
                continue;
            }
            let tau = zero.hull(G::pt((one - G::pt(sig.lower().max(0.0))).upper()));
            let h_of = |t: G| path_bound((s0 + f.0 * t).upper(), m);
            if !self.edge_clear(k, ((s0, zero), f), (G::pt(lam), zero), tau, dir, c, &h_of) {
                return false;
            }
        }
        true
    }

    /// Proves `|P(x − h d)| > δ_b` (one sign) for the points `x = o + x f` of
    /// an edge (`(o, f)` in the frame, the parameter `x` in `range`) where
    /// `|L| ≤ δ_a`, `L = c0 + c1 x` along it, and `0 ≤ h ≤ h_of(x)`; `d` is
    /// `dir` in `(s, t)`, `c = dᵀ(∇²P/2)d`. The piece is expanded at the
    /// middle of its parameter range (see [`Piece`]).
    #[allow(clippy::too_many_arguments)]
    fn edge_clear(
        &self,
        k: usize,
        ((o_s, o_t), f): ((G, G), (G, G)),
        (c0, c1): (G, G),
        range: G,
        dir: (G, G),
        c: G,
        h_of: &impl Fn(G) -> G,
    ) -> bool {
        let da = self.da;
        let range = if c1.nonzero() {
            let (x, y) = ((G::pt(-da) - c0) / c1, (G::pt(da) - c0) / c1);
            clamp_hull(x.hull(y), range)
        } else {
            let l = c0 + c1 * range;
            (l.lower() <= da && l.upper() >= -da).then_some(range)
        };
        let Some(range) = range else { return true };
        let mid = G::pt(0.5 * (range.lower() + range.upper()));
        let f_st = frame_dir(k, f.0, f.1);
        let (p, gs, gt) = self.jet(frame_point(k, o_s + mid * f.0, o_t + mid * f.1));
        let piece = Piece {
            p,
            b: gs * f_st.0 + gt * f_st.1,
            a: self.half_hessian(f_st, f_st),
            d0: gs * dir.0 + gt * dir.1,
            d1: G::pt(2.0) * self.half_hessian(f_st, dir),
            c,
            db: self.db,
        };
        piece.clear(range - mid, &|mu: G| h_of(mid + mu), SPLITS, &self.budget)
    }
}

/// `L = l0' + lσ σ + lτ τ` in the frame of a sliver `{σ ≤ m}`, with its
/// values at the sliver's corners `(0, 1)` (`top`), `(m, 0)` (`base`) and
/// `(m, 1 − m)` (`far`); `l0'` is the value at `(0, 0)`.
#[derive(Clone, Copy)]
struct SliverLine<G> {
    l0: G,
    ls: G,
    lt: G,
    top: G,
    base: G,
    far: G,
}

/// The sliver frame's point `(σ, τ)` in `(s, t)`: `σ` is the barycentric
/// coordinate `k` of the tri-box and `τ` the next one, `v` for `k = 0`, else
/// `u`: `k = 0`: `(σ, τ)`; `k = 1`: `(τ, σ)`; `k = 2`: `(τ, 1 − σ − τ)`.
fn frame_point<G: Geo>(k: usize, sig: G, tau: G) -> (G, G) {
    let (s, t) = frame_dir(k, sig, tau);
    if k == 2 {
        (s, G::pt(1.0) + t)
    } else {
        (s, t)
    }
}

/// The linear part of [`frame_point`]: a direction `(σ, τ)` in `(s, t)`.
fn frame_dir<G: Geo>(k: usize, a: G, b: G) -> (G, G) {
    match k {
        0 => (a, b),
        1 => (b, a),
        _ => (b, -a - b),
    }
}

/// `G::pt` of an upper bound `h` on the length of a backward path, within
/// `[0, cap]` for a `cap` every path obeys (`m` where `h ≤ σ(x) ≤ m`, 1 where
/// `h ≤ τ(x) ≤ 1`), and `cap` itself for a NaN bound: never a bound that
/// would cover less of the path.
fn path_bound<G: Geo>(h: f64, cap: f64) -> G {
    G::pt(if h.is_nan() { cap } else { h.clamp(0.0, cap) })
}

/// How often [`Piece::clear`] may halve a piece that fails as a whole.
const SPLITS: u32 = 12;

/// How many halvings [`Piece::clear`] may make in one
/// [`Verifier::sliver_free`]: they go deep only next to the point that makes
/// a proof tight (the minimum of a conic touching the sliver's side, found
/// by the float clip to ~2⁻²⁰ of the tri-box), so a failing proof stays
/// cheaper than the enclosure clip it falls back to.
const CLEAR_BUDGET: u32 = 48;

/// How many halvings the slab try of [`Verifier::swept_along_sigma`] may make
/// where the strip leaves the tri-box within the slab, before the sweep with
/// exits: there the try usually succeeds (the slab beyond the edge is small)
/// or needs the halvings the sweep's end piece would make anyway (a bound
/// `m` set by `P = 0` where the strip meets an edge). Measured on the
/// paper's examples (certified `hc`, no probes): 0 halvings is slower than
/// the sweep alone on Example 3, 8 takes 5–7% off it, 16 no more.
const SLAB_TRY_BUDGET: u32 = 8;

/// `P(x0 + μ f − h d) = E(μ) − D(μ) h + C h²` on an exit piece of
/// [`Verifier::sliver_free`]: exactly `E = p + b μ + a μ²`, `D = d0 + d1 μ`.
struct Piece<G> {
    p: G,
    b: G,
    a: G,
    d0: G,
    d1: G,
    c: G,
    db: f64,
}

impl<G: Geo> Piece<G> {
    /// Proves `|P| > δ_b` (one sign) for `μ ∈ mu`, `0 ≤ h ≤ h_max(μ-range)`;
    /// where the whole piece fails, its halves are tried (`splits` levels,
    /// each halving taken from `budget`):
    /// [`bounded_away`] bounds `E` and `D` separately, which loses the
    /// coupling through `μ` on a long piece.
    fn clear(&self, mu: G, h_max: &impl Fn(G) -> G, splits: u32, budget: &Cell<u32>) -> bool {
        let d = self.d0 + self.d1 * mu;
        let h = h_max(mu);
        let e = self.p + mu * self.b + square(mu) * self.a;
        if bounded_away(e, d, self.c, h, self.db)
            || bounded_away(quadratic_range(self.p, self.b, self.a, mu), d, self.c, h, self.db)
        {
            return true;
        }
        if splits == 0 || budget.get() == 0 {
            return false;
        }
        budget.set(budget.get() - 1);
        let (lo, hi) = (mu.lower(), mu.upper());
        let mid = 0.5 * (lo + hi);
        if !(lo < mid && mid < hi) {
            return false;
        }
        self.clear(G::pt(lo).hull(G::pt(mid)), h_max, splits - 1, budget)
            && self.clear(G::pt(mid).hull(G::pt(hi)), h_max, splits - 1, budget)
    }
}

/// `{x² : x ∈ a}` (not `a · a`, which is negative where `a` straddles 0).
fn square<G: Geo>(a: G) -> G {
    if a.lower() >= 0.0 || a.upper() <= 0.0 {
        a * a
    } else {
        let m = G::pt(a.mag());
        G::pt(0.0).hull(m * m)
    }
}

/// An enclosure of `{p + b μ + a μ² : μ ∈ mu}` that is tight for a wide
/// `mu` (the sum of the terms' enclosures is not: it treats `μ` and `μ²` as
/// independent): the values at the ends of `mu`, and at the vertex
/// `−b / (2a)` if it may lie in `mu`.
fn quadratic_range<G: Geo>(p: G, b: G, a: G, mu: G) -> G {
    let at = |x: f64| {
        let x = G::pt(x);
        p + x * (b + a * x)
    };
    let ends = at(mu.lower()).hull(at(mu.upper()));
    if !a.nonzero() {
        // The vertex is anywhere (or absent): keep the term-wise enclosure.
        return ends.hull(p + mu * b + square(mu) * a);
    }
    let two = G::pt(2.0);
    let vertex = -b / (two * a);
    if vertex.upper() < mu.lower() || vertex.lower() > mu.upper() {
        ends
    } else {
        ends.hull(p - square(b) / (two * two * a))
    }
}

/// `a ∩ b` as an enclosure, `None` when provably empty.
fn clamp_hull<G: Geo>(a: G, b: G) -> Option<G> {
    let (lo, hi) = (a.lower().max(b.lower()), a.upper().min(b.upper()));
    (lo <= hi).then(|| G::pt(lo).hull(G::pt(hi)))
}

/// Proves `E − D h + C h² > δ` for all `h ∈ [0, h_max]` and all members of
/// the enclosures `e`, `d`, `c`, or `< −δ` for all of them. For `h ≥ 0` the
/// expression is at least `g(h) = E_lo − D_hi h + C_lo h²`, whose minimum on
/// the interval is at an end, or at the vertex `h* = D_hi / (2 C_lo)` when
/// `g` is convex and falls at 0; the mirror image bounds it from above.
fn bounded_away<G: Geo>(e: G, d: G, c: G, h_max: G, delta: f64) -> bool {
    let above = |e_lo: f64, d_hi: f64, c_lo: f64| {
        // NaN anywhere proves nothing.
        if e_lo.is_nan() || d_hi.is_nan() || c_lo.is_nan() || e_lo <= delta {
            return false;
        }
        let (e, d, c) = (G::pt(e_lo), G::pt(d_hi), G::pt(c_lo));
        let at_end = (e - d * h_max + c * h_max * h_max).lower();
        if at_end.is_nan() || at_end <= delta {
            return false;
        }
        if d_hi > 0.0 && c_lo > 0.0 {
            let two = G::pt(2.0);
            let vertex = d / (two * c);
            // h* beyond h_max: g falls on the whole interval, minimum at h_max.
            return vertex.lower() >= h_max.upper() || (e - d * vertex / two).lower() > delta;
        }
        true
    };
    above(e.lower(), d.upper(), c.lower()) || above(-e.upper(), -d.lower(), -c.upper())
}

#[cfg(test)]
mod tests {
    use super::super::{proposed_and_verified, ClipBounds};
    use super::*;
    use crate::scalar::geo::GeoIv;
    use crate::scalar::point;
    use inari::Interval;

    /// The verified float clip never claims too much, checked independently
    /// with inari: on random fat lines and fat conics (and pairs of fat
    /// lines) through a random point, every point proven (by direct interval
    /// evaluation) to lie in the tri-box and in both fat regions satisfies the
    /// returned bounds, and an `Empty` claim has no such point. The points
    /// are where the minima sit: crossings of the strip's lines
    /// (`L = λ`, 41 values of `λ`) with `P = 0` and `P = ±δ_b`, crossings of
    /// the tri-box edges with `L = ±δ_a` and with `P = ±δ_b`, and a grid.
    #[test]
    fn verified_clips_hold_every_feasible_point() {
        let mut rng = crate::rng::Rng(0x5eed_c11b);
        let (mut kept, mut empty, mut declined, mut checked) = (0, 0, 0, 0);
        let (mut proofs, mut refuted, mut slab) = ([0; 4], 0, [0; 2]);
        for case in 0..500 {
            let mut r = || rng.next_f64();
            let (s0, t0) = (1.4 * r() - 0.2, 1.4 * r() - 0.2);
            let log_uniform = |x: f64, lo: f64, hi: f64| (lo.ln() + x * (hi.ln() - lo.ln())).exp();
            let (da, db) = (log_uniform(r(), 1e-9, 0.3), log_uniform(r(), 1e-9, 0.3));
            let (mut g1, mut g2) = (2.0 * r() - 1.0, 2.0 * r() - 1.0);
            // Strips parallel to a side of the tri-box (lτ = 0 in frame k = 0,
            // 1 or 2), which symmetric systems produce.
            match case % 7 {
                1 => g2 = 0.0,
                2 => g1 = 0.0,
                3 => g2 = g1,
                _ => {}
            }
            let l = [-(g1 * s0 + g2 * t0) + 0.1 * da * (2.0 * r() - 1.0), g1, g2];
            let (h1, h2) = (2.0 * r() - 1.0, 2.0 * r() - 1.0);
            let curv = [0.0, 0.3, 1.0, 4.0][case % 4];
            let (q3, q4, q5) = (
                curv * (2.0 * r() - 1.0),
                curv * (2.0 * r() - 1.0),
                curv * (2.0 * r() - 1.0),
            );
            // Q(s, t) = h1 (s − s0) + h2 (t − t0) + the quadratic terms in (s − s0, t − t0).
            let q = [
                -(h1 * s0 + h2 * t0) + q3 * s0 * s0 + q4 * s0 * t0 + q5 * t0 * t0,
                h1 - 2.0 * q3 * s0 - q4 * t0,
                h2 - q4 * s0 - 2.0 * q5 * t0,
                q3,
                q4,
                q5,
            ];
            let conic = case % 5 != 0;
            // Two lines in three with coefficient enclosures 2e-12 wide (as
            // the solver's are, so a zero coefficient is not proven non-zero)
            // or 0.06 wide (so strips with slopes of both signs use every
            // exit piece); the strip is then the union over the members, and
            // the points below are taken for the corner members too.
            let lw = [0.0, 1e-12, 0.03][case % 3];
            let line = Linear {
                c: l.map(|x| GeoIv::pt(x - lw).hull(GeoIv::pt(x + lw))),
            };
            let fat_line = Fat::Line(line, da);
            let other = if conic {
                Fat::Conic(Quadratic { c: q.map(GeoIv::pt) }, db)
            } else {
                Fat::Line(
                    Linear {
                        c: [q[0], q[1], q[2]].map(GeoIv::pt),
                    },
                    db,
                )
            };
            let claim = proposed_and_verified(&[fat_line, other]);
            let verifier = Verifier::new(&line, da, &other);
            let qs = if conic { q } else { [q[0], q[1], q[2], 0.0, 0.0, 0.0] };
            let members: Vec<[f64; 3]> = if lw > 0.0 {
                (0..8)
                    .map(|b| [0, 1, 2].map(|i| l[i] + if b >> i & 1 == 1 { lw } else { -lw }))
                    .chain([l])
                    .collect()
            } else {
                vec![l]
            };
            let qv = |s: f64, t: f64| qs[0] + qs[1] * s + qs[2] * t + qs[3] * s * s + qs[4] * s * t + qs[5] * t * t;
            // Proven feasible, and the proven barycentric coordinates.
            let proven = |s: f64, t: f64| -> Option<[Interval; 3]> {
                let (si, ti) = (point(s), point(t));
                let c = |x: f64| point(x);
                let in_strip = members.iter().any(|l| {
                    let lx = c(l[0]) + c(l[1]) * si + c(l[2]) * ti;
                    lx.inf() >= -da && lx.sup() <= da
                });
                let qx = c(qs[0])
                    + c(qs[1]) * si
                    + c(qs[2]) * ti
                    + c(qs[3]) * si * si
                    + c(qs[4]) * si * ti
                    + c(qs[5]) * ti * ti;
                let w = c(1.0) - si - ti;
                let inside = |x: Interval, d: f64| x.inf() >= -d && x.sup() <= d;
                (s >= 0.0 && t >= 0.0 && w.inf() >= 0.0 && in_strip && inside(qx, db)).then_some([si, ti, w])
            };
            let mut pts: Vec<(f64, f64)> = Vec::new();
            // Zeros of `f` along `x ↦ point(x)`, x ∈ [0, 1], by scanning and bisection.
            let mut zeros = |point_at: &dyn Fn(f64) -> Option<(f64, f64)>, f: &dyn Fn(f64, f64) -> f64| {
                let n = 400;
                let val = |x: f64| point_at(x).map(|(s, t)| f(s, t));
                for i in 0..n {
                    let (mut a, mut b) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                    let (Some(fa), Some(fb)) = (val(a), val(b)) else {
                        continue;
                    };
                    if fa == 0.0 {
                        pts.extend(point_at(a));
                    }
                    if fa.signum() * fb.signum() >= 0.0 {
                        continue;
                    }
                    let sa = fa.signum();
                    for _ in 0..60 {
                        let m = 0.5 * (a + b);
                        match val(m) {
                            Some(v) if v.signum() == sa => a = m,
                            Some(_) => b = m,
                            None => break,
                        }
                    }
                    pts.extend(point_at(a));
                    pts.extend(point_at(b));
                }
            };
            for &l in &members {
                for i in 0..=40 {
                    let lam = da * (i as f64 / 20.0 - 1.0) * 0.999;
                    // The line L = λ as a graph over the coordinate with the larger slope.
                    let on_line = move |x: f64| {
                        if l[2].abs() >= l[1].abs() {
                            Some((x, (lam - l[0] - l[1] * x) / l[2]))
                        } else {
                            Some(((lam - l[0] - l[2] * x) / l[1], x))
                        }
                    };
                    for level in [0.0, 0.999 * db, -0.999 * db] {
                        zeros(&on_line, &|s, t| qv(s, t) - level);
                    }
                }
            }
            let edges: [&dyn Fn(f64) -> Option<(f64, f64)>; 3] =
                [&|x| Some((0.0, x)), &|x| Some((x, 0.0)), &|x| Some((x, 1.0 - x))];
            for edge in edges {
                for l in &members {
                    for level in [0.999 * da, -0.999 * da] {
                        zeros(edge, &|s, t| l[0] + l[1] * s + l[2] * t - level);
                    }
                }
                for level in [0.0, 0.999 * db, -0.999 * db] {
                    zeros(edge, &|s, t| qv(s, t) - level);
                }
            }
            for i in 0..=60 {
                for j in 0..=60 - i {
                    pts.push((i as f64 / 60.0, j as f64 / 60.0));
                }
            }
            match claim {
                None => declined += 1,
                Some(ClipBounds::Empty) => empty += 1,
                Some(ClipBounds::Keep(_)) => kept += 1,
            }
            let feasible: Vec<[Interval; 3]> = pts.iter().filter_map(|&(s, t)| proven(s, t)).collect();
            checked += feasible.len();
            for bary in &feasible {
                match claim {
                    None => {}
                    Some(ClipBounds::Empty) => panic!("case {case}: Empty, but {bary:?} is feasible"),
                    Some(ClipBounds::Keep(m)) => {
                        for k in 0..3 {
                            assert!(bary[k].sup() >= m[k], "case {case}: {bary:?} is feasible, below {m:?}");
                        }
                    }
                }
            }
            // The proofs themselves, on claims that are false as often as
            // true: just below and above the smallest feasible coordinate
            // found, and at random.
            for k in 0..3 {
                let low = feasible.iter().map(|b| b[k].inf()).fold(f64::INFINITY, f64::min);
                let mut tries: Vec<f64> = (0..8).map(|_| r()).collect();
                if low.is_finite() {
                    tries.extend([1e-3, 1e-6, -1e-6, -1e-3, -0.1].map(|x| low * (1.0 + x)));
                }
                for m in tries.into_iter().filter(|m| *m > 0.0 && *m <= 1.0) {
                    // The proof, and each sweep on its own (either is valid
                    // wherever its coefficient is non-zero).
                    let frame = verifier.sliver_line(k, m);
                    let fresh = || verifier.budget.set(CLEAR_BUDGET);
                    // Proofs (and failures) by the slab shortcut of the sweep along σ.
                    let SliverLine {
                        l0,
                        ls,
                        lt,
                        top,
                        base,
                        far,
                    } = frame;
                    let by_slab = lt.nonzero() && verifier.strip_spans((l0, top)) && verifier.strip_spans((base, far));
                    let sweeps = [
                        Some(verifier.sliver_free(k, m)),
                        lt.nonzero().then(|| {
                            fresh();
                            verifier.swept_along_sigma(k, m, frame)
                        }),
                        ls.nonzero().then(|| {
                            fresh();
                            verifier.swept_along_tau(k, m, frame)
                        }),
                        ls.nonzero().then(|| {
                            fresh();
                            verifier.swept_across(k, m, frame)
                        }),
                    ];
                    if by_slab {
                        slab[usize::from(sweeps[1] == Some(true))] += 1;
                    }
                    for (how, proven) in sweeps.into_iter().enumerate() {
                        match proven {
                            Some(true) => {
                                proofs[how] += 1;
                                for bary in &feasible {
                                    assert!(
                                        bary[k].sup() > m,
                                        "case {case}: sliver {k} ≤ {m} proven free ({how}), but {bary:?}"
                                    );
                                }
                            }
                            Some(false) if how == 0 && feasible.iter().any(|b| b[k].sup() <= m) => refuted += 1,
                            _ => {}
                        }
                    }
                }
            }
        }
        assert!(
            kept > 100
                && empty > 100
                && checked > 20000
                && proofs.iter().all(|&p| p > 1000)
                && refuted > 1000
                && slab.iter().all(|&n| n > 1000),
            "{kept} {empty} {declined} {checked} {proofs:?} {refuted} {slab:?}"
        );
    }

    /// A NaN anywhere in the Taylor form or the path length proves nothing,
    /// and a NaN path length becomes the cap, not 0.
    #[test]
    fn nan_proves_nothing() {
        let (p, nan) = (GeoIv::pt, GeoIv::pt(f64::NAN));
        assert!(bounded_away(p(1.0), p(0.1), p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), nan, p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), p(0.1), nan, p(0.5), 0.5));
        assert!(!bounded_away(nan, p(0.1), p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), p(0.1), p(1.0), nan, 0.5));
        assert_eq!(path_bound::<f64>(f64::NAN, 0.3), 0.3);
        assert_eq!(path_bound::<f64>(-1.0, 0.3), 0.0);
        assert_eq!(path_bound::<f64>(0.7, 0.3), 0.3);
    }
}
