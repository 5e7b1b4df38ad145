//! Tensor-product Bernstein polynomials in `N` variables on the unit box, with
//! interval coefficients, and what the solver reads off them: restriction to
//! sub-boxes (de Casteljau at floats, blossoms for arbitrary boxes),
//! enclosures at points and over boxes, and derivative hulls.
//!
//! ```text
//! p(x) = Σ_{i ∈ I} c_i Π_d B^{n_d}_{i_d}(x_d),   x ∈ [0, 1]^N,   I = Π_d {0, …, n_d}
//! ```
//! Coefficients are stored row-major: axis 0 varies slowest, `c_i` at
//! `Σ_d i_d·stride_d` with `stride_d = Π_{e > d} (n_e + 1)`.
//!
//! Every operation is done in the crate's branchless interval kernel
//! ([`Iv`]: each endpoint rounded to nearest and moved one float outward), so
//! a result encloses the exact result of the same operation on every
//! polynomial whose coefficients lie in the enclosures.

use crate::error::{Error, Result};
use crate::scalar::iv::Iv;
use inari::Interval;

/// Degrees above this are refused (per axis).
pub(crate) const MAX_AXIS_DEGREE: usize = 40;

/// Tensors with more coefficients than this are refused.
pub(crate) const MAX_COEFFS: usize = 1 << 22;

/// A tensor-product Bernstein polynomial in `N` variables on `[0, 1]^N`
/// (see the module docs of [`nd`](super) for the formula), its coefficients
/// enclosed in intervals.
///
/// Built from `f64` coefficients (taken as exact numbers) or from
/// [`Interval`] enclosures (then every statement of the solver holds for
/// every polynomial whose coefficients lie in them).
///
/// ```
/// use rootclip::solve::nd::BernsteinNd;
/// // p(x, y, z) = x + y + z − 1 has coefficients i + j + k − 1 of degree (1, 1, 1).
/// let c = (0..8).map(|k| ((k >> 2) + ((k >> 1) & 1) + (k & 1)) as f64 - 1.0).collect();
/// let p = BernsteinNd::<3>::new([1, 1, 1], c)?;
/// let v = p.eval([0.25, 0.25, 0.5]);
/// assert!(v.inf() <= 0.0 && 0.0 <= v.sup() && v.wid() < 1e-14);
/// # Ok::<(), rootclip::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct BernsteinNd<const N: usize> {
    pub(crate) deg: [usize; N],
    pub(crate) c: Vec<Iv>,
}

impl<const N: usize> BernsteinNd<N> {
    /// A polynomial of degree `degree[d]` in `x_d` from its `Π (n_d + 1)`
    /// coefficients, row-major (axis 0 slowest), each `f64` an exact number.
    /// Errors: a wrong count or a degree above 40 ([`Error::Shape`]), a
    /// tensor above `2²²` coefficients ([`Error::TooLarge`]), NaN or ±∞
    /// ([`Error::NonFinite`]).
    pub fn new(degree: [usize; N], coeffs: Vec<f64>) -> Result<Self> {
        Self::check(degree, coeffs.len())?;
        if let Some(k) = coeffs.iter().position(|c| !c.is_finite()) {
            return Err(Error::NonFinite(format!("coefficient {k} is {}", coeffs[k])));
        }
        Ok(Self {
            deg: degree,
            c: coeffs.into_iter().map(Iv::point).collect(),
        })
    }

    /// As [`BernsteinNd::new`], from enclosures of the coefficients.
    /// Errors as there; an empty or unbounded interval is
    /// [`Error::NonFinite`].
    pub fn from_intervals(degree: [usize; N], coeffs: &[Interval]) -> Result<Self> {
        Self::check(degree, coeffs.len())?;
        if let Some(k) = coeffs
            .iter()
            .position(|c| c.is_empty() || !c.inf().is_finite() || !c.sup().is_finite())
        {
            return Err(Error::NonFinite(format!("coefficient {k} is {:?}", coeffs[k])));
        }
        Ok(Self {
            deg: degree,
            c: coeffs.iter().map(|x| Iv::new(x.inf(), x.sup())).collect(),
        })
    }

    fn check(degree: [usize; N], len: usize) -> Result<()> {
        if N == 0 {
            return Err(Error::Shape("a polynomial needs at least one variable".into()));
        }
        if let Some(d) = degree.iter().find(|&&d| d > MAX_AXIS_DEGREE) {
            return Err(Error::Shape(format!("degree {d} is above {MAX_AXIS_DEGREE}")));
        }
        let want = degree
            .iter()
            .try_fold(1usize, |a, &d| a.checked_mul(d + 1))
            .filter(|&w| w <= MAX_COEFFS)
            .ok_or_else(|| Error::TooLarge(format!("degree {degree:?} has more than {MAX_COEFFS} coefficients")))?;
        if len != want {
            return Err(Error::Shape(format!(
                "degree {degree:?} needs {want} coefficients, got {len}"
            )));
        }
        Ok(())
    }

