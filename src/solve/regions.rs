//! Regions of the plane that the solvers' boxes stand for: touching boxes
//! grouped into one region, undecided regions that lie near each other
//! joined, and certified boxes that may hold one root merged (by a Krawczyk
//! proof on their hull).

use crate::solve::krawczyk::{Bivariate, IBox, System, Verdict};
use crate::solve::solution::{Box2, Cluster, Solution, Stats, UndecidedReason};
use inari::Interval;

/// A box the iteration stopped at (or a region joined from such boxes), with
/// the diameters along the path that reached it.
#[derive(Clone)]
pub(crate) struct Found {
    pub(crate) bx: IBox,
    pub(crate) diameters: Vec<f64>,
}

/// The closed boxes share a point.
pub(crate) fn overlaps(a: IBox, b: IBox) -> bool {
    !a[0].disjoint(b[0]) && !a[1].disjoint(b[1])
}

fn hull(a: IBox, b: IBox) -> IBox {
    [a[0].convex_hull(b[0]), a[1].convex_hull(b[1])]
}

/// Certified boxes that overlap may hold the same root (a root on a shared
/// tri-box edge). If Krawczyk proves a unique root in their hull, they are one
/// root; otherwise (rare) both stay, since each holds exactly one root but
/// they might be different.
pub(crate) fn merge_roots<P: Bivariate>(
    mut found: Vec<Found>,
    global: &System<P>,
    stats: &mut Stats,
) -> (Vec<Found>, Vec<Found>) {
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

/// Groups of boxes connected by overlap (closed boxes; touching counts), by
/// union–find over the pairs that [`touching_pairs`] finds.
pub(crate) fn group_overlapping(items: Vec<Found>) -> Vec<Vec<Found>> {
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
pub(crate) fn undecided_clusters(leaves: Vec<Found>) -> Vec<Cluster> {
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
/// the exact retry ([`finish_exact`](super::finish_exact)) settles each region on its own, where
/// the hull of two regions 1e-7 apart (two close roots) would hold both.
pub(crate) fn touching_regions(leaves: Vec<Found>) -> Vec<Cluster> {
    group_overlapping(leaves)
        .into_iter()
        .map(hull_of)
        .map(undecided)
        .collect()
}

/// [`undecided_clusters`]' joining of near regions, for a solution from
/// [`touching_regions`]: undecided clusters whose joint hull is at most
/// [`NEAR`] wide, or that nearly touch ([`nearly_touch`]), become one.
pub(crate) fn join_undecided(mut sol: Solution) -> Solution {
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

pub(crate) fn hull_of(group: Vec<Found>) -> Found {
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
