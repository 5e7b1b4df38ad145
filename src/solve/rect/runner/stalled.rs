//! The steps of the box runner that draw on the exact input, for a box the
//! float steps cannot settle: a restart of a box swamped by rounding
//! ([`Restarts`]), exact Krawczyk on a stalled box, and the test of a leaf.

use super::*;

impl Runner {
    /// Whether the input is exact and rounding has [`swamped`] the node's
    /// coefficients (only exact input has anything to restart from).
    pub(super) fn swamped(&self, node: &Node) -> bool {
        self.problem.exact.is_some() && swamped(&node.c, self.shape)
    }

    /// The node restarted ([`Runner::restart`]) if it is `swamped`
    /// ([`Runner::swamped`]) and a quarter as wide as at its last restart; a
    /// failed restart is recorded in the node (`restart_failed`, and its
    /// width as `restart_w`).
    pub(super) fn try_restart(&mut self, node: &mut Node, swamped: bool) -> Option<Node> {
        let w = self.rel_width(node);
        let w = w[0].max(w[1]);
        if !swamped || 4.0 * w > node.restart_w {
            return None;
        }
        let fresh = self.restart(node);
        if fresh.is_none() {
            node.restart_w = w;
            node.restart_failed = true;
        }
        fresh
    }

    /// The node recomputed from the exact input ([`Restarts::restrict`]):
    /// its coefficients on a box holding it (its outer box, up to the
    /// rounding of a clip), each within a few ulps of its own magnitude
    /// where the node's had the rounding of the domain's. `None` without an
    /// exact system, or where no precision tried clears the rounding.
    pub(super) fn restart(&mut self, node: &Node) -> Option<Node> {
        if self.restarts.is_none() {
            let r = self.problem.exact.as_ref().and_then(|sys| {
                let (m, n, [f, g]) = sys.tensor_input()?;
                Some(Restarts::new(m, n, f, g))
            });
            self.restarts = Some(r);
        }
        let (c, bx) = self.restarts.as_mut()?.as_mut()?.restrict(self.shape, node.outer())?;
        let mut fresh = Node {
            c,
            bx,
            id: node.id,
            key: None,
            exact_w: node.exact_w,
            restart_w: 0.0,
            restart_failed: false,
        };
        let w = self.rel_width(&fresh);
        fresh.restart_w = w[0].max(w[1]);
        fresh.id = self.push_trace(node.id, fresh.outer());
        self.stats.exact_restarts += 1;
        Some(fresh)
    }

    /// A stalled box tried by exact Krawczyk (exact input only; `swamped`
    /// as [`Runner::swamped`]):
    /// `Some(Done)` if that settles it — a unique root of a box around it
    /// lies inside the node (recorded) or outside it, or there is none —
    /// and `None` otherwise (also without an exact system).
    ///
    /// Exact Krawczyk proves `K ⊂ int X` on the node's outer box widened by
    /// an eighth ([`ExactSystem::certify`]): that box holds exactly one root,
    /// in `K`. Inside the node's inner box, the root is the node's; disjoint
    /// from its outer box, the node holds none; straddling an edge, it is
    /// left to the usual steps (a neighbour may claim it).
    ///
    /// Only a node that rounding swamps and no restart cleared gets the
    /// exact Jacobian enclosures, which cost milliseconds per box at high
    /// degree; any other node gets the test with the Jacobian in floats
    /// ([`ExactSystem::certify_fast`]): a clean one stalled on several roots
    /// or a multiple one, not on rounding, and a swamped one will be
    /// restarted once a quarter as wide.
    pub(super) fn try_exact(&mut self, node: &Node, swamped: bool) -> Option<Step> {
        let sys = self.problem.exact.clone()?;
        self.stats.krawczyk_calls += 1;
        let o = node.outer();
        let bx = Box2 { u: o[0], v: o[1] };
        let verdict = if node.restart_failed && swamped {
            sys.certify(bx)
        } else {
            sys.certify_fast(bx)
        };
        match verdict {
            Verdict::Unique(k) => {
                let kb = [k.u, k.v];
                let inside = (0..2).all(|a| kb[a][0] > node.bx[a][0].hi && kb[a][1] < node.bx[a][1].lo);
                let outside = (0..2).any(|a| kb[a][1] < o[a][0] || kb[a][0] > o[a][1]);
                if inside {
                    self.add_root(k.ibox(), node.id);
                    Some(Step::Done)
                } else if outside {
                    self.stats.krawczyk_exclusions += 1;
                    Some(Step::Done)
                } else {
                    None
                }
            }
            Verdict::NoRoot => {
                self.stats.krawczyk_exclusions += 1;
                Some(Step::Done)
            }
            Verdict::Undecided(()) => None,
        }
    }

    /// A box below `eps` that local Krawczyk did not settle.
    pub(super) fn leaf(&mut self, node: &Node) {
        self.stats.leaves += 1;
        self.stats.krawczyk_calls += 1;
        let x = node.ibox();
        // Exact input: exact Krawczyk sees through the rounding that left
        // this leaf (the inari test on the same coefficients would not).
        let verdict = match self.problem.exact.clone() {
            Some(sys) => match sys.certify(Box2::of(x)) {
                Verdict::Unique(k) => Verdict::Unique(k.ibox()),
                Verdict::NoRoot => Verdict::NoRoot,
                Verdict::Undecided(()) => Verdict::Undecided(x),
            },
            None => self.system().certify(x),
        };
        match verdict {
            Verdict::Unique(k) => {
                if k[0].disjoint(x[0]) || k[1].disjoint(x[1]) {
                    self.stats.krawczyk_exclusions += 1;
                } else {
                    // The root may lie just outside this box (in a neighbour):
                    // no objective bound from this box's coefficients then.
                    self.add_root(k, node.id);
                }
            }
            Verdict::NoRoot => self.stats.krawczyk_exclusions += 1,
            Verdict::Undecided(_) => self.undecided.push(Found {
                bx: x,
                diameters: self.diameters(node.id),
            }),
        }
    }
}
