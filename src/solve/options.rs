//! What a solve is asked: the domain, the method and its budgets.

use super::driver::{self, Limits, SplitRule};
use super::method::Method;
use crate::error::{Error, Result};

/// The domain of the unknowns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Domain {
    /// `{u, v ≥ 0, u + v ≤ 1}`.
    Triangle,
    /// `[0, 1]²`.
    Square,
}

/// How a system on the unit square (a tensor patch, for rays) is solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum SquareRoute {
    /// As two triangles of degree `m + n` with the chosen [`Method`] (the
    /// conversion of Liu et al. 2016).
    Triangles,
    /// Natively on boxes by Bézier clipping (Nishita, Sederberg & Kakimoto
    /// 1990; `method`, `probe`, `split` and `max_depth` do not apply),
    /// falling back to [`SquareRoute::Triangles`] when its budget runs out.
    /// The default: faster than the triangles at every degree measured
    /// (bidegree (2, 2) to (12, 12): 2–26×; degree 20–200 cases that the
    /// triangles of degree `m + n` do not finish; `docs/performance.md`).
    #[default]
    Rect,
    /// As [`SquareRoute::Rect`] with fat-line clipping on boxes.
    RectFatLine,
    /// As [`SquareRoute::Rect`] with hybrid clipping (a fat line and a fat
    /// conic) on boxes.
    RectHybrid,
}

/// How a system on the unit triangle, given exactly ([`solve`](super::solve)
/// or [`solve_bb`](super::solve_bb) with rational coefficients), is solved.
/// Input known only by enclosures always takes [`TriangleRoute::Triangle`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum TriangleRoute {
    /// On tri-boxes with the chosen [`Method`] (Liu et al.'s (2016) Algorithm 1; the
    /// tables run this route).
    Triangle,
    /// By Bézier clipping on boxes of the unit square, the system converted
    /// exactly to tensor form there, boxes beyond the hypotenuse dropped and
    /// roots near it settled exactly; falls back to
    /// [`TriangleRoute::Triangle`] when its budget runs out. The default:
    /// faster than the tri-boxes at every degree measured (1.3–2× on random
    /// dense systems of degree 2–20, 15–20× on the degree 20–25 line
    /// arrangements; `docs/performance.md`).
    #[default]
    Rect,
}

/// Options of a solve. Start from [`SolveOptions::default`] and change what
/// you need:
///
/// ```
/// use rootclip::solve::{Method, SolveOptions};
/// let opts = SolveOptions::default().with_method(Method::Bezier).with_eps(1e-10);
/// assert_eq!(opts.max_boxes, 50_000);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct SolveOptions {
    /// Clipping method on triangles (default [`Method::Hc`]).
    pub method: Method,
    /// Regions are refined until their diameter is below `eps` (default
    /// `1e-12`; any positive finite number); certified boxes are then
    /// contracted by Krawczyk iteration, usually far below `eps`.
    pub eps: f64,
    /// Budget: tri-boxes (or boxes) processed per triangle (or per box
    /// solve); default 50,000. A run that reaches it ends with
    /// `complete = false` and its leftovers.
    pub max_boxes: usize,
    /// Budget: recursion depth (default 400).
    pub max_depth: usize,
    /// Probe converging or stalled tri-boxes with Krawczyk during the
    /// iteration, certify or exclude them early, and stop refining undecided
    /// ones at multiple roots (default `true`). A probe only ever proves; it
    /// decides where the iteration stops, not what is true. `false` runs the
    /// paper's Algorithm 1 without probes (the tables do).
    pub probe: bool,
    /// When a step splits 1-to-4 (default [`SplitRule::Halving`]).
    pub split: SplitRule,
    /// Before a split, a second hybrid clip with the equations' roles
    /// swapped (default `true`; `false` with `probe = false` is the paper's
    /// Algorithm 1 as printed).
    pub swap_roles: bool,
    /// How [`Domain::Square`] is solved (default [`SquareRoute::Rect`]; the
    /// paper's conversion is [`SquareRoute::Triangles`]).
    pub square_route: SquareRoute,
    /// How exact input on [`Domain::Triangle`] is solved (default
    /// [`TriangleRoute::Rect`]).
    pub triangle_route: TriangleRoute,
    /// Wall-clock budget of a [`solve`](super::solve) or
    /// [`solve_bb`](super::solve_bb) (default none): once it has passed, no
    /// further tri-box or box is processed; the regions not yet explored
    /// become leftovers and the answer has `complete = false` (never a
    /// wrong one). Checked between boxes, so a run ends within one box's
    /// work of it plus the final certification of what was found.
    pub timeout: Option<std::time::Duration>,
    /// When the running solve's `timeout` passes (set at its start).
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) deadline: Option<std::time::Instant>,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: Method::Hc,
            eps: 1e-12,
            max_boxes: 50_000,
            max_depth: 400,
            probe: true,
            split: SplitRule::Halving,
            swap_roles: true,
            square_route: SquareRoute::Rect,
            triangle_route: TriangleRoute::Rect,
            timeout: None,
            deadline: None,
        }
    }
}

impl SolveOptions {
    /// The same options with `method`.
    pub fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// The same options with `eps`.
    pub fn with_eps(mut self, eps: f64) -> Self {
        self.eps = eps;
        self
    }

    /// The same options with the budget `max_boxes`.
    pub fn with_max_boxes(mut self, max_boxes: usize) -> Self {
        self.max_boxes = max_boxes;
        self
    }

    /// The same options with a wall-clock budget ([`SolveOptions::timeout`]).
    pub fn with_timeout(mut self, timeout: std::time::Duration) -> Self {
        self.timeout = Some(timeout);
        self
    }

    /// The options of a solve starting now: its deadline set from
    /// `timeout` (kept if already set, for the parts of one solve).
    pub(crate) fn started(&self) -> Self {
        let mut o = *self;
        if o.deadline.is_none() {
            o.deadline = o.timeout.and_then(|t| std::time::Instant::now().checked_add(t));
        }
        o
    }

    /// The same options with the square route.
    pub fn with_square_route(mut self, route: SquareRoute) -> Self {
        self.square_route = route;
        self
    }

    /// The same options with the triangle route.
    pub fn with_triangle_route(mut self, route: TriangleRoute) -> Self {
        self.triangle_route = route;
        self
    }

    /// Checks the options: `eps` must be positive and finite, the budgets
    /// non-zero ([`Error::InvalidOption`]).
    ///
    /// ```
    /// use rootclip::solve::SolveOptions;
    /// assert!(SolveOptions::default().with_eps(f64::NAN).validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        if !(self.eps.is_finite() && self.eps > 0.0) {
            return Err(Error::InvalidOption(format!(
                "eps must be a positive finite number, got {}",
                self.eps
            )));
        }
        if self.max_boxes == 0 || self.max_depth == 0 {
            return Err(Error::InvalidOption(
                "max_boxes and max_depth must be at least 1".into(),
            ));
        }
        Ok(())
    }

    pub(crate) fn limits(&self) -> Limits {
        Limits {
            method: self.method,
            eps: self.eps,
            max_boxes: self.max_boxes,
            max_depth: self.max_depth,
            max_exact: driver::MAX_EXACT_BOXES,
            probe_below: if self.probe { 1e-3 } else { 0.0 },
            split: self.split,
            swap_roles: self.swap_roles,
            deadline: self.deadline,
        }
    }
}
