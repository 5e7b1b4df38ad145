//! The number trait behind the Bernstein–Bézier algebra, and its three kernels.
//!
//! Every polynomial type in [`crate::poly`] is generic over [`Scalar`]. The
//! three kernels play three roles:
//!
//! | kernel | role | rounding |
//! |---|---|---|
//! | `f64` | fast *proposals* (approximants, Newton midpoints) | round-to-nearest, no guarantee |
//! | [`Interval`] (inari) | rigorous *enclosures*: every operation rounds outward, so the exact result of the same computation on any members of the inputs lies in the output | outward |
//! | [`BigRational`] | exact reference arithmetic (oracles, tests, parsing) | exact |
//!
//! inari implements no `num-traits`, so the trait is ours (the same choice the
//! `geo`/`robust` crates make for their kernels).
//!
//! # Conversions
//! * [`rational_to_interval`]: the *tightest* interval with `f64` endpoints
//!   containing a rational. A rational that is not a float (such as 1/10) becomes
//!   an interval of width one ulp, never a point.
//! * [`rational_to_f64`] rounds to nearest.
//!
//! # Speed of the interval kernel
//! The hot loops of [`crate::poly`] run interval arithmetic on bare endpoint
//! pairs (the crate-private `endpoints` module): the same operations in the
//! same order, each endpoint the same float inari's operators produce, but
//! without inari's switch of the FPU rounding mode per operation, which made
//! interval code 10–25 times slower than `f64`.

use inari::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use std::any::{Any, TypeId};
use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt::Debug;
use std::hash::{BuildHasherDefault, Hasher};
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::{Arc, Mutex, OnceLock};

mod endpoints;
pub(crate) mod iv;
pub(crate) mod rational_interval;
pub(crate) use endpoints::{
    cached_endpoints, endpoint_net, endpoint_of, endpoints_of, from_endpoint, from_endpoints, store_endpoints, Arith,
    Endpoints,
};

/// What a kernel can say about the sign of a value.
///
/// For the rigorous kernels a definite answer is a proof about every member of
/// the enclosure; for `f64` it is only the sign of the rounded value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Every member is `< 0`.
    Negative,
    /// The value is exactly zero (a point interval `[0, 0]`).
    Zero,
    /// Every member is `> 0`.
    Positive,
    /// The enclosure contains values of both signs, or zero and non-zero ones.
    Straddles,
}

/// Which arithmetic a kernel performs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// Plain `f64`: round-to-nearest, may propose, never proves.
    Float,
    /// `inari::Interval`: outward rounding, proves.
    Interval,
    /// `BigRational`: exact, proves.
    Exact,
}

impl Kernel {
    /// `true` for kernels whose sign and magnitude answers are proofs.
    pub fn is_rigorous(self) -> bool {
        !matches!(self, Kernel::Float)
    }
}

/// Keys of the per-kernel matrix cache (see [`Scalar::cached_matrix`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MatrixKey {
    /// Univariate L2 reduction, degree `n` to `k`.
    UniReduce(usize, usize),
    /// Triangular L2 reduction, degree `n` to `k`.
    TriReduce(usize, usize),
    /// Univariate degree elevation, degree `n` to `m`.
    UniElevate(usize, usize),
    /// Triangular degree elevation, degree `n` to `m`.
    TriElevate(usize, usize),
    /// Tensor bidegree `(m, n)` on the unit square to a triangle of degree `m + n`.
    TensorToTri(usize, usize),
    /// Weights of the triangular BB product of degrees `m` and `n`.
    TriProduct(usize, usize),
}

type Cache<S> = Mutex<HashMap<MatrixKey, Arc<[S]>>>;

