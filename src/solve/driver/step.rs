//! One step of Algorithm 1 ([`step`]) as a sequence of named phases.

use super::estimates::{newton_kappa, separating_combination, uniform_sign, Combination};
use super::precision::{at_working_precision, finer, restart_pair, restrict_pair, EXACT_BELOW};
use super::state::{
    at_level, push_node, singular_floor, Ctx, Leaf, Precision, Probe, Run, SplitRule, EARLY_CERTIFY, FUTILE_PROBES,
    KAPPA_PROBE, SINGULAR_FLOOR,
};
use crate::poly::TriBall;
use crate::scalar::geo::Geo;
use crate::solve::fatcurve::ClipBounds;
use crate::solve::method::{clip_bounds, clip_bounds_swapped, Method};
use crate::solve::tribox::TriBox;

/// One step of Algorithm 1 on `item` (see the module docs), phase by phase:
/// the pair at the working precision, the separating-combination test, the
/// clip, check-sign on the kept tri-box, a more precise restart where it
/// stalled at the rounding floor, the probe, and the decision — a leaf, clip
/// again, or split 1-to-4. Every exclusion is counted where it happens.
pub(super) fn step<G: Geo>(cx: &mut Ctx, item: Leaf, stack: &mut Vec<Leaf>, probe: &mut dyn FnMut(&TriBox) -> Probe) {
    let level = cx.out.nodes[item.node].level + 1;
    let diam = item.tb.diam();
    let item = at_working_precision::<G>(cx, item, diam);
    if combination_excludes(cx, &item) {
        return;
    }
    let Some(mins) = clip_mins::<G>(cx, &item) else {
        return;
    };
    let leaf = clip_to::<G>(cx, item, mins, diam);
    if sign_excludes(cx, &leaf.fa, &leaf.fb) {
        return;
    }
    let new_diam = leaf.tb.diam();
    let kept = Clipped {
        progressed: cx.limits.split.progressed(mins, diam, new_diam),
        leaf,
        level,
        diam: new_diam,
    };
    if let Some(next) = stalled_finer::<G>(cx, &kept) {
        return restart_finer(cx, kept, next, stack);
    }
    let (probed, verdict) = probe_clipped(cx, &kept, probe);
    match decide::<G>(cx, &kept, probed, verdict) {
        Decision::Excluded => {}
        Decision::Leaf => {
            let leaf = kept.into_child(&mut cx.out);
            cx.out.leaves.push(leaf);
        }
        Decision::Continue => stack.push(kept.into_child(&mut cx.out)),
        Decision::Split => split_and_push(cx, kept, stack),
    }
}

/// A tri-box after the clip of a [`step`] and its check-sign: what the later
/// phases read.
struct Clipped {
    /// The kept tri-box and its pair; `node` is still the parent's.
    leaf: Leaf,
    /// The level of the tri-boxes this step produces.
    level: usize,
    /// The kept tri-box's diameter.
    diam: f64,
    /// Whether the clip made enough progress to skip the split
    /// ([`SplitRule::progressed`]).
    progressed: bool,
}

impl Clipped {
    /// The kept tri-box recorded in the trace as a child at its level.
    fn into_child(self, out: &mut Run) -> Leaf {
        at_level(out, self.leaf, self.level, self.diam)
    }
}

/// What a [`step`] does with a clipped tri-box after its probe.
enum Decision {
    /// Proven free of roots (already counted): dropped.
    Excluded,
    /// Refined no further: certified unique by the probe, its separating sign
    /// lost to rounding, or stalled below the singular floor.
    Leaf,
    /// The clip progressed: clip it again.
    Continue,
    /// Stalled: split it 1-to-4.
    Split,
}

impl SplitRule {
    /// Whether a clip from diameter `diam` to `new_diam` with bounds `mins`
    /// made progress: no split then (Algorithm 1, line 7).
    fn progressed(self, mins: [f64; 3], diam: f64, new_diam: f64) -> bool {
        match self {
            SplitRule::Halving => new_diam <= 0.5 * diam,
            SplitRule::PaperLiteral => mins.iter().sum::<f64>() > 0.5 * diam && new_diam < diam,
        }
    }
}

