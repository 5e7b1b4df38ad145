//! The verdict of a Krawczyk test, shared by every variant.

#[cfg(doc)]
use crate::solve::solution::Box2;
use inari::Interval;

/// A 2-D box `[u, v]`.
pub type IBox = [Interval; 2];

/// What a Krawczyk test proves about a box `X`: the one verdict of every
/// variant of [`crate::solve::krawczyk`] and of the driver's probes.
///
/// `B` is the box a variant speaks in: an [`IBox`] (inari and piecewise),
/// `[Iv; 2]` in a box's local coordinates (the box solver's test), a
/// [`Box2`] (exact). `U` is what an undecided test still knows: `B` where
/// the variant computes `K(X) ∩ X`, `()` where it keeps nothing (the local
/// and exact tests, and the driver's probes, `Verdict<()>`, which keep no
/// box at all: the caller keeps the certificate).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict<B = IBox, U = B> {
    /// Exactly one root in the box, simple, and it lies in the given
    /// sub-box `K(X)`.
    Unique(B),
    /// No root in the box.
    NoRoot,
    /// Neither could be proven; the root set within the box lies in the given
    /// enclosure `K(X) ∩ X`.
    Undecided(U),
}