/// A number type the Bernstein–Bézier algebra can run on.
///
/// Implemented for `f64`, [`Interval`] and [`BigRational`]. Arithmetic is by
/// value (`Copy` kernels pay nothing for the clones generic code makes).
///
/// Contract for the rigorous kernels ([`Kernel::is_rigorous`]): every
/// operation returns an enclosure of the exact result for all members of its
/// inputs; [`Scalar::sign_class`] and [`Scalar::mag`] answer for every member.
pub trait Scalar:
    Clone
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The kind of arithmetic.
    const KERNEL: Kernel;
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// An integer (exact for `|n| <= 2^53` in the float kernels; the interval
    /// kernel encloses larger ones).
    fn from_i64(n: i64) -> Self;
    /// A finite float, exactly; `None` for NaN or ±∞.
    fn from_f64(x: f64) -> Option<Self>;
    /// A rational: exact (rational kernel), tightest enclosure (interval
    /// kernel, see [`rational_to_interval`]), nearest float (`f64`).
    fn from_rational(q: &BigRational) -> Self;
    /// A representative float: the value, the interval midpoint, or the
    /// nearest float to the rational.
    fn to_f64(&self) -> f64;
    /// The sign; see [`Sign`].
    fn sign_class(&self) -> Sign;
    /// An upper bound on `|x|` over the enclosure, rounded up (rigorous
    /// kernels) or to nearest (`f64`).
    fn mag(&self) -> f64;
    /// A lower bound on every member (rounded down for the rigorous kernels).
    fn lower(&self) -> f64;
    /// An upper bound on every member (rounded up for the rigorous kernels).
    fn upper(&self) -> f64;
    /// `false` if the value is NaN, infinite or an unbounded/empty interval.
    fn is_finite(&self) -> bool;
    /// `|x|` (for intervals: the enclosure of `|t|` over members `t`).
    fn abs(&self) -> Self;
    /// The larger of two values (for intervals: the enclosure of `max(s, t)`).
    fn max(self, other: Self) -> Self;
    /// A single representative as a value of this kernel: the point interval
    /// at the midpoint for intervals, the value itself otherwise.
    fn to_point(&self) -> Self;
    /// The per-kernel cache of rational matrices converted to this kernel.
    fn matrix_cache() -> &'static Cache<Self>;

    /// A matrix built once per key in exact arithmetic by `build` and cached
    /// converted to this kernel (tightest intervals for [`Interval`]).
    ///
    /// Hot loops call this per operation, so a thread-local copy answers
    /// repeat lookups without a lock; the process-wide cache behind it
    /// ([`Scalar::matrix_cache`]) makes sure each matrix is built once.
    fn cached_matrix(key: MatrixKey, build: impl FnOnce() -> Vec<BigRational>) -> Arc<[Self]> {
        if let Some(m) = local_matrix::<Self>(key) {
            return m;
        }
        let cache = Self::matrix_cache();
        // Bind the lookup first: a guard held across the match would deadlock
        // on the insert below.
        let found = lock(cache).get(&key).cloned();
        let shared = match found {
            Some(m) => m,
            None => {
                let converted: Arc<[Self]> = build().iter().map(Self::from_rational).collect();
                lock(cache).entry(key).or_insert(converted).clone()
            }
        };
        // A private copy per thread keeps the reference count of a hot matrix
        // off a cache line that other threads write.
        let local: Arc<[Self]> = Arc::from(&shared[..]);
        remember_local_matrix(key, local.clone());
        local
    }
}

/// Per-thread front of the matrix caches, keyed by kernel and matrix.
type LocalCache = HashMap<(TypeId, MatrixKey), Box<dyn Any>, BuildHasherDefault<FxHasher>>;

thread_local! {
    static LOCAL_MATRICES: RefCell<LocalCache> =
        const { RefCell::new(HashMap::with_hasher(BuildHasherDefault::new())) };
}

/// This thread's copy of matrix `key` with entries of type `T`, if any.
fn local_matrix<T: 'static>(key: MatrixKey) -> Option<Arc<[T]>> {
    LOCAL_MATRICES
        .try_with(|c| {
            let cache = c.borrow();
            let entry = cache.get(&(TypeId::of::<T>(), key))?;
            entry.downcast_ref::<Arc<[T]>>().cloned()
        })
        .ok()
        .flatten()
}

fn remember_local_matrix<T: 'static>(key: MatrixKey, m: Arc<[T]>) {
    // During thread teardown the local cache is gone; the global one still
    // answers, so there is nothing to do.
    let _ = LOCAL_MATRICES.try_with(|c| {
        if let Ok(mut cache) = c.try_borrow_mut() {
            cache.insert((TypeId::of::<T>(), key), Box::new(m));
        }
    });
}

