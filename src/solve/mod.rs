//! The certified solver: every root of `f(u, v) = g(u, v) = 0` over the unit
//! triangle or the unit square, with the [`Solution`] contract.
//!
//! * [`solve`] takes exact polynomials ([`Polynomial`], e.g. from
//!   [`parse_polynomial`](crate::parse_polynomial)); [`solve_bb`] takes
//!   Bernstein–Bézier coefficients in `f64`, exact rationals or intervals.
//! * [`SolveOptions`] chooses the clipping [`Method`] (Liu et al. 2016:
//!   Bézier, linear, hybrid with and without preprocessing), `eps`, the
//!   budgets, the [`SquareRoute`] and, for exact input on the triangle, the
//!   [`TriangleRoute`].
//! * [`solve_uni`] finds every root of one univariate polynomial
//!   ([`UniBezier`](crate::UniBezier)) on its interval, with the
//!   [`UniSolution`] contract (Descartes' rule, interval Newton, exact
//!   arithmetic at the ends and where rounding leaves a region undecided).
//!
//! Floating point proposes; only rigorous arithmetic discards or certifies:
//! the coefficients on every tri-box carry one rigorous radius from a-priori
//! bounds of the float work (recomputed in double-double or exact arithmetic
//! where rounding would limit a small tri-box); fat-curve widths are rigorous
//! upper bounds and every clip is proven sliver by sliver; check-sign needs
//! every coefficient strictly on one side of 0; every final region goes
//! through Krawczyk's operator on the original system, and roots near the
//! boundary of an exact system are settled in exact arithmetic. The whole
//! argument, step by step, is in `docs/rigor.md` of the repository.

mod common_factor;
pub(crate) mod degenerate;
pub(crate) mod driver;
mod envelope;
mod exact_input;
pub(crate) mod fatcurve;
#[cfg(feature = "serde")]
mod json;
pub(crate) mod krawczyk;
pub(crate) mod linalg;
pub(crate) mod method;
pub mod nd;
mod options;
pub(crate) mod rect;
pub(crate) mod referee;
mod regions;
pub(crate) mod settle;
mod solution;
pub(crate) mod tribox;
mod univariate;

pub use options::{Domain, SolveOptions, SquareRoute, TriangleRoute};
pub use referee::{classify_roots, ClaimVerdict, RootClassification};

use crate::error::{Error, Result};
use crate::poly::{Polynomial, TensorBezier, TriBall, TriBezier};
use crate::scalar::geo::GeoIv;
use crate::scalar::{interval, point, Scalar};
pub use driver::SplitRule;
use driver::{path_diameters, Counters, Exact, ExactPair, Leaf, Limits, Probe};
use exact_input::{solve_exact_square, solve_exact_triangle};
use inari::Interval;
use krawczyk::{Bivariate, IBox, System, Verdict};
pub use method::Method;
use num_rational::BigRational;
use regions::{group_overlapping, hull_of, join_undecided, merge_roots, touching_regions, Found};
pub use solution::{Box2, Cluster, Leftover, Root, Solution, Stats, UndecidedReason};
pub use univariate::{
    solve_uni, UniCluster, UniOptions, UniPolynomial, UniRoot, UniSolution, UniStats, MAX_UNI_DEGREE,
};

/// How a root triangle's local `(s, t)` maps to the domain's `(u, v)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Frame {
    /// `(u, v) = (s, t)`.
    Identity,
    /// `(u, v) = (1 − s, 1 − t)` (the square's upper-right half).
    Reflect,
}

impl Frame {
    fn map_box(self, x: IBox) -> IBox {
        match self {
            Frame::Identity => x,
            Frame::Reflect => [point(1.0) - x[0], point(1.0) - x[1]],
        }
    }

    fn map_point(self, p: [f64; 2]) -> [f64; 2] {
        match self {
            Frame::Identity => p,
            Frame::Reflect => [1.0 - p[0], 1.0 - p[1]],
        }
    }
}

/// Beyond this power of two (either way) an exact equation's BB coefficients
/// are scaled towards 1 before they are enclosed in floats.
const EXTREME_LOG2: i64 = 256;

