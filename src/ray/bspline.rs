//! B-spline and NURBS surfaces for the ray front end: validated input, Bézier
//! extraction by knot insertion, and certified hits with the duplicates at
//! knot lines merged only when a proof says they are one hit.
//!
//! # Surface
//! ```text
//! S(u, v) = Σ_i Σ_j w_ij P_ij N_i,p(u) N_j,q(v) / Σ_i Σ_j w_ij N_i,p(u) N_j,q(v),
//!           (u, v) ∈ [u_p, u_{n_u}] × [v_q, v_{n_v}],
//! ```
//! with `N_i,p` the B-spline basis of degree `p` on the knot vector
//! `u_0 ≤ … ≤ u_{n_u+p}` (Cox–de Boor), `n_u × n_v` control points stored
//! row-major (`P_ij` at index `i·n_v + j`) and all `w_ij = 1` without weights.
//! Clamped and unclamped knot vectors are both accepted; the domain is always
//! `[knots[p], knots[n]]`.
//!
//! # Decomposition (Boehm 1980, doi:10.1016/0010-4485(80)90154-2; Piegl &
//! Tiller, *The NURBS Book*, §5.2 and Algorithm A5.6)
//! Every distinct knot value in the domain, both ends included, is inserted
//! until it has multiplicity `p` (in `u`; `q` in `v`), on the homogeneous
//! coordinates `(w·x, w·y, w·z, w)` (on `(x, y, z)` alone for a polynomial
//! surface, so that its pieces stay polynomial). On each span `[ξ_a, ξ_{a+1}]`
//! of positive length the `p + 1` control points whose basis functions live
//! there are then the Bézier net of the piece; zero-length spans give no piece.
//! The insertions are convex combinations in `f64`: a piece's control points
//! are the exact ones up to a few ulps of the net's magnitude per inserted
//! knot. Certificates (below) speak about the pieces *as stored* — exactly as
//! a [`TensorPatch`]'s certificates speak about its `f64` input.
//!
//! Neighbouring pieces take their common boundary row (or column) from the
//! same entries of the refined net, bit for bit, so the stored pieces join
//! exactly: along a knot line both pieces are the same rational curve.
//!
//! # Hits
//! [`intersect_bspline`] culls every piece whose control-net bounding box
//! (enlarged by `1e-9` of its size; the convex hull property makes this
//! conservative) the ray provably misses for `t` in the range, intersects the others
//! with [`intersect`](super::intersect), and maps each `(u, v)` box from the
//! piece's `[0, 1]²` to knot parameters by `u = u₀ + (u₁ − u₀)·s` in interval
//! arithmetic (outward). A certified box then holds exactly one root of its
//! piece's system; when it reaches across a knot line, that root may be one
//! of the piece's polynomial *extension* lying within the box's width of the
//! line (the [`Root::on_boundary`](crate::solve::Root::on_boundary) contract
//! of the solver, now at interior lines too).
//!
//! # Duplicates at knot lines
//! A hit on a knot line is found by both neighbouring pieces (four at a
//! corner). Overlapping boxes alone do not prove that two reports are one hit
//! (a crease can be crossed twice within a box width), so a group of
//! overlapping certified reports is merged only when Krawczyk's operator on
//! the piecewise system proves a single zero; otherwise all are kept. See
//! [`merge`].
//!
//! # Degenerate cases
//! A ray in the plane of a planar piece makes the whole ray
//! [`RayOutcome::Degenerate`] with [`Degeneracy::ZeroEquation`]; an unresolved
//! piece makes it [`Degeneracy::Unresolved`] with every hit found (all pieces),
//! `complete` only if every piece finished within its budget.

mod exact;
mod merge;

use super::bezier::{intersect_bezier, select, sort_by_t, BezierRef};
use super::patch::{TensorPatch, MAX_DEGREE};
use super::{Degeneracy, Hit, HitBox, HitStatus, Query, Ray, RayHits, RayOptions, RayOutcome};
use crate::error::{Error, Result};
use crate::poly::TensorBezier;
use crate::scalar::{interval, point};
use glam::DVec3;
use inari::Interval;

/// Refined control nets above this many entries are refused ([`Error::TooLarge`]).
pub(crate) const MAX_REFINED_NET: usize = 4_000_000;

/// A B-spline or NURBS surface of bidegree `(p, q)`; see the module docs for
/// the formula. Built once, it holds its Bézier pieces.
#[derive(Clone, Debug)]
pub struct BsplineSurface {
    degree: (usize, usize),
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    counts: (usize, usize),
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
    /// Distinct knot values in the domain, both ends included.
    breaks_u: Vec<f64>,
    breaks_v: Vec<f64>,
    /// Row-major over the spans: piece `(a, b)` at `a·(breaks_v.len() − 1) + b`.
    pieces: Vec<BezierPiece>,
}

