//! The solver's regions as hits: certified roots and undecided clusters,
//! their `t` range checked and settled, and the query's selection.

use super::hit::{Degeneracy, Hit, HitBox, HitStatus, RayHits, RayOutcome};
use super::patch::BezierRef;
use super::query::{Query, Ray, MAX_CLUSTERS};
use super::settle;
use crate::solve::settle::Settled;
use crate::solve::{Box2, UndecidedReason};

/// The outcome of a solve's hits: unresolved if the solve was incomplete or
/// ended in too many undecided regions, else the hits the query asks for.
pub(super) fn finish(hits: &mut Vec<Hit>, complete: bool, clusters: usize, query: Query) -> RayOutcome {
    let hits_taken = std::mem::take(hits);
    if !complete || clusters > MAX_CLUSTERS {
        return RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits {
            complete,
            hits: hits_taken,
        }));
    }
    let mut hits = hits_taken;
    select(&mut hits, query);
    RayOutcome::Hits(RayHits { complete: true, hits })
}

/// Keeps the hits a query asks for (the list is sorted by `t`).
pub(super) fn select(hits: &mut Vec<Hit>, query: Query) {
    match query {
        Query::All => {}
        Query::Nearest => {
            let all = RayHits {
                complete: true,
                hits: std::mem::take(hits),
            };
            *hits = all.nearest().into_iter().cloned().collect();
        }
        Query::Any => {
            if let Some(h) = hits.iter().find(|h| h.is_certified()) {
                *hits = vec![h.clone()];
            }
        }
    }
}

/// Sorts hits by `t` (midpoint), then `u`, `v`.
pub(super) fn sort_by_t(hits: &mut [Hit]) {
    hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.u.total_cmp(&b.u)).then(a.v.total_cmp(&b.v)));
}

/// The hit of a solver region — a certified root (`cluster = None`) or an
/// undecided cluster — with its `t` enclosure; `None` if `t` is provably
/// outside `range`. A root is certified only if it is also proven to lie in
/// the patch's closed domain (else [`UndecidedReason::Boundary`]) and its `t`
/// in the range (else [`UndecidedReason::RangeEnd`]): by the boxes, or, where
/// rounding leaves either in doubt, in exact arithmetic (`settle.rs`), which
/// may also prove a miss (`None`).
pub(super) fn region_hit(
    b: BezierRef,
    ray: &Ray,
    bx: Box2,
    cluster: Option<UndecidedReason>,
    t: [f64; 2],
    range: [f64; 2],
) -> Option<Hit> {
    let [lo, hi] = range;
    if t[1] < lo || t[0] > hi {
        return None;
    }
    let mut inside = b.domain_contains(bx);
    let finite = t[0].is_finite() && t[1].is_finite();
    let (mut above, mut below) = (t[0] >= lo && finite, t[1] <= hi && finite);
    let mut t = t;
    if cluster.is_none() && !(inside && above && below) {
        match settle::settle(b, ray, bx, range, !below) {
            Settled::Inside => {
                (inside, above, below) = (true, true, true);
                t = [t[0].max(lo), t[1].min(hi)];
            }
            Settled::Outside => return None,
            Settled::Undecided => {}
        }
    }
    let status = match cluster {
        Some(reason) => HitStatus::Undecided(reason),
        None if !inside => HitStatus::Undecided(UndecidedReason::Boundary),
        None if !(above && below) => HitStatus::Undecided(UndecidedReason::RangeEnd),
        None => HitStatus::Certified,
    };
    let (u, v) = (0.5 * (bx.u[0] + bx.u[1]), 0.5 * (bx.v[0] + bx.v[1]));
    let (point, normal) = b.point_and_normal(u, v);
    Some(Hit {
        t: 0.5 * (t[0] + t[1]),
        u,
        v,
        point,
        normal,
        status,
        bx: HitBox { u: bx.u, v: bx.v, t },
    })
}
