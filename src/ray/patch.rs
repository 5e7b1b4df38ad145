//! Patch types of the ray front end: triangular and tensor-product Bézier
//! patches, polynomial or rational, with validated input.
//!
//! A patch is stored as its *homogeneous* control net `(w·x, w·y, w·z, w)`
//! (with `w = 1` for polynomial patches) in two kernels: `f64` for points,
//! partials and normals, and [`Interval`] for everything that is proven (the
//! reduced system and the enclosure of `t`). The interval net encloses the
//! exact products `w·x` of the input floats.

use crate::error::{Error, Result};
use crate::poly::{tri_len, Direction, TensorBezier, TriBezier};
use crate::scalar::iv::{down, up, Iv};
use crate::scalar::{interval, point};
use crate::solve::Box2;
use crate::Scalar;
use glam::DVec3;
use inari::Interval;

/// A triangular Bézier patch of degree `n` (Liu et al. 2016, Eq. (2)):
///
/// ```text
/// S(u, v) = Σ_{j=0}^{n} Σ_{i=0}^{n−j} w_ij R_ij B^n_ij(u, v) / Σ w_ij B^n_ij(u, v),
/// B^n_ij = n!/(i! j! (n−i−j)!) u^i v^j (1−u−v)^(n−i−j),   u, v ≥ 0, u + v ≤ 1,
/// ```
/// control points ordered `j = 0..=n` outer, `i = 0..=n−j` inner; all
/// `w_ij = 1` when no weights are given.
#[derive(Clone, Debug)]
pub struct TriPatch {
    degree: usize,
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
    magnitude: Magnitude,
    net: Net<TriBezier<f64>>,
    inet: Net<TriBezier<Interval>>,
}

/// A tensor-product Bézier patch of bidegree `(m, n)` on `[0, 1]²`:
/// `S(u, v) = Σ w_ij P_ij B^m_i(u) B^n_j(v) / Σ w_ij B^m_i(u) B^n_j(v)`,
/// control point `P_ij` at index `i·(n+1) + j` (row-major).
#[derive(Clone, Debug)]
pub struct TensorPatch {
    degree: (usize, usize),
    points: Vec<DVec3>,
    weights: Option<Vec<f64>>,
    magnitude: Magnitude,
    net: Net<TensorBezier<f64>>,
    inet: Net<TensorBezier<Interval>>,
    /// The homogeneous net `(wx, wy, wz, w)` per control point as [`Iv`]
    /// enclosures (the same sets as `inet`), for the box route's hot path.
    ivnet: Vec<[Iv; 4]>,
    /// The patch is exactly its `points` and `weights` (false once
    /// [`TensorPatch::widen`] made it stand for nearby nets).
    exact: bool,
}

/// The homogeneous coordinate polynomials `(w·x, w·y, w·z, w)`.
#[derive(Clone, Debug)]
pub(crate) struct Net<P> {
    pub(crate) c: [P; 4],
}

/// What the ray code needs from a BB polynomial type (triangle or tensor).
pub(crate) trait Bb<S: Scalar>: Clone {
    fn value(&self, u: S, v: S) -> S;
    fn d_u(&self) -> Self;
    fn d_v(&self) -> Self;
    /// `[p, ∂p/∂u, ∂p/∂v]` at `(u, v)`.
    fn jet(&self, u: S, v: S) -> [S; 3] {
        [
            self.value(u.clone(), v.clone()),
            self.d_u().value(u.clone(), v.clone()),
            self.d_v().value(u, v),
        ]
    }
}

/// `[p, ∂p/∂u, ∂p/∂v]` of a tensor BB polynomial on `[0, 1]²` in `f64`, on
/// the stack ([`uni_jet_f64`] row by row, then on the columns).
fn tensor_jet_f64(c: &[f64], m: usize, n: usize, u: f64, v: f64) -> [f64; 3] {
    // The bicubic (and lower) with constant sizes: unrolled, the same floats.
    match (m, n) {
        (3, 3) => tensor_jet_in(c, 3, 3, u, v),
        (2, 2) => tensor_jet_in(c, 2, 2, u, v),
        (1, 1) => tensor_jet_in(c, 1, 1, u, v),
        _ => tensor_jet_in(c, m, n, u, v),
    }
}