/// One rational (or polynomial) tensor Bézier piece of a [`BsplineSurface`]:
/// the surface on `[u₀, u₁] × [v₀, v₁]` is the piece on `[0, 1]²` with
/// `u = u₀ + (u₁ − u₀)·s`, `v = v₀ + (v₁ − v₀)·t`.
#[derive(Clone, Debug)]
pub struct BezierPiece {
    /// The piece on `[0, 1]²`.
    patch: TensorPatch,
    u: [f64; 2],
    v: [f64; 2],
    /// Bounding box of the control points.
    lo: DVec3,
    hi: DVec3,
    /// The interval homogeneous net `(wx, wy, wz, w)` on the piece's
    /// rectangle in knot parameters (for the merge proofs).
    hom: [TensorBezier<Interval>; 4],
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
    /// [`MAX_REFINED_NET`] entries ([`Error::TooLarge`]).
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
        // largest homogeneous coordinate (convex combinations never exceed
        // it). A point passes through at most one step per insertion, and
        // the homogeneous products and the pieces' (h/w)·w round trip add a
        // few u·M more: so every piece's exact net lies within
        // 16u·M·(K + 4) of the computed one, K = insertions, and the pieces
        // are widened by that much (`TensorPatch::widen`) — their
        // certificates then hold for the exact surface.
        let hom_max = points
            .iter()
            .enumerate()
            .map(|(k, pt)| {
                let w = weights.as_deref().map_or(1.0, |w| w[k]);
                (pt.abs() * w.abs()).max_element().max(w.abs())
            })
            .fold(0.0f64, f64::max);
        let insertions = p * breaks_u.len() + q * breaks_v.len();
        let err = 16.0 * f64::EPSILON / 2.0 * hom_max * (insertions + 4) as f64;
        let grid = Grid {
            p,
            q,
            knots_u: &knots_u,
            knots_v: &knots_v,
            nv,
            err,
        };
        let pieces = if rational {
            let w = weights.as_deref().unwrap_or(&[]);
            let hom: Vec<[f64; 4]> = points
                .iter()
                .zip(w)
                .map(|(p, &w)| [w * p.x, w * p.y, w * p.z, w])
                .collect();
            grid.pieces(hom, |h: &[f64; 4]| (DVec3::new(h[0], h[1], h[2]) / h[3], Some(h[3])))?
        } else {
            let cart: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
            grid.pieces(cart, |c: &[f64; 3]| (DVec3::from_array(*c), None))?
        };
        Ok(Self {
            degree,
            knots_u,
            knots_v,
            counts: (nu, nv),
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
    /// Bound on the f64 knot insertion's error per homogeneous coordinate.
    err: f64,
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
        err: f64,
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

// ---------------------------------------------------------------------------
// Hits
// ---------------------------------------------------------------------------

/// Every hit of `ray` with the B-spline/NURBS `surface` for `t` in the range, in knot
/// parameters, sorted by `t`; see the module docs for the culling, the
/// mapping, the merge of duplicates at knot lines and the degenerate cases.
/// Each piece is solved with `opts` (budgets are per piece).
///
/// ```
/// use glam::DVec3;
/// use rootclip::ray::{intersect, BsplineSurface, Patch, Ray, RayOptions, RayOutcome};
/// // A biquadratic bump over [0, 3] × [0, 1], clamped, three pieces in u.
/// let ku = vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let pts = (0..5).flat_map(|i| (0..3).map(move |j| DVec3::new(i as f64, j as f64, ((i + j) % 2) as f64))).collect();
/// let s = BsplineSurface::new((2, 2), ku, kv, pts, None).unwrap();
/// let ray = Ray::new(s.eval(1.3, 0.6) + DVec3::Z, -DVec3::Z).unwrap();
/// let RayOutcome::Hits(h) = intersect(&Patch::from(s), &ray, &RayOptions::default()).unwrap() else { panic!() };
/// assert!(h.complete && h.hits.len() == 1 && h.hits[0].is_certified());
/// assert!(h.hits[0].bx.u[0] <= 1.3 + 1e-12 && 1.3 - 1e-12 <= h.hits[0].bx.u[1]);
/// ```
pub(crate) fn intersect_bspline(surface: &BsplineSurface, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    // Each piece answers `All` (or `Any`, which may stop the loop); the
    // query is applied to the merged list.
    let piece_opts = RayOptions {
        query: if opts.query == Query::Any {
            Query::Any
        } else {
            Query::All
        },
        ..opts.clone()
    };
    let mut found = Vec::new();
    let (mut complete, mut unresolved) = (true, false);
    for (k, piece) in surface.pieces.iter().enumerate() {
        if !box_may_meet(piece.lo, piece.hi, ray, opts.t_range) {
            continue;
        }
        let hits = match intersect_bezier(BezierRef::Tensor(&piece.patch), ray, &piece_opts)? {
            RayOutcome::Hits(h) => h.hits,
            RayOutcome::Degenerate(Degeneracy::ZeroEquation) => {
                return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation))
            }
            RayOutcome::Degenerate(Degeneracy::Unresolved(h)) => {
                unresolved = true;
                complete &= h.complete;
                h.hits
            }
        };
        // A root the piece could not place on its side of an edge (its net
        // carries knot-insertion error) is settled on the exact net.
        let hits: Vec<Hit> = hits
            .into_iter()
            .filter_map(|h| settle_on_edge(surface, piece, ray, h, opts.t_range))
            .collect();
        let done = opts.query == Query::Any && hits.iter().any(Hit::is_certified);
        found.extend(hits.into_iter().map(|h| (to_knot_hit(piece, h), k)));
        if done {
            break;
        }
    }
    let mut hits = merge::merge_knot_line_duplicates(surface, ray, found, opts.t_range);
    sort_by_t(&mut hits);
    Ok(if unresolved {
        RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits { complete, hits }))
    } else {
        select(&mut hits, opts.query);
        RayOutcome::Hits(RayHits { complete: true, hits })
    })
}

