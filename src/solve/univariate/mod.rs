//! The certified univariate solver: every root of a Bernstein–Bézier
//! polynomial on its interval, with the [`UniSolution`] contract.
//!
//! # Method
//! On the local parameter `t ∈ [0, 1]` (`x = a + t (b − a)`):
//! 1. **Subdivision** of `[0, 1]`. On each sub-interval the BB coefficients
//!    are enclosed (two de Casteljau passes from the input's enclosures,
//!    rounded outward) and **Descartes' rule of signs** decides: no sign
//!    change for any member of the enclosures (a coefficient whose enclosure
//!    contains 0 counting as a possible change either way) and non-zero end
//!    values: no root; exactly one change for every member and opposite end
//!    signs: exactly one root, simple. Otherwise the **Bézier clip** (the
//!    control polygon's convex hull meets zero only in `[λ₀, λ₁]`, bounded
//!    outward) shrinks it, or it is bisected.
//! 2. **Interval Newton** `N(X) = m − p(m)/p'(X)` (outward rounding; `p'(X)`
//!    the hull of the derivative's coefficients on `X`) certifies:
//!    `N(X) ⊂ int X` proves exactly one root in `X`, simple;
//!    `N(X) ∩ X = ∅` proves none. A certified interval is contracted by
//!    `X ← N(X) ∩ X` (and bisection on proven signs) to the rounding floor.
//!    Intervals the search could not decide (narrower than `eps`, or where
//!    rounding hides every sign) are grouped and tested again, widened a
//!    little and then contracted or grown towards `N(X)`.
//! 3. **Exact arithmetic** for exact input (`f64` or rational
//!    coefficients): the undecided regions are isolated again with
//!    Descartes' rule and interval Newton on exact rational coefficients
//!    (two simple roots 1e-12 apart are separated; a double root stays
//!    undecided, in a region a few ulps wide), and a root whose interval
//!    reaches over an end of the domain is settled by the exact signs of `p`
//!    at that end and at the interval's far end: a root exactly at the end
//!    is in, one a subnormal outside is out.
//!
//! Floating point proposes (midpoints, clip bounds, split points); only
//! outward-rounded interval arithmetic or exact rationals exclude or
//! certify. The argument in full is in `docs/rigor.md` of the repository.
//!
//! References: Descartes' rule on Bernstein coefficients — Eigenwillig,
//! Sharma & Yap (2006), *Almost tight recursion tree bounds for the
//! Descartes method*, ISSAC, doi:10.1145/1145768.1145786; Bézier clipping —
//! Nishita, Sederberg & Kakimoto (1990), doi:10.1145/97880.97918; interval
//! Newton — Moore (1966), *Interval Analysis*.

mod bernstein;
mod exact;
mod interval;
mod solution;

pub use solution::{UniCluster, UniOptions, UniRoot, UniSolution, UniStats};

use crate::error::{Error, Result};
use crate::poly::UniBezier;
use crate::scalar::iv::Iv;
use crate::scalar::{point, rational_to_interval};
use crate::solve::krawczyk::Verdict;
use crate::solve::solution::UndecidedReason;
use bernstein::Sign3;
use inari::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

type Q = BigRational;

/// The largest degree [`solve_uni`] takes ([`Error::TooLarge`] beyond):
/// every sub-interval costs `O(n²)` operations, exact ones on rationals of
/// `O(n)` floats' size.
pub const MAX_UNI_DEGREE: usize = 64;

/// Exact tests (rational restrictions) per solve, over all undecided regions.
const EXACT_TESTS: usize = 256;
/// Bisections along any path of the exact isolation.
const EXACT_DEPTH: usize = 64;
/// Groups of at most this many touching leaves whose hull fails are tested
/// leaf by leaf (two roots a few leaves apart).
const SMALL_GROUP: usize = 16;

/// A Bernstein–Bézier polynomial [`solve_uni`] takes: [`UniBezier`] with
/// `f64`, [`BigRational`] or [`Interval`] coefficients. Sealed.
pub trait UniPolynomial: sealed::Sealed {}

mod sealed {
    use num_rational::BigRational;

