//! Restarts from the exact input: a box whose coefficients rounding has
//! swamped is recomputed from the exact system in double-double, so that
//! its coefficients are again a few ulps of *its own* magnitudes.
//!
//! # Why
//! Every box's coefficients descend from the domain's, rounded to `f64`:
//! each carries an error of a few ulps of the domain's largest coefficient
//! `M₀`. Where the system is tiny compared with `M₀` — between the middle
//! roots of a product of 30 lines the values are about `10⁻¹⁸ M₀` — that
//! error is wider than the coefficients themselves, every clip stalls, and
//! only exact arithmetic (milliseconds per box) decides anything. Recomputed
//! from the exact input in double-double, the error is `~100 (m + n) u² M₀`
//! (`u = 2⁻⁵³`), about `10⁻²⁹ M₀`: the float steps work again down to
//! boxes whose values are `10⁻¹³` of the domain's.
//!
//! # The restriction
//! The box `[α_u, α_u + (1 − α_u) γ_u] × [α_v, α_v + (1 − α_v) γ_v]` of the
//! unit square (floats `α`, `γ`: the same exact sub-boxes as a clip, see
//! `rect` docs) is reached by two de Casteljau subdivisions per direction
//! (keep `[α, 1]`, then its first `γ`), each step `c' = x + τ (y − x)` with
//! the float `τ ∈ [0, 1]` in double-double arithmetic ([`lerp_dd`]).
//!
//! # Error bound
//! Let every value (exact or stored) be at most `M` in magnitude; the steps
//! are convex combinations, so `M = M₀ + R` serves throughout. One step
//! errs by at most `34 u² M` ([`lerp_dd`]), and errors already in `x`, `y`
//! pass through the convex combination `(1 − τ) x + τ y` without growing.
//! A coefficient of the box is the result of at most `2 (m + n)` steps, so
//! ```text
//! R = R₀ + 2 (m + n) (34 u² M + 10⁻³⁰⁰)
//! ```
//! bounds its error, where `R₀` bounds the input's rounding to double-double
//! and `10⁻³⁰⁰` every underflow of a step (at most ten roundings of at most
//! `2⁻¹⁰⁷⁴` each). The box's `f64` intervals are `h ± (|l| + R)` rounded
//! outward.
//!
//! # Beyond double-double
//! Where even `10⁻²⁹ M₀` swamps the box (near a point where one equation
//! vanishes to order 20, its values fall to `10⁻³⁰ M₀` within a few
//! hundredths), the same two subdivisions run in fixed point on big
//! integers ([`BigSystem`]): values `X·2⁻ˢ` with `|X| < 2^P`, a step
//! `X' = X + ⌊T (Y − X) / 2ᵏ⌋` for `τ = T/2ᵏ` (floats are dyadic). Each
//! floor errs by less than one unit, errors pass through the convex
//! combination without growing, so after at most `2 (m + n)` steps and the
//! input's own floor the error is below `2 (m + n) + 1` units. `P` starts
//! at 192 bits and doubles, up to [`MAX_BITS`], until the box's largest
//! coefficient is `2⁵²` times that bound. A restart is taken in the first
//! precision whose widths are within [`CLEAN`] of the box's magnitudes.

use super::net::Shape;
use super::spans::clip_gamma;
use crate::poly::dyadic::dyadic;
use crate::scalar::eft::{two_prod, two_sum, Dd};
use crate::scalar::iv::{self, Iv};
use crate::scalar::{rational_to_f64, rational_to_interval};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

/// A box's endpoints per direction, each an enclosure.
type Ends = [[Iv; 2]; 2];

/// The unit roundoff `2⁻⁵³`.
const U: f64 = f64::EPSILON / 2.0;

/// A polynomial of bidegree `(m, n)` on the unit square in double-double,
/// scaled by a power of two to largest coefficient about 1, with a bound
/// `rad` of every coefficient's error and `mag` of every magnitude.
#[derive(Clone, Debug)]
struct DdNet {
    c: Vec<Dd>,
    rad: f64,
    mag: f64,
}

/// `f` and `g` of an exact system on the unit square in double-double: the
/// source of restarts ([`DdSystem::restrict`]).
#[derive(Clone, Debug)]
pub(super) struct DdSystem {
    m: usize,
    n: usize,
    polys: [DdNet; 2],
}