/// A piece's hit, settled in exact arithmetic if it is undecided only at the
/// piece's edge ([`UndecidedReason::Boundary`](crate::solve::UndecidedReason::Boundary)):
/// certified if its root is on the piece with `t` in the range, `None` if it
/// is off it or out of range, unchanged if undecided.
///
/// A settled hit's box is cut to the piece (past its edge the surface is
/// another piece, which may hold a hit of its own within the box). A root
/// exactly on an interior knot line is a root of both neighbouring pieces;
/// it is kept by the piece below the line only.
fn settle_on_edge(surface: &BsplineSurface, piece: &BezierPiece, ray: &Ray, h: Hit, range: [f64; 2]) -> Option<Hit> {
    use crate::solve::settle::{Edge, Settled, Shape};
    use crate::solve::Box2;
    if !h.on_edge() {
        return Some(h);
    }
    let (p, q) = surface.degree;
    let check_hi = h.bx.t[1] > range[1] || h.bx.t[1].is_nan();
    let Some(systems) = exact::exact_piece_net(surface, piece)
        .and_then(|net| super::settle::systems_of_net(Shape::Tensor(p, q), &net, ray, range, check_hi))
    else {
        return Some(h);
    };
    let bx = Box2 { u: h.bx.u, v: h.bx.v };
    match super::settle::settle_all(&systems, bx) {
        Settled::Inside => {
            let on = systems[0].root_edges(bx);
            let below_line = (on.contains(&Edge::U0) && piece.u[0] > surface.breaks_u[0])
                || (on.contains(&Edge::V0) && piece.v[0] > surface.breaks_v[0]);
            if below_line {
                return None;
            }
            let clamp = |x: [f64; 2]| [x[0].max(0.0), x[1].min(1.0)];
            Some(Hit {
                status: HitStatus::Certified,
                bx: HitBox {
                    u: clamp(h.bx.u),
                    v: clamp(h.bx.v),
                    t: [h.bx.t[0].max(range[0]), h.bx.t[1].min(range[1])],
                },
                ..h
            })
        }
        Settled::Outside => None,
        Settled::Undecided => Some(h),
    }
}

/// `false` only if the ray provably misses, for `t` in `range`, the box
/// `[lo, hi]` enlarged by `1e-9` of its size (slab test in interval
/// arithmetic).
fn box_may_meet(lo: DVec3, hi: DVec3, ray: &Ray, range: [f64; 2]) -> bool {
    let scale = (hi - lo)
        .max_element()
        .max(lo.abs().max_element())
        .max(hi.abs().max_element());
    let pad = 1e-9 * scale + f64::MIN_POSITIVE;
    let (o, d) = (ray.origin(), ray.dir());
    let (mut enter, mut exit) = (range[0], range[1]);
    for c in 0..3 {
        let (l, h) = (lo[c] - pad, hi[c] + pad);
        if d[c] == 0.0 {
            if o[c] < l || o[c] > h {
                return false;
            }
            continue;
        }
        let a = (point(l) - point(o[c])) / point(d[c]);
        let b = (point(h) - point(o[c])) / point(d[c]);
        if a.is_empty() || b.is_empty() {
            return true;
        }
        let (near, far) = if d[c] > 0.0 { (a, b) } else { (b, a) };
        enter = enter.max(near.inf());
        exit = exit.min(far.sup());
    }
    enter <= exit
}

/// `[x₀ + (x₁ − x₀)·lo, x₀ + (x₁ − x₀)·hi]`, rounded outward.
fn to_knot_interval(range: [f64; 2], b: [f64; 2]) -> Interval {
    let x0 = point(range[0]);
    x0 + (point(range[1]) - x0) * interval(b[0], b[1])
}

/// A piece's hit with its `(u, v)` box mapped outward to knot parameters
/// (`point` and `normal` are the piece's: the same surface point, and the
/// spans' positive lengths do not turn the normal).
fn to_knot_hit(piece: &BezierPiece, h: Hit) -> Hit {
    let (u, v) = (to_knot_interval(piece.u, h.bx.u), to_knot_interval(piece.v, h.bx.v));
    Hit {
        u: u.mid(),
        v: v.mid(),
        bx: HitBox {
            u: [u.inf(), u.sup()],
            v: [v.inf(), v.sup()],
            t: h.bx.t,
        },
        ..h
    }
}