    /// The degrees `(n_0, …, n_{N−1})`.
    pub fn degree(&self) -> [usize; N] {
        self.deg
    }

    /// The enclosure of coefficient `c_i`.
    pub fn coeff(&self, i: [usize; N]) -> Interval {
        let x = self.c[index(&self.deg, &i)];
        crate::scalar::interval(x.lo, x.hi)
    }

    /// An enclosure of `p(x)` at a point given in floats (any point of
    /// `ℝ^N`; outside the unit box by extrapolation, which is as rigorous
    /// but wider).
    pub fn eval(&self, x: [f64; N]) -> Interval {
        let v = eval_point(&self.c, &self.deg, &x);
        crate::scalar::interval(v.lo, v.hi)
    }

    /// An enclosure of `{p(x) : x ∈ box}` for a box given by float bounds.
    pub fn eval_box(&self, bx: [[f64; 2]; N]) -> Interval {
        let v = eval_box(&self.c, &self.deg, &bx);
        crate::scalar::interval(v.lo, v.hi)
    }
}

/// `Π (n_d + 1)`.
pub(crate) fn len_of(deg: &[usize]) -> usize {
    deg.iter().map(|d| d + 1).product()
}

/// `Π_{e > d} (n_e + 1)`.
pub(crate) fn stride(deg: &[usize], d: usize) -> usize {
    deg[d + 1..].iter().map(|e| e + 1).product()
}

/// The row-major index of multi-index `i`.
pub(crate) fn index(deg: &[usize], i: &[usize]) -> usize {
    i.iter().zip(deg).fold(0, |acc, (&k, &n)| acc * (n + 1) + k)
}

/// One de Casteljau step `(1 − t)·a + t·b`: [`Iv::lerp`] for `t ∈ [0, 1]`,
/// general products for extrapolation.
#[inline]
fn lerp(a: Iv, b: Iv, t: f64) -> Iv {
    if (0.0..=1.0).contains(&t) {
        Iv::lerp(a, b, t)
    } else {
        Iv::lerp_any(a, b, t)
    }
}

/// Subdivides `c` (degrees `deg`) along axis `d` at the float `t ∈ (0, 1)`,
/// keeping `[t, 1]` (`right`) or `[0, t]` in that axis: the coefficients of
/// the same polynomial on the sub-box, enclosed. Whole slabs (contiguous runs
/// of `stride_d` coefficients) are combined at once.
pub(crate) fn subdivide(c: &mut [Iv], deg: &[usize], d: usize, t: f64, right: bool) {
    let k = deg[d];
    let w = stride(deg, d);
    let block = (k + 1) * w;
    for blk in c.chunks_exact_mut(block) {
        for r in 1..=k {
            if right {
                for i in 0..=k - r {
                    let (head, tail) = blk.split_at_mut((i + 1) * w);
                    for (x, y) in head[i * w..].iter_mut().zip(&tail[..w]) {
                        *x = Iv::lerp(*x, *y, t);
                    }
                }
            } else {
                for i in (r..=k).rev() {
                    let (head, tail) = blk.split_at_mut(i * w);
                    for (y, x) in tail[..w].iter_mut().zip(&head[(i - 1) * w..]) {
                        *y = Iv::lerp(*x, *y, t);
                    }
                }
            }
        }
    }
}

/// The coefficients of `c` on the interval `[a, b]` of axis `d` (any floats
/// `a < b`, extrapolation included), by the blossom
/// `c'_j = P(a, …, a, b, …, b)` (`j` arguments `b`) of each line.
// Used by the unit tests and by the surface intersection's sub-patches.
#[allow(dead_code)]
pub(crate) fn restrict_axis(c: &mut [Iv], deg: &[usize], d: usize, a: f64, b: f64) {
    let k = deg[d];
    if k == 0 {
        return;
    }
    let w = stride(deg, d);
    let block = (k + 1) * w;
    let mut line = vec![Iv::point(0.0); k + 1];
    let mut work = vec![Iv::point(0.0); k + 1];
    let mut out = vec![Iv::point(0.0); k + 1];
    for blk in c.chunks_exact_mut(block) {
        for o in 0..w {
            for (i, x) in line.iter_mut().enumerate() {
                *x = blk[i * w + o];
            }
            for (j, slot) in out.iter_mut().enumerate() {
                work.copy_from_slice(&line);
                for r in 0..k {
                    let t = if r < j { b } else { a };
                    for i in 0..k - r {
                        work[i] = lerp(work[i], work[i + 1], t);
                    }
                }
                *slot = work[0];
            }
            for (i, x) in out.iter().enumerate() {
                blk[i * w + o] = *x;
            }
        }
    }
}

