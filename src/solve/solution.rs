//! What a solve returns: certified roots, undecided clusters, regions a
//! budget left, and counters — shared by the triangle solver
//! ([`solve`](crate::solve::solve)) and the box solver
//! ([`rect`](crate::solve::rect)), and re-exported from [`crate::solve`].

use crate::scalar::interval;
use crate::solve::krawczyk::IBox;

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

    pub(crate) fn of(x: IBox) -> Self {
        Self {
            u: [x[0].inf(), x[0].sup()],
            v: [x[1].inf(), x[1].sup()],
        }
    }

    /// The same box as intervals (the inverse of [`Box2::of`]).
    pub(crate) fn ibox(&self) -> IBox {
        [interval(self.u[0], self.u[1]), interval(self.v[0], self.v[1])]
    }
}

/// A certified root: its box holds exactly one root of the system, a simple
/// one (see the [`Solution`] contract).
///
/// JSON (feature `serde`): the fields and `"certified": true` (every root
/// is; spelled out for readers of mixed lists), ignored when read.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "super::json::RootRepr", from = "super::json::RootRepr")
)]
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
    /// whole domain), along the deepest path that reached it (empty for the
    /// box solvers).
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
///
/// JSON (feature `serde`): the fields and `"reason_text"`, the reason in
/// English ([`UndecidedReason::describe`]), ignored when read.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "super::json::ClusterRepr", from = "super::json::ClusterRepr")
)]
pub struct Cluster {
    /// A closed box covering the region.
    #[cfg_attr(feature = "serde", serde(rename = "box"))]
    pub bx: Box2,
    /// Why it is undecided.
    pub reason: UndecidedReason,
    /// Diameters by level along the path to one of its tri-boxes (empty
    /// for the box solvers).
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

/// Counters of a solve (summed over the triangles or boxes it ran on).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(default))]
pub struct Stats {
    /// Tri-boxes (or boxes) processed.
    pub boxes: usize,
    /// Clips that shrank a region.
    pub clips: usize,
    /// 1-to-4 (or 1-to-2) splits.
    pub splits: usize,
    /// Regions discarded by check-sign.
    pub sign_exclusions: usize,
    /// Regions discarded because the fat regions (or hulls) do not meet.
    pub clip_exclusions: usize,
    /// Krawczyk probes during the iteration.
    pub probes: usize,
    /// Regions discarded by a probe.
    pub probe_exclusions: usize,
    /// Tri-boxes recomputed in compensated arithmetic (noisy or stalled).
    pub compensated_restarts: usize,
    /// Tri-boxes whose polynomials were computed in compensated arithmetic.
    pub compensated_boxes: usize,
    /// Stalled tri-boxes recomputed from the exact input, and boxes swamped
    /// by rounding recomputed from it in higher precision.
    pub exact_restarts: usize,
    /// Tri-boxes whose polynomials were computed from the exact input.
    pub exact_boxes: usize,
    /// Second hybrid clips with the equations' roles swapped.
    pub role_swaps: usize,
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
    /// Wall-clock seconds the solve took ([`solve`](crate::solve::solve)
    /// and [`solve_bb`](crate::solve::solve_bb); 0 where not measured).
    pub seconds: f64,
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
/// * For exact input ([`solve`](crate::solve::solve), [`solve_bb`](crate::solve::solve_bb)
///   with `f64` or rational coefficients) that root also lies in the closed domain:
///   a root whose box touches the boundary is settled in exact arithmetic
///   (`settle`) — kept if in the domain, dropped if outside, else reported
///   as a [`UndecidedReason::Boundary`] cluster. (For interval input an
///   `on_boundary` root may lie within its box's width outside the domain.)
/// * Clusters promise nothing about their content.
///
/// These hold for every system whose coefficients lie in the input
/// enclosures; for exact (rational) input, for that system.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