impl DdNet {
    /// `c · 2^−e` (`e` from the largest coefficient) in double-double: `h`
    /// the nearest float, `l` the nearest to the rest, `rad` the largest
    /// width of the rest's tightest enclosure. `None` if every coefficient
    /// is 0 or a part is not finite.
    fn new(c: &[BigRational]) -> Option<Self> {
        let e = top_exponent(c)?;
        let (mut out, mut rad, mut mag) = (Vec::with_capacity(c.len()), 0.0f64, 0.0f64);
        for q in c {
            let (num, den) = times_pow2(q, -e);
            let q = BigRational::new_raw(num, den);
            let h = rational_to_f64(&q);
            let rest = rational_to_interval(&(&q - BigRational::from_float(h)?));
            let (h, l) = two_sum(h, rest.inf());
            rad = rad.max(iv::up(rest.sup() - rest.inf()));
            mag = mag.max(iv::up(h.abs() + l.abs()));
            out.push(Dd { h, l });
        }
        (rad.is_finite() && mag.is_finite()).then_some(Self { c: out, rad, mag })
    }
}

impl DdSystem {
    /// `f` and `g` (bidegree `(m, n)`, row-major, on the unit square) in
    /// double-double; `None` if either vanishes identically or does not fit
    /// the float range after scaling, or on a length mismatch.
    pub(super) fn new(m: usize, n: usize, f: &[BigRational], g: &[BigRational]) -> Option<Self> {
        let len = (m + 1) * (n + 1);
        if f.len() != len || g.len() != len {
            return None;
        }
        Some(Self {
            m,
            n,
            polys: [DdNet::new(f)?, DdNet::new(g)?],
        })
    }

    /// The coefficients of `f` and `g` (each scaled by a power of two) on a
    /// box of the unit square holding `outer` (float endpoints), as `f64`
    /// intervals in the layout of [`Shape::pair`], and that box's endpoints
    /// (enclosures of the exact ones). `None` if `outer` does not meet the
    /// square or the shape differs.
    pub(super) fn restrict(&self, sh: Shape, outer: [[f64; 2]; 2]) -> Option<(Vec<Iv>, Ends)> {
        if (sh.m, sh.n) != (self.m, self.n) || sh.polys < 2 {
            return None;
        }
        let (params, bx) = restart_box(outer)?;
        let steps = (2 * (self.m + self.n)) as f64;
        let mut out = Vec::with_capacity(sh.polys * sh.len);
        for p in &self.polys {
            let mut c = p.c.clone();
            for (d, &(alpha, gamma)) in params.iter().enumerate() {
                restrict(&mut c, self.m, self.n, d, alpha, gamma);
            }
            let m = iv::up(p.mag + p.rad) * (1.0 + 1e-10);
            let rad = iv::up(p.rad + steps * (34.0 * U * U * m + 1e-300));
            out.extend(c.iter().map(|x| {
                let r = iv::up(x.l.abs() + rad);
                Iv::new(iv::down(x.h - r), iv::up(x.h + r))
            }));
        }
        out.resize(sh.polys * sh.len, Iv::point(0.0));
        out.iter().all(|x| x.is_finite()).then_some((out, bx))
    }
}

/// Fixed-point precision of [`BigSystem`]'s first try, and its limit (bits).
const FIRST_BITS: u64 = 192;
const MAX_BITS: u64 = 3072;

/// A node is swamped by rounding when the widths of an equation's
/// coefficients exceed this fraction of their largest magnitude.
pub(super) const NOISY: f64 = 1e-6;

/// A restart is taken when every equation's widths are at most this
/// fraction of its largest magnitude (so that the float steps after it have
/// room before the node is [`NOISY`] again); otherwise the next precision
/// is tried.
const CLEAN: f64 = 1e-12;

/// Whether rounding has swamped the coefficients `c` (`sh`'s layout): some
/// equation's widths exceed [`NOISY`] of its largest magnitude.
pub(super) fn swamped(c: &[Iv], sh: Shape) -> bool {
    !within(c, sh, NOISY)
}

/// Whether every equation's widths in `c` are at most `rel` of its largest
/// magnitude.
fn within(c: &[Iv], sh: Shape, rel: f64) -> bool {
    c.chunks_exact(sh.len).take(2).all(|c| {
        let (mut wid, mut mag) = (0.0f64, 0.0f64);
        for x in c {
            wid = wid.max(x.hi - x.lo);
            mag = mag.max(x.lo.abs().max(x.hi.abs()));
        }
        wid <= rel * mag
    })
}