    pub trait Sealed {
        fn input(&self) -> crate::Result<Input>;
    }

    /// The coefficients [`solve_uni`](super::solve_uni) works on, and the
    /// domain.
    pub struct Input {
        /// Exact coefficients (exact input), or `None` (enclosures).
        pub exact: Option<Vec<BigRational>>,
        /// Enclosures (of the exact coefficients, for exact input).
        pub enclosed: Vec<inari::Interval>,
        pub domain: [BigRational; 2],
    }
}

use sealed::Input;

fn exactly(x: f64, what: &str) -> Result<Q> {
    Q::from_float(x).ok_or_else(|| Error::NonFinite(format!("{what} is {x}")))
}

fn exact_input(coeffs: Vec<Q>, domain: [Q; 2]) -> Input {
    Input {
        enclosed: coeffs.iter().map(rational_to_interval).collect(),
        exact: Some(coeffs),
        domain,
    }
}

impl UniPolynomial for UniBezier<f64> {}
impl sealed::Sealed for UniBezier<f64> {
    fn input(&self) -> Result<Input> {
        let c = self
            .coeffs()
            .iter()
            .map(|&x| exactly(x, "a coefficient"))
            .collect::<Result<_>>()?;
        let [a, b] = self.domain();
        Ok(exact_input(
            c,
            [exactly(*a, "a domain end")?, exactly(*b, "a domain end")?],
        ))
    }
}
impl UniPolynomial for UniBezier<BigRational> {}
impl sealed::Sealed for UniBezier<BigRational> {
    fn input(&self) -> Result<Input> {
        Ok(exact_input(self.coeffs().to_vec(), self.domain().clone()))
    }
}
impl UniPolynomial for UniBezier<Interval> {}
impl sealed::Sealed for UniBezier<Interval> {
    fn input(&self) -> Result<Input> {
        if let Some(k) = self
            .coeffs()
            .iter()
            .position(|c| c.is_empty() || !c.is_common_interval())
        {
            return Err(Error::NonFinite(format!("coefficient {k} is empty or unbounded")));
        }
        let end = |x: &Interval| {
            if x.inf() == x.sup() {
                exactly(x.inf(), "a domain end")
            } else {
                Err(Error::Shape(
                    "solve_uni needs a domain with exact ends (point intervals)".into(),
                ))
            }
        };
        let [a, b] = self.domain();
        Ok(Input {
            exact: None,
            enclosed: self.coeffs().to_vec(),
            domain: [end(a)?, end(b)?],
        })
    }
}

/// Every root of the polynomial `f` on its closed interval `[a, b]`, with
/// the [`UniSolution`] contract:
/// * `f64` and [`BigRational`] coefficients: the polynomial with exactly
///   these coefficients (a float is an exact rational); roots at or within
///   rounding of `a` or `b` are settled in exact arithmetic, and the regions
///   rounding leaves undecided are retried exactly;
/// * [`Interval`] coefficients: every polynomial whose coefficients lie in
///   the enclosures (the domain's ends must be point intervals).
///
/// Errors: NaN or infinite coefficients ([`Error::NonFinite`]), an
/// identically zero polynomial (every point is a root: [`Error::Degenerate`];
/// for interval input only when every coefficient is exactly zero — a zero
/// *enclosure* yields one undecided region), a degree above
/// [`MAX_UNI_DEGREE`] ([`Error::TooLarge`]), invalid options
/// ([`Error::InvalidOption`]).
///
/// ```
/// use rootclip::solve::{solve_uni, UniOptions};
/// use rootclip::UniBezier;
/// // (x − 1/4)(x − 1/2) on [0, 1]: BB coefficients 1/8, 1/8 − 3/8, 1/8 − 3/4 + 1.
/// let f = UniBezier::on_unit(vec![0.125, -0.25, 0.375])?;
/// let sol = solve_uni(&f, &UniOptions::default())?;
/// assert!(sol.complete && sol.clusters.is_empty());
/// assert_eq!(sol.roots.len(), 2);
/// // Contracted to the rounding floor: a few ulps of the coefficients
/// // (evaluated in outward-rounded intervals) over |f'(1/4)| = 1/4.
/// let [lo, hi] = sol.roots[0].interval;
/// assert!(lo <= 0.25 && 0.25 <= hi && hi - lo < 1e-14);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn solve_uni<P: UniPolynomial>(f: &P, opts: &UniOptions) -> Result<UniSolution> {
    opts.validate()?;
    let input = f.input()?;
    let n = input.enclosed.len() - 1;
    if n > MAX_UNI_DEGREE {
        return Err(Error::TooLarge(format!(
            "degree {n} exceeds the univariate limit {MAX_UNI_DEGREE}"
        )));
    }
    let poly = Prepared::new(input)?;
    Ok(poly.solve(opts))
}