/// The multiplicative hash of rustc's `FxHasher`: the keys are a few small
/// integers, for which SipHash's flooding resistance buys nothing and costs
/// more than the rest of a lookup.
#[derive(Default)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    // A panic while holding the lock cannot leave a half-written entry (insert is
    // atomic from the map's view), so a poisoned cache is still sound.
    m.lock().unwrap_or_else(|e| e.into_inner())
}

macro_rules! cache_fn {
    ($t:ty) => {
        fn matrix_cache() -> &'static Cache<$t> {
            static CACHE: OnceLock<Cache<$t>> = OnceLock::new();
            CACHE.get_or_init(Default::default)
        }
    };
}

impl Scalar for f64 {
    const KERNEL: Kernel = Kernel::Float;
    fn zero() -> Self {
        0.0
    }
    fn one() -> Self {
        1.0
    }
    fn from_i64(n: i64) -> Self {
        n as f64
    }
    fn from_f64(x: f64) -> Option<Self> {
        x.is_finite().then_some(x)
    }
    fn from_rational(q: &BigRational) -> Self {
        rational_to_f64(q)
    }
    fn to_f64(&self) -> f64 {
        *self
    }
    fn sign_class(&self) -> Sign {
        if *self > 0.0 {
            Sign::Positive
        } else if *self < 0.0 {
            Sign::Negative
        } else if *self == 0.0 {
            Sign::Zero
        } else {
            Sign::Straddles
        }
    }
    fn mag(&self) -> f64 {
        f64::abs(*self)
    }
    fn lower(&self) -> f64 {
        *self
    }
    fn upper(&self) -> f64 {
        *self
    }
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    fn abs(&self) -> Self {
        f64::abs(*self)
    }
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    fn to_point(&self) -> Self {
        *self
    }
    cache_fn!(f64);
}

impl Scalar for Interval {
    const KERNEL: Kernel = Kernel::Interval;
    fn zero() -> Self {
        point(0.0)
    }
    fn one() -> Self {
        point(1.0)
    }
    fn from_i64(n: i64) -> Self {
        // Integers up to 2^53 are floats: the point is the tightest enclosure,
        // as the rational route would find, without the big-integer detour.
        if n.unsigned_abs() <= 1 << 53 {
            return point(n as f64);
        }
        rational_to_interval(&BigRational::from_integer(BigInt::from(n)))
    }
    fn from_f64(x: f64) -> Option<Self> {
        x.is_finite().then(|| point(x))
    }
    fn from_rational(q: &BigRational) -> Self {
        rational_to_interval(q)
    }
    fn to_f64(&self) -> f64 {
        self.mid()
    }
    fn sign_class(&self) -> Sign {
        if self.is_empty() {
            Sign::Straddles
        } else if self.inf() > 0.0 {
            Sign::Positive
        } else if self.sup() < 0.0 {
            Sign::Negative
        } else if self.inf() == 0.0 && self.sup() == 0.0 {
            Sign::Zero
        } else {
            Sign::Straddles
        }
    }
    fn mag(&self) -> f64 {
        if self.is_empty() {
            f64::INFINITY
        } else {
            Interval::mag(*self)
        }
    }
    fn lower(&self) -> f64 {
        if self.is_empty() {
            f64::NEG_INFINITY
        } else {
            self.inf()
        }
    }
    fn upper(&self) -> f64 {
        if self.is_empty() {
            f64::INFINITY
        } else {
            self.sup()
        }
    }
    fn is_finite(&self) -> bool {
        !self.is_empty() && self.inf().is_finite() && self.sup().is_finite()
    }
    fn abs(&self) -> Self {
        Interval::abs(*self)
    }
    fn max(self, other: Self) -> Self {
        Interval::max(self, other)
    }
    fn to_point(&self) -> Self {
        let m = self.mid();
        if m.is_finite() {
            point(m)
        } else {
            *self
        }
    }
    cache_fn!(Interval);
}