/// Multiplication by the power of two that brings the largest of `coeffs`
/// near 1, when that lies beyond `2^±EXTREME_LOG2` (the identity otherwise,
/// and for all-zero input). Scaling an equation by a positive constant does
/// not move its roots; without it, BB coefficients near the `f64` range
/// overflow in the conversions (an input scaled by 1e300 is still a valid
/// system), and tiny ones lose their low bits to underflow.
fn scaler(coeffs: &[BigRational]) -> impl Fn(&BigRational) -> BigRational {
    use num_traits::{One, Zero};
    // floor(log2 |q|) within one.
    let log2 = |q: &BigRational| q.numer().bits() as i64 - q.denom().bits() as i64;
    let top = coeffs.iter().filter(|c| !c.is_zero()).map(log2).max().unwrap_or(0);
    let e = if top.abs() > EXTREME_LOG2 { -top } else { 0 };
    let factor = num_bigint::BigInt::one() << e.unsigned_abs();
    move |q: &BigRational| match e.cmp(&0) {
        std::cmp::Ordering::Equal => q.clone(),
        std::cmp::Ordering::Greater => q * &factor,
        std::cmp::Ordering::Less => q / &factor,
    }
}

/// Every root of `f(u, v) = g(u, v) = 0` over `domain`, for exact
/// polynomials (e.g. from [`parse_polynomial`](crate::parse_polynomial)),
/// with the [`Solution`] contract.
///
/// The polynomials are converted to BB form exactly (degree `n` = the larger
/// total degree on the triangle, the larger degrees in `u` and `v` on the
/// square), checked for a common factor exactly, then solved with proofs in
/// floating-point and interval arithmetic; roots on the domain's boundary
/// are settled in exact arithmetic.
///
/// Errors: an identically zero equation or a common factor (a curve of
/// roots cannot be listed: [`Error::Degenerate`]), a conversion too large
/// ([`Error::TooLarge`]), invalid options ([`Error::InvalidOption`]).
///
/// ```
/// use rootclip::{parse_polynomial, solve::{solve, Domain, SolveOptions}};
/// let f = parse_polynomial("u^3 - v")?;
/// let g = parse_polynomial("u^3 + v - 1/4")?;
/// let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default())?;
/// assert!(sol.complete && sol.roots.len() == 1);
/// assert!(sol.roots[0].bx.contains(0.5, 0.125));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn solve(f: &Polynomial, g: &Polynomial, domain: Domain, opts: &SolveOptions) -> Result<Solution> {
    let t0 = std::time::Instant::now();
    timed(t0, solve_exact(f, g, domain, opts))
}

/// The solve's wall-clock time in its [`Stats::seconds`].
fn timed(t0: std::time::Instant, sol: Result<Solution>) -> Result<Solution> {
    sol.map(|mut s| {
        s.stats.seconds = t0.elapsed().as_secs_f64();
        s
    })
}

fn solve_exact(f: &Polynomial, g: &Polynomial, domain: Domain, opts: &SolveOptions) -> Result<Solution> {
    opts.validate()?;
    let opts = &opts.started();
    not_zero(f.is_zero(), g.is_zero())?;
    for p in [f, g] {
        p.check_conversion_cost(domain == Domain::Square)?;
    }
    no_common_factor(f, g)?;
    match domain {
        Domain::Triangle => {
            let n = f.total_degree().max(1).max(g.total_degree()) as usize;
            solve_exact_triangle(f.to_triangle(n), g.to_triangle(n), [f, g], opts)
        }
        Domain::Square => {
            let ((m, n), (p, q)) = (f.degrees(), g.degrees());
            let (dm, dn) = (m.max(p) as usize, n.max(q) as usize);
            solve_exact_square(f.to_square().elevate(dm, dn)?, g.to_square().elevate(dm, dn)?, opts)
        }
    }
}

/// A Bernstein–Bézier polynomial [`solve_bb`] takes: [`TriBezier`] (the
/// unit triangle) or [`TensorBezier`] on the unit square, with `f64`,
/// [`BigRational`] or [`Interval`] coefficients. Sealed.
pub trait BbPolynomial: sealed::Sealed {}

