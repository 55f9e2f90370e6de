//! Rigid elements (RBE2), applied by constraint elimination: a dependent grid's DOFs
//! are not solved; its motion is its independent grid's rigid-body motion,
//! `[u; θ]_m = Λ [u; θ]_n` with `Λ = [Tₘᵀ Tₙ, −Tₘᵀ[d]× Tₙ; 0, Tₘᵀ Tₙ]`
//! ([`crate::elements::Placement::turn_of`]), d = xₘ − xₙ and T each grid's
//! displacement frame. An element or mass on a dependent grid is attached to the
//! independent grid through Λ (its local DOFs there are Λ times the independent
//! grid's), which is Tᵀ K T of the constraint elimination element by element; a load
//! on it goes to the independent grid as Λᵀ f; its displacement is recovered as Λ uₙ.
//! A rigid element stores no energy and has no mass: the ledger needs nothing of it.
//!
//! Chains (GN itself dependent on another RBE2) are followed to the grid that is
//! independent; a cycle, or a grid made dependent twice, is an error naming both
//! cards. Only the whole rigid body is supported (CM = 123456): a dependent grid
//! keeping some components of its own would need its element split between grids.

use crate::deck::cards::{Bulk, CardRef};
use crate::deck::Diagnostic;
use crate::elements::{Element, Placement};
use crate::geometry::Geometry;
use nalgebra::{Matrix6, Vector3};
use std::collections::BTreeMap;

/// A dependent grid's tie to its independent grid.
#[derive(Debug, Clone)]
pub struct Tie {
    /// The independent grid (the end of a chain).
    pub gn: i64,
    /// Λ: the independent grid's T1..R3 (its frame) to the dependent grid's (its frame).
    pub map: Matrix6<f64>,
    /// The RBE2 that makes the grid dependent.
    pub at: CardRef,
}

/// Every dependent grid of the deck's RBE2s, by grid id.
#[derive(Debug, Clone, Default)]
pub struct Rigid {
    /// Dependent grid → its tie.
    pub ties: BTreeMap<i64, Tie>,
}

/// The RBE2s of a deck resolved (see the module's doc); errors for what cannot be.
pub fn resolve(b: &Bulk, geo: &Geometry, errors: &mut Vec<Diagnostic>) -> Rigid {
    let mut first: BTreeMap<i64, &crate::deck::cards::Rbe2> = BTreeMap::new();
    for r in &b.rbe2s {
        if r.cm.0 != 0b111111 {
            errors.push(r.at.error(format!(
                "RBE2 {}: CM = {} makes some components dependent; only the whole rigid body (CM = 123456) is \
                 supported",
                r.eid,
                r.cm.iter().map(|c| c.to_string()).collect::<String>()
            )));
            continue;
        }
        for &g in std::iter::once(&r.gn).chain(&r.gm) {
            if !geo.positions.contains_key(&g) && !b.grids.iter().any(|x| x.id == g) {
                errors.push(r.at.error(format!("RBE2 {} references grid {g}, which does not exist", r.eid)));
            }
        }
        for &g in &r.gm {
            match first.get(&g) {
                Some(other) => errors.push(r.at.error(format!(
                    "RBE2 {} makes grid {g} dependent, which RBE2 {} (at {}) already makes dependent: a DOF can \
                     be dependent once",
                    r.eid, other.eid, other.at.pos
                ))),
                None => {
                    first.insert(g, r);
                }
            }
        }
    }
    let mut rigid = Rigid::default();
    let mut cycles_said = Vec::new();
    for (&gm, &r) in &first {
        // Follow the chain to the independent grid.
        let (mut end, mut seen) = (r.gn, vec![gm]);
        let mut cycle = None;
        while let Some(&next) = first.get(&end) {
            if seen.contains(&end) {
                // The other card of the cycle (the first along the chain that is not r).
                cycle = seen
                    .iter()
                    .filter_map(|g| first.get(g))
                    .find(|c| c.eid != r.eid)
                    .copied()
                    .or(Some(next));
                break;
            }
            seen.push(end);
            end = next.gn;
        }
        if let Some(by) = cycle {
            let mut pair = [r.eid, by.eid];
            pair.sort();
            if !cycles_said.contains(&pair) {
                cycles_said.push(pair);
                errors.push(r.at.error(format!(
                    "RBE2 {} and RBE2 {} (at {}) make a cycle of dependent grids ({}): no grid of it is \
                     independent",
                    r.eid,
                    by.eid,
                    by.at.pos,
                    seen.iter().map(|g| g.to_string()).collect::<Vec<_>>().join(" → ")
                )));
            }
            continue;
        }
        let (Some(xm), Some(xn)) = (geo.positions.get(&gm), geo.positions.get(&end)) else {
            continue;
        };
        let d = Vector3::from(*xm) - Vector3::from(*xn);
        rigid.ties.insert(
            gm,
            Tie {
                gn: end,
                map: Placement::turn_of(&geo.frame(gm), &geo.frame(end), d.into()),
                at: r.at.clone(),
            },
        );
    }
    rigid
}

impl Rigid {
    /// The element attached through its dependent grids' ties (unchanged without any):
    /// each dependent grid replaced by its independent grid, its turn composed with Λ.
    /// `dofs_of` gives a grid's solved DOFs.
    pub fn attach(&self, mut e: Element, dofs_of: impl Fn(i64) -> [Option<usize>; 6]) -> Element {
        if !e.grids.iter().any(|g| self.ties.contains_key(g)) {
            return e;
        }
        let n = e.grids.len();
        let mut p = match e.placement.take() {
            Some(p) => (*p).clone(),
            None => Placement {
                turn: vec![Matrix6::identity(); n],
                points: e.kernel.points(),
            },
        };
        for k in 0..n {
            if let Some(t) = self.ties.get(&e.grids[k]) {
                p.turn[k] *= t.map;
                e.grids[k] = t.gn;
                e.dofs[k] = dofs_of(t.gn);
            }
        }
        e.placed(p)
    }

    /// A load on grid `g` (its six components in its frame) as the grid that carries
    /// it: an independent grid's is its own, a dependent grid's goes to its
    /// independent grid as Λᵀ f.
    pub fn carry(&self, g: i64, f: [f64; 6]) -> (i64, [f64; 6]) {
        match self.ties.get(&g) {
            None => (g, f),
            Some(t) => {
                let v = t.map.transpose() * nalgebra::Vector6::from(f);
                (t.gn, v.into())
            }
        }
    }
}