/// Beyond this power of two (either way) the largest coefficient is scaled
/// towards 1 (by a power of two: the roots do not move), so that the
/// derivative's coefficients cannot overflow and tiny ones keep their bits
/// clear of the subnormal range.
const EXTREME_LOG2: i64 = 256;

/// The polynomial on `[0, 1]` in the solver's kernels (see [`EXTREME_LOG2`]).
struct Prepared {
    exact: Option<Vec<Q>>,
    iv: Vec<Iv>,
    domain: [Q; 2],
}

impl Prepared {
    fn new(input: Input) -> Result<Self> {
        let Input {
            exact,
            enclosed,
            domain,
        } = input;
        if (&domain[1] - &domain[0]).is_negative() || domain[0] == domain[1] {
            return Err(Error::Degenerate("the domain [a, b] needs a < b".into()));
        }
        let zero = Error::Degenerate("the polynomial is identically zero: every point is a root".into());
        let (exact, enclosed) = match exact {
            Some(c) => {
                if c.iter().all(Zero::is_zero) {
                    return Err(zero);
                }
                let e = c.iter().filter(|x| !x.is_zero()).map(log2).max().unwrap_or(0);
                let c: Vec<Q> = if e.abs() > EXTREME_LOG2 {
                    c.iter().map(|x| times_pow2(x, -e)).collect()
                } else {
                    c
                };
                let iv: Vec<Interval> = c.iter().map(rational_to_interval).collect();
                (Some(c), iv)
            }
            None => {
                if enclosed.iter().all(|x| x.inf() == 0.0 && x.sup() == 0.0) {
                    return Err(zero);
                }
                let top = enclosed.iter().map(|x| x.mag()).fold(0.0, f64::max);
                let e = if top > 0.0 {
                    top.log2().floor().clamp(-1000.0, 1000.0)
                } else {
                    0.0
                };
                if e.abs() > EXTREME_LOG2 as f64 {
                    let s = point(2f64.powi(-(e as i32)));
                    (None, enclosed.iter().map(|&x| x * s).collect())
                } else {
                    (None, enclosed)
                }
            }
        };
        let iv = enclosed.iter().map(|x: &Interval| Iv::new(x.inf(), x.sup())).collect();
        Ok(Self { exact, iv, domain })
    }

    fn solve(&self, opts: &UniOptions) -> UniSolution {
        let mut stats = UniStats::default();
        let found = interval::search(&self.iv, opts.eps, opts.max_boxes, &mut stats);
        let mut roots = found.roots;
        let mut undecided = self.certify_leaves(found.leaves, &mut roots, &mut stats);
        if let Some(c) = &self.exact {
            undecided = self.isolate_exactly(c, undecided, &mut roots, &mut stats);
        }
        let mut clusters: Vec<([f64; 2], UndecidedReason)> = undecided
            .into_iter()
            .map(|x| (x, UndecidedReason::MultipleOrClose))
            .collect();
        let mut settled = Vec::with_capacity(roots.len());
        for r in roots {
            match self.settle(r) {
                Place::Inside(t) => settled.push(t),
                Place::Outside => stats.outside_domain += 1,
                Place::Undecided => clusters.push((r, UndecidedReason::Boundary)),
            }
        }
        let (roots, merged) = self.merge_roots(settled);
        clusters.extend(merged.into_iter().map(|x| (x, UndecidedReason::MultipleOrClose)));
        self.in_domain(roots, clusters, found.leftovers, stats)
    }