mod sealed {
    use crate::poly::{TensorBezier, TriBezier};
    use inari::Interval;
    use num_rational::BigRational;

    pub trait Sealed {
        fn input(&self) -> crate::Result<BbInput<'_>>;
    }

    /// What [`solve_bb`] solves: an exact system (floats are exact rationals),
    /// or an enclosure.
    // Built once per solve and consumed at once: boxing buys nothing.
    #[allow(clippy::large_enum_variant)]
    pub enum BbInput<'a> {
        Triangle(TriBezier<BigRational>),
        Square(TensorBezier<BigRational>),
        TriangleEnclosure(&'a TriBezier<Interval>),
        SquareEnclosure(&'a TensorBezier<Interval>),
    }
}

use sealed::BbInput;

fn exactly(x: f64) -> Result<BigRational> {
    BigRational::from_float(x).ok_or_else(|| Error::NonFinite(format!("a coefficient is {x}")))
}

fn unit_square<S: Scalar>(p: &TensorBezier<S>) -> Result<()> {
    let (u, v) = p.domain();
    let is = |x: &S, y: f64| x.lower() == y && x.upper() == y;
    if [u, v].iter().all(|d| is(&d[0], 0.0) && is(&d[1], 1.0)) {
        Ok(())
    } else {
        Err(Error::Shape(
            "solve_bb needs tensor polynomials on the unit square [0, 1]²".into(),
        ))
    }
}

impl BbPolynomial for TriBezier<f64> {}
impl sealed::Sealed for TriBezier<f64> {
    fn input(&self) -> Result<BbInput<'_>> {
        let c = self.coeffs().iter().map(|&x| exactly(x)).collect::<Result<Vec<_>>>()?;
        Ok(BbInput::Triangle(TriBezier::new(self.degree(), c)?))
    }
}
impl BbPolynomial for TriBezier<BigRational> {}
impl sealed::Sealed for TriBezier<BigRational> {
    fn input(&self) -> Result<BbInput<'_>> {
        Ok(BbInput::Triangle(self.clone()))
    }
}
impl BbPolynomial for TriBezier<Interval> {}
impl sealed::Sealed for TriBezier<Interval> {
    fn input(&self) -> Result<BbInput<'_>> {
        Ok(BbInput::TriangleEnclosure(self))
    }
}
impl BbPolynomial for TensorBezier<f64> {}
impl sealed::Sealed for TensorBezier<f64> {
    fn input(&self) -> Result<BbInput<'_>> {
        unit_square(self)?;
        let (m, n) = self.degree();
        let c = self.coeffs().iter().map(|&x| exactly(x)).collect::<Result<Vec<_>>>()?;
        Ok(BbInput::Square(TensorBezier::on_unit_square(m, n, c)?))
    }
}
impl BbPolynomial for TensorBezier<BigRational> {}
impl sealed::Sealed for TensorBezier<BigRational> {
    fn input(&self) -> Result<BbInput<'_>> {
        unit_square(self)?;
        Ok(BbInput::Square(self.clone()))
    }
}
impl BbPolynomial for TensorBezier<Interval> {}
impl sealed::Sealed for TensorBezier<Interval> {
    fn input(&self) -> Result<BbInput<'_>> {
        unit_square(self)?;
        Ok(BbInput::SquareEnclosure(self))
    }
}

