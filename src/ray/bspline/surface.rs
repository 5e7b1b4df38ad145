//! [`BsplineSurface`]: validated input and Bézier extraction by knot
//! insertion (see the parent module's docs for the formula and the error
//! bound).

use crate::error::{Error, Result};
use crate::poly::TensorBezier;
use crate::ray::patch::{Magnitude, TensorPatch, MAX_DEGREE};
use crate::scalar::point;
use glam::DVec3;
use inari::Interval;

/// Refined control nets above this many entries are refused ([`Error::TooLarge`]).
pub(crate) const MAX_REFINED_NET: usize = 4_000_000;

/// A B-spline or NURBS surface of bidegree `(p, q)`; see the module docs for
/// the formula. Built once, it holds its Bézier pieces.
#[derive(Clone, Debug)]
pub struct BsplineSurface {
    pub(super) degree: (usize, usize),
    pub(super) knots_u: Vec<f64>,
    pub(super) knots_v: Vec<f64>,
    pub(super) counts: (usize, usize),
    pub(super) points: Vec<DVec3>,
    pub(super) weights: Option<Vec<f64>>,
    pub(crate) magnitude: Magnitude,
    /// Distinct knot values in the domain, both ends included.
    pub(super) breaks_u: Vec<f64>,
    pub(super) breaks_v: Vec<f64>,
    /// Row-major over the spans: piece `(a, b)` at `a·(breaks_v.len() − 1) + b`.
    pub(super) pieces: Vec<BezierPiece>,
}

/// One rational (or polynomial) tensor Bézier piece of a [`BsplineSurface`]:
/// the surface on `[u₀, u₁] × [v₀, v₁]` is the piece on `[0, 1]²` with
/// `u = u₀ + (u₁ − u₀)·s`, `v = v₀ + (v₁ − v₀)·t`.
#[derive(Clone, Debug)]
pub struct BezierPiece {
    /// The piece on `[0, 1]²`.
    pub(super) patch: TensorPatch,
    pub(super) u: [f64; 2],
    pub(super) v: [f64; 2],
    /// Bounding box of the control points.
    pub(super) lo: DVec3,
    pub(super) hi: DVec3,
    /// The interval homogeneous net `(wx, wy, wz, w)` on the piece's
    /// rectangle in knot parameters (for the merge proofs).
    pub(super) hom: [TensorBezier<Interval>; 4],
}

impl BezierPiece {
    /// The piece on `[0, 1]²`, a tensor patch of bidegree `(p, q)`.
    pub fn patch(&self) -> &TensorPatch {
        &self.patch
    }

    /// `[u₀, u₁]`, the piece's span in `u` (knot parameters).
    pub fn u_range(&self) -> [f64; 2] {
        self.u
    }

    /// `[v₀, v₁]`, the piece's span in `v` (knot parameters).
    pub fn v_range(&self) -> [f64; 2] {
        self.v
    }

    /// The knot parameters `(u₀ + (u₁ − u₀)·s, v₀ + (v₁ − v₀)·t)` of the
    /// piece's `(s, t)`, in `f64`.
    pub fn to_knots(&self, s: f64, t: f64) -> (f64, f64) {
        (
            self.u[0] + (self.u[1] - self.u[0]) * s,
            self.v[0] + (self.v[1] - self.v[0]) * t,
        )
    }

    /// The piece's `(s, t)` of knot parameters `(u, v)`, in `f64`.
    pub fn to_local(&self, u: f64, v: f64) -> (f64, f64) {
        (
            (u - self.u[0]) / (self.u[1] - self.u[0]),
            (v - self.v[0]) / (self.v[1] - self.v[0]),
        )
    }
}