    /// Groups touching leaves and certifies each group (or, for a small
    /// group whose hull fails, each leaf); returns what stays undecided.
    fn certify_leaves(
        &self,
        mut leaves: Vec<[f64; 2]>,
        roots: &mut Vec<[f64; 2]>,
        stats: &mut UniStats,
    ) -> Vec<[f64; 2]> {
        leaves.sort_by(by_lo);
        let mut undecided = Vec::new();
        for group in touching(leaves) {
            let hull = [group[0][0], group.iter().map(|x| x[1]).fold(f64::MIN, f64::max)];
            match interval::certify(&self.iv, hull, stats) {
                Verdict::Unique(k) => roots.push(k),
                Verdict::NoRoot => stats.newton_exclusions += 1,
                Verdict::Undecided(()) if group.len() > 1 && group.len() <= SMALL_GROUP => {
                    for leaf in group {
                        match interval::certify(&self.iv, leaf, stats) {
                            Verdict::Unique(k) => roots.push(k),
                            Verdict::NoRoot => stats.newton_exclusions += 1,
                            Verdict::Undecided(()) => undecided.push(leaf),
                        }
                    }
                }
                Verdict::Undecided(()) => undecided.push(hull),
            }
        }
        joined(undecided)
    }

    /// Exact isolation of the undecided regions (exact input), within one
    /// budget of exact tests; what it cannot decide stays undecided.
    fn isolate_exactly(
        &self,
        c: &[Q],
        regions: Vec<[f64; 2]>,
        roots: &mut Vec<[f64; 2]>,
        stats: &mut UniStats,
    ) -> Vec<[f64; 2]> {
        if regions.is_empty() {
            return regions;
        }
        // Isolating the distinct roots on the square-free part terminates
        // where p's multiple roots would keep every piece undecided; each
        // is then certified simple for p, or left (tightly) undecided.
        let sf = exact::SquareFree::new(c);
        let mut left = Vec::new();
        for x in regions {
            let budget = EXACT_TESTS.saturating_sub(stats.exact_tests);
            if budget == 0 {
                left.push(x);
                continue;
            }
            let limits = exact::Limits {
                depth: EXACT_DEPTH,
                tests: budget,
            };
            let found = exact::isolate(&sf.s, x, &limits);
            stats.exact_tests += found.tests;
            for r in found.roots {
                match sf.simple(r, &mut stats.exact_tests, EXACT_TESTS) {
                    Some(k) => roots.push(k),
                    None => left.push(r),
                }
            }
            left.extend(found.undecided);
        }
        joined(left)
    }

    /// The sign of `p` at the float `t`, proven (exact, or for every member).
    fn sign_at(&self, t: f64) -> Sign3 {
        match &self.exact {
            Some(c) => match exact::sign_at(c, t) {
                Ordering::Less => Sign3::Neg,
                Ordering::Equal => Sign3::Zero,
                Ordering::Greater => Sign3::Pos,
            },
            None if t == 0.0 => Sign3::of(self.iv[0]),
            None if t == 1.0 => Sign3::of(self.iv[self.iv.len() - 1]),
            None => Sign3::of(bernstein::eval(&self.iv, t)),
        }
    }

    /// Where the root certified in `t` (exactly one, simple) lies relative
    /// to `[0, 1]`. Over an end `e`: `p(e) = 0` puts the root at `e`;
    /// otherwise the signs of `p` at `e` and at the interval's far end `f`
    /// decide: equal (an even number of roots between, so none of the one
    /// simple root) puts it beyond `e`, opposite between `e` and `f`, a zero
    /// at `f` at `f`. Exact for exact input; for enclosures, undecided where
    /// a sign is not proven.
    fn settle(&self, mut t: [f64; 2]) -> Place {
        if t[1] < 0.0 || t[0] > 1.0 {
            return Place::Outside;
        }
        if t[0] < 0.0 {
            match (self.sign_at(0.0), self.sign_at(t[1])) {
                (Sign3::Zero, _) => return Place::Inside([0.0, t[1].min(1.0)]),
                (_, Sign3::Zero) if t[1] <= 1.0 => return Place::Inside([0.0, t[1]]),
                (_, Sign3::Zero) => return Place::Outside,
                (e, f) if e.strict() && e == f => return Place::Outside,
                (e, f) if e.opposite(f) => t[0] = 0.0,
                _ => return Place::Undecided,
            }
        }
        if t[1] > 1.0 {
            match (self.sign_at(1.0), self.sign_at(t[0])) {
                (Sign3::Zero, _) | (_, Sign3::Zero) => return Place::Inside([t[0], 1.0]),
                (e, f) if e.strict() && e == f => return Place::Outside,
                (e, f) if e.opposite(f) => t[1] = 1.0,
                _ => return Place::Undecided,
            }
        }
        Place::Inside(t)
    }