/// Every root of `f = g = 0` for polynomials given by their BB coefficients:
/// on the unit triangle for [`TriBezier`] (Liu et al. 2016, Eq. (1)), on the
/// unit square for [`TensorBezier`]; degrees may differ (the lower one is
/// elevated). The [`Solution`] contract holds for:
/// * `f64` and [`BigRational`] coefficients: the system with exactly these
///   coefficients (a float is an exact rational), as for [`solve`]: common
///   factors are detected ([`Error::Degenerate`]) and roots on the boundary
///   settled exactly;
/// * [`Interval`] coefficients: every system whose coefficients lie in the
///   enclosures; a common factor then ends in undecided regions or a budget,
///   never in a wrong "no roots", and an `on_boundary` root may lie within
///   its box's width outside the domain.
///
/// Errors: NaN or infinite coefficients ([`Error::NonFinite`]), an
/// identically zero equation or a common factor ([`Error::Degenerate`]), a
/// tensor polynomial not on the unit square ([`Error::Shape`]), invalid
/// options ([`Error::InvalidOption`]).
///
/// ```
/// use rootclip::{solve::{solve_bb, SolveOptions}, TriBezier};
/// // Degree 1 on the unit triangle, coefficients at the vertices w, u, v
/// // (storage order of `poly::tri_indices`): f = u − 1/4, g = v − 1/2.
/// let f = TriBezier::new(1, vec![-0.25, 0.75, -0.25])?;
/// let g = TriBezier::new(1, vec![-0.5, -0.5, 0.5])?;
/// let sol = solve_bb(&f, &g, &SolveOptions::default())?;
/// assert_eq!(sol.roots.len(), 1);
/// assert!(sol.roots[0].bx.contains(0.25, 0.5));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn solve_bb<P: BbPolynomial>(f: &P, g: &P, opts: &SolveOptions) -> Result<Solution> {
    let t0 = std::time::Instant::now();
    timed(t0, solve_bb_timed(f, g, opts))
}

fn solve_bb_timed<P: BbPolynomial>(f: &P, g: &P, opts: &SolveOptions) -> Result<Solution> {
    opts.validate()?;
    let opts = &opts.started();
    match (f.input()?, g.input()?) {
        (BbInput::Triangle(f), BbInput::Triangle(g)) => {
            not_zero(f.is_zero(), g.is_zero())?;
            let (pf, pg) = (Polynomial::from_triangle(&f), Polynomial::from_triangle(&g));
            no_common_factor(&pf, &pg)?;
            let n = f.degree().max(g.degree()).max(1);
            solve_exact_triangle(f.elevate(n)?, g.elevate(n)?, [&pf, &pg], opts)
        }
        (BbInput::Square(f), BbInput::Square(g)) => {
            not_zero(
                f.coeffs().iter().all(num_traits::Zero::is_zero),
                g.coeffs().iter().all(num_traits::Zero::is_zero),
            )?;
            no_common_factor(&Polynomial::from_square(&f), &Polynomial::from_square(&g))?;
            let ((m, n), (p, q)) = (f.degree(), g.degree());
            let (dm, dn) = (m.max(p), n.max(q));
            solve_exact_square(f.elevate(dm, dn)?, g.elevate(dm, dn)?, opts)
        }
        (BbInput::TriangleEnclosure(f), BbInput::TriangleEnclosure(g)) => solve_triangle(f, g, opts),
        (BbInput::SquareEnclosure(f), BbInput::SquareEnclosure(g)) => solve_square(f, g, opts),
        _ => unreachable!("f and g have the same type"),
    }
}

fn not_zero(f_zero: bool, g_zero: bool) -> Result<()> {
    if f_zero || g_zero {
        let which = if f_zero { "f" } else { "g" };
        return Err(Error::ZeroEquation(format!(
            "equation {which} is identically zero: every point of the other curve is a root"
        )));
    }
    Ok(())
}

fn no_common_factor(f: &Polynomial, g: &Polynomial) -> Result<()> {
    if degenerate::has_common_factor(f, g) {
        return Err(Error::CommonFactor {
            factor: common_factor::gcd(f, g).to_string(),
        });
    }
    Ok(())
}

/// The solution of a system with a common factor ([`solve_reduced`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ReducedSolution {
    /// The common factor `h = gcd(f, g)` over ℚ (leading coefficient 1; the
    /// constant 1 when `f` and `g` are coprime), as an exact expression. Its
    /// zeros in the domain are roots of the system: a curve, not listed.
    pub common_factor: String,
    /// The solve of `f/h = g/h = 0`, with the [`Solution`] contract for that
    /// system: its roots are roots of `f = g = 0`, and every root of
    /// `f = g = 0` in the domain is one of them or a zero of `h`. A root here
    /// where `h ≠ 0` is an isolated, simple root of the original system too
    /// (its Jacobian there is `h` times the reduced one).
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub solution: Solution,
}