impl BsplineSurface {
    /// A surface of bidegree `(p, q)` from its knot vectors, `n_u·n_v`
    /// row-major control points (`n_u = knots_u.len() − p − 1`, likewise
    /// `n_v`) and optional weights in the same order. Weights that are all
    /// exactly 1 are treated as a polynomial surface.
    ///
    /// Knot vectors must be finite and non-decreasing with at least
    /// `2p + 2` entries (so `n_u ≥ p + 1`); the domain `[knots[p], knots[n_u]]`
    /// must be non-empty; a knot value strictly inside the domain may repeat
    /// at most `p` times (the surface stays continuous), any other value at
    /// most `p + 1` times (a clamped end; more would make a basis function
    /// vanish identically).
    ///
    /// Errors: a degree outside `1..=MAX_DEGREE`, a knot vector too short,
    /// decreasing or with a knot repeated too often, or a wrong number of
    /// points or weights ([`Error::Shape`]); NaN or ±∞ in knots, points or
    /// weights, or an overflowing `w·P` ([`Error::NonFinite`]); an empty
    /// domain or a weight `≤ 0` ([`Error::Degenerate`]); a refined net above
    /// 4,000,000 entries ([`Error::TooLarge`]).
    ///
    /// ```
    /// use glam::DVec3;
    /// use rootclip::ray::BsplineSurface;
    /// // Bilinear in u, v on knots [0, 0, 1, 2, 2]: two flat pieces z = 0.
    /// let pts = (0..3).flat_map(|i| (0..2).map(move |j| DVec3::new(i as f64, j as f64, 0.0))).collect();
    /// let s = BsplineSurface::new((1, 1), vec![0.0, 0.0, 1.0, 2.0, 2.0], vec![0.0, 0.0, 1.0, 1.0], pts, None).unwrap();
    /// assert_eq!(s.pieces().len(), 2);
    /// assert!((s.eval(1.5, 0.25) - DVec3::new(1.5, 0.25, 0.0)).length() < 1e-15);
    /// assert!(BsplineSurface::new((1, 1), vec![0.0, 1.0, 0.5, 2.0], vec![0.0, 0.0, 1.0, 1.0], vec![DVec3::ZERO; 4], None).is_err());
    /// ```
    pub fn new(
        degree: (usize, usize),
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        points: Vec<DVec3>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self> {
        let (p, q) = degree;
        if p == 0 || q == 0 || p > MAX_DEGREE || q > MAX_DEGREE {
            return Err(Error::Shape(format!(
                "B-spline bidegree must be in 1..={MAX_DEGREE} each, got ({p}, {q})"
            )));
        }
        let nu = check_knots("knots_u", &knots_u, p)?;
        let nv = check_knots("knots_v", &knots_v, q)?;
        check_points(&points, weights.as_deref(), nu, nv)?;
        let rational = weights.as_ref().is_some_and(|w| w.iter().any(|&x| x != 1.0));
        let (breaks_u, breaks_v) = (breaks(&knots_u, p, nu), breaks(&knots_v, q, nv));
        let size = (p * (breaks_u.len() - 1) + 1).saturating_mul(q * (breaks_v.len() - 1) + 1);
        if size > MAX_REFINED_NET {
            return Err(Error::TooLarge(format!(
                "the Bézier pieces need a refined net of {size} control points (limit {MAX_REFINED_NET})"
            )));
        }
        // Knot insertion runs in f64. Each insertion replaces a point by
        // fl((1 − α̃)a + α̃ b) with α̃ = fl((x − t_i)/(t_{i+p} − t_i)), |α̃ − α| ≤ 3u
        // (u = 2⁻⁵³): its error against the exact (1 − α)A + αB is at most the
        // previous error plus |α̃ − α||b − a| + 4u(|a| + |b|) ≤ 14u·M, with M the
        // largest magnitude of that coordinate in the net (convex combinations
        // never exceed it; each coordinate is combined on its own). A point
        // passes through at most one step per insertion, and the homogeneous
        // products and the pieces' (h/w)·w round trip add a few u·M more: so
        // every piece's exact net lies within 16u·M_c·(K + 4) of the computed
        // one in coordinate c, K = insertions, and the pieces are widened by
        // that much (`TensorPatch::widen`) — their certificates then hold for
        // the exact surface. A polynomial surface is refined about the centre
        // c of its net's bounding box (translation commutes with the convex
        // combinations), so M_c is half its extent rather than its distance
        // from the origin; translating there and back adds u·|P_c| at most.
        let insertions = p * breaks_u.len() + q * breaks_v.len();
        let bound = |m: f64| 16.0 * f64::EPSILON / 2.0 * m * (insertions + 4) as f64;
        let max_abs = |f: &dyn Fn(usize) -> f64| (0..points.len()).map(|k| f(k).abs()).fold(0.0f64, f64::max);
        let pieces = if rational {
            let w = weights.as_deref().unwrap_or(&[]);
            let hom: Vec<[f64; 4]> = points
                .iter()
                .zip(w)
                .map(|(p, &w)| [w * p.x, w * p.y, w * p.z, w])
                .collect();
            let err: [f64; 4] = std::array::from_fn(|c| bound(max_abs(&|k| hom[k][c])));
            let grid = Grid {
                p,
                q,
                knots_u: &knots_u,
                knots_v: &knots_v,
                nv,
                err,
            };
            grid.pieces(hom, |h: &[f64; 4]| (DVec3::new(h[0], h[1], h[2]) / h[3], Some(h[3])))?
        } else {
            let (lo, hi) = points.iter().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(l, h), x| (l.min(*x), h.max(*x)),
            );
            let centre = (0.5 * lo + 0.5 * hi).to_array();
            let cart: Vec<[f64; 3]> = points
                .iter()
                .map(|p| std::array::from_fn(|c| p[c] - centre[c]))
                .collect();
            let err: [f64; 4] = std::array::from_fn(|c| {
                if c == 3 {
                    0.0
                } else {
                    bound(max_abs(&|k| cart[k][c])) + f64::EPSILON * max_abs(&|k| points[k][c])
                }
            });
            let grid = Grid {
                p,
                q,
                knots_u: &knots_u,
                knots_v: &knots_v,
                nv,
                err,
            };
            grid.pieces(cart, |c: &[f64; 3]| {
                (DVec3::new(c[0] + centre[0], c[1] + centre[1], c[2] + centre[2]), None)
            })?
        };
        Ok(Self {
            degree,
            knots_u,
            knots_v,
            counts: (nu, nv),
            magnitude: Magnitude::of(&points, weights.as_deref()),
            points,
            weights,
            breaks_u,
            breaks_v,
            pieces,
        })
    }

