//! Exact input (rational coefficients, from [`solve`](super::solve) or
//! [`solve_bb`](super::solve_bb)): the routes of each domain
//! ([`TriangleRoute`], [`SquareRoute`]) and the exact finish every route
//! shares — small undecided regions retried by exact Krawczyk, roots on the
//! boundary settled.

use super::krawczyk::{System, Verdict};
use super::regions::join_undecided;
use super::solution::{Box2, Cluster, Root, Solution, Stats, UndecidedReason};
use super::{
    check_system, locate, rect, rect_options, scaler, settle, solve_pieces, square_pieces, Domain, Frame, Piece, Place,
    SolveOptions, SquareRoute, TriangleRoute,
};
use crate::error::Result;
use crate::poly::{Polynomial, TensorBezier, TriBezier};
use crate::scalar::Scalar;
use inari::Interval;
use num_rational::BigRational;

/// The exact system on the unit triangle (equal degrees, coprime, not zero).
pub(super) fn solve_exact_triangle(
    ef: TriBezier<BigRational>,
    eg: TriBezier<BigRational>,
    monomial: [&Polynomial; 2],
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
    if opts.triangle_route == TriangleRoute::Rect {
        if let Some(sol) = triangle_by_boxes(monomial, &sys, opts)? {
            return Ok(sol);
        }
    }
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
        &sys,
        opts.deadline,
    ))
}

/// [`TriangleRoute::Rect`]: the exact triangle system `sys` (of `pf`, `pg`
/// in monomial form) solved on boxes of the unit square, where the same
/// polynomials have an exact tensor form of bidegree (degree in `u`, degree
/// in `v`); the boxes
/// beyond the hypotenuse are dropped by the box solver, and the roots whose
/// boxes reach an edge of the triangle are settled exactly against `sys`.
/// `None` when the box solver's budget ran out (the caller falls back to
/// tri-boxes).
fn triangle_by_boxes(
    [pf, pg]: [&Polynomial; 2],
    sys: &settle::ExactSystem,
    opts: &SolveOptions,
) -> Result<Option<Solution>> {
    if [pf, pg].iter().any(|p| p.check_conversion_cost(true).is_err()) {
        // The tensor form would cost more than the tri-boxes' own.
        return Ok(None);
    }
    let ((m, n), (p, q)) = (pf.degrees(), pg.degrees());
    let (dm, dn) = ((m.max(p) as usize).max(1), (n.max(q) as usize).max(1));
    let (tf, tg, boxes) = scaled_tensor_system(pf.to_square().elevate(dm, dn)?, pg.to_square().elevate(dm, dn)?)?;
    let enclose = |q: &BigRational| Interval::from_rational(q);
    let sol = rect::solve_rect_exact(
        &tf.map(enclose),
        &tg.map(enclose),
        std::sync::Arc::new(boxes.clone()),
        true,
        &rect_options(opts),
    )?
    .solution;
    let late = || opts.deadline.is_some_and(|d| std::time::Instant::now() >= d);
    if !sol.complete && !late() {
        return Ok(None);
    }
    let sol = finish_exact(sol, &boxes, sys, opts.deadline);
    let stuck = separable_clusters(&sol, &boxes);
    if stuck && dm + dn <= TRIANGLES_RETRY_DEGREE && !late() {
        // As on the square: two simple roots closer than rounding
        // separates on boxes may separate on tri-boxes with exact restarts.
        return Ok(None);
    }
    Ok(Some(sol))
}

/// The exact system on the unit square (equal bidegrees, coprime, not zero).
pub(super) fn solve_exact_square(
    ef: TensorBezier<BigRational>,
    eg: TensorBezier<BigRational>,
    opts: &SolveOptions,
) -> Result<Solution> {
    let enclose = |q: &BigRational| Interval::from_rational(q);
    let (dm, dn) = ef.degree();
    let (ef, eg, sys) = scaled_tensor_system(ef, eg)?;
    if opts.square_route != SquareRoute::Triangles {
        let ropts = rect_options(opts);
        let sol = rect::solve_rect_exact(
            &ef.map(enclose),
            &eg.map(enclose),
            std::sync::Arc::new(sys.clone()),
            false,
            &ropts,
        )?
        .solution;
        let late = || opts.deadline.is_some_and(|d| std::time::Instant::now() >= d);
        if !sol.complete && !late() {
            // Out of budget (e.g. two curves running nearly parallel
            // along a diagonal, which axis-aligned boxes separate only
            // when they are as thin as the gap): the triangle route's fat
            // curves and exact restarts handle those.
            return solve_exact_square_triangles(&ef, &eg, &sys, opts);
        }
        let sol = finish_exact(sol, &sys, &sys, opts.deadline);
        let stuck = separable_clusters(&sol, &sys);
        if stuck && dm + dn <= TRIANGLES_RETRY_DEGREE && !late() {
            // Two simple roots closer than rounding separates on boxes (a
            // line nearly tangent to a conic): the triangles' exact
            // restarts may separate them. Both answers are certified; the
            // one with fewer undecided regions is kept.
            let tri = solve_exact_square_triangles(&ef, &eg, &sys, opts)?;
            if tri.complete && tri.clusters.len() < sol.clusters.len() {
                return Ok(tri);
            }
        }
        return Ok(sol);
    }
    solve_exact_square_triangles(&ef, &eg, &sys, opts)
}

