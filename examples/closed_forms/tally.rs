//! Judging a closed form's answer against the referee, query by query.

use super::oracle::Referee;

/// A closed-form hit lies "at" a certified hit when it is within this
/// distance of the certified interval in every parameter (`t`, and `u` in
/// 3D). Near a tangency the formula's `t` is off by about `√ε_mach ≈ 1e-8`
/// even when it finds the hit; a distinct certified hit is never this
/// close to another in the families measured except at tangencies, which
/// the greedy one-to-one matching handles.
pub const TOL: f64 = 1e-6;

/// One hit as a closed form reports it.
#[derive(Clone, Copy, Debug)]
pub struct Claim {
    pub t: f64,
    pub u: Option<f64>,
}

/// Counts over a family.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub queries: usize,
    /// Certified hits (`s ≥ 0`, on the curve or patch).
    pub oracle_hits: usize,
    /// Undecided regions of the referee (tangencies, mostly).
    pub oracle_open: usize,
    /// Queries the referee calls degenerate (a curve of hits).
    pub oracle_degenerate: usize,
    /// Queries where a budget stopped the referee (its unexplored regions
    /// are among the undecided ones).
    pub oracle_incomplete: usize,
    /// Hits the closed form returned.
    pub cf_hits: usize,
    /// Certified hits with no closed-form hit within [`TOL`].
    pub lost: usize,
    /// Closed-form hits within [`TOL`] of no certified hit and of no
    /// undecided region: the referee proves there is no hit there.
    pub invented: usize,
    /// Certified hits the closed form reports more than [`TOL`] away (a
    /// lost hit and an invented one in the same query, paired).
    pub misplaced: usize,
    /// Closed-form hits within [`TOL`] of an undecided region only.
    pub in_open: usize,
    /// Undecided regions with no closed-form hit within [`TOL`] (at an
    /// exact tangency: the formula reports no hit at all).
    pub open_unclaimed: usize,
    /// 3D: queries the exact reduction to 2D decided (the tensor-patch
    /// referee left them undecided).
    pub oracle_reduced: usize,
    /// Queries where the formula failed (divided by zero, overflowed).
    pub failed: usize,
    /// Certified hits of those queries.
    pub failed_hits: usize,
    /// Queries with at least one loss or invention.
    pub wrong_queries: usize,
    /// The largest distance of a matched closed-form hit from its certified
    /// interval.
    pub worst: f64,
    /// The largest distance of a misplaced hit (an unmatched closed-form
    /// hit) from the nearest unmatched certified hit of its query.
    pub worst_misplaced: f64,
}

fn gap(x: f64, iv: [f64; 2]) -> f64 {
    (iv[0] - x).max(x - iv[1]).max(0.0)
}

fn distance(c: &Claim, t: [f64; 2], u: Option<[f64; 2]>) -> f64 {
    let dt = gap(c.t, t);
    match (c.u, u) {
        (Some(cu), Some(iu)) => dt.max(gap(cu, iu)),
        _ => dt,
    }
}

impl Tally {
    /// Adds one query: the closed form's hits (`None` if it failed) against
    /// the referee.
    pub fn add(&mut self, claims: Option<&[Claim]>, referee: &Referee) {
        self.queries += 1;
        if referee.degenerate {
            self.oracle_degenerate += 1;
            self.cf_hits += claims.map_or(0, <[Claim]>::len);
            return;
        }
        self.oracle_hits += referee.hits.len();
        self.oracle_reduced += usize::from(referee.reduced);
        self.oracle_incomplete += usize::from(!referee.complete);
        self.oracle_open += referee.open.len();
        let Some(claims) = claims else {
            self.failed += 1;
            self.failed_hits += referee.hits.len();
            self.open_unclaimed += referee.open.len();
            return;
        };
        self.open_unclaimed += referee
            .open
            .iter()
            .filter(|o| !claims.iter().any(|c| distance(c, o.t, o.u) <= TOL))
            .count();
        self.cf_hits += claims.len();
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for (i, c) in claims.iter().enumerate() {
            for (j, h) in referee.hits.iter().enumerate() {
                let dist = distance(c, h.t, h.u);
                if dist <= TOL {
                    pairs.push((dist, i, j));
                }
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (mut claim_used, mut hit_used) = (vec![false; claims.len()], vec![false; referee.hits.len()]);
        for (dist, i, j) in pairs {
            if !claim_used[i] && !hit_used[j] {
                claim_used[i] = true;
                hit_used[j] = true;
                self.worst = self.worst.max(dist);
            }
        }
        let lost = hit_used.iter().filter(|u| !**u).count();
        let mut invented = 0;
        for (c, used) in claims.iter().zip(&claim_used) {
            if *used {
                continue;
            }
            if referee.open.iter().any(|o| distance(c, o.t, o.u) <= TOL) {
                self.in_open += 1;
            } else {
                invented += 1;
                let nearest = referee
                    .hits
                    .iter()
                    .zip(&hit_used)
                    .filter(|(_, used)| !**used)
                    .map(|(h, _)| distance(c, h.t, h.u))
                    .fold(f64::INFINITY, f64::min);
                if nearest.is_finite() {
                    self.worst_misplaced = self.worst_misplaced.max(nearest);
                }
            }
        }
        let misplaced = lost.min(invented);
        self.misplaced += misplaced;
        self.lost += lost - misplaced;
        self.invented += invented - misplaced;
        if lost + invented > 0 {
            self.wrong_queries += 1;
        }
    }
}