    /// The bidegree `(p, q)`.
    pub fn degree(&self) -> (usize, usize) {
        self.degree
    }

    /// The knot vector in `u`.
    pub fn knots_u(&self) -> &[f64] {
        &self.knots_u
    }

    /// The knot vector in `v`.
    pub fn knots_v(&self) -> &[f64] {
        &self.knots_v
    }

    /// `(n_u, n_v)`, the number of control points in each direction.
    pub fn counts(&self) -> (usize, usize) {
        self.counts
    }

    /// The control points, row-major (`P_ij` at `i·n_v + j`).
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights, if given.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The parameter domain `([u_p, u_{n_u}], [v_q, v_{n_v}])`.
    pub fn domain(&self) -> ([f64; 2], [f64; 2]) {
        let ends = |b: &[f64]| [b[0], b[b.len() - 1]];
        (ends(&self.breaks_u), ends(&self.breaks_v))
    }

    /// The Bézier pieces, row-major over the non-empty spans (`u` outer).
    pub fn pieces(&self) -> &[BezierPiece] {
        &self.pieces
    }

    /// The piece whose closed rectangle holds `(u, v)` (the later one on a
    /// knot line; outside the domain, the nearest one, whose polynomial then
    /// extends the surface).
    pub fn piece_at(&self, u: f64, v: f64) -> &BezierPiece {
        let span = |b: &[f64], x: f64| b[1..b.len() - 1].partition_point(|&k| k <= x);
        let (a, b) = (span(&self.breaks_u, u), span(&self.breaks_v, v));
        &self.pieces[a * (self.breaks_v.len() - 1) + b]
    }

    /// `S(u, v)` in `f64`, evaluated on the piece holding `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        let piece = self.piece_at(u, v);
        let (s, t) = piece.to_local(u, v);
        piece.patch.eval(s, t)
    }

    /// `(∂S/∂u, ∂S/∂v)` in `f64`, in knot parameters (one-sided on a knot
    /// line: the later piece's).
    pub fn partials(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        let piece = self.piece_at(u, v);
        let (s, t) = piece.to_local(u, v);
        let (ds, dt) = piece.patch.partials(s, t);
        (ds / (piece.u[1] - piece.u[0]), dt / (piece.v[1] - piece.v[0]))
    }
}

/// Checks one knot vector (see [`BsplineSurface::new`]) and returns the
/// number of control points it implies.
fn check_knots(name: &str, knots: &[f64], p: usize) -> Result<usize> {
    if knots.len() < 2 * p + 2 {
        return Err(Error::Shape(format!(
            "{name} has {} knots; degree {p} needs at least 2·{p} + 2 = {} (length = control points + degree + 1)",
            knots.len(),
            2 * p + 2
        )));
    }
    if let Some(k) = knots.iter().position(|x| !x.is_finite()) {
        return Err(Error::NonFinite(format!("{name}[{k}] is {}", knots[k])));
    }
    if let Some(k) = (1..knots.len()).find(|&k| knots[k] < knots[k - 1]) {
        return Err(Error::Shape(format!(
            "{name} decreases at index {k} ({} after {}); knots must be non-decreasing",
            knots[k],
            knots[k - 1]
        )));
    }
    let n = knots.len() - p - 1;
    let (lo, hi) = (knots[p], knots[n]);
    if lo >= hi {
        return Err(Error::Degenerate(format!(
            "{name}: the parameter domain [knots[{p}], knots[{n}]] = [{lo}, {hi}] is empty"
        )));
    }
    for run in knots.chunk_by(|a, b| a == b) {
        let (x, m) = (run[0], run.len());
        let inside = lo < x && x < hi;
        if inside && m > p {
            return Err(Error::Shape(format!(
                "{name}: interior knot {x} has multiplicity {m} > degree {p} (the surface would tear there)"
            )));
        }
        if m > p + 1 {
            return Err(Error::Shape(format!(
                "{name}: knot {x} has multiplicity {m} > degree + 1 = {}",
                p + 1
            )));
        }
    }
    Ok(n)
}