    /// What is proven about the roots in `x`: `Some(false)`, none;
    /// `Some(true)`, at most one, and a simple one if there is one (so
    /// exactly one where `x` is known to hold a root); `None`, neither.
    /// Exact input: the exact values at the ends, Descartes' rule on the
    /// open interval, exact Newton; enclosures: Descartes and Newton on `x`
    /// and on `x` widened a little (a root on its edge).
    fn at_most_one(&self, x: [f64; 2]) -> Option<bool> {
        if let Some(c) = &self.exact {
            let cx = exact::restrict(c, &Q::from_float(x[0])?, &Q::from_float(x[1])?);
            let n = cx.len() - 1;
            let (z0, z1) = (cx[0].is_zero(), cx[n].is_zero());
            let v = exact::sign_changes(&cx);
            if v <= 1 && n > 0 {
                // A root at an end is simple iff the derivative's end
                // coefficient (∝ c₁ − c₀, or c_n − c_{n−1}) is non-zero.
                let simple = !(z0 && cx[1].is_zero() || z1 && cx[n - 1].is_zero());
                let count = usize::from(z0) + usize::from(z1) + v;
                return match count {
                    0 => Some(false),
                    1 if simple => Some(true),
                    _ => None,
                };
            }
            match exact::newton(c, &cx, x) {
                Verdict::NoRoot => return Some(false),
                Verdict::Unique(_) => return Some(true),
                Verdict::Undecided(_) => {}
            }
        }
        for y in [x, interval::widen(x, 0.1 * interval::width(x))] {
            let cy = bernstein::restrict(&self.iv, y[0], y[1]);
            match (interval::descartes(&cy), interval::newton(&self.iv, &cy, y)) {
                (interval::Descartes::NoRoot, _) | (_, Verdict::NoRoot) => return Some(false),
                (interval::Descartes::One, _) | (_, Verdict::Unique(_)) => return Some(true),
                _ => {}
            }
        }
        None
    }