/// Whether the separating combination of `item`'s pair is one-signed
/// (counted as a sign exclusion).
///
/// Every root is a root of any combination w_f f + w_g g: one that is
/// one-signed on the tri-box excludes it for the price of two jets and a
/// combination, before the (far costlier) clip. The combination closest to
/// vanishing at the centre varies least over the tri-box, so it is the
/// likeliest to keep one sign where the curves pass without meeting.
fn combination_excludes(cx: &mut Ctx, item: &Leaf) -> bool {
    let excluded = separating_combination(&item.fa, &item.fb) == Combination::NoRoot;
    if excluded {
        cx.out.counters.sign_exclusions += 1;
    }
    excluded
}

/// Check-sign: whether `fa` or `fb` has one strict sign on its tri-box
/// (counted as a sign exclusion).
fn sign_excludes(cx: &mut Ctx, fa: &TriBall, fb: &TriBall) -> bool {
    let excluded = uniform_sign(fa).is_some() || uniform_sign(fb).is_some();
    if excluded {
        cx.out.counters.sign_exclusions += 1;
    }
    excluded
}

/// The clip bounds of `item` by the run's method (with the roles swapped as
/// well where [`Limits::swap_roles`](super::Limits::swap_roles) asks),
/// `None` when they prove it empty (counted as a clip exclusion).
fn clip_mins<G: Geo>(cx: &mut Ctx, item: &Leaf) -> Option<[f64; 3]> {
    let limits = cx.limits;
    let incenter = item.tb.incenter_bary();
    let bounds = if limits.swap_roles && matches!(limits.method, Method::Hc | Method::HcNoPre) {
        // Where the clip keeps more than half, the clip with f and g swapped
        // as well (its fat line is g's), intersected.
        let (bounds, swapped) = clip_bounds_swapped::<G>(limits.method, &item.fa, &item.fb, incenter);
        cx.out.counters.role_swaps += usize::from(swapped);
        bounds
    } else {
        clip_bounds::<G>(limits.method, &item.fa, &item.fb, incenter)
    };
    match bounds {
        ClipBounds::Empty => {
            cx.out.counters.clip_exclusions += 1;
            None
        }
        ClipBounds::Keep(m) => Some(m),
    }
}

/// `item` clipped to `mins` (verified in a rigorous kernel) and its pair
/// restricted to the kept tri-box, where that is smaller than `diam`
/// (counted); else `item` itself.
fn clip_to<G: Geo>(cx: &mut Ctx, item: Leaf, mins: [f64; 3], diam: f64) -> Leaf {
    let clipped = if mins.iter().sum::<f64>() > 0.0 {
        if G::RIGOROUS {
            item.tb.clip(mins)
        } else {
            item.tb.clip_unverified(mins)
        }
    } else {
        None
    };
    match clipped {
        Some(tb) if tb.diam() < diam => {
            cx.out.counters.clips += 1;
            let (fa, fb, precision) = restrict_pair(cx, item.precision, &tb);
            Leaf {
                tb,
                fa,
                fb,
                precision,
                ..item
            }
        }
        _ => item,
    }
}

/// The finer precision a rigorous run recomputes a stalled tri-box in, when
/// it is below [`EXACT_BELOW`] (the rounding floor) and there is one.
fn stalled_finer<G: Geo>(cx: &Ctx, kept: &Clipped) -> Option<Precision> {
    if G::RIGOROUS && !kept.progressed && kept.diam < EXACT_BELOW {
        finer(cx, kept.leaf.precision, kept.diam)
    } else {
        None
    }
}

/// Stalled at the rounding floor: the kept tri-box at precision `next`,
/// pushed as a child to redo.
fn restart_finer(cx: &mut Ctx, kept: Clipped, next: Precision, stack: &mut Vec<Leaf>) {
    let (fa, fb, precision) = restart_pair(cx, next, &kept.leaf.tb);
    let node = push_node(&mut cx.out, kept.leaf.node, kept.level, kept.diam);
    stack.push(Leaf {
        node,
        fa,
        fb,
        precision,
        ..kept.leaf
    });
}