fn check_points(points: &[DVec3], weights: Option<&[f64]>, nu: usize, nv: usize) -> Result<()> {
    let want = nu * nv;
    if points.len() != want {
        return Err(Error::Shape(format!(
            "the knot vectors imply {nu} × {nv} = {want} control points (n = knots − degree − 1 per direction), got {}",
            points.len()
        )));
    }
    if let Some(k) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::NonFinite(format!(
            "control point {k} is {:?}",
            points[k].to_array()
        )));
    }
    let Some(w) = weights else { return Ok(()) };
    if w.len() != want {
        return Err(Error::Shape(format!(
            "the surface needs {want} weights, got {}",
            w.len()
        )));
    }
    if let Some(k) = w.iter().position(|x| !x.is_finite()) {
        return Err(Error::NonFinite(format!("weight {k} is {}", w[k])));
    }
    // Positive weights keep the denominator positive on the whole domain (it is
    // a convex combination of them), so the hits are the homogeneous roots.
    if let Some(k) = w.iter().position(|&x| x <= 0.0) {
        return Err(Error::Degenerate(format!(
            "weight {k} is {}; weights must be positive",
            w[k]
        )));
    }
    // A subnormal weight's products underflow (the f64 points would be 0/0).
    if let Some(k) = w.iter().position(|&x| x < f64::MIN_POSITIVE) {
        return Err(Error::NonFinite(format!(
            "weight {k} is {:e}, below the smallest normal float 2^-1022 (its products underflow)",
            w[k]
        )));
    }
    if let Some(k) = (0..want).find(|&k| !(points[k] * w[k]).is_finite()) {
        return Err(Error::NonFinite(format!("weighted control point {k} overflows")));
    }
    Ok(())
}

/// The distinct knot values in the domain `[knots[p], knots[n]]`.
fn breaks(knots: &[f64], p: usize, n: usize) -> Vec<f64> {
    let mut b: Vec<f64> = knots[p..=n].to_vec();
    b.dedup();
    b
}

/// The knot vectors and sizes the decomposition works on.
struct Grid<'a> {
    p: usize,
    q: usize,
    knots_u: &'a [f64],
    knots_v: &'a [f64],
    nv: usize,
    /// Bounds on the f64 knot insertion's error per homogeneous coordinate
    /// `(w x, w y, w z, w)`.
    err: [f64; 4],
}

impl Grid<'_> {
    /// Refines the net (`n_u·n_v` row-major entries of `D` coordinates) in `u`
    /// and then in `v`, and cuts it into pieces; `cartesian` turns an entry
    /// into a control point and its weight.
    fn pieces<const D: usize>(
        &self,
        net: Vec<[f64; D]>,
        cartesian: impl Fn(&[f64; D]) -> (DVec3, Option<f64>),
    ) -> Result<Vec<BezierPiece>> {
        let rows: Vec<Vec<[f64; D]>> = net.chunks(self.nv).map(<[_]>::to_vec).collect();
        let (ex_u, rows) = extract(self.knots_u, self.p, rows)?;
        let columns: Vec<Vec<[f64; D]>> = (0..self.nv).map(|j| rows.iter().map(|r| r[j]).collect()).collect();
        let (ex_v, columns) = extract(self.knots_v, self.q, columns)?;
        let mut pieces = Vec::with_capacity(ex_u.first.len() * ex_v.first.len());
        for (a, &iu) in ex_u.first.iter().enumerate() {
            for (b, &jv) in ex_v.first.iter().enumerate() {
                let mut pts = Vec::with_capacity((self.p + 1) * (self.q + 1));
                let mut ws = Vec::with_capacity((self.p + 1) * (self.q + 1));
                for i in 0..=self.p {
                    for j in 0..=self.q {
                        let (pt, w) = cartesian(&columns[jv + j][iu + i]);
                        pts.push(pt);
                        ws.extend(w);
                    }
                }
                let weights = (ws.len() == pts.len()).then_some(ws);
                let u = [ex_u.breaks[a], ex_u.breaks[a + 1]];
                let v = [ex_v.breaks[b], ex_v.breaks[b + 1]];
                pieces.push(BezierPiece::new(self.p, self.q, pts, weights, u, v, self.err)?);
            }
        }
        Ok(pieces)
    }
}

