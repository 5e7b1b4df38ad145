//! Native rectangular clipping for tensor-product systems: Bézier clipping
//! (Nishita, Sederberg & Kakimoto 1990) on boxes, with the same proofs as the
//! triangle solver and Krawczyk certificates in each box's own coordinates.
//!
//! # The iteration
//! A box `B = [a, b] × [c, d]` carries interval enclosures of the Bernstein
//! coefficients `f_ij`, `g_ij` of the system restricted to `B` (local
//! coordinates `(s, t) ∈ [0, 1]²`). One step:
//! 1. **check-sign**: if every `f_ij` (or every `g_ij`) is strictly positive,
//!    or strictly negative, `B` holds no root (the Bernstein basis is a
//!    positive partition of unity);
//! 2. **objective** (with an objective `k = p/q`, `q > 0`, and [`Query::Nearest`]):
//!    once a root is certified, `B` is dropped when `k` enclosed over `B`
//!    (interval de Casteljau on the domain's coefficients of `p` and `q`)
//!    lies above the certified root's upper bound; the whole domain is
//!    dropped at once when every `p_ij/q_ij < k_min` (then `k < k_min`: `k`
//!    is a convex combination of the ratios);
//! 3. **Krawczyk** in local coordinates once `B` is small: `X = [0, 1]²`,
//!    `F'(X)` enclosed by the hull of the derivative's Bernstein coefficients
//!    `m(f_{i+1,j} − f_ij)`, `n(f_{i,j+1} − f_ij)`, `F(½, ½)` by interval de
//!    Casteljau. `K(X) ⊂ (0, 1)²` proves exactly one root in `B`, simple, in the
//!    interior — so no neighbouring box can claim it; `K(X) ∩ X = ∅` proves
//!    none. A certified box is then contracted by iterating `K`;
//! 4. **clip** in `s` and in `t`: for `f(s, t) = Σ_i B^m_i(s) c_i(t)` with
//!    `c_i(t) ∈ [L_i, U_i] = [min_j f_ij, max_j f_ij]`, a root `s*` puts
//!    `(s*, 0)` in the convex hull of the segments `{i/m} × [L_i, U_i]`, so
//!    `s*` lies between the smallest and largest abscissa where a segment
//!    joining two of those points of opposite sign crosses zero (or where
//!    `L_i ≤ 0 ≤ U_i`). The crossings are computed in `f64` and widened by
//!    `4·10⁻¹⁵` (their error is below `7·2⁻⁵³`, since every value is in
//!    `[0, 1]` and the quotient `y_i/(y_i − y_j)` of opposite signs never
//!    cancels). The kept span is the intersection over `f` and `g`, with a
//!    quarter of its width added on each side (so that a simple root never
//!    ends within rounding of an edge, where Krawczyk cannot prove it) and
//!    no side narrower than 10⁻³ of the other. With [`RectClip::FatLine`]
//!    the spans come instead from the parallelogram where two rigorous
//!    strips around the equations' least-squares planes meet (linear
//!    clipping on boxes; `fatline.rs`), with [`RectClip::Hybrid`] from the
//!    extremes of the region where a strip around `f` meets a band around a
//!    fitted conic for `g` (hybrid clipping on boxes; `hybrid.rs`);
//! 5. a step that did not halve the box's area **splits** it across its
//!    longer side at `63/128` (off the centre, so that a root at a "round"
//!    parameter such as ½ is rarely on a split line).
//!
//! # Exact sub-boxes
//! A clip to `[α, β]` is done as two de Casteljau splits at *floats*: keep
//! `[α, 1]`, then its first `γ ≥ (β − α)/(1 − α)` (rounded up). So each box is
//! an exact real sub-box of its parent — its coefficients are enclosures for
//! exactly it — while its endpoints in the domain are known as intervals
//! (`a + (b − a)·α` is not a float). Reported boxes use the outer endpoints.
//!
//! # Restarts (exact input)
//! Every box's coefficients descend from the domain's and carry their
//! rounding, a few ulps of the domain's largest coefficient. Where the
//! system is far smaller than that (between the middle roots of a product
//! of 30 lines, near a point where one equation vanishes to order 20) the
//! rounding swamps the box: its widths exceed `10⁻⁶` of its magnitudes, and
//! every clip stalls. Such a stalled box is recomputed from the exact input
//! on a box holding it (`restart.rs`): in double-double, or in fixed point
//! on big integers of growing precision, until its widths are within
//! `10⁻¹²` of its magnitudes; again only once a quarter as wide. A swamped
//! box that clipped below `eps` is restarted before its leaf test. A clean
//! stalled box (two close roots, not rounding) is tried by exact Krawczyk
//! with the `f64` Jacobian only below `10⁻⁴`; a swamped one below `10⁻²`,
//! with exact Jacobian enclosures only if no restart cleared it.
//!
//! # Leaves
//! A box narrower than `eps` that Krawczyk could not settle in its interior
//! (a root on a split line or on the domain's boundary, or a multiple root)
//! is tried by Krawczyk with ε-inflation on the whole system in domain
//! coordinates: a unique root outside the box excludes it; a unique root
//! touching it is a candidate (two candidates that overlap are merged when
//! Krawczyk proves one root in their hull); otherwise the leaf is undecided.
//!
//! Interval arithmetic: the hot loops use `Iv` (nearest rounding moved one
//! float outward), certification of leaves uses inari.
//!
//! # Layout
//! `runner.rs` holds the entry points and the loop over boxes (and, in
//! `runner/stalled.rs`, its steps that use the exact input); `options.rs`
//! the options and results; `restart.rs` the exact input in higher
//! precisions;
//! `net.rs` a box and its coefficients; `proof.rs` step 3 (the operator
//! itself is `krawczyk::local`) and the lost-sign test; `spans.rs` step 4
//! with Bézier hulls and the clips and splits of step 5; `fatline.rs` and
//! `hybrid.rs` the other clipping methods of step 4.

mod fatline;
mod hybrid;
mod net;
mod options;
mod proof;
mod restart;
mod runner;
mod spans;

pub(crate) use net::eval_box;
#[cfg_attr(not(feature = "internals"), allow(unused_imports))] // Objective, RectSolution: for tests.
pub use options::{Objective, Query, RectClip, RectOptions, RectSolution};
pub use runner::solve_rect;
pub(crate) use runner::{solve_rect_exact, solve_rect_iv, RectProblem, Squares};