#[inline(always)]
fn tensor_jet_in(c: &[f64], m: usize, n: usize, u: f64, v: f64) -> [f64; 3] {
    let mut vals = [0.0f64; MAX_DEGREE + 1];
    let mut dvs = [0.0f64; MAX_DEGREE + 1];
    let mut row = [0.0f64; MAX_DEGREE + 1];
    for (i, line) in c.chunks_exact(n + 1).take(m + 1).enumerate() {
        row[..=n].copy_from_slice(line);
        (vals[i], dvs[i]) = uni_jet_f64(&mut row[..=n], v);
    }
    let (p, pu) = uni_jet_f64(&mut vals[..=m], u);
    let (pv, _) = uni_jet_f64(&mut dvs[..=m], u);
    [p, pu, pv]
}

/// Value and derivative of a univariate BB polynomial on `[0, 1]` at `t`:
/// de Casteljau stopped one level early leaves `p₀, p₁`, and then
/// `p = (1 − t)p₀ + t p₁`, `p' = k (p₁ − p₀)`.
#[inline(always)]
fn uni_jet_f64(c: &mut [f64], t: f64) -> (f64, f64) {
    let k = c.len() - 1;
    if k == 0 {
        return (c[0], 0.0);
    }
    let s = 1.0 - t;
    for r in 1..k {
        for i in 0..=k - r {
            c[i] = s * c[i] + t * c[i + 1];
        }
    }
    (s * c[0] + t * c[1], k as f64 * (c[1] - c[0]))
}

impl<S: Scalar> Bb<S> for TriBezier<S> {
    fn value(&self, u: S, v: S) -> S {
        self.eval(u, v)
    }
    fn d_u(&self) -> Self {
        self.deriv_u()
    }
    fn d_v(&self) -> Self {
        self.deriv_v()
    }
}

impl<S: Scalar> Bb<S> for TensorBezier<S> {
    fn value(&self, u: S, v: S) -> S {
        self.eval(u, v)
    }
    fn d_u(&self) -> Self {
        self.deriv(Direction::U)
    }
    fn d_v(&self) -> Self {
        self.deriv(Direction::V)
    }
}

/// Checks points and weights; returns the homogeneous coefficients as
/// `[wx, wy, wz, w]` columns in `f64` (rounded) and in intervals (enclosing).
type Columns = (Vec<[f64; 4]>, Vec<[Interval; 4]>);

fn homogeneous(points: &[DVec3], weights: Option<&[f64]>, want: usize) -> Result<Columns> {
    if points.len() != want {
        return Err(Error::Shape(format!(
            "the patch needs {want} control points, got {}",
            points.len()
        )));
    }
    if let Some(k) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::NonFinite(format!(
            "control point {k} is {:?}",
            points[k].to_array()
        )));
    }
    if let Some(w) = weights {
        if w.len() != want {
            return Err(Error::Shape(format!("the patch needs {want} weights, got {}", w.len())));
        }
        if let Some(k) = w.iter().position(|x| !x.is_finite()) {
            return Err(Error::NonFinite(format!("weight {k} is {}", w[k])));
        }
        // Positive weights keep the denominator positive on the whole domain, so
        // the roots of the homogeneous system are exactly the hits.
        if let Some(k) = w.iter().position(|&x| x <= 0.0) {
            return Err(Error::Degenerate(format!(
                "weight {k} is {}; weights must be positive",
                w[k]
            )));
        }
        // A subnormal weight's products underflow: the patch's points in
        // f64 would be 0/0 (NaN), so the input is rejected.
        if let Some(k) = w.iter().position(|&x| x < f64::MIN_POSITIVE) {
            return Err(Error::NonFinite(format!(
                "weight {k} is {:e}, below the smallest normal float 2^-1022 (its products underflow)",
                w[k]
            )));
        }
    }
    let mut fl = Vec::with_capacity(want);
    let mut iv = Vec::with_capacity(want);
    for (k, p) in points.iter().enumerate() {
        let w = weights.map_or(1.0, |w| w[k]);
        let wi = point(w);
        fl.push([w * p.x, w * p.y, w * p.z, w]);
        iv.push([wi * point(p.x), wi * point(p.y), wi * point(p.z), wi]);
    }
    if iv.iter().flatten().any(|c| !c.is_finite()) {
        return Err(Error::NonFinite("a weighted control point overflows".into()));
    }
    Ok((fl, iv))
}

fn column<S: Clone>(rows: &[[S; 4]], c: usize) -> Vec<S> {
    rows.iter().map(|r| r[c].clone()).collect()
}