/// The polynomial on the box `bx` (float bounds, any box): each axis
/// restricted by its blossom ([`restrict_axis`]).
#[allow(dead_code)]
pub(crate) fn restrict<const N: usize>(c: &[Iv], deg: &[usize; N], bx: &[[f64; 2]; N]) -> Vec<Iv> {
    let mut out = c.to_vec();
    for (d, &[a, b]) in bx.iter().enumerate() {
        if [a, b] != [0.0, 1.0] {
            restrict_axis(&mut out, deg, d, a, b);
        }
    }
    out
}

/// Collapses the last axis of `c` (degrees `deg[..=last]`) into one value per
/// line by `reduce`, writing the results to the front of `c`.
fn collapse_last(c: &mut [Iv], n: usize, mut reduce: impl FnMut(&mut [Iv]) -> Iv) -> usize {
    let lines = c.len() / (n + 1);
    for l in 0..lines {
        let v = reduce(&mut c[l * (n + 1)..(l + 1) * (n + 1)]);
        c[l] = v;
    }
    lines
}

/// An enclosure of the polynomial at the point `x` (floats, any point).
pub(crate) fn eval_point(c: &[Iv], deg: &[usize], x: &[f64]) -> Iv {
    let mut work = c.to_vec();
    let mut len = work.len();
    for d in (0..deg.len()).rev() {
        let n = deg[d];
        let t = x[d];
        len = collapse_last(&mut work[..len], n, |line| {
            for r in 1..=n {
                for i in 0..=n - r {
                    line[i] = lerp(line[i], line[i + 1], t);
                }
            }
            line[0]
        });
    }
    work[0]
}

/// An enclosure of the polynomial over the box `bx` (floats), by interval de
/// Casteljau with [`Iv::lerp_range`] on each axis.
pub(crate) fn eval_box(c: &[Iv], deg: &[usize], bx: &[[f64; 2]]) -> Iv {
    let mut work = c.to_vec();
    let mut len = work.len();
    for d in (0..deg.len()).rev() {
        let n = deg[d];
        let [t0, t1] = bx[d];
        // The kind of step decided once per axis, not once per lerp: the
        // steps are those of `lerp_range`, inlined.
        let unit = (0.0..=1.0).contains(&t0) && (0.0..=1.0).contains(&t1);
        let w = &mut work[..len];
        len = match (t0 == t1, unit) {
            (true, true) => collapse_last(w, n, |line| casteljau(line, |a, b| Iv::lerp(a, b, t0))),
            (false, true) => collapse_last(w, n, |line| {
                casteljau(line, |a, b| Iv::lerp(a, b, t0).hull(Iv::lerp(a, b, t1)))
            }),
            _ => collapse_last(w, n, |line| casteljau(line, |a, b| Iv::lerp_range(a, b, t0, t1))),
        };
    }
    work[0]
}

/// De Casteljau's triangle on one line with the step `step(a, b)`.
#[inline(always)]
fn casteljau(line: &mut [Iv], step: impl Fn(Iv, Iv) -> Iv) -> Iv {
    let n = line.len() - 1;
    for r in 1..=n {
        for i in 0..=n - r {
            line[i] = step(line[i], line[i + 1]);
        }
    }
    line[0]
}

/// The value at the point `x` of the polynomial whose coefficients are the
/// midpoints of `c`, in `f64` (a proposal, never a proof).
pub(crate) fn eval_mid(c: &[Iv], deg: &[usize], x: &[f64]) -> f64 {
    let mut work: Vec<f64> = c.iter().map(|v| v.mid()).collect();
    let mut len = work.len();
    for d in (0..deg.len()).rev() {
        let n = deg[d];
        let t = x[d];
        let lines = len / (n + 1);
        for l in 0..lines {
            let line = &mut work[l * (n + 1)..(l + 1) * (n + 1)];
            for r in 1..=n {
                for i in 0..=n - r {
                    line[i] += t * (line[i + 1] - line[i]);
                }
            }
            work[l] = work[l * (n + 1)];
        }
        len = lines;
    }
    work[0]
}

/// The coefficients of `∂p/∂x_d` (degree `n_d − 1` in `x_d`;
/// the zero polynomial of degree 0 there when `n_d = 0`), enclosed.
pub(crate) fn derivative(c: &[Iv], deg: &[usize], d: usize) -> (Vec<usize>, Vec<Iv>) {
    let k = deg[d];
    let mut nd = deg.to_vec();
    if k == 0 {
        return (nd, vec![Iv::point(0.0); c.len()]);
    }
    nd[d] = k - 1;
    let w = stride(deg, d);
    let mut out = Vec::with_capacity(len_of(&nd));
    for blk in c.chunks_exact((k + 1) * w) {
        for i in 0..k {
            for o in 0..w {
                out.push(blk[(i + 1) * w + o].sub(blk[i * w + o]).scale(k as f64));
            }
        }
    }
    (nd, out)
}