/// Every root of `f = g = 0` over `domain` that is not on a common curve:
/// with `h = gcd(f, g)` (exact, over ℚ), the system `f/h = g/h = 0` solved
/// with the [`Solution`] contract, and `h` itself ([`ReducedSolution`]).
/// Without a common factor this is [`solve`] with `h = 1`.
///
/// Errors: as [`solve`], except for a common factor; an identically zero
/// equation is still [`Error::ZeroEquation`] (then every point of the other
/// curve is a root, and nothing remains to list).
///
/// ```
/// use rootclip::{parse_polynomial, solve::{solve, solve_reduced, Domain, SolveOptions}, Error};
/// // (u − v)(u + v − 1) = (u − v)(2u − 1/3) = 0: the line u = v, and (1/6, 5/6).
/// let f = parse_polynomial("(u - v)*(u + v - 1)")?;
/// let g = parse_polynomial("(u - v)*(2*u - 1/3)")?;
/// let opts = SolveOptions::default();
/// assert!(matches!(solve(&f, &g, Domain::Triangle, &opts), Err(Error::CommonFactor { .. })));
/// let r = solve_reduced(&f, &g, Domain::Triangle, &opts)?;
/// assert_eq!(r.common_factor, "-u + v");
/// assert!(r.solution.complete && r.solution.roots.len() == 1);
/// assert!(r.solution.roots[0].bx.contains(1.0 / 6.0, 5.0 / 6.0));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn solve_reduced(f: &Polynomial, g: &Polynomial, domain: Domain, opts: &SolveOptions) -> Result<ReducedSolution> {
    not_zero(f.is_zero(), g.is_zero())?;
    let one = Polynomial::constant(num_traits::One::one());
    let h = if degenerate::has_common_factor(f, g) {
        common_factor::gcd(f, g)
    } else {
        one
    };
    let (rf, rg) = match (common_factor::quotient(f, &h), common_factor::quotient(g, &h)) {
        (Some(a), Some(b)) => (a, b),
        _ => {
            return Err(Error::Degenerate(
                "the common factor does not divide the equations".into(),
            ))
        }
    };
    let solution = if rf.as_constant().is_some() || rg.as_constant().is_some() {
        // A non-zero constant equation: no root off the curve.
        Solution {
            complete: true,
            roots: Vec::new(),
            clusters: Vec::new(),
            leftovers: Vec::new(),
            stats: Stats::default(),
        }
    } else {
        solve(&rf, &rg, domain, opts)?
    };
    Ok(ReducedSolution {
        common_factor: h.to_string(),
        solution,
    })
}

fn check_system(f: &TriBezier<Interval>, g: &TriBezier<Interval>) -> Result<()> {
    for (name, p) in [("f", f), ("g", g)] {
        if p.coeffs().iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFinite(format!("a coefficient of {name} is NaN or infinite")));
        }
        if p.is_zero() {
            return Err(Error::ZeroEquation(format!("equation {name} is identically zero")));
        }
    }
    Ok(())
}

/// Solves `f = g = 0` on the unit triangle, `f`, `g` in BB form there (any
/// degrees; interval coefficients are enclosures of the intended system).
/// See [`Solution`] for the contract. Common factors are not detected here
/// (use [`solve`] for exact input); a curve of roots then ends in clusters or
/// a budget, never in a wrong "no roots".
pub(crate) fn solve_triangle(
    f: &TriBezier<Interval>,
    g: &TriBezier<Interval>,
    opts: &SolveOptions,
) -> Result<Solution> {
    opts.validate()?;
    check_system(f, g)?;
    let n = f.degree().max(g.degree());
    let (f, g) = (f.elevate_cached(n), g.elevate_cached(n));
    let global = System::new(f.clone(), g.clone());
    let floats = [&f, &g].iter().all(|p| p.coeffs().iter().all(|c| c.inf() == c.sup()));
    Ok(join_undecided(solve_pieces(
        vec![Piece {
            f,
            g,
            frame: Frame::Identity,
            exact: None,
            floats,
        }],
        &global,
        Domain::Triangle,
        opts,
    )))
}