impl TriPatch {
    /// A patch of degree `n ≥ 1` from `(n+1)(n+2)/2` control points in the
    /// order of Eq. (2) and optional weights in the same order. Errors: wrong
    /// counts ([`Error::Shape`]), NaN or ±∞ or a subnormal weight
    /// ([`Error::NonFinite`]), a weight `≤ 0` ([`Error::Degenerate`]).
    ///
    /// ```
    /// use rootclip::glam::DVec3;
    /// use rootclip::ray::TriPatch;
    /// // A quadratic dome over the unit triangle: corners on z = 0, edge midpoints raised.
    /// let pts = vec![
    ///     DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.5, 0.0, 0.5), DVec3::new(1.0, 0.0, 0.0),
    ///     DVec3::new(0.0, 0.5, 0.5), DVec3::new(0.5, 0.5, 0.5), DVec3::new(0.0, 1.0, 0.0),
    /// ];
    /// let dome = TriPatch::new(2, pts, None)?;
    /// assert!((dome.eval(1.0 / 3.0, 1.0 / 3.0).z - 1.0 / 3.0).abs() < 1e-15);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn new(degree: usize, points: Vec<DVec3>, weights: Option<Vec<f64>>) -> Result<Self> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(Error::Shape(format!(
                "triangle degree must be in 1..={MAX_DEGREE}, got {degree}"
            )));
        }
        let (fl, iv) = homogeneous(&points, weights.as_deref(), tri_len(degree))?;
        let net = Net {
            c: [0, 1, 2, 3].map(|c| TriBezier::new(degree, column(&fl, c))),
        };
        let inet = Net {
            c: [0, 1, 2, 3].map(|c| TriBezier::new(degree, column(&iv, c))),
        };
        Ok(Self {
            degree,
            magnitude: Magnitude::of(&points, weights.as_deref()),
            points,
            weights,
            net: lift(net)?,
            inet: lift(inet)?,
        })
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The control points in the order of Eq. (2).
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights, if rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// `S(u, v)` in `f64`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        eval_f64(&self.net, u, v)
    }

    /// `(∂S/∂u, ∂S/∂v)` in `f64` (`w = 1 − u − v` moves with `u` and `v`).
    pub fn partials(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        partials_f64(&self.net, u, v)
    }

    /// The unit normal `S_u × S_v / |S_u × S_v|` in `f64` (zero where the
    /// partials are parallel).
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let (su, sv) = self.partials(u, v);
        su.cross(sv).normalize_or_zero()
    }

    pub(crate) fn inet(&self) -> &Net<TriBezier<Interval>> {
        &self.inet
    }

    pub(crate) fn magnitude(&self) -> Magnitude {
        self.magnitude
    }
}