/// The hull of `∂p/∂x_d` over the box the coefficients live on: the hull of
/// the derivative's Bernstein coefficients `n_d (c_{i+e_d} − c_i)`.
pub(crate) fn derivative_hull(c: &[Iv], deg: &[usize], d: usize) -> Iv {
    let k = deg[d];
    if k == 0 {
        return Iv::point(0.0);
    }
    let w = stride(deg, d);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for blk in c.chunks_exact((k + 1) * w) {
        for i in 0..k {
            let (a, b) = (&blk[i * w..(i + 1) * w], &blk[(i + 1) * w..(i + 2) * w]);
            for (x, y) in a.iter().zip(b) {
                let v = y.sub(*x);
                lo = lo.min(v.lo);
                hi = hi.max(v.hi);
                if v.lo.is_nan() || v.hi.is_nan() {
                    return Iv::new(f64::NEG_INFINITY, f64::INFINITY);
                }
            }
        }
    }
    Iv::new(lo, hi).scale(k as f64)
}

/// For each index `i` of axis `d`, the least lower and the largest upper
/// bound of the coefficients with `i_d = i` (the projection of the control
/// net on the plane `(x_d, value)`).
pub(crate) fn project(c: &[Iv], deg: &[usize], d: usize, lo: &mut [f64], hi: &mut [f64]) {
    let k = deg[d];
    let w = stride(deg, d);
    lo[..=k].fill(f64::INFINITY);
    hi[..=k].fill(f64::NEG_INFINITY);
    for blk in c.chunks_exact((k + 1) * w) {
        for i in 0..=k {
            for x in &blk[i * w..(i + 1) * w] {
                lo[i] = lo[i].min(x.lo);
                hi[i] = hi[i].max(x.hi);
                if x.lo.is_nan() || x.hi.is_nan() {
                    lo[i] = f64::NEG_INFINITY;
                    hi[i] = f64::INFINITY;
                }
            }
        }
    }
}

/// Every coefficient strictly positive, or every one strictly negative: no
/// zero on the box (the tensor Bernstein basis is a positive partition of
/// unity).
pub(crate) fn one_signed(c: &[Iv]) -> bool {
    c.iter().all(|x| x.lo > 0.0) || c.iter().all(|x| x.hi < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `p(x, y) = (x − 1/4)(y − 3/4)·2 + x` on the unit square, degree (1, 1):
    /// coefficients are the values at the corners for a bilinear polynomial.
    fn bilinear() -> (Vec<usize>, Vec<Iv>) {
        let f = |x: f64, y: f64| (x - 0.25) * (y - 0.75) * 2.0 + x;
        let c = [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)]
            .iter()
            .map(|&(x, y)| Iv::point(f(x, y)))
            .collect();
        (vec![1, 1], c)
    }

    #[test]
    fn restriction_and_evaluation_agree() {
        let (deg, c) = bilinear();
        let f = |x: f64, y: f64| (x - 0.25) * (y - 0.75) * 2.0 + x;
        let bx = [[-0.5, 0.25], [0.5, 1.5]];
        let r = restrict(&c, &[1, 1], &bx);
        for (k, &(s, t)) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)].iter().enumerate() {
            let x = bx[0][0] + s * (bx[0][1] - bx[0][0]);
            let y = bx[1][0] + t * (bx[1][1] - bx[1][0]);
            assert!(r[k].lo <= f(x, y) && f(x, y) <= r[k].hi);
        }
        let v = eval_point(&c, &deg, &[0.3, 0.9]);
        assert!(v.lo <= f(0.3, 0.9) && f(0.3, 0.9) <= v.hi);
        let b = eval_box(&c, &deg, &[[0.0, 1.0], [0.0, 1.0]]);
        assert!(b.lo <= -0.125 && b.hi >= 1.375); // the corner values bound a bilinear form
        let mut s = c.clone();
        subdivide(&mut s, &deg, 0, 0.5, true);
        let v = eval_point(&s, &deg, &[0.5, 0.5]);
        assert!(v.lo <= f(0.75, 0.5) && f(0.75, 0.5) <= v.hi);
        let (dd, dc) = derivative(&c, &deg, 1);
        assert_eq!(dd, vec![1, 0]);
        let v = eval_point(&dc, &dd, &[0.5, 0.0]);
        assert!(v.lo <= 0.5 && 0.5 <= v.hi);
        assert!(derivative_hull(&c, &deg, 1).lo <= -0.5);
    }
}
