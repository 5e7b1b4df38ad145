//! The certified solver: every root of `f(u, v) = g(u, v) = 0` over the unit
//! triangle or the unit square.
//!
//! Floating point proposes; only rigorous arithmetic discards or certifies:
//! * the BB coefficients on every tri-box are ball polynomials
//!   ([`TriBall`](crate::poly::TriBall): float coefficients and one rigorous
//!   radius, from a-priori bounds of the float work) computed from the input
//!   for exactly the reported (`f64`) vertices ([`tribox`]); where rounding
//!   would limit a small tri-box, in compensated (double-double) arithmetic
//!   or exactly from the rational input ([`driver::Precision`]);
//! * fat-curve widths are rigorous upper bounds, clip bounds are minima over
//!   enclosed critical points ([`fatcurve`]), check-sign needs every
//!   coefficient interval strictly on one side of 0 ([`driver`]);
//! * every final tri-box goes through Krawczyk's operator on the original
//!   system ([`krawczyk`]).
//!
//! Methods: [`Method`] (Liu et al. 2016: Bézier, linear, hybrid with and
//! without preprocessing).

pub(crate) mod degenerate;
pub(crate) mod driver;
pub(crate) mod fatcurve;
pub(crate) mod krawczyk;
pub(crate) mod method;
pub(crate) mod num;
mod options;
pub(crate) mod rect;
pub(crate) mod settle;
pub(crate) mod tribox;

pub use options::{Domain, SolveOptions, SquareRoute};

use crate::error::{Error, Result};
use crate::poly::{Polynomial, TensorBezier, TriBall, TriBezier};
use crate::scalar::{interval, point, Scalar};
pub use driver::SplitRule;
use driver::{path_diameters, Counters, Exact, ExactPair, Leaf, Limits, Probe};
use inari::Interval;
use krawczyk::{Bivariate, IBox, System, Verdict};
pub use method::Method;
use num::GeoIv;
use num_rational::BigRational;

/// A closed axis-aligned box in `(u, v)`: `[u₀, u₁] × [v₀, v₁]`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Box2 {
    /// `[lo, hi]` in `u`.
    pub u: [f64; 2],
    /// `[lo, hi]` in `v`.
    pub v: [f64; 2],
}

impl Box2 {
    /// The box `u × v` (bounds as given; a box with `lo > hi` is empty and
    /// contains nothing).
    pub fn new(u: [f64; 2], v: [f64; 2]) -> Self {
        Self { u, v }
    }

    /// `true` if the point lies in the closed box.
    ///
    /// ```
    /// use rootclip::solve::Box2;
    /// let b = Box2::new([0.0, 0.5], [0.25, 1.0]);
    /// assert!(b.contains(0.5, 0.25) && !b.contains(0.6, 0.5));
    /// ```
    pub fn contains(&self, u: f64, v: f64) -> bool {
        self.u[0] <= u && u <= self.u[1] && self.v[0] <= v && v <= self.v[1]
    }

    /// `true` if the closed boxes share a point (touching counts).
    pub fn overlaps(&self, o: &Box2) -> bool {
        self.u[0] <= o.u[1] && o.u[0] <= self.u[1] && self.v[0] <= o.v[1] && o.v[0] <= self.v[1]
    }

    /// The midpoint `(u, v)`.
    pub fn center(&self) -> [f64; 2] {
        [0.5 * (self.u[0] + self.u[1]), 0.5 * (self.v[0] + self.v[1])]
    }

    /// The larger side, `max(u₁ − u₀, v₁ − v₀)`.
    pub fn width(&self) -> f64 {
        (self.u[1] - self.u[0]).max(self.v[1] - self.v[0])
    }

    fn of(x: IBox) -> Self {
        Self {
            u: [x[0].inf(), x[0].sup()],
            v: [x[1].inf(), x[1].sup()],
        }
    }

    /// The same box as intervals (the inverse of [`Box2::of`]).
    fn ibox(&self) -> IBox {
        [interval(self.u[0], self.u[1]), interval(self.v[0], self.v[1])]
    }
}

/// A certified root: its box holds exactly one root of the system, a simple
/// one (see the [`Solution`] contract).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Root {
    /// Midpoint of the box.
    pub u: f64,
    /// Midpoint of the box.
    pub v: f64,
    /// The closed box: it contains exactly one root of the system, and that
    /// root is simple.
    #[cfg_attr(feature = "serde", serde(rename = "box"))]
    pub bx: Box2,
    /// The box touches the domain's boundary: the root is on it, or within
    /// the box's width of it (inside it, for exact input: see [`Solution`]).
    pub on_boundary: bool,
    /// Diameters of the tri-boxes holding this root, by level (index 0 is the
    /// whole domain), along the deepest path that reached it (not serialized).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub diameters: Vec<f64>,
}