impl TensorPatch {
    /// A patch of bidegree `(m, n)`, `m, n ≥ 1`, from `(m+1)(n+1)` row-major
    /// control points and optional weights. Errors as [`TriPatch::new`].
    ///
    /// ```
    /// use rootclip::glam::DVec3;
    /// use rootclip::ray::TensorPatch;
    /// // A rational quarter cylinder x² + z² = 1, z ≥ 0, x ≥ 0, along y ∈ [0, 2].
    /// let pts = vec![
    ///     DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 2.0, 0.0),
    ///     DVec3::new(1.0, 0.0, 1.0), DVec3::new(1.0, 2.0, 1.0),
    ///     DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 2.0, 1.0),
    /// ];
    /// let w = vec![1.0, 1.0, 0.5f64.sqrt(), 0.5f64.sqrt(), 1.0, 1.0];
    /// let cyl = TensorPatch::new(2, 1, pts, Some(w))?;
    /// let p = cyl.eval(0.3, 0.5);
    /// assert!((p.x * p.x + p.z * p.z - 1.0).abs() < 1e-15 && (p.y - 1.0).abs() < 1e-15);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn new(m: usize, n: usize, points: Vec<DVec3>, weights: Option<Vec<f64>>) -> Result<Self> {
        if m == 0 || n == 0 || m > MAX_DEGREE || n > MAX_DEGREE {
            return Err(Error::Shape(format!(
                "tensor bidegree must be in 1..={MAX_DEGREE} each, got ({m}, {n})"
            )));
        }
        let (fl, iv) = homogeneous(&points, weights.as_deref(), (m + 1) * (n + 1))?;
        let net = Net {
            c: [0, 1, 2, 3].map(|c| TensorBezier::on_unit_square(m, n, column(&fl, c))),
        };
        let inet = Net {
            c: [0, 1, 2, 3].map(|c| TensorBezier::on_unit_square(m, n, column(&iv, c))),
        };
        let ivnet = iv.iter().map(|r| r.map(|x| Iv::new(x.inf(), x.sup()))).collect();
        Ok(Self {
            degree: (m, n),
            magnitude: Magnitude::of(&points, weights.as_deref()),
            points,
            weights,
            net: lift(net)?,
            inet: lift(inet)?,
            ivnet,
            exact: true,
        })
    }

    /// The patch is exactly the surface of its stored floats (not a B-spline
    /// piece whose net carries knot-insertion error).
    pub(crate) fn net_is_exact(&self) -> bool {
        self.exact
    }

    /// Widens the enclosure of each homogeneous coordinate `(w x, w y, w z,
    /// w)` by `err[c]` on each side (the weight's only when the patch is
    /// rational): the patch then stands for every net within those bounds of
    /// its points, e.g. the exact Bézier pieces of a B-spline whose knot
    /// insertion ran in `f64` with those error bounds.
    pub(crate) fn widen(&mut self, err: [f64; 4]) -> Result<()> {
        self.exact = false;
        let rational = self.weights.is_some();
        for row in &mut self.ivnet {
            for (c, x) in row.iter_mut().enumerate() {
                if c < 3 || rational {
                    *x = Iv::new(down(x.lo - err[c]), up(x.hi + err[c]));
                }
            }
        }
        if let Some(k) = self.ivnet.iter().position(|r| r[3].lo.is_nan() || r[3].lo <= 0.0) {
            return Err(Error::Degenerate(format!(
                "weight {k} may not be positive within the knot insertion's error bound"
            )));
        }
        let (m, n) = self.degree;
        let inet = Net {
            c: [0, 1, 2, 3].map(|c| {
                let col = self.ivnet.iter().map(|r| interval(r[c].lo, r[c].hi)).collect();
                TensorBezier::on_unit_square(m, n, col)
            }),
        };
        self.inet = lift(inet)?;
        Ok(())
    }

    pub(crate) fn magnitude(&self) -> Magnitude {
        self.magnitude
    }

    /// The homogeneous net as [`Iv`] enclosures, row-major.
    pub(crate) fn ivnet(&self) -> &[[Iv; 4]] {
        &self.ivnet
    }

    /// The bidegree `(m, n)`.
    pub fn degree(&self) -> (usize, usize) {
        self.degree
    }

    /// The control points, row-major.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights, if rational.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// `S(u, v)` in `f64`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        self.frame(u, v).0
    }

    /// `(∂S/∂u, ∂S/∂v)` in `f64`.
    pub fn partials(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        let (_, su, sv) = self.frame(u, v);
        (su, sv)
    }

    /// The unit normal `S_u × S_v / |S_u × S_v|` in `f64` (zero where the
    /// partials are parallel).
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let (_, su, sv) = self.frame(u, v);
        su.cross(sv).normalize_or_zero()
    }

    /// `(S, ∂S/∂u, ∂S/∂v)` in `f64` in one pass: de Casteljau with
    /// derivatives on each homogeneous coordinate (no allocation for degrees
    /// up to the degree limit of 40), then the quotient rule.
    pub fn frame(&self, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
        let (m, n) = self.degree;
        let j: [[f64; 3]; 4] = std::array::from_fn(|k| tensor_jet_f64(self.net.c[k].coeffs(), m, n, u, v));
        let (x, w) = (DVec3::new(j[0][0], j[1][0], j[2][0]), j[3][0]);
        let d = |a: usize| (DVec3::new(j[0][a], j[1][a], j[2][a]) * w - x * j[3][a]) / (w * w);
        (x / w, d(1), d(2))
    }

    /// The same surface as two triangular patches of degree `m + n` (the
    /// exact conversion of [`TensorBezier::to_triangles`], rounded to `f64`
    /// control points): the first covers `u + v ≤ 1` with `(u, v)` as its
    /// parameters, the second `u + v ≥ 1` with parameters `(1 − u, 1 − v)`.
    pub fn to_triangles(&self) -> Result<[TriPatch; 2]> {
        let mut halves = Vec::with_capacity(4);
        for p in &self.net.c {
            halves.push(p.to_triangles()?);
        }
        let n = self.degree.0 + self.degree.1;
        let make = |h: usize| -> Result<TriPatch> {
            let w: Vec<f64> = halves[3][h].coeffs().to_vec();
            let pts = (0..w.len())
                .map(|k| {
                    DVec3::new(
                        halves[0][h].coeffs()[k],
                        halves[1][h].coeffs()[k],
                        halves[2][h].coeffs()[k],
                    ) / w[k]
                })
                .collect();
            TriPatch::new(n, pts, self.weights.as_ref().map(|_| w))
        };
        Ok([make(0)?, make(1)?])
    }

    pub(crate) fn inet(&self) -> &Net<TensorBezier<Interval>> {
        &self.inet
    }

    /// An enclosure of a normal direction `N = (X_u W − X W_u) × (X_v W − X W_v)`
    /// (a positive multiple `W⁴` of `S_u × S_v`, for the homogeneous net
    /// `(X, W)`) over the parameter box `u × v`, by interval de Casteljau on
    /// the net and its derivative nets.
    pub(crate) fn normal_enclosure(&self, u: Interval, v: Interval) -> [Interval; 3] {
        let c = &self.inet.c;
        let jet: [[Interval; 3]; 4] =
            std::array::from_fn(|k| [c[k].value(u, v), c[k].d_u().value(u, v), c[k].d_v().value(u, v)]);
        let w = jet[3];
        let tangent = |a: usize| -> [Interval; 3] { std::array::from_fn(|k| jet[k][a] * w[0] - jet[k][0] * w[a]) };
        let (su, sv) = (tangent(1), tangent(2));
        [
            su[1] * sv[2] - su[2] * sv[1],
            su[2] * sv[0] - su[0] * sv[2],
            su[0] * sv[1] - su[1] * sv[0],
        ]
    }
}