/// One root triangle: the system on it, its frame, and the exact system when known.
struct Piece {
    f: TriBezier<Interval>,
    g: TriBezier<Interval>,
    frame: Frame,
    exact: Option<ExactPair>,
    /// Every coefficient is a float (a point interval): the input is exact.
    floats: bool,
}

/// Solves `f = g = 0` on the unit square, `f`, `g` in tensor BB form there,
/// through the exact conversion to two triangles. A root on the diagonal is
/// reported once. See [`Solution`] for the contract.
pub(crate) fn solve_square(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    opts: &SolveOptions,
) -> Result<Solution> {
    opts.validate()?;
    let (m, n) = f.degree();
    let (p, q) = g.degree();
    let (f, g) = (f.elevate(m.max(p), n.max(q))?, g.elevate(m.max(p), n.max(q))?);
    if opts.square_route != SquareRoute::Triangles && m.max(p) >= 1 && n.max(q) >= 1 {
        // (An input the box solver rejects goes to the triangles, which
        // give their own answer or error.)
        if let Ok(r) = rect::solve_rect(&f, &g, None, &rect_options(opts)) {
            if r.solution.complete || opts.deadline.is_some_and(|d| std::time::Instant::now() >= d) {
                return Ok(join_undecided(r.solution));
            }
        }
        // Out of budget: the triangle route, as for exact input.
    }
    square_pieces(&f, &g, None, opts).map(join_undecided)
}

/// The box solver's options for a solve's.
fn rect_options(opts: &SolveOptions) -> rect::RectOptions {
    rect::RectOptions {
        eps: opts.eps,
        max_boxes: opts.max_boxes,
        clip: match opts.square_route {
            SquareRoute::RectFatLine => rect::RectClip::FatLine,
            SquareRoute::RectHybrid => rect::RectClip::Hybrid,
            _ => rect::RectClip::Bezier,
        },
        deadline: opts.deadline,
        ..rect::RectOptions::default()
    }
}

type ExactHalves = ([TriBezier<BigRational>; 2], [TriBezier<BigRational>; 2]);

fn square_pieces(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    exact: Option<ExactHalves>,
    opts: &SolveOptions,
) -> Result<Solution> {
    let [fa, fb] = f.to_triangles()?;
    let [ga, gb] = g.to_triangles()?;
    check_system(&fa, &ga)?;
    let global = System::new(fa.clone(), ga.clone());
    let (ea, eb) = match exact {
        Some(([fea, feb], [gea, geb])) => (Some([fea, gea]), Some([feb, geb])),
        None => (None, None),
    };
    let pieces = vec![
        Piece {
            f: fa,
            g: ga,
            frame: Frame::Identity,
            exact: ea,
            floats: false,
        },
        Piece {
            f: fb,
            g: gb,
            frame: Frame::Reflect,
            exact: eb,
            floats: false,
        },
    ];
    Ok(solve_pieces(pieces, &global, Domain::Square, opts))
}