/// The sources of restarts for one exact system, each built on first use:
/// double-double first, then fixed point of growing precision.
#[derive(Debug)]
pub(super) struct Restarts {
    m: usize,
    n: usize,
    input: [Vec<BigRational>; 2],
    dd: Option<Option<DdSystem>>,
    big: Vec<BigSystem>,
}

impl Restarts {
    /// For `f`, `g` of bidegree `(m, n)` on the unit square (row-major).
    pub(super) fn new(m: usize, n: usize, f: &[BigRational], g: &[BigRational]) -> Self {
        Self {
            m,
            n,
            input: [f.to_vec(), g.to_vec()],
            dd: None,
            big: Vec::new(),
        }
    }

    /// The coefficients on a box holding `outer` and the box (as
    /// [`DdSystem::restrict`]) in the cheapest precision that leaves their
    /// widths within [`CLEAN`] of their magnitudes; `None` if none up to
    /// [`MAX_BITS`] does, or for another shape.
    pub(super) fn restrict(&mut self, sh: Shape, outer: [[f64; 2]; 2]) -> Option<(Vec<Iv>, Ends)> {
        if (sh.m, sh.n) != (self.m, self.n) || sh.polys < 2 {
            return None;
        }
        let (m, n, [f, g]) = (self.m, self.n, &self.input);
        let dd = self.dd.get_or_insert_with(|| DdSystem::new(m, n, f, g));
        if let Some(fresh) = dd.as_ref().and_then(|dd| dd.restrict(sh, outer)) {
            if within(&fresh.0, sh, CLEAN) {
                return Some(fresh);
            }
        }
        let mut bits = FIRST_BITS;
        let mut level = 0;
        while bits <= MAX_BITS {
            if self.big.len() == level {
                self.big.push(BigSystem::new(m, n, f, g, bits)?);
            }
            if let Some(fresh) = self.big[level].restrict(sh, outer) {
                if within(&fresh.0, sh, CLEAN) {
                    return Some(fresh);
                }
            }
            (bits, level) = (2 * bits, level + 1);
        }
        None
    }
}

/// `f` and `g` on the unit square in fixed point on big integers (module
/// docs): each polynomial `p` as `X_i = ⌊p_i · 2^s⌋` for `s` with
/// `max |X_i| ≈ 2^bits`.
#[derive(Clone, Debug)]
pub(super) struct BigSystem {
    m: usize,
    n: usize,
    bits: u64,
    polys: [Vec<BigInt>; 2],
}

impl BigSystem {
    /// `f` and `g` (bidegree `(m, n)`, row-major) with `bits` bits; `None`
    /// if either vanishes identically or on a length mismatch.
    pub(super) fn new(m: usize, n: usize, f: &[BigRational], g: &[BigRational], bits: u64) -> Option<Self> {
        let len = (m + 1) * (n + 1);
        if f.len() != len || g.len() != len {
            return None;
        }
        let fixed = |c: &[BigRational]| -> Option<Vec<BigInt>> {
            let s = bits as i64 - top_exponent(c)?;
            Some(
                c.iter()
                    .map(|q| {
                        let (num, den) = times_pow2(q, s);
                        num.div_floor(&den)
                    })
                    .collect(),
            )
        };
        Some(Self {
            m,
            n,
            bits,
            polys: [fixed(f)?, fixed(g)?],
        })
    }