/// The largest magnitude of a patch's control point coordinates and the
/// range of its weights: whether a query should be scaled by a power of two
/// first (`ray::intersect`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Magnitude {
    /// `max |x|` over the control points' coordinates.
    pub(crate) coords: f64,
    /// `[min w, max w]` (`[1, 1]` without weights).
    pub(crate) weights: [f64; 2],
}

impl Magnitude {
    pub(crate) fn of(points: &[DVec3], weights: Option<&[f64]>) -> Self {
        Self {
            coords: points.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max),
            weights: weights.map_or([1.0, 1.0], |w| {
                [
                    w.iter().copied().fold(f64::INFINITY, f64::min),
                    w.iter().copied().fold(0.0, f64::max),
                ]
            }),
        }
    }
}

/// Degrees above this are refused (the solver's work grows like `n⁴`).
pub(crate) const MAX_DEGREE: usize = 40;

fn lift<P>(net: Net<Result<P>>) -> Result<Net<P>> {
    let [a, b, c, d] = net.c;
    Ok(Net { c: [a?, b?, c?, d?] })
}

fn eval_f64<P: Bb<f64>>(net: &Net<P>, u: f64, v: f64) -> DVec3 {
    let h: [_; 4] = std::array::from_fn(|k| net.c[k].value(u, v));
    DVec3::new(h[0], h[1], h[2]) / h[3]
}

fn partials_f64<P: Bb<f64>>(net: &Net<P>, u: f64, v: f64) -> (DVec3, DVec3) {
    let jets: [[f64; 3]; 4] = std::array::from_fn(|k| net.c[k].jet(u, v));
    let (x, w) = (DVec3::new(jets[0][0], jets[1][0], jets[2][0]), jets[3][0]);
    // Quotient rule on (X/W): (X' W − X W') / W².
    let d = |a: usize| (DVec3::new(jets[0][a], jets[1][a], jets[2][a]) * w - x * jets[3][a]) / (w * w);
    (d(1), d(2))
}

/// The enclosure of `S` over the box `(U, V)`: each homogeneous coordinate
/// by interval de Casteljau, then divided by the weight's enclosure.
pub(crate) fn eval_interval<P: Bb<Interval>>(net: &Net<P>, u: Interval, v: Interval) -> [Interval; 3] {
    let h: [_; 4] = std::array::from_fn(|k| net.c[k].value(u, v));
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

/// A borrowed Bézier patch of either kind.
#[derive(Clone, Copy, Debug)]
pub(crate) enum BezierRef<'a> {
    Tri(&'a TriPatch),
    Tensor(&'a TensorPatch),
}

impl BezierRef<'_> {
    /// The point and the unit normal at `(u, v)` in `f64`.
    pub(crate) fn point_and_normal(self, u: f64, v: f64) -> (DVec3, DVec3) {
        match self {
            BezierRef::Tri(p) => {
                let (su, sv) = p.partials(u, v);
                (p.eval(u, v), su.cross(sv).normalize_or_zero())
            }
            BezierRef::Tensor(p) => {
                let (x, su, sv) = p.frame(u, v);
                (x, su.cross(sv).normalize_or_zero())
            }
        }
    }

    /// The closed box lies in the patch's closed parameter domain (the unit
    /// square, or the triangle `u, v ≥ 0, u + v ≤ 1` with the sum rounded up).
    pub(crate) fn domain_contains(self, bx: Box2) -> bool {
        let lower = bx.u[0] >= 0.0 && bx.v[0] >= 0.0;
        match self {
            BezierRef::Tri(_) => lower && (point(bx.u[1]) + point(bx.v[1])).sup() <= 1.0,
            BezierRef::Tensor(_) => lower && bx.u[1] <= 1.0 && bx.v[1] <= 1.0,
        }
    }
}