/// Why a region is undecided: the one vocabulary of "not proven" for
/// [`Cluster`]s and for ray hits ([`crate::ray::HitStatus`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum UndecidedReason {
    /// Krawczyk neither proved a unique root nor excluded one: a multiple
    /// (double, tangential) root, or roots closer together than `eps`.
    MultipleOrClose,
    /// Both equations may vanish identically along an edge of the domain
    /// (every coefficient of both on that edge contains 0): possibly a curve
    /// of roots there, as when a ray passes through a patch's collapsed edge.
    /// The region is a thin strip along the edge; the rest of the domain is
    /// solved as usual.
    VanishingEdge,
    /// The box holds exactly one simple root, within rounding of the
    /// domain's boundary (for a ray: of the patch's edge), and exact
    /// arithmetic could not tell whether it lies in the domain or just
    /// outside it.
    Boundary,
    /// Rays only: the box holds exactly one transversal hit on the patch, but
    /// its `t` lies within rounding of an end of the requested `t` range (an
    /// origin on the surface, say) and whether it is inside is not proven.
    RangeEnd,
}

impl UndecidedReason {
    /// The stable machine-readable code: `"multiple_or_close"`,
    /// `"vanishing_edge"`, `"boundary"` or `"range_end"`.
    pub fn code(self) -> &'static str {
        match self {
            UndecidedReason::MultipleOrClose => "multiple_or_close",
            UndecidedReason::VanishingEdge => "vanishing_edge",
            UndecidedReason::Boundary => "boundary",
            UndecidedReason::RangeEnd => "range_end",
        }
    }

    /// A one-line English description for output.
    pub fn describe(self) -> &'static str {
        match self {
            UndecidedReason::MultipleOrClose => {
                "Krawczyk undecided: multiple root (tangential curves) or roots closer than eps"
            }
            UndecidedReason::Boundary => {
                "one simple root within rounding of the domain's boundary: inside or just outside is undecided"
            }
            UndecidedReason::VanishingEdge => {
                "both equations may vanish along this domain edge (a curve of roots, e.g. a collapsed patch edge)"
            }
            UndecidedReason::RangeEnd => {
                "one transversal hit whose t lies within rounding of an end of the t range: in or out is undecided"
            }
        }
    }
}

/// An undecided region: it may hold any number of roots (including none).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cluster {
    /// A closed box covering the region.
    #[cfg_attr(feature = "serde", serde(rename = "box"))]
    pub bx: Box2,
    /// Why it is undecided.
    pub reason: UndecidedReason,
    /// Diameters by level along the path to one of its tri-boxes (not
    /// serialized).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub diameters: Vec<f64>,
}

/// A region a budget left unexplored: roots there are neither listed nor
/// excluded.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Leftover {
    /// The region's bounding box in `(u, v)`.
    #[cfg_attr(feature = "serde", serde(rename = "box"))]
    pub bx: Box2,
    /// The triangle's vertices in `(u, v)` (enclosed: exact for the triangle
    /// domain) when the region is a tri-box; `None` for a box of the
    /// rectangle solver, whose region is `bx` itself.
    pub triangle: Option<[[f64; 2]; 3]>,
}

/// Counters of a solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Tri-boxes processed, clips, splits, exclusions (summed over triangles).
    pub run: Counters,
    /// Krawczyk operator evaluations.
    pub krawczyk_calls: usize,
    /// Final tri-boxes handed to certification.
    pub leaves: usize,
    /// Final tri-boxes proven root-free by Krawczyk.
    pub krawczyk_exclusions: usize,
    /// Certified roots dropped because they lie provably outside the domain.
    pub outside_domain: usize,
    /// Deepest level reached.
    pub max_level: usize,
}

/// The result of a solve.
///
/// # Contract
/// * If `complete` is `true`, every root of the system in the closed domain
///   lies in one of `roots[..].bx` or `clusters[..].bx`.
/// * Whatever `complete` says, every root that is not in a `roots` or
///   `clusters` box lies in a `leftovers` region (the budget stopped there);
///   `complete` is `true` iff `leftovers` is empty.
/// * Each `roots[i].bx` contains exactly one root of the system (in the plane —
///   a box may reach slightly outside the domain; see `on_boundary`), and it
///   is a simple root. Distinct entries are distinct roots.
/// * For exact input ([`solve`]) that root also lies in the closed domain:
///   a root whose box touches the boundary is settled in exact arithmetic
///   ([`settle`]) — kept if in the domain, dropped if outside, else reported
///   as a [`UndecidedReason::Boundary`] cluster. (For interval input,
///   [`solve_triangle`], [`solve_square`], an `on_boundary` root may lie
///   within its box's width outside the domain.)
/// * Clusters promise nothing about their content.
///
/// These hold for every system whose coefficients lie in the input
/// enclosures; for exact (rational) input, for that system.
#[derive(Clone, Debug)]
pub struct Solution {
    /// See the contract.
    pub complete: bool,
    /// Certified roots.
    pub roots: Vec<Root>,
    /// Undecided regions.
    pub clusters: Vec<Cluster>,
    /// Regions left by a budget.
    pub leftovers: Vec<Leftover>,
    /// Counters.
    pub stats: Stats,
}