    /// As [`DdSystem::restrict`], in fixed point; `None` also where the
    /// box's largest coefficient is not 2⁵² times the error bound.
    pub(super) fn restrict(&self, sh: Shape, outer: [[f64; 2]; 2]) -> Option<(Vec<Iv>, Ends)> {
        if (sh.m, sh.n) != (self.m, self.n) || sh.polys < 2 {
            return None;
        }
        let (params, bx) = restart_box(outer)?;
        let steps = 2 * (self.m + self.n) as u64 + 1;
        let mut out = Vec::with_capacity(sh.polys * sh.len);
        for p in &self.polys {
            let (m, n) = (self.m, self.n);
            // Fixed widths for the precisions tried (values below 2^(bits + 2)).
            let c = match self.bits {
                b if b + 4 <= 4 * 64 => restrict_fx::<4>(p, m, n, &params),
                b if b + 4 <= 7 * 64 => restrict_fx::<7>(p, m, n, &params),
                b if b + 4 <= 13 * 64 => restrict_fx::<13>(p, m, n, &params),
                _ => None,
            };
            let c = match c {
                Some(c) => c,
                None => {
                    let mut c = p.clone();
                    for (d, &(alpha, gamma)) in params.iter().enumerate() {
                        restrict_fixed(&mut c, m, n, d, alpha, gamma)?;
                    }
                    c
                }
            };
            // X ± E in units, shifted so the largest has 53 bits: exact
            // floats. Fewer than 52 bits above E: not enough precision.
            let e = BigInt::from(steps);
            let top = c.iter().map(|x| x.bits()).max().unwrap_or(0);
            if top < e.bits() + 52 {
                return None;
            }
            let shift = (top - 53) as usize;
            let to_f64 = |x: BigInt| x.to_i64().map(|v| v as f64);
            let scale = 2f64.powi(-53);
            for x in &c {
                let lo = to_f64((x - &e) >> shift)?;
                let hi = to_f64(((x + &e) >> shift) + 1)?;
                out.push(Iv::new(lo * scale, hi * scale));
            }
        }
        out.resize(sh.polys * sh.len, Iv::point(0.0));
        Some((out, bx))
    }
}

/// An integer type the fixed-point steps run on: [`BigInt`], or [`Fx`] of
/// a fixed width (the same integers, without allocation).
trait FixedPoint: Clone {
    /// `c[into] = c[a] + ⌊t (c[b] − c[a]) / 2ᵏ⌋` (`into` is `a` or `b`),
    /// with `scratch` for the difference.
    fn step(c: &mut [Self], a: usize, b: usize, into: usize, t: u64, k: usize, scratch: &mut Self);
}

impl FixedPoint for BigInt {
    fn step(c: &mut [Self], a: usize, b: usize, into: usize, t: u64, k: usize, z: &mut Self) {
        z.clone_from(&c[b]);
        *z -= &c[a];
        *z *= t;
        *z >>= k;
        if into != a {
            let (lo, hi) = c.split_at_mut(into);
            hi[0].clone_from(&lo[a]);
        }
        c[into] += &*z;
    }
}

/// A signed integer of `N` 64-bit limbs, two's complement, little-endian:
/// enough for the fixed-point values (`|X| < 2^(64N − 3)`), and their
/// products by `T < 2⁵³` in one more limb.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Fx<const N: usize>([u64; N]);

impl<const N: usize> Fx<N> {
    /// `x` if it fits in `64N − 3` bits (so that the steps' convex
    /// combinations, a unit or so above their inputs, and their differences
    /// fit in `64N − 1`).
    fn from_big(x: &BigInt) -> Option<Self> {
        if x.bits() + 3 > 64 * N as u64 {
            return None;
        }
        let bytes = x.to_signed_bytes_le();
        let fill = if x.sign() == num_bigint::Sign::Minus { 0xff } else { 0 };
        let mut limbs = [0u64; N];
        for (i, l) in limbs.iter_mut().enumerate() {
            let mut b = [fill; 8];
            for (j, v) in b.iter_mut().enumerate() {
                if let Some(&x) = bytes.get(8 * i + j) {
                    *v = x;
                }
            }
            *l = u64::from_le_bytes(b);
        }
        Some(Self(limbs))
    }

    fn to_big(self) -> BigInt {
        let bytes: Vec<u8> = self.0.iter().flat_map(|l| l.to_le_bytes()).collect();
        BigInt::from_signed_bytes_le(&bytes)
    }
}

