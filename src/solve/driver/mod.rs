//! Algorithm 1 of Liu et al. (2016) as a work-list loop over tri-boxes, generic
//! over the kernel: `Interval` for the certified solver, `f64` for the same
//! iteration without proofs (to measure the cost of rigor).
//!
//! One *step* (one call of Algorithm 1) clips a tri-box and, when the clip did
//! not halve its diameter, splits the clipped tri-box 1-to-4. The tri-boxes it
//! produces are one level deeper. Check-sign (§2.3.4) discards a tri-box when
//! every coefficient of `f` or of `g` on it has one strict sign.
//!
//! One step's phases are in `step`; the precision a tri-box's polynomials
//! are computed in (float balls, compensated, exact) is managed in
//! `precision`.

pub(crate) mod edges;
pub(crate) mod estimates;
pub(crate) mod precision;
pub(crate) mod state;
mod step;

pub use edges::VANISHING;
use state::Node;
pub use state::{
    path_diameters, Counters, Exact, ExactPair, Leaf, Limits, Precision, Probe, Run, SplitRule, MAX_EXACT_BOXES,
};

use super::tribox::TriBox;
use crate::poly::TriBall;
use crate::scalar::geo::Geo;
use edges::{cut_vanishing_edges, too_small};
use estimates::uniform_sign;
use state::Ctx;
use step::step;

/// Runs Algorithm 1 on the root triangle, on which `f` and `g` are given
/// (same degree). `probe` is asked about stalled small tri-boxes (see
/// [`Limits::probe_below`]). `G` is the geometry kernel (module docs).
pub fn run<G: Geo>(
    f: &TriBall,
    g: &TriBall,
    exact: Exact,
    limits: &Limits,
    probe: &mut dyn FnMut(&TriBox) -> Probe,
) -> Run {
    let scale_exp = TriBall::normalizing_exponent(&[f, g]);
    let (fs, gs) = (f.scaled_pow2(scale_exp), g.scaled_pow2(scale_exp));
    let exact = match exact {
        _ if !G::RIGOROUS => Exact::None,
        // The balls are the system only while they are points.
        Exact::Floats if fs.rad() > 0.0 || gs.rad() > 0.0 => Exact::None,
        e => e,
    };
    let mut cx = Ctx {
        f: fs,
        g: gs,
        exact,
        exact_floats: None,
        dd: None,
        limits,
        out: Run {
            leaves: Vec::new(),
            leftovers: Vec::new(),
            nodes: Vec::new(),
            counters: Counters::default(),
            futile_probes: 0,
            fine_boxes: 0,
            strips: Vec::new(),
            scale_exp,
        },
    };
    if uniform_sign(&cx.f).is_some() || uniform_sign(&cx.g).is_some() {
        cx.out.counters.sign_exclusions += 1;
        return cx.out;
    }
    let (root, fa, fb) = cut_vanishing_edges(&cx.f, &cx.g, &mut cx.out.strips);
    cx.out.nodes.push(Node {
        parent: None,
        level: 0,
        diam: root.diam(),
    });
    let mut stack = vec![Leaf {
        tb: root,
        node: 0,
        fa,
        fb,
        precision: Precision::Float,
    }];
    while let Some(item) = stack.pop() {
        let node = cx.out.nodes[item.node];
        if item.tb.diam() < limits.eps || too_small(&item.tb) {
            cx.out.leaves.push(item);
            continue;
        }
        if cx.out.counters.boxes >= limits.max_boxes
            || node.level >= limits.max_depth
            || limits.deadline.is_some_and(|d| std::time::Instant::now() >= d)
        {
            cx.out.leftovers.push(item);
            continue;
        }
        cx.out.counters.boxes += 1;
        step::<G>(&mut cx, item, &mut stack, probe);
    }
    cx.out
}

#[cfg(test)]
mod tests {
    use super::estimates::newton_kappa;
    use super::*;
    use crate::scalar::rational_to_f64;

    pub(super) fn ball(expr: &str) -> TriBall {
        let p = crate::parse_polynomial(expr).unwrap().to_triangle(2);
        TriBall::from_points(&p.map(rational_to_f64))
    }

    /// κ on the unit triangle against values worked by hand: 0 for a linear
    /// system (Newton is exact), `max_i Σ_k |(J⁻¹)_ik| ‖h_k‖` for a circle
    /// and a line at the centroid (J = [[2/3, 2/3], [1, −1]], J⁻¹ =
    /// [[3/4, 1/2], [3/4, −1/2]], ‖h_f‖ = 2 + 0 + 2 = 4, h_g = 0: κ = 3), ∞ for
    /// parallel gradients.
    #[test]
    fn newton_kappa_by_hand() {
        assert_eq!(newton_kappa(&ball("u - 1/3"), &ball("v - 1/4")), 0.0);
        let k = newton_kappa(&ball("u^2 + v^2 - 1/4"), &ball("u - v"));
        assert!((k - 3.0).abs() < 1e-12, "{k}");
        assert_eq!(newton_kappa(&ball("u - v"), &ball("2*u - 2*v + 1")), f64::INFINITY);
    }
}
