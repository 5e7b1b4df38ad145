//! Refereeing a method's hits by rootclip's certified ones, and the table's
//! statistics.

use crate::peers::Certified;

/// A method's tally over the rays.
#[derive(Default)]
pub struct Tally {
    /// Time per ray, µs (each the minimum of its repetitions).
    pub micros: Vec<f64>,
    /// Hits reported in `[0, 3]`.
    pub hits: usize,
    /// Certified hits with no hit of the method within the tolerance.
    pub missed: usize,
    /// Hits of the method within the tolerance of no hit rootclip found
    /// (certified or not).
    pub invented: usize,
    /// Hits beyond the first matching the same certified hit.
    pub duplicates: usize,
    /// `missed` at the loose tolerance.
    pub missed_loose: usize,
    /// `invented` at the loose tolerance.
    pub invented_loose: usize,
    /// Rays the method flags as doubtful (brepkit's `grazed`; rootclip's
    /// undecided hits or degenerate rays).
    pub flagged: usize,
    /// Of `missed`, those on flagged rays.
    pub missed_flagged: usize,
}

/// Whether `t` lies within `tol` (relative to `max(1, |t|)`) of the box.
fn near(t: f64, bx: [f64; 2], tol: f64) -> bool {
    let slack = tol * t.abs().max(1.0);
    bx[0] - slack <= t && t <= bx[1] + slack
}

impl Tally {
    /// Adds one ray: the method's hits `ts` (and whether it flagged the
    /// ray) against rootclip's answer, at the tolerances `tol` and `loose`.
    pub fn add(&mut self, micros: f64, (ts, flagged): (&[f64], bool), answer: &Certified, tol: f64, loose: f64) {
        self.micros.push(micros);
        self.hits += ts.len();
        let (missed, invented, duplicates) = referee(ts, answer, tol);
        self.missed += missed;
        if flagged {
            self.flagged += 1;
            self.missed_flagged += missed;
        }
        self.invented += invented;
        self.duplicates += duplicates;
        let (missed, invented, _) = referee(ts, answer, loose);
        self.missed_loose += missed;
        self.invented_loose += invented;
    }

    /// Mean, median, p99 and max of the time per ray, µs.
    pub fn distribution(&self) -> [f64; 4] {
        let mut s = self.micros.clone();
        s.sort_by(f64::total_cmp);
        let n = s.len().max(1);
        let q = |p: f64| {
            s.get(((p * (n - 1) as f64).round() as usize).min(n - 1))
                .copied()
                .unwrap_or(f64::NAN)
        };
        [s.iter().sum::<f64>() / n as f64, q(0.5), q(0.99), q(1.0)]
    }
}

/// `(missed, invented, duplicates)` of the hits `ts` on one ray. Each hit
/// takes the nearest certified hit within the tolerance that no earlier hit
/// took (two true hits closer than the tolerance stay two), else counts as
/// a duplicate of the nearest taken one. A hit near only an uncertified
/// rootclip hit is neither invented nor a match (rootclip cannot referee
/// it; the header counts those).
fn referee(ts: &[f64], answer: &Certified, tol: f64) -> (usize, usize, usize) {
    let gap = |t: f64, bx: [f64; 2]| (bx[0] - t).max(t - bx[1]).max(0.0);
    let mut taken = vec![false; answer.certified.len()];
    let (mut invented, mut duplicates) = (0, 0);
    for &t in ts {
        let nearest = |free: bool| {
            (0..taken.len())
                .filter(|&k| taken[k] != free && near(t, answer.certified[k], tol))
                .min_by(|&a, &b| gap(t, answer.certified[a]).total_cmp(&gap(t, answer.certified[b])))
        };
        if let Some(k) = nearest(true) {
            taken[k] = true;
        } else if nearest(false).is_some() {
            duplicates += 1;
        } else if !answer.uncertified.iter().any(|&bx| near(t, bx, tol)) {
            invented += 1;
        }
    }
    let missed = taken.iter().filter(|&&m| !m).count();
    (missed, invented, duplicates)
}