impl<const N: usize> FixedPoint for Fx<N> {
    fn step(c: &mut [Self], a: usize, b: usize, into: usize, t: u64, k: usize, _: &mut Self) {
        let (x, y) = (c[a].0, c[b].0);
        // d = y − x (fits: both below 2^(64N − 2) in magnitude).
        let mut d = [0u64; N];
        let mut borrow = false;
        for i in 0..N {
            let (v, b1) = y[i].overflowing_sub(x[i]);
            let (v, b2) = v.overflowing_sub(borrow as u64);
            d[i] = v;
            borrow = b1 || b2;
        }
        // p = d·t in N + 1 limbs: the unsigned product, less t·2^(64N) if
        // d < 0 (two's complement).
        let neg = (d[N - 1] as i64) < 0;
        let mut p = [0u64; N];
        let mut carry = 0u128;
        for i in 0..N {
            let v = d[i] as u128 * t as u128 + carry;
            p[i] = v as u64;
            carry = v >> 64;
        }
        let top = if neg {
            (carry as u64).wrapping_sub(t)
        } else {
            carry as u64
        };
        // ⌊p / 2ᵏ⌋: arithmetic shift of the N + 1 limbs.
        let ext = if (top as i64) < 0 { u64::MAX } else { 0 };
        let limb = |j: usize| match j.cmp(&N) {
            std::cmp::Ordering::Less => p[j],
            std::cmp::Ordering::Equal => top,
            std::cmp::Ordering::Greater => ext,
        };
        let (q, r) = (k / 64, k % 64);
        let mut z = [0u64; N];
        for (i, zi) in z.iter_mut().enumerate() {
            let (lo, hi) = (limb(i.saturating_add(q)), limb(i.saturating_add(q).saturating_add(1)));
            *zi = if r == 0 { lo } else { (lo >> r) | (hi << (64 - r)) };
        }
        // c[into] = x + z.
        let mut out = [0u64; N];
        let mut carry = false;
        for i in 0..N {
            let (v, c1) = x[i].overflowing_add(z[i]);
            let (v, c2) = v.overflowing_add(carry as u64);
            out[i] = v;
            carry = c1 || c2;
        }
        c[into] = Fx(out);
    }
}

/// The net `c` (bidegree `(m, n)`, row-major, fixed point) restricted in
/// direction `d` to `[α, 1]` and then to the first `γ` of that, each step
/// `X + ⌊T (Y − X) / 2ᵏ⌋` (module docs). `None` for a non-finite parameter.
fn restrict_fixed<T: FixedPoint>(c: &mut [T], m: usize, n: usize, d: usize, alpha: f64, gamma: f64) -> Option<()> {
    let mut z = c.first()?.clone();
    let frac = |x: f64| -> Option<(u64, usize)> {
        // τ ∈ [0, 1] is T·2⁻ᵏ with T ≤ 2⁵³, k ≥ 0.
        let (t, e) = dyadic(x)?;
        Some((t.to_u64()?, usize::try_from(e).ok()?))
    };
    let taus = [frac(alpha)?, frac(gamma)?];
    de_casteljau_restrict(c, m, n, d, alpha, gamma, |c, a, b, into, pass| {
        let (t, k) = taus[pass];
        T::step(c, a, b, into, t, k, &mut z);
    });
    Some(())
}

/// [`restrict_fixed`] on `N`-limb integers, converted from and back to
/// [`BigInt`]; `None` if a value does not fit.
fn restrict_fx<const N: usize>(c: &[BigInt], m: usize, n: usize, params: &[(f64, f64); 2]) -> Option<Vec<BigInt>> {
    let mut x: Vec<Fx<N>> = c.iter().map(Fx::from_big).collect::<Option<_>>()?;
    for (d, &(alpha, gamma)) in params.iter().enumerate() {
        restrict_fixed(&mut x, m, n, d, alpha, gamma)?;
    }
    Some(x.into_iter().map(Fx::to_big).collect())
}

/// `e` with every non-zero `|q|` of `c` below `2^(e + 1)` (bit lengths of
/// numerator less denominator); `None` if every coefficient is 0.
fn top_exponent(c: &[BigRational]) -> Option<i64> {
    c.iter()
        .filter(|q| !q.is_zero())
        .map(|q| q.numer().bits() as i64 - q.denom().bits() as i64)
        .max()
}

/// Numerator and denominator of `q · 2^s`, unreduced.
fn times_pow2(q: &BigRational, s: i64) -> (BigInt, BigInt) {
    if s >= 0 {
        (q.numer() << s as usize, q.denom().clone())
    } else {
        (q.numer().clone(), q.denom() << (-s) as usize)
    }
}