impl BezierPiece {
    fn new(
        p: usize,
        q: usize,
        pts: Vec<DVec3>,
        weights: Option<Vec<f64>>,
        u: [f64; 2],
        v: [f64; 2],
        err: [f64; 4],
    ) -> Result<Self> {
        let (lo, hi) = pts.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(l, h), x| (l.min(*x), h.max(*x)),
        );
        let mut tensor = TensorPatch::new(p, q, pts, weights)?;
        tensor.widen(err)?;
        let rect = |r: [f64; 2]| [point(r[0]), point(r[1])];
        let inet = tensor.inet();
        let hom = [0, 1, 2, 3].map(|c| TensorBezier::new(p, q, inet.c[c].coeffs().to_vec(), rect(u), rect(v)));
        let [a, b, c, d] = hom;
        Ok(Self {
            patch: tensor,
            u,
            v,
            lo,
            hi,
            hom: [a?, b?, c?, d?],
        })
    }
}

/// The Bézier spans of a refined knot vector: its breakpoints in the domain
/// and, per span, the index of the span's first control point.
struct Extraction {
    breaks: Vec<f64>,
    first: Vec<usize>,
}

/// Inserts every knot value of the domain (ends included) up to multiplicity
/// `p` into the curve with control "points" `ctrl` (rows of coordinates),
/// and locates the Bézier segments. Interior multiplicities are at most `p`
/// (validated), so after the insertions they are exactly `p` and segment
/// `a + 1` starts at the control point where segment `a` ends.
fn extract<const D: usize>(
    knots: &[f64],
    p: usize,
    mut ctrl: Vec<Vec<[f64; D]>>,
) -> Result<(Extraction, Vec<Vec<[f64; D]>>)> {
    let mut knots = knots.to_vec();
    let breaks = breaks(&knots, p, ctrl.len());
    for &x in &breaks {
        let mult = knots.iter().filter(|&&k| k == x).count();
        for _ in mult..p {
            insert_knot(&mut knots, &mut ctrl, p, x)?;
        }
    }
    // Span a is [t_r, t_{r+1}] with r the last index of ξ_a; its Bézier net is
    // P_{r−p} … P_r (t_{r−p+1..=r} = ξ_a and t_{r+1..=r+p} = ξ_{a+1}).
    // r ≥ p: ξ_a ≥ t_p and ξ_a has multiplicity ≥ p (≥ p + 1 if it starts at
    // index 0), so the subtraction cannot fail; checked all the same.
    let first = breaks[..breaks.len() - 1]
        .iter()
        .map(|&x| {
            knots
                .partition_point(|&k| k <= x)
                .checked_sub(p + 1)
                .ok_or_else(|| Error::Degenerate(format!("no Bézier span starts at knot {x}")))
        })
        .collect::<Result<_>>()?;
    Ok((Extraction { breaks, first }, ctrl))
}

/// Boehm's insertion of `x ∈ [t_p, t_n]` into the last non-empty domain span
/// `[t_r, t_{r+1}] ∋ x`: `Q_i = α_i P_i + (1 − α_i) P_{i−1}`,
/// `α_i = (x − t_i)/(t_{i+p} − t_i)` for `r − p < i ≤ r`; `Q_i = P_i` before,
/// `P_{i−1}` after. Every `α_i ∈ [0, 1]` (its denominator is at least the
/// span's length), so each new point is a convex combination.
fn insert_knot<const D: usize>(knots: &mut Vec<f64>, ctrl: &mut Vec<Vec<[f64; D]>>, p: usize, x: f64) -> Result<()> {
    let n = ctrl.len();
    let r = (p..n)
        .rev()
        .find(|&r| knots[r] <= x && knots[r] < knots[r + 1])
        .ok_or_else(|| Error::Degenerate(format!("knot {x} lies outside the parameter domain")))?;
    let mut out = Vec::with_capacity(n + 1);
    out.extend_from_slice(&ctrl[..=r - p]);
    for i in r - p + 1..=r {
        let alpha = (x - knots[i]) / (knots[i + p] - knots[i]);
        let row = ctrl[i - 1]
            .iter()
            .zip(&ctrl[i])
            .map(|(a, b)| std::array::from_fn(|c| (1.0 - alpha) * a[c] + alpha * b[c]))
            .collect();
        out.push(row);
    }
    out.extend_from_slice(&ctrl[r..]);
    *ctrl = out;
    knots.insert(r + 1, x);
    Ok(())
}