fn solve_pieces(pieces: Vec<Piece>, global: &System, domain: Domain, opts: &SolveOptions) -> Solution {
    let limits = opts.limits();
    let mut stats = Stats::default();
    let (mut roots, mut clusters) = (Vec::new(), Vec::new());
    let mut leftovers = Vec::new();
    let mut strips = Vec::new();
    for Piece {
        f,
        g,
        frame,
        exact,
        floats,
    } in &pieces
    {
        // Certify in the piece's own frame: its polynomials are evaluated by
        // interpolation there. (The square's other half would extrapolate with
        // barycentric weights up to ~2.3 in size, amplifying rounding by
        // ~2.3^degree and defeating Krawczyk on tiny boxes.) The identity
        // frame's piece is the global system.
        let owned;
        let local = match frame {
            Frame::Identity => global,
            Frame::Reflect => {
                owned = System::new(f.clone(), g.clone());
                &owned
            }
        };
        // A probe's certificate is kept: a leaf it stopped is certified on
        // the same box again below, unless it touches other leaves.
        let mut proven: Vec<(IBox, IBox)> = Vec::new();
        let mut probe = |tb: &tribox::TriBox| {
            let x = tribox::box_of(tb);
            match local.certify_within(x, PROBE_ROUNDS) {
                Verdict::Unique(k) => {
                    proven.push((x, k));
                    Verdict::Unique(())
                }
                Verdict::NoRoot => Verdict::NoRoot,
                Verdict::Undecided(_) => Verdict::Undecided(()),
            }
        };
        let ball = |p: &TriBezier<Interval>| TriBall::enclose(p).unwrap_or_else(|_| TriBall::unbounded(p.degree()));
        let exact = match (exact, floats) {
            (Some(p), _) => Exact::Rational(p),
            (None, true) => Exact::Floats,
            (None, false) => Exact::None,
        };
        let run = driver::run::<GeoIv>(&ball(f), &ball(g), exact, &limits, &mut probe);
        add_counters(&mut stats, &run.counters);
        stats.krawczyk_calls += run.counters.probes;
        stats.max_level = stats
            .max_level
            .max(run.nodes.iter().map(|n| n.level).max().unwrap_or(0));
        stats.leaves += run.leaves.len();
        let leaves: Vec<Found> = run
            .leaves
            .iter()
            .map(|leaf| Found {
                bx: local_box(leaf),
                diameters: path_diameters(&run.nodes, leaf.node),
            })
            .collect();
        let (r, c) = certify_groups(group_overlapping(leaves), local, &proven, &mut stats);
        let to_global = |x: Found| Found {
            bx: frame.map_box(x.bx),
            diameters: x.diameters,
        };
        let (r, undecided) = merge_roots(r, local, &mut stats);
        roots.extend(r.into_iter().map(to_global));
        clusters.extend(c.into_iter().chain(undecided).map(to_global));
        strips.extend(run.strips.iter().map(|&[u, v]| Cluster {
            bx: Box2::of(frame.map_box([interval(u[0], u[1]), interval(v[0], v[1])])),
            reason: UndecidedReason::VanishingEdge,
            diameters: Vec::new(),
        }));
        for leaf in &run.leftovers {
            let bx = frame.map_box(local_box(leaf));
            let triangle = leaf.tb.verts.map(|p| frame.map_point(p));
            leftovers.push(Leftover {
                bx: Box2::of(bx),
                triangle: Some(triangle),
            });
        }
    }
    // Across pieces (the square's diagonal), in the global frame: there the
    // first half's polynomials are evaluated next to their own triangle.
    let (roots, undecided) = merge_roots(roots, global, &mut stats);
    clusters.extend(undecided);
    let mut out_roots = Vec::new();
    for r in roots {
        match locate(r.bx, domain) {
            Place::Outside => stats.outside_domain += 1,
            place => out_roots.push(Root {
                u: r.bx[0].mid(),
                v: r.bx[1].mid(),
                bx: Box2::of(r.bx),
                on_boundary: place == Place::Boundary,
                diameters: r.diameters,
            }),
        }
    }
    out_roots.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
    let clusters = touching_regions(clusters).into_iter().chain(strips).collect();
    Solution {
        complete: leftovers.is_empty(),
        roots: out_roots,
        clusters,
        leftovers,
        stats,
    }
}

/// Krawczyk steps a probe of a tri-box during the iteration may take before
/// it gives up: a simple root well inside a converging tri-box is certified
/// by the first or second step; one that needs more is left to further clips
/// (and the final certification, which tries harder).
const PROBE_ROUNDS: usize = 2;

/// Largest group whose leaves are certified one by one when their hull fails.
const SMALL_GROUP: usize = 16;