/// `f`, `g` (one bidegree) each scaled by a power of two ([`scaler`]), and
/// their exact system.
fn scaled_tensor_system(
    ef: TensorBezier<BigRational>,
    eg: TensorBezier<BigRational>,
) -> Result<(
    TensorBezier<BigRational>,
    TensorBezier<BigRational>,
    settle::ExactSystem,
)> {
    let (m, n) = ef.degree();
    let (ef, eg) = (ef.map_coeffs(scaler(ef.coeffs())), eg.map_coeffs(scaler(eg.coeffs())));
    let sys = settle::ExactSystem::new(
        settle::Shape::Tensor(m, n),
        ef.coeffs().to_vec(),
        eg.coeffs().to_vec(),
        None,
    )?;
    Ok((ef, eg, sys))
}

/// Whether some `multiple_or_close` region of `sol` might be close simple
/// roots that the tri-boxes separate: one not known to hold an exact
/// multiple root ([`settle::ExactSystem::holds_exact_multiple_root`]; such a
/// region stays undecided on every route).
fn separable_clusters(sol: &Solution, sys: &settle::ExactSystem) -> bool {
    sol.clusters
        .iter()
        .any(|c| c.reason == UndecidedReason::MultipleOrClose && !sys.holds_exact_multiple_root(c.bx))
}

/// Bidegrees `m + n` up to which a box-route answer with undecided regions
/// is retried on the two triangles (of degree `m + n`).
const TRIANGLES_RETRY_DEGREE: usize = 24;

/// The exact square as two triangles of degree `m + n`.
fn solve_exact_square_triangles(
    ef: &TensorBezier<BigRational>,
    eg: &TensorBezier<BigRational>,
    sys: &settle::ExactSystem,
    opts: &SolveOptions,
) -> Result<Solution> {
    let enclose = |q: &BigRational| Interval::from_rational(q);
    let exact = Some((ef.to_triangles()?, eg.to_triangles()?));
    Ok(finish_exact(
        square_pieces(&ef.map(enclose), &eg.map(enclose), exact, opts)?,
        sys,
        sys,
        opts.deadline,
    ))
}

/// Undecided regions at most this wide are retried by exact Krawczyk.
const EXACT_CERTIFY_BELOW: f64 = 1e-6;
/// At most this many exact Krawczyk tests per region (one that does not
/// settle at once is bisected, at most three times). The total grows with
/// the number of regions, i.e. with the roots, and the solve's deadline
/// ends it (regions not tried stay undecided).
const EXACT_CERTIFY_MAX: usize = 15;

/// Retries small undecided regions with Krawczyk in exact arithmetic
/// ([`settle::ExactSystem::certify`]), bisecting a region that does not
/// settle at once (two roots 1e-9 apart share one): if every piece is
/// proven to hold one simple root or none, the region is replaced by those
/// roots (a root whose box overlaps another root's stays undecided: it could
/// be the same root); otherwise it stays. The regions arrive as the driver
/// left them ([`touching_regions`]), so two close roots in two regions are
/// retried one by one; the regions left are then joined ([`join_undecided`]).
/// Then every certified root on the boundary is settled
/// ([`settle_boundary`]) against `domain`, the same system in the domain's
/// own form (`sys` may be another exact form of it, cheaper for Krawczyk).
fn finish_exact(
    mut sol: Solution,
    sys: &settle::ExactSystem,
    domain: &settle::ExactSystem,
    deadline: Option<std::time::Instant>,
) -> Solution {
    let mut kept = Vec::with_capacity(sol.clusters.len());
    for c in std::mem::take(&mut sol.clusters) {
        if deadline.is_some_and(|d| std::time::Instant::now() >= d) {
            kept.push(c);
            continue;
        }
        let mut budget = EXACT_CERTIFY_MAX;
        let small = c.bx.u[1] - c.bx.u[0] <= EXACT_CERTIFY_BELOW && c.bx.v[1] - c.bx.v[0] <= EXACT_CERTIFY_BELOW;
        // A (nearly) singular Jacobian at the centre: a multiple root, or
        // roots closer than these tests separate; not worth the exact cost.
        if c.reason != UndecidedReason::MultipleOrClose || !small || sys.nearly_singular(c.bx) {
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
            let place = locate(bx.ibox(), domain.domain());
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
    settle_boundary(join_undecided(sol), domain)
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
        Verdict::Unique(k) => {
            found.push(k);
            true
        }
        Verdict::NoRoot => {
            stats.krawczyk_exclusions += 1;
            true
        }
        Verdict::Undecided(()) if depth > 0 => {
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
        Verdict::Undecided(()) => false,
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
