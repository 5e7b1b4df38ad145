//! What a ray query is asked: the ray, and the options of a query.

use crate::error::{Error, Result};
pub use crate::solve::rect::Query;
use crate::solve::{SolveOptions, SquareRoute};
use glam::DVec3;

/// A ray `o + t·d`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Ray {
    origin: DVec3,
    dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (not normalized; `t` is measured in
    /// units of `dir`). Errors: NaN/∞, or a direction subnormal in every
    /// component (`t` would overflow) ([`Error::NonFinite`]); zero direction
    /// ([`Error::Degenerate`]).
    ///
    /// ```
    /// use rootclip::glam::DVec3;
    /// use rootclip::ray::Ray;
    /// let ray = Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, 2.0))?;
    /// assert_eq!(ray.at(1.5), DVec3::new(0.0, 0.0, 3.0));
    /// assert!(Ray::new(DVec3::ZERO, DVec3::ZERO).is_err());
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn new(origin: DVec3, dir: DVec3) -> Result<Self> {
        if !origin.is_finite() || !dir.is_finite() {
            return Err(Error::NonFinite(format!(
                "ray origin {:?} / direction {:?}",
                origin.to_array(),
                dir.to_array()
            )));
        }
        if dir == DVec3::ZERO {
            return Err(Error::Degenerate("the ray direction is zero".into()));
        }
        // t scales as 1/|d|: with every component subnormal it overflows
        // f64 at any distance above about 2^-52.
        if dir.abs().max_element() < f64::MIN_POSITIVE {
            return Err(Error::NonFinite(format!(
                "the ray direction {:?} is subnormal (below 2^-1022 in every component): t would overflow",
                dir.to_array()
            )));
        }
        Ok(Self { origin, dir })
    }

    /// The origin `o`.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The direction `d`.
    pub fn dir(&self) -> DVec3 {
        self.dir
    }

    /// `o + t·d` in `f64`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// More undecided regions than this make a ray [`Degeneracy::Unresolved`].
pub(crate) const MAX_CLUSTERS: usize = 16;

/// Options of [`intersect`](super::intersect) and
/// [`intersect_batch`](super::intersect_batch).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct RayOptions {
    /// Solver options: `eps` and `max_boxes` (per triangle or per box solve;
    /// default 20,000 here: a transversal ray needs a few dozen, more means
    /// a curve of hits) apply to every route, `method` and `split` to
    /// triangles. `solve.square_route` is not used: see `route`.
    pub solve: SolveOptions,
    /// How tensor patches (and B-spline pieces) are solved (default
    /// [`SquareRoute::Rect`]: Bézier clipping on boxes, the fastest; a ray
    /// whose box solve runs out of budget is retried through the triangles).
    pub route: SquareRoute,
    /// All hits, the nearest, or any (shadow rays).
    pub query: Query,
    /// The closed range `[t_min, t_max]` of `t` whose hits are wanted
    /// (default `[0, ∞]`: the ray; `[−∞, ∞]` is the whole line). In JSON an
    /// infinite end is `null`.
    #[cfg_attr(feature = "serde", serde(with = "crate::serde_util::range"))]
    pub t_range: [f64; 2],
}

impl Default for RayOptions {
    fn default() -> Self {
        Self {
            solve: SolveOptions {
                max_boxes: 20_000,
                ..SolveOptions::default()
            },
            route: SquareRoute::Rect,
            query: Query::All,
            t_range: [0.0, f64::INFINITY],
        }
    }
}

impl RayOptions {
    /// The same options with `query`.
    pub fn with_query(mut self, query: Query) -> Self {
        self.query = query;
        self
    }

    /// The same options with the `t` range `[t_min, t_max]`.
    pub fn with_t_range(mut self, t_min: f64, t_max: f64) -> Self {
        self.t_range = [t_min, t_max];
        self
    }

    /// The same options with the tensor route.
    pub fn with_route(mut self, route: SquareRoute) -> Self {
        self.route = route;
        self
    }

    /// The same options with a wall-clock budget per ray: every solve the
    /// ray starts (routes, retries, B-spline pieces) stops at one deadline,
    /// and the ray then ends [`Degeneracy::Unresolved`](super::Degeneracy::Unresolved)
    /// with `complete = false` and the hits found.
    pub fn with_timeout(mut self, timeout: std::time::Duration) -> Self {
        self.solve.timeout = Some(timeout);
        self
    }

    /// The same options with another box budget per solve
    /// ([`SolveOptions::max_boxes`]).
    pub fn with_max_boxes(mut self, max_boxes: usize) -> Self {
        self.solve.max_boxes = max_boxes;
        self
    }

    /// Checks the options: the solver's ([`SolveOptions::validate`]) and a
    /// `t` range that is not NaN and not empty ([`Error::InvalidOption`]).
    pub fn validate(&self) -> Result<()> {
        self.solve.validate()?;
        let [lo, hi] = self.t_range;
        if lo.is_nan() || hi.is_nan() || lo > hi || lo == f64::INFINITY || hi == f64::NEG_INFINITY {
            return Err(Error::InvalidOption(format!(
                "t range must be a non-empty [t_min, t_max], got [{lo}, {hi}]"
            )));
        }
        Ok(())
    }
}