/// Certifies each group of touching leaves through its hull (a root on a
/// shared edge is then found once); a small group whose hull fails is tried
/// leaf by leaf (two roots closer than a few tri-boxes), a large one becomes
/// an undecided cluster.
///
/// `proven` lists boxes already certified (box, Krawczyk box): a group of one
/// such leaf takes its certificate without recomputing it.
fn certify_groups<P: Bivariate>(
    groups: Vec<Vec<Found>>,
    global: &System<P>,
    proven: &[(IBox, IBox)],
    stats: &mut Stats,
) -> (Vec<Found>, Vec<Found>) {
    let (mut roots, mut clusters) = (Vec::new(), Vec::new());
    for group in groups {
        let len = group.len();
        let whole = hull_of(group.clone());
        let known = proven.iter().find(|(x, _)| len == 1 && *x == whole.bx);
        let verdict = match known {
            Some(&(_, k)) => Verdict::Unique(k),
            None => {
                stats.krawczyk_calls += 1;
                global.certify(whole.bx)
            }
        };
        match verdict {
            Verdict::Unique(k) => roots.push(Found {
                bx: k,
                diameters: whole.diameters,
            }),
            Verdict::NoRoot => stats.krawczyk_exclusions += len,
            Verdict::Undecided(_) if len > 1 && len <= SMALL_GROUP => {
                for leaf in group {
                    stats.krawczyk_calls += 1;
                    match global.certify(leaf.bx) {
                        Verdict::Unique(k) => roots.push(Found {
                            bx: k,
                            diameters: leaf.diameters,
                        }),
                        Verdict::NoRoot => stats.krawczyk_exclusions += 1,
                        Verdict::Undecided(_) => clusters.push(leaf),
                    }
                }
            }
            Verdict::Undecided(_) => clusters.push(whole),
        }
    }
    (roots, clusters)
}

fn add_counters(a: &mut Stats, b: &Counters) {
    // Destructured, so that a new counter cannot be forgotten here.
    let Counters {
        boxes,
        clips,
        splits,
        sign_exclusions,
        clip_exclusions,
        probes,
        probe_exclusions,
        compensated_restarts,
        compensated_boxes,
        exact_restarts,
        exact_boxes,
        role_swaps,
    } = *b;
    a.boxes += boxes;
    a.clips += clips;
    a.splits += splits;
    a.sign_exclusions += sign_exclusions;
    a.clip_exclusions += clip_exclusions;
    a.probes += probes;
    a.probe_exclusions += probe_exclusions;
    a.compensated_restarts += compensated_restarts;
    a.compensated_boxes += compensated_boxes;
    a.exact_restarts += exact_restarts;
    a.exact_boxes += exact_boxes;
    a.role_swaps += role_swaps;
}

fn local_box(leaf: &Leaf) -> IBox {
    tribox::box_of(&leaf.tb)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Place {
    Inside,
    Boundary,
    Outside,
}

/// Where a certified box lies relative to the closed domain (proven).
fn locate(x: IBox, domain: Domain) -> Place {
    let (u, v) = (x[0], x[1]);
    match domain {
        Domain::Triangle => {
            let sum = u + v;
            if u.sup() < 0.0 || v.sup() < 0.0 || sum.inf() > 1.0 {
                Place::Outside
            } else if u.inf() > 0.0 && v.inf() > 0.0 && sum.sup() < 1.0 {
                Place::Inside
            } else {
                Place::Boundary
            }
        }
        Domain::Square => {
            if u.sup() < 0.0 || v.sup() < 0.0 || u.inf() > 1.0 || v.inf() > 1.0 {
                Place::Outside
            } else if u.inf() > 0.0 && v.inf() > 0.0 && u.sup() < 1.0 && v.sup() < 1.0 {
                Place::Inside
            } else {
                Place::Boundary
            }
        }
    }
}

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
/// The same clipping iteration in plain `f64`, without any proof: returns the
/// centres of the final tri-boxes (on the unit triangle). For measuring the
/// cost of rigor and as a fast heuristic; never a certificate.
pub(crate) fn solve_triangle_f64(f: &TriBezier<f64>, g: &TriBezier<f64>, opts: &SolveOptions) -> Vec<[f64; 2]> {
    let limits = Limits {
        probe_below: 0.0,
        ..opts.limits()
    };
    let n = f.degree().max(g.degree());
    let (f, g) = (f.elevate_cached(n), g.elevate_cached(n));
    let run = driver::run::<f64>(
        &TriBall::from_points(&f),
        &TriBall::from_points(&g),
        Exact::None,
        &limits,
        &mut |_| Probe::Undecided(()),
    );
    run.leaves.iter().map(|l| l.tb.point_at([1.0 / 3.0; 3])).collect()
}