/// The box of the unit square reached from `outer` by the floats `(α, γ)`
/// of a clip per direction, and its endpoints' enclosures; `None` if
/// `outer` misses the square.
fn restart_box(outer: [[f64; 2]; 2]) -> Option<([(f64, f64); 2], Ends)> {
    let mut params = [(0.0, 1.0); 2];
    let mut bx = [[Iv::point(0.0), Iv::point(1.0)]; 2];
    for d in 0..2 {
        let (lo, hi) = (outer[d][0].max(0.0), outer[d][1].min(1.0));
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return None;
        }
        // As a clip: [α, α + (1 − α)γ] ⊇ [lo, hi].
        let gamma = clip_gamma(lo, hi);
        params[d] = (lo, gamma);
        let a = Iv::point(lo);
        bx[d] = [
            a,
            if gamma < 1.0 {
                Iv::lerp(a, Iv::point(1.0), gamma)
            } else {
                Iv::point(1.0)
            },
        ];
    }
    Some((params, bx))
}

/// One de Casteljau step `x + τ (y − x)` in double-double (`τ ∈ [0, 1]` a
/// float, `|x.l| ≤ u|x.h|` and the same for `y`), renormalized.
///
/// # Error
/// With `|x|, |y| ≤ M`: TwoSum gives `y.h − x.h = d_h + e₁` exactly, and
/// `d_l = fl(e₁ + fl(y.l − x.l))` errs by `≤ 6.01 u² M`; TwoProd gives
/// `τ d_h = p_h + e₂` exactly, and `p_l = fl(e₂ + fl(τ d_l))` by
/// `≤ 10.1 u² M`; TwoSum gives `x.h + p_h = s_h + e₃` exactly, and
/// `s_l = fl(e₃ + fl(x.l + p_l))` by `≤ 17.5 u² M`; the last TwoSum is
/// exact. So the result is `x + τ (y − x)` within `33.7 u² M` (and an
/// underflow of the products, `≤ 10·2⁻¹⁰⁷⁴`).
#[inline(always)]
fn lerp_dd(x: Dd, y: Dd, tau: f64) -> Dd {
    let (dh, e1) = two_sum(y.h, -x.h);
    let dl = e1 + (y.l - x.l);
    let (ph, e2) = two_prod(tau, dh);
    let pl = e2 + tau * dl;
    let (sh, e3) = two_sum(x.h, ph);
    let sl = e3 + (x.l + pl);
    let (h, l) = two_sum(sh, sl);
    Dd { h, l }
}

/// The net `c` (bidegree `(m, n)`, row-major) restricted in direction `d`
/// to `[α, 1]` and then to the first `γ` of that, in double-double.
fn restrict(c: &mut [Dd], m: usize, n: usize, d: usize, alpha: f64, gamma: f64) {
    let taus = [alpha, gamma];
    de_casteljau_restrict(c, m, n, d, alpha, gamma, |c, a, b, into, pass| {
        c[into] = lerp_dd(c[a], c[b], taus[pass]);
    });
}

/// The de Casteljau steps that restrict the net `c` (bidegree `(m, n)`,
/// row-major) in direction `d` to `[α, 1]` (if `α > 0`; pass 0) and then
/// to the first `γ` of that (if `γ < 1`; pass 1): `step(c, a, b, into,
/// pass)` sets `c[into]` (`a` in pass 0, `b` in pass 1) to `c[a] +
/// τ (c[b] − c[a])` for that pass's `τ`. Whole rows at once in `u` (index
/// `i·w + j` over `j`), one row at a time in `v`.
fn de_casteljau_restrict<T>(
    c: &mut [T],
    m: usize,
    n: usize,
    d: usize,
    alpha: f64,
    gamma: f64,
    mut step: impl FnMut(&mut [T], usize, usize, usize, usize),
) {
    let w = n + 1;
    let k = if d == 0 { m } else { n };
    let (count, stride, jump) = if d == 0 { (w, w, 1) } else { (m + 1, 1, w) };
    let at = |line: usize, i: usize| line * jump + i * stride;
    if alpha > 0.0 {
        for r in 1..=k {
            for i in 0..=k - r {
                for line in 0..count {
                    let (a, b) = (at(line, i), at(line, i + 1));
                    step(c, a, b, a, 0);
                }
            }
        }
    }
    if gamma < 1.0 {
        for r in 1..=k {
            for i in (r..=k).rev() {
                for line in 0..count {
                    let (a, b) = (at(line, i - 1), at(line, i));
                    step(c, a, b, b, 1);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