/// Whether the kept tri-box is to be probed, and the probe's verdict
/// (`Undecided` when not probed, or throttled).
///
/// Probes: a converging clip below EARLY_CERTIFY, or below ½ where
/// newton_kappa predicts contraction, may already be certified
/// (Krawczyk's contraction then converges quadratically without further
/// clips); a stalled one below `probe_below` may be certified or excluded,
/// and below SINGULAR_FLOOR it is not split further.
fn probe_clipped(cx: &mut Ctx, kept: &Clipped, probe: &mut dyn FnMut(&TriBox) -> Probe) -> (bool, Probe) {
    let (new_diam, next) = (kept.diam, &kept.leaf);
    let probe_here = cx.limits.probe_below > 0.0
        && if kept.progressed {
            new_diam < EARLY_CERTIFY || (new_diam < 0.5 && newton_kappa(&next.fa, &next.fb) < KAPPA_PROBE)
        } else {
            new_diam < cx.limits.probe_below
        };
    // After a long run of futile probes (all undecided: curves running
    // within a hair of each other over a long stretch, where every tri-box
    // stalls), probe only every 16th tri-box; a probe only saves work.
    let throttled = cx.out.futile_probes >= FUTILE_PROBES && cx.out.counters.boxes % 16 != 0;
    let verdict = if probe_here && !throttled {
        cx.out.counters.probes += 1;
        let v = probe(&next.tb);
        cx.out.futile_probes = if v == Probe::Undecided(()) {
            cx.out.futile_probes + 1
        } else {
            0
        };
        v
    } else {
        Probe::Undecided(())
    };
    (probe_here, verdict)
}

/// What becomes of the kept tri-box after its probe (`probed`: it was to be
/// probed; exclusions counted): a stalled, probed, undecided tri-box of a
/// rigorous run gets the separating-combination test on its new pair, and
/// stops at the singular floor ([`singular_floor`]).
fn decide<G: Geo>(cx: &mut Ctx, kept: &Clipped, probed: bool, verdict: Probe) -> Decision {
    let (new_diam, progressed) = (kept.diam, kept.progressed);
    let stop_here = match verdict {
        Probe::NoRoot => {
            cx.out.counters.probe_exclusions += 1;
            return Decision::Excluded;
        }
        Probe::Unique(()) => true,
        Probe::Undecided(()) if !progressed && probed && G::RIGOROUS => {
            match separating_combination(&kept.leaf.fa, &kept.leaf.fb) {
                Combination::NoRoot => {
                    cx.out.counters.sign_exclusions += 1;
                    return Decision::Excluded;
                }
                Combination::Lost => true,
                Combination::Open => {
                    if new_diam < SINGULAR_FLOOR {
                        cx.out.fine_boxes += 1;
                    }
                    new_diam < singular_floor(cx, kept.leaf.precision)
                }
            }
        }
        Probe::Undecided(()) => false,
    };
    if stop_here {
        Decision::Leaf
    } else if progressed {
        Decision::Continue
    } else {
        Decision::Split
    }
}

/// The kept tri-box split 1-to-4, each child's pair restricted at the kept
/// tri-box's precision and pushed unless check-sign excludes it; a tri-box
/// too small to split is a leaf.
fn split_and_push(cx: &mut Ctx, kept: Clipped, stack: &mut Vec<Leaf>) {
    let Some(kids) = kept.leaf.tb.split4() else {
        // Collapsed at the rounding floor: hand it to the certification phase.
        let leaf = kept.into_child(&mut cx.out);
        return cx.out.leaves.push(leaf);
    };
    cx.out.counters.splits += 1;
    let (precision, parent) = (kept.leaf.precision, kept.leaf.node);
    // Push in reverse so the corner at V1 is processed first.
    for kid in kids.into_iter().rev() {
        let (ka, kb, precision) = restrict_pair(cx, precision, &kid);
        if sign_excludes(cx, &ka, &kb) {
            continue;
        }
        let node = push_node(&mut cx.out, parent, kept.level, kid.diam());
        stack.push(Leaf {
            tb: kid,
            node,
            fa: ka,
            fb: kb,
            precision,
        });
    }
}