impl Solution {
    /// `recursions(ε)`: for each root (and cluster), the first level whose
    /// tri-box diameter is `< ε`; the maximum over them. `None` if some root's
    /// path never got below `ε` or there are no roots.
    pub fn recursions(&self, eps: f64) -> Option<usize> {
        let paths = self
            .roots
            .iter()
            .map(|r| &r.diameters)
            .chain(self.clusters.iter().map(|c| &c.diameters));
        let mut worst: Option<usize> = None;
        for d in paths {
            let level = d.iter().position(|&x| x < eps)?;
            worst = Some(worst.map_or(level, |w: usize| w.max(level)));
        }
        worst
    }
}

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
    opts.validate()?;
    not_zero(f.is_zero(), g.is_zero())?;
    for p in [f, g] {
        p.check_conversion_cost(domain == Domain::Square)?;
    }
    no_common_factor(f, g)?;
    match domain {
        Domain::Triangle => {
            let n = f.total_degree().max(1).max(g.total_degree()) as usize;
            solve_exact_triangle(f.to_triangle(n), g.to_triangle(n), opts)
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
    opts.validate()?;
    match (f.input()?, g.input()?) {
        (BbInput::Triangle(f), BbInput::Triangle(g)) => {
            not_zero(f.is_zero(), g.is_zero())?;
            no_common_factor(&Polynomial::from_triangle(&f), &Polynomial::from_triangle(&g))?;
            let n = f.degree().max(g.degree()).max(1);
            solve_exact_triangle(f.elevate(n)?, g.elevate(n)?, opts)
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
        return Err(Error::Degenerate(format!(
            "equation {which} is identically zero: every point of the other curve is a root"
        )));
    }
    Ok(())
}

fn no_common_factor(f: &Polynomial, g: &Polynomial) -> Result<()> {
    if degenerate::has_common_factor(f, g) {
        return Err(Error::Degenerate(
            "f and g share a common factor: the system has a curve of roots".into(),
        ));
    }
    Ok(())
}

/// The exact system on the unit triangle (equal degrees, coprime, not zero).
fn solve_exact_triangle(
    ef: TriBezier<BigRational>,
    eg: TriBezier<BigRational>,
    opts: &SolveOptions,
) -> Result<Solution> {
    let enclose = |q: &BigRational| Interval::from_rational(q);
    let n = ef.degree();
    let (ef, eg) = (ef.map(scaler(ef.coeffs())), eg.map(scaler(eg.coeffs())));
    let (tf, tg) = (ef.map(enclose), eg.map(enclose));
    check_system(&tf, &tg)?;
    let global = System::new(tf.clone(), tg.clone());
    let sys = settle::ExactSystem::new(
        settle::Shape::Triangle(n),
        ef.coeffs().to_vec(),
        eg.coeffs().to_vec(),
        None,
    )?;
    let piece = Piece {
        f: tf,
        g: tg,
        frame: Frame::Identity,
        exact: Some([ef, eg]),
        floats: false,
    };
    Ok(finish_exact(
        solve_pieces(vec![piece], &global, Domain::Triangle, opts),
        &sys,
    ))
}

/// The exact system on the unit square (equal bidegrees, coprime, not zero).
fn solve_exact_square(
    ef: TensorBezier<BigRational>,
    eg: TensorBezier<BigRational>,
    opts: &SolveOptions,
) -> Result<Solution> {
    let enclose = |q: &BigRational| Interval::from_rational(q);
    let (dm, dn) = ef.degree();
    let (ef, eg) = (ef.map_coeffs(scaler(ef.coeffs())), eg.map_coeffs(scaler(eg.coeffs())));
    let sys = settle::ExactSystem::new(
        settle::Shape::Tensor(dm, dn),
        ef.coeffs().to_vec(),
        eg.coeffs().to_vec(),
        None,
    )?;
    if opts.square_route != SquareRoute::Triangles {
        let ropts = rect::RectOptions {
            eps: opts.eps,
            max_boxes: opts.max_boxes,
            clip: match opts.square_route {
                SquareRoute::RectFatLine => rect::RectClip::FatLine,
                SquareRoute::RectHybrid => rect::RectClip::Hybrid,
                _ => rect::RectClip::Bezier,
            },
            ..rect::RectOptions::default()
        };
        let sol = rect::solve_rect(&ef.map(enclose), &eg.map(enclose), None, &ropts)?.solution;
        if sol.complete {
            return Ok(finish_exact(sol, &sys));
        }
        // Out of budget (e.g. two curves running nearly parallel
        // along a diagonal, which axis-aligned boxes separate only
        // when they are as thin as the gap): the triangle route's fat
        // curves and exact restarts handle those.
    }
    let exact = Some((ef.to_triangles()?, eg.to_triangles()?));
    Ok(finish_exact(
        square_pieces(&ef.map(enclose), &eg.map(enclose), exact, opts)?,
        &sys,
    ))
}

/// Undecided regions at most this wide are retried by exact Krawczyk.
const EXACT_CERTIFY_BELOW: f64 = 1e-6;
/// At most this many exact Krawczyk tests per solve (each region that does
/// not settle at once is bisected, at most three times).
const EXACT_CERTIFY_MAX: usize = 24;

/// Retries small undecided regions with Krawczyk in exact arithmetic
/// ([`settle::ExactSystem::certify`]), bisecting a region that does not
/// settle at once (two roots 1e-9 apart share one): if every piece is
/// proven to hold one simple root or none, the region is replaced by those
/// roots (a root whose box overlaps another root's stays undecided: it could
/// be the same root); otherwise it stays. The regions arrive as the driver
/// left them ([`touching_regions`]), so two close roots in two regions are
/// retried one by one; the regions left are then joined ([`join_undecided`]).
/// Then every certified root on the boundary is settled
/// ([`settle_boundary`]).
fn finish_exact(mut sol: Solution, sys: &settle::ExactSystem) -> Solution {
    let mut kept = Vec::with_capacity(sol.clusters.len());
    let mut budget = EXACT_CERTIFY_MAX;
    for c in std::mem::take(&mut sol.clusters) {
        let small = c.bx.u[1] - c.bx.u[0] <= EXACT_CERTIFY_BELOW && c.bx.v[1] - c.bx.v[0] <= EXACT_CERTIFY_BELOW;
        // A (nearly) singular Jacobian at the centre: a multiple root, or
        // roots closer than these tests separate; not worth the exact cost.
        let near_singular = || {
            let j = sys.jacobian_f64(0.5 * (c.bx.u[0] + c.bx.u[1]), 0.5 * (c.bx.v[0] + c.bx.v[1]));
            let det = j[0] * j[3] - j[1] * j[2];
            let scale = (j[0] * j[0] + j[1] * j[1]).sqrt() * (j[2] * j[2] + j[3] * j[3]).sqrt();
            // (NaN counts as singular.)
            det.abs().partial_cmp(&(1e-11 * scale)) != Some(std::cmp::Ordering::Greater)
        };
        if c.reason != UndecidedReason::MultipleOrClose || !small || near_singular() {
            kept.push(c);
            continue;
        }
        let mut found = Vec::new();
        if !certify_region(sys, c.bx, 3, &mut budget, &mut found, &mut sol.stats) {
            kept.push(c);
            continue;
        }
        let mut rejected = false;
        for bx in found {
            if sol.roots.iter().any(|r| r.bx.overlaps(&bx)) {
                rejected = true;
                continue;
            }
            let place = locate(bx.ibox(), sys.domain());
            if place == Place::Outside {
                sol.stats.outside_domain += 1;
                continue;
            }
            sol.roots.push(Root {
                u: 0.5 * (bx.u[0] + bx.u[1]),
                v: 0.5 * (bx.v[0] + bx.v[1]),
                bx,
                on_boundary: place == Place::Boundary,
                diameters: c.diameters.clone(),
            });
        }
        if rejected {
            kept.push(c);
        }
    }
    sol.clusters = kept;
    sol.roots.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
    settle_boundary(join_undecided(sol), sys)
}

/// Certifies the region `bx` in exact arithmetic, bisecting it up to
/// `depth` times: `true` if every piece holds one simple root (its box is
/// pushed to `found`) or none.
fn certify_region(
    sys: &settle::ExactSystem,
    bx: Box2,
    depth: usize,
    budget: &mut usize,
    found: &mut Vec<Box2>,
    stats: &mut Stats,
) -> bool {
    if *budget == 0 {
        return false;
    }
    *budget -= 1;
    stats.krawczyk_calls += 1;
    match sys.certify(bx) {
        settle::Certificate::Unique(k) => {
            found.push(k);
            true
        }
        settle::Certificate::NoRoot => {
            stats.krawczyk_exclusions += 1;
            true
        }
        settle::Certificate::Undecided if depth > 0 => {
            let (a, b) = if bx.u[1] - bx.u[0] >= bx.v[1] - bx.v[0] {
                let m = 0.5 * (bx.u[0] + bx.u[1]);
                (Box2 { u: [bx.u[0], m], ..bx }, Box2 { u: [m, bx.u[1]], ..bx })
            } else {
                let m = 0.5 * (bx.v[0] + bx.v[1]);
                (Box2 { v: [bx.v[0], m], ..bx }, Box2 { v: [m, bx.v[1]], ..bx })
            };
            certify_region(sys, a, depth - 1, budget, found, stats)
                && certify_region(sys, b, depth - 1, budget, found, stats)
        }
        settle::Certificate::Undecided => false,
    }
}

/// Settles every certified root whose box touches the domain's boundary in
/// exact arithmetic ([`settle`]): kept if it is in the closed domain,
/// dropped if it is outside, and turned into a
/// [`UndecidedReason::Boundary`] region if neither is proven.
fn settle_boundary(mut sol: Solution, sys: &settle::ExactSystem) -> Solution {
    let mut kept = Vec::with_capacity(sol.roots.len());
    for r in std::mem::take(&mut sol.roots) {
        if !r.on_boundary {
            kept.push(r);
            continue;
        }
        match sys.settle(r.bx) {
            settle::Settled::Inside => kept.push(r),
            settle::Settled::Outside => sol.stats.outside_domain += 1,
            settle::Settled::Undecided => sol.clusters.push(Cluster {
                bx: r.bx,
                reason: UndecidedReason::Boundary,
                diameters: r.diameters,
            }),
        }
    }
    sol.roots = kept;
    sol
}

fn check_system(f: &TriBezier<Interval>, g: &TriBezier<Interval>) -> Result<()> {
    for (name, p) in [("f", f), ("g", g)] {
        if p.coeffs().iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFinite(format!("a coefficient of {name} is NaN or infinite")));
        }
        if p.is_zero() {
            return Err(Error::Degenerate(format!("equation {name} is identically zero")));
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
    square_pieces(&f, &g, None, opts).map(join_undecided)
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

#[derive(Clone)]
struct Found {
    bx: IBox,
    diameters: Vec<f64>,
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
                    Probe::Unique
                }
                Verdict::NoRoot => Probe::NoRoot,
                Verdict::Undecided(_) => Probe::Undecided,
            }
        };
        let ball = |p: &TriBezier<Interval>| TriBall::enclose(p).unwrap_or_else(|_| TriBall::unbounded(p.degree()));
        let exact = match (exact, floats) {
            (Some(p), _) => Exact::Rational(p),
            (None, true) => Exact::Floats,
            (None, false) => Exact::None,
        };
        let run = driver::run::<GeoIv>(&ball(f), &ball(g), exact, &limits, &mut probe);
        add_counters(&mut stats.run, &run.counters);
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

/// Groups of boxes connected by overlap (closed boxes; touching counts), by
/// union–find over the pairs that [`touching_pairs`] finds.
fn group_overlapping(items: Vec<Found>) -> Vec<Vec<Found>> {
    let n = items.len();
    let rects: Vec<Box2> = items.iter().map(|f| Box2::of(f.bx)).collect();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    touching_pairs(&rects, |i, j| {
        let (a, b) = (find(&mut parent, i), find(&mut parent, j));
        parent[a] = b;
    });
    let mut groups: Vec<Vec<Found>> = Vec::new();
    let mut slot = vec![usize::MAX; n];
    for (i, item) in items.into_iter().enumerate() {
        let r = find(&mut parent, i);
        if slot[r] == usize::MAX {
            slot[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[slot[r]].push(item);
    }
    groups
}

/// Calls `found(i, j)` for every pair of closed boxes that share a point
/// ([`Box2::overlaps`]; some pairs may be reported twice). Leaves are
/// many and similar in size, often strung along one coordinate (a sliver of
/// near-roots along an edge), where a sweep over `u` compares all pairs: so
/// they are hashed into a grid of cells the size of the median rectangle, and
/// only rectangles sharing a cell are compared (rectangles much larger than a
/// cell are compared with every other). Small inputs compare all pairs.
fn touching_pairs(rects: &[Box2], mut found: impl FnMut(usize, usize)) {
    let n = rects.len();
    let side = |r: &Box2| (r.u[1] - r.u[0]).max(r.v[1] - r.v[0]);
    let mut sizes: Vec<f64> = rects.iter().map(side).collect();
    sizes.sort_by(f64::total_cmp);
    let cell = sizes.get(n / 2).copied().unwrap_or(0.0);
    let usable = n > 64 && cell > 0.0 && cell.is_finite();
    let key = |x: f64| (x / cell).floor() as i64;
    // Rectangles spanning more than 8 cells either way (or not finite).
    let big = |r: &Box2| !usable || !r.u.iter().chain(&r.v).all(|x| x.is_finite()) || side(r) > 8.0 * cell;
    let (mut large, mut grid) = (Vec::new(), std::collections::HashMap::<(i64, i64), Vec<usize>>::new());
    for (i, r) in rects.iter().enumerate() {
        if big(r) {
            large.push(i);
            continue;
        }
        for a in key(r.u[0])..=key(r.u[1]) {
            for b in key(r.v[0])..=key(r.v[1]) {
                grid.entry((a, b)).or_default().push(i);
            }
        }
    }
    for members in grid.values() {
        for (k, &i) in members.iter().enumerate() {
            for &j in &members[k + 1..] {
                if rects[i].overlaps(&rects[j]) {
                    found(i, j);
                }
            }
        }
    }
    for &i in &large {
        for j in 0..n {
            if j != i && rects[i].overlaps(&rects[j]) {
                found(i, j);
            }
        }
    }
}

/// Undecided regions within this distance of each other (their joint hull at
/// most this wide in both directions) are reported as one.
const NEAR: f64 = 1e-5;

/// The gap up to which a region [`nearly_touch`]es another: 2⁻¹⁶ of its
/// larger side. Stalled tri-boxes around a multiple root are separated by
/// slivers their clips proved root-free, ~2⁻²⁰ of the kept tri-box wide
/// (`fatcurve::VERIFY_MARGIN`); regions that close are one region to a user.
fn touch_gap(b: &IBox) -> f64 {
    let side = b[0].wid().max(b[1].wid());
    if side.is_finite() {
        side / 65536.0
    } else {
        0.0
    }
}

/// The boxes are apart by at most [`touch_gap`] of the smaller one in each
/// direction (touching and overlapping boxes included).
fn nearly_touch(a: &IBox, b: &IBox) -> bool {
    let tol = touch_gap(a).min(touch_gap(b));
    let gap = |x: Interval, y: Interval| (y.inf() - x.sup()).max(x.inf() - y.sup()).max(0.0);
    gap(a[0], b[0]) <= tol && gap(a[1], b[1]) <= tol
}

/// The undecided leaves as clusters: leaves that touch are one region, and
/// regions whose joint hull is at most [`NEAR`] wide, or that nearly touch
/// ([`nearly_touch`]), are joined too. Near a
/// triple root the leaves that rounding leaves undecided are scattered over
/// a ~1e-5 neighbourhood with excluded gaps between them; one region says
/// the same, soundly (a hull covers more), and readably.
fn undecided_clusters(leaves: Vec<Found>) -> Vec<Cluster> {
    let regions = join_near(group_overlapping(leaves).into_iter().map(hull_of).collect());
    regions.into_iter().map(undecided).collect()
}

/// `region` as an undecided cluster.
fn undecided(region: Found) -> Cluster {
    Cluster {
        bx: Box2::of(region.bx),
        reason: UndecidedReason::MultipleOrClose,
        diameters: region.diameters,
    }
}

/// The undecided leaves as clusters, touching leaves as one region, but
/// regions near each other not joined yet ([`join_undecided`] does that):
/// the exact retry ([`finish_exact`]) settles each region on its own, where
/// the hull of two regions 1e-7 apart (two close roots) would hold both.
fn touching_regions(leaves: Vec<Found>) -> Vec<Cluster> {
    group_overlapping(leaves)
        .into_iter()
        .map(hull_of)
        .map(undecided)
        .collect()
}

/// [`undecided_clusters`]' joining of near regions, for a solution from
/// [`touching_regions`]: undecided clusters whose joint hull is at most
/// [`NEAR`] wide, or that nearly touch ([`nearly_touch`]), become one.
fn join_undecided(mut sol: Solution) -> Solution {
    let (near, other): (Vec<Cluster>, Vec<Cluster>) = std::mem::take(&mut sol.clusters)
        .into_iter()
        .partition(|c| c.reason == UndecidedReason::MultipleOrClose);
    let regions: Vec<Found> = near
        .into_iter()
        .map(|c| Found {
            bx: c.bx.ibox(),
            diameters: c.diameters,
        })
        .collect();
    sol.clusters = join_near(regions).into_iter().map(undecided).chain(other).collect();
    sol
}

/// Joins regions whose joint hull is at most [`NEAR`] wide in both
/// directions, or that nearly touch ([`nearly_touch`]), until no two can be
/// joined. Each pass sweeps the regions in order of their lower `u` and
/// tries them against the joined regions that could still take them (lower
/// `u` within `NEAR`, or upper `u` within their touching gap), so thousands
/// of leaves along a curve of near-roots cost about linear time per pass,
/// not quadratic; a pass that joins nothing ends it.
fn join_near(mut regions: Vec<Found>) -> Vec<Found> {
    let near = |a: &IBox, b: &IBox| {
        let h = hull(*a, *b);
        (h[0].wid() <= NEAR && h[1].wid() <= NEAR) || nearly_touch(a, b)
    };
    loop {
        let before = regions.len();
        regions.sort_by(|a, b| a.bx[0].inf().total_cmp(&b.bx[0].inf()));
        let mut out: Vec<Found> = Vec::with_capacity(regions.len());
        let mut open: Vec<usize> = Vec::new();
        for r in regions {
            let lo = r.bx[0].inf();
            // A joined region starting more than NEAR to the left of this
            // one (and of every later one) can take none of them.
            open.retain(|&k| out[k].bx[0].inf() >= lo - NEAR || out[k].bx[0].sup() + touch_gap(&out[k].bx) >= lo);
            match open.iter().find(|&&k| near(&out[k].bx, &r.bx)) {
                Some(&k) => {
                    let m = &mut out[k];
                    m.bx = hull(m.bx, r.bx);
                    if r.diameters.len() > m.diameters.len() {
                        m.diameters = r.diameters;
                    }
                }
                None => {
                    open.push(out.len());
                    out.push(r);
                }
            }
        }
        regions = out;
        if regions.len() == before {
            return regions;
        }
    }
}

fn hull_of(group: Vec<Found>) -> Found {
    let mut it = group.into_iter();
    let first = it.next().expect("groups are non-empty");
    it.fold(first, |acc, x| Found {
        bx: hull(acc.bx, x.bx),
        diameters: if x.diameters.len() > acc.diameters.len() {
            x.diameters
        } else {
            acc.diameters
        },
    })
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

fn add_counters(a: &mut Counters, b: &Counters) {
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

fn overlaps(a: IBox, b: IBox) -> bool {
    !a[0].disjoint(b[0]) && !a[1].disjoint(b[1])
}

fn hull(a: IBox, b: IBox) -> IBox {
    [a[0].convex_hull(b[0]), a[1].convex_hull(b[1])]
}

/// Certified boxes that overlap may hold the same root (a root on a shared
/// tri-box edge). If Krawczyk proves a unique root in their hull, they are one
/// root; otherwise (rare) both stay, since each holds exactly one root but
/// they might be different.
fn merge_roots<P: Bivariate>(mut found: Vec<Found>, global: &System<P>, stats: &mut Stats) -> (Vec<Found>, Vec<Found>) {
    let mut out: Vec<Found> = Vec::new();
    let mut undecided: Vec<Found> = Vec::new();
    'next: while let Some(r) = found.pop() {
        for i in 0..out.len() {
            let o = &out[i];
            if !overlaps(o.bx, r.bx) {
                continue;
            }
            stats.krawczyk_calls += 1;
            if let Verdict::Unique(k) = global.certify(hull(o.bx, r.bx)) {
                let o = &mut out[i];
                o.bx = k;
                if r.diameters.len() > o.diameters.len() {
                    o.diameters = r.diameters;
                }
                continue 'next;
            }
            // Each box holds exactly one root. On their intersection (no
            // inflation): one root there is both boxes' root; none means the
            // two roots are distinct; otherwise neither claim can stand.
            let meet = [o.bx[0].intersection(r.bx[0]), o.bx[1].intersection(r.bx[1])];
            stats.krawczyk_calls += 1;
            match global.krawczyk(meet) {
                Verdict::Unique(_) => {
                    let o = &mut out[i];
                    o.bx = meet;
                    continue 'next;
                }
                Verdict::NoRoot => {}
                Verdict::Undecided(_) => {
                    let o = out.swap_remove(i);
                    undecided.push(Found {
                        bx: hull(o.bx, r.bx),
                        diameters: r.diameters,
                    });
                    continue 'next;
                }
            }
        }
        out.push(r);
    }
    (out, undecided)
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
        &mut |_| Probe::Undecided,
    );
    run.leaves.iter().map(|l| l.tb.point_at([1.0 / 3.0; 3])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::interval;

    fn found(u: f64, v: f64, w: f64) -> Found {
        Found {
            bx: [interval(u, u + w), interval(v, v + w)],
            diameters: vec![w],
        }
    }

    /// The grid pairing finds exactly the touching pairs brute force finds:
    /// random rectangles of mixed sizes, rectangles sharing only an edge or a
    /// corner, zero-width ones, a few huge ones and thousands strung along
    /// one line.
    /// Regions apart by less than 2⁻¹⁶ of the smaller one join; regions
    /// further apart (and wider than `NEAR`) stay apart; the sweep finds a
    /// nearly touching region to the right of a long one.
    #[test]
    fn nearly_touching_regions_join() {
        let region = |u0: f64, u1: f64, v0: f64, v1: f64| Found {
            bx: [interval(u0, u1), interval(v0, v1)],
            diameters: Vec::new(),
        };
        let joined = join_near(vec![
            region(0.0, 1e-3, 0.0, 1e-3),
            region(1e-3 + 1e-9, 2e-3, 0.0, 1e-3),
            region(0.5, 0.6, 0.5, 0.6),
            region(0.6 + 1e-3, 0.7, 0.5, 0.6),
            region(0.1, 0.3, 0.0, 1e-3),
            region(0.3 + 1e-9, 0.3 + 1e-3, 0.0, 1e-3),
            region(0.4, 0.401, 0.0, 1e-3),
            region(0.401 + 1e-7, 0.402, 0.0, 1e-3),
        ]);
        let mut lows: Vec<(f64, f64)> = joined.iter().map(|r| (r.bx[0].inf(), r.bx[0].sup())).collect();
        lows.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(
            lows,
            vec![
                (0.0, 2e-3),
                (0.1, 0.3 + 1e-3),
                (0.4, 0.401),
                (0.401 + 1e-7, 0.402),
                (0.5, 0.6),
                (0.6 + 1e-3, 0.7)
            ]
        );
    }

    #[test]
    fn touching_pairs_match_brute_force() {
        let mut rng = crate::rng::Rng(0x2545_f491_4f6c_dd1d);
        let mut rnd = move || rng.next_f64();
        for case in 0..6 {
            let n = [10, 70, 300, 1000, 2000, 500][case];
            let mut rects: Vec<[f64; 4]> = (0..n)
                .map(|k| {
                    let size = [1e-3, 1e-9, 0.0, 0.3][k % 4] * rnd();
                    let (u, v) = if case == 4 {
                        (1e-12 * rnd(), k as f64 * 1e-9)
                    } else {
                        (rnd(), rnd())
                    };
                    [u, u + size, v, v + size * rnd()]
                })
                .collect();
            // Exact edge and corner contacts.
            let r0 = rects[0];
            rects.push([r0[1], r0[1] + 0.1, r0[2], r0[3]]);
            rects.push([r0[1], r0[1] + 0.1, r0[3], r0[3] + 0.1]);
            rects.push([-1.0, 2.0, 0.5, 0.5]);
            let boxes: Vec<Box2> = rects
                .iter()
                .map(|r| Box2 {
                    u: [r[0], r[1]],
                    v: [r[2], r[3]],
                })
                .collect();
            let mut got = std::collections::BTreeSet::new();
            touching_pairs(&boxes, |i, j| {
                got.insert((i.min(j), i.max(j)));
            });
            let mut want = std::collections::BTreeSet::new();
            for i in 0..rects.len() {
                for j in i + 1..rects.len() {
                    let (a, b) = (rects[i], rects[j]);
                    if a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3] {
                        want.insert((i, j));
                    }
                }
            }
            assert_eq!(got, want, "case {case}");
        }
    }

    /// Thousands of undecided leaves scattered along a 1e-5 sliver (a curve
    /// of near-roots) become one region, in linear time; regions farther
    /// apart than `NEAR` stay apart, and every input box stays covered.
    #[test]
    fn near_regions_join_at_scale() {
        let mut leaves: Vec<Found> = (0..6000)
            .map(|i| found(1e-12 * (i % 7) as f64, 1.5e-9 * i as f64, 1e-12))
            .collect();
        leaves.push(found(0.5, 0.5, 1e-9));
        leaves.push(found(0.5 + 2.0 * NEAR, 0.5, 1e-9));
        let inputs: Vec<IBox> = leaves.iter().map(|f| f.bx).collect();
        let joined = join_near(leaves);
        assert_eq!(joined.len(), 3, "{:?}", joined.iter().map(|f| f.bx).collect::<Vec<_>>());
        for b in &inputs {
            assert!(joined.iter().any(|f| b[0].subset(f.bx[0]) && b[1].subset(f.bx[1])));
        }
        for f in &joined {
            assert!(f.bx[0].wid() <= NEAR && f.bx[1].wid() <= NEAR);
        }
    }
}