impl Scalar for BigRational {
    const KERNEL: Kernel = Kernel::Exact;
    fn zero() -> Self {
        <BigRational as Zero>::zero()
    }
    fn one() -> Self {
        BigRational::from_integer(BigInt::from(1))
    }
    fn from_i64(n: i64) -> Self {
        BigRational::from_integer(BigInt::from(n))
    }
    fn from_f64(x: f64) -> Option<Self> {
        BigRational::from_float(x)
    }
    fn from_rational(q: &BigRational) -> Self {
        q.clone()
    }
    fn to_f64(&self) -> f64 {
        rational_to_f64(self)
    }
    fn sign_class(&self) -> Sign {
        if self.is_positive() {
            Sign::Positive
        } else if self.is_negative() {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    fn mag(&self) -> f64 {
        rational_to_interval(self).mag()
    }
    fn lower(&self) -> f64 {
        rational_to_interval(self).inf()
    }
    fn upper(&self) -> f64 {
        rational_to_interval(self).sup()
    }
    fn is_finite(&self) -> bool {
        true
    }
    fn abs(&self) -> Self {
        Signed::abs(self)
    }
    fn max(self, other: Self) -> Self {
        Ord::max(self, other)
    }
    fn to_point(&self) -> Self {
        self.clone()
    }
    cache_fn!(BigRational);
}

/// The point interval `[x, x]`. `x` must be finite (the caller's invariant).
pub fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
}

/// The interval `[lo, hi]`; the entire line if the bounds are NaN or reversed
/// (always an enclosure, never a panic).
pub fn interval(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
}

/// The nearest `f64` to `q` (ties to even); ±∞ beyond the float range.
pub fn rational_to_f64(q: &BigRational) -> f64 {
    match ToPrimitive::to_f64(q) {
        Some(x) if !x.is_nan() => x,
        _ if q.is_negative() => f64::NEG_INFINITY,
        _ => f64::INFINITY,
    }
}

/// The tightest interval `[lo, hi]` with `f64` endpoints that contains `q`.
///
/// Exact when `q` is a float (a point interval); otherwise `lo` and `hi` are
/// adjacent floats with `lo < q < hi`. Beyond the float range the outer end is
/// infinite (`[f64::MAX, +∞]`).
///
/// ```
/// use num_rational::BigRational;
/// use rootclip::scalar::rational_to_interval;
/// let tenth = BigRational::new(1.into(), 10.into());
/// let x = rational_to_interval(&tenth);
/// assert!(x.inf() < 0.1 && 0.1 <= x.sup() || x.inf() <= 0.1 && 0.1 < x.sup());
/// assert_eq!(x.sup().next_down(), x.inf());
/// ```
pub fn rational_to_interval(q: &BigRational) -> Interval {
    if let Some(x) = small_rational_to_interval(q) {
        return x;
    }
    let approx = rational_to_f64(q);
    if !approx.is_finite() {
        return if q.is_negative() {
            interval(f64::NEG_INFINITY, -f64::MAX)
        } else {
            interval(f64::MAX, f64::INFINITY)
        };
    }
    let exact = |x: f64| BigRational::from_float(x).expect("finite float");
    let back = exact(approx);
    if &back == q {
        return point(approx);
    }
    // `to_f64` is correctly rounded in num-rational 0.4, but the bracket is
    // verified exactly rather than trusted, so this stays an enclosure even if
    // the conversion were off by more than an ulp.
    if &back < q {
        let mut hi = approx.next_up();
        while hi.is_finite() && &exact(hi) < q {
            hi = hi.next_up();
        }
        let lo = if hi.is_finite() { hi.next_down() } else { approx };
        interval(lo, hi)
    } else {
        let mut lo = approx.next_down();
        while lo.is_finite() && &exact(lo) > q {
            lo = lo.next_down();
        }
        let hi = if lo.is_finite() { lo.next_up() } else { approx };
        interval(lo, hi)
    }
}

/// [`rational_to_interval`] for `q = n/d` with `|n|, d ≤ 2⁵³` (both exact in
/// `f64`), without big-integer work: the nearest quotient `x = n ⊘ d` has the
/// exact remainder `r = n − x·d` (one FMA; exact for a correctly rounded
/// quotient of floats, Boldo–Muller), and `n/d − x = r/d` with `d > 0`
/// (num-rational keeps denominators positive), so the sign of `r` says on
/// which side of `x` the rational lies — and the adjacent float on that side
/// closes the tightest bracket. `None` outside that range.
fn small_rational_to_interval(q: &BigRational) -> Option<Interval> {
    const EXACT: u64 = 1 << 53;
    let (n, d) = (q.numer().to_i64()?, q.denom().to_i64()?);
    if n.unsigned_abs() > EXACT || d <= 0 || d as u64 > EXACT {
        return None;
    }
    let (n, d) = (n as f64, d as f64);
    let x = n / d;
    let r = (-x).mul_add(d, n);
    Some(if r == 0.0 {
        point(x)
    } else if r > 0.0 {
        interval(x, x.next_up())
    } else {
        interval(x.next_down(), x)
    })
}

/// `true` if the interval `x` contains the rational `q` (exact comparison).
pub fn interval_contains_rational(x: Interval, q: &BigRational) -> bool {
    if x.is_empty() {
        return false;
    }
    let below = match BigRational::from_float(x.inf()) {
        Some(lo) => &lo <= q,
        None => x.inf() == f64::NEG_INFINITY,
    };
    let above = match BigRational::from_float(x.sup()) {
        Some(hi) => q <= &hi,
        None => x.sup() == f64::INFINITY,
    };
    below && above
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn tenth_is_not_a_point() {
        let x = rational_to_interval(&q(1, 10));
        assert!(x.inf() < x.sup());
        assert_eq!(x.inf().next_up(), x.sup());
        assert!(interval_contains_rational(x, &q(1, 10)));
    }

    /// The small-rational fast path gives exactly the interval of the
    /// exact bracket search, including near the ends of its range.
    #[test]
    fn small_rationals_match_the_exact_bracket() {
        let slow = |q: &BigRational| {
            let approx = rational_to_f64(q);
            let back = BigRational::from_float(approx).unwrap();
            if &back == q {
                (approx, approx)
            } else if &back < q {
                (approx, approx.next_up())
            } else {
                (approx.next_down(), approx)
            }
        };
        let big = 1i64 << 53;
        let mut rng = crate::rng::Rng(0x9e3779b97f4a7c15);
        let mut next = || rng.next_u64() >> 11;
        let mut cases: Vec<(i64, i64)> = vec![
            (0, 1),
            (1, 3),
            (-1, 3),
            (big, 3),
            (-big, big - 1),
            (big - 1, big),
            (7, big),
        ];
        for _ in 0..20_000 {
            let n = (next() % (2 * big as u64 + 1)) as i64 - big;
            let d = 1 + (next() % big as u64) as i64;
            let small = 1 + (next() % 1000) as i64;
            cases.push((n, d));
            cases.push((n % 1000, small));
        }
        for (n, d) in cases {
            let q = BigRational::new(n.into(), d.into());
            let x = small_rational_to_interval(&q).expect("in range");
            assert_eq!((x.inf(), x.sup()), slow(&q), "{n}/{d}");
            assert!(interval_contains_rational(x, &q));
        }
        // Beyond 2^53 the exact path takes over.
        assert!(small_rational_to_interval(&q(big + 1, 2)).is_none());
    }

    #[test]
    fn dyadic_is_a_point() {
        let x = rational_to_interval(&q(-3, 8));
        assert_eq!((x.inf(), x.sup()), (-0.375, -0.375));
        assert_eq!(x.sign_class(), Sign::Negative);
    }

    #[test]
    fn huge_and_tiny() {
        let big = BigRational::from_integer(BigInt::from(10).pow(400));
        let x = rational_to_interval(&big);
        assert_eq!(x.sup(), f64::INFINITY);
        assert!(interval_contains_rational(x, &big));
        let tiny = BigRational::new(1.into(), BigInt::from(10).pow(400));
        let y = rational_to_interval(&tiny);
        assert!(y.inf() == 0.0 && y.sup() > 0.0);
        assert!(interval_contains_rational(y, &tiny));
        assert_eq!(y.sign_class(), Sign::Straddles);
    }

    #[test]
    fn signs() {
        assert_eq!(interval(-1.0, 1.0).sign_class(), Sign::Straddles);
        assert_eq!(interval(0.0, 0.0).sign_class(), Sign::Zero);
        assert_eq!(Interval::EMPTY.sign_class(), Sign::Straddles);
        assert_eq!(Interval::ENTIRE.mag(), f64::INFINITY);
        assert_eq!(<f64 as Scalar>::sign_class(&f64::NAN), Sign::Straddles);
        assert_eq!(<BigRational as Scalar>::from_f64(f64::NAN), None);
    }
}