    /// Sorted roots with overlapping intervals resolved: one root if their
    /// hull holds exactly one (it lies in the intersection), distinct if the
    /// intersection holds none, else one undecided region.
    fn merge_roots(&self, mut roots: Vec<[f64; 2]>) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        roots.sort_by(by_lo);
        let (mut out, mut clusters): (Vec<[f64; 2]>, Vec<[f64; 2]>) = (Vec::new(), Vec::new());
        for r in roots {
            let Some(&last) = out.last() else {
                out.push(r);
                continue;
            };
            if r[0] > last[1] {
                out.push(r);
                continue;
            }
            let hull = [last[0], last[1].max(r[1])];
            let meet = [r[0], last[1].min(r[1])];
            if self.at_most_one(hull) == Some(true) {
                *out.last_mut().expect("non-empty") = meet;
            } else if self.at_most_one(meet) == Some(false) {
                out.push(r);
            } else {
                out.pop();
                clusters.push(hull);
            }
        }
        (out, clusters)
    }

    /// Maps the results from `[0, 1]` to the domain (outward), sorts them,
    /// and checks each root interval again where the map rounds.
    fn in_domain(
        &self,
        roots: Vec<[f64; 2]>,
        mut clusters: Vec<([f64; 2], UndecidedReason)>,
        mut leftovers: Vec<[f64; 2]>,
        stats: UniStats,
    ) -> UniSolution {
        let frame = Frame::new(&self.domain);
        let mut out_roots = Vec::with_capacity(roots.len());
        for t in roots {
            let x = frame.to_x(t);
            // The outward map adds at most an ulp or so; the interval must
            // still hold exactly one root: test its preimage (⊇ t, so it
            // holds the root).
            if !frame.identity && self.at_most_one(frame.to_t(x)) != Some(true) {
                clusters.push((t, UndecidedReason::MultipleOrClose));
                continue;
            }
            out_roots.push(UniRoot {
                x: 0.5 * x[0] + 0.5 * x[1],
                interval: x,
                on_boundary: t[0] <= 0.0 || t[1] >= 1.0,
            });
        }
        out_roots.sort_by(|a, b| by_lo(&a.interval, &b.interval));
        clusters.sort_by(|a, b| by_lo(&a.0, &b.0));
        let mut out_clusters: Vec<UniCluster> = Vec::new();
        for (t, reason) in clusters {
            let t = [t[0].max(0.0), t[1].min(1.0)];
            let x = frame.to_x(t);
            match out_clusters.last_mut() {
                Some(last) if last.reason == reason && last.interval[1] >= x[0] => {
                    last.interval[1] = last.interval[1].max(x[1]);
                }
                _ => out_clusters.push(UniCluster { interval: x, reason }),
            }
        }
        leftovers.sort_by(by_lo);
        UniSolution {
            complete: leftovers.is_empty(),
            roots: out_roots,
            clusters: out_clusters,
            leftovers: leftovers.into_iter().map(|t| frame.to_x(t)).collect(),
            stats,
        }
    }
}

/// Where a certified root lies relative to the domain.
enum Place {
    /// In the closed domain; the interval, cut to the domain, still holds it.
    Inside([f64; 2]),
    /// Outside.
    Outside,
    /// Not proven either way.
    Undecided,
}

/// `x = a + t (b − a)`, exactly in rationals, rounded outward to floats.
struct Frame {
    a: Q,
    w: Q,
    identity: bool,
}

impl Frame {
    fn new(domain: &[Q; 2]) -> Self {
        let (a, w) = (domain[0].clone(), &domain[1] - &domain[0]);
        let identity = a.is_zero() && w.is_one();
        Self { a, w, identity }
    }

    fn to_x(&self, t: [f64; 2]) -> [f64; 2] {
        if self.identity {
            return t;
        }
        let map = |t: f64| &self.a + Q::from_float(t).unwrap_or_else(Q::zero) * &self.w;
        [
            rational_to_interval(&map(t[0])).inf(),
            rational_to_interval(&map(t[1])).sup(),
        ]
    }

    fn to_t(&self, x: [f64; 2]) -> [f64; 2] {
        let map = |x: f64| (Q::from_float(x).unwrap_or_else(Q::zero) - &self.a) / &self.w;
        [
            rational_to_interval(&map(x[0])).inf(),
            rational_to_interval(&map(x[1])).sup(),
        ]
    }
}

/// `floor(log2 |q|)` within one.
fn log2(q: &Q) -> i64 {
    q.numer().bits() as i64 - q.denom().bits() as i64
}

fn times_pow2(q: &Q, e: i64) -> Q {
    let f = Q::from_integer(BigInt::one() << e.unsigned_abs());
    if e >= 0 {
        q * f
    } else {
        q / f
    }
}

/// Sorted intervals split into runs of touching ones.
fn touching(sorted: Vec<[f64; 2]>) -> Vec<Vec<[f64; 2]>> {
    let mut groups: Vec<Vec<[f64; 2]>> = Vec::new();
    for x in sorted {
        match groups.last_mut() {
            Some(g) if g.iter().map(|y| y[1]).fold(f64::MIN, f64::max) >= x[0] => g.push(x),
            _ => groups.push(vec![x]),
        }
    }
    groups
}

/// The hulls of the runs of touching intervals.
fn joined(mut v: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    v.sort_by(by_lo);
    touching(v)
        .into_iter()
        .map(|g| [g[0][0], g.iter().map(|x| x[1]).fold(f64::MIN, f64::max)])
        .collect()
}

/// Intervals ordered by lower, then upper end.
fn by_lo(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}
