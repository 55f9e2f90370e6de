//! Dropping inert DOFs: groups of solved DOFs that no load, initial condition,
//! contact or dynamic load ever reaches stay exactly zero for the whole run, so they
//! need not be solved.
//!
//! Two DOFs are coupled when an assembled stiffness, mass or damping entry between
//! them is nonzero, or when both appear in the contact (its driver functional, its loads, the
//! impactor) or in one TF. A group of coupled DOFs is *live* when any of its DOFs has a
//! nonzero initial displacement or velocity, belongs to the contact or carries a
//! dynamic load; every other
//! group is governed by M ü + K u = 0 with zero initial state and stays at zero. The
//! classic case is a flat plate struck transversely: with no membrane–bending coupling
//! (B = 0) the in-plane T1/T2 DOFs form such a group.
//!
//! Dropping a group is exact, not an approximation: the remaining equations are the
//! same, and the dropped DOFs are reported as zero in every output.

use super::System;
use crate::model::{Functional, Model, Source};

struct UnionFind(Vec<usize>);

impl UnionFind {
    fn find(&mut self, mut i: usize) -> usize {
        while self.0[i] != i {
            self.0[i] = self.0[self.0[i]];
            i = self.0[i];
        }
        i
    }
    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra] = rb;
        }
    }
}

/// Which solved DOFs are live (see the module doc), from the assembled system.
fn live_dofs(model: &Model, sys: &System) -> Vec<bool> {
    let n = model.n();
    let mut uf = UnionFind((0..n).collect());
    for t in sys.k.iter().chain(sys.m.iter()).chain(sys.c.iter()) {
        if t.val != 0.0 {
            uf.union(t.row, t.col);
        }
    }
    let mut seeds: Vec<usize> = (0..n).filter(|&i| model.u0[i] != 0.0 || model.v0[i] != 0.0).collect();
    if let Some(c) = &model.contact {
        let mut group: Vec<usize> = c.driver.iter().map(|&(j, _)| j).collect();
        group.extend(c.loads.iter().map(|l| l.dof));
        group.extend(c.impactor.dofs.iter().copied());
        group.extend(c.nonconservative.iter().map(|&(j, _)| j));
        for w in group.windows(2) {
            uf.union(w[0], w[1]);
        }
        seeds.extend(group);
    }
    if let Some(ex) = &model.excitation {
        seeds.extend(ex.terms.iter().map(|t| t.dof));
    }
    for d in model.dependent.iter().filter(|d| !d.tied) {
        for w in d.functional.windows(2) {
            uf.union(w[0].0, w[1].0);
        }
    }
    let mut live_root = vec![false; n];
    for s in seeds {
        let r = uf.find(s);
        live_root[r] = true;
    }
    (0..n).map(|i| live_root[uf.find(i)]).collect()
}

/// Returns the model with the inert DOFs removed (renumbered densely; their count
/// added to `inert_dofs`) and its system (`sys` restricted, not assembled again), or
/// `None` when every DOF is live.
pub fn drop_inert(model: &Model, sys: &System) -> Option<(Model, System)> {
    let live = live_dofs(model, sys);
    if live.iter().all(|&l| l) {
        return None;
    }
    let mut map = vec![None; model.n()];
    let mut next = 0;
    for (i, _) in live.iter().enumerate().filter(|(_, &l)| l) {
        map[i] = Some(next);
        next += 1;
    }
    let re = |i: usize| map[i].expect("contact and dependent DOFs are live");
    let re_opt = |o: Option<usize>| o.and_then(|i| map[i]);
    let re_fun = |f: &Functional| -> Functional { f.iter().map(|&(j, c)| (re(j), c)).collect() };
    let mut m = model.clone();
    m.dofs = keep(&model.dofs, &live);
    m.u0 = keep(&model.u0, &live);
    m.v0 = keep(&model.v0, &live);
    for d in &mut m.dependent {
        d.functional = if d.tied {
            // An inert DOF stays zero: its term drops out.
            d.functional.iter().filter_map(|&(j, c)| Some((map[j]?, c))).collect()
        } else {
            re_fun(&d.functional)
        };
    }
    for e in std::sync::Arc::make_mut(&mut m.elements).iter_mut() {
        e.dofs.iter_mut().flatten().for_each(|d| *d = re_opt(*d));
        if let Some(links) = &mut e.links {
            // An inert DOF stays zero: its term drops out.
            for terms in std::sync::Arc::make_mut(links).iter_mut().flatten() {
                *terms = terms.iter().filter_map(|&(j, a)| Some((map[j]?, a))).collect();
            }
        }
    }
    if let Some(c) = &mut m.contact {
        c.driver = re_fun(&c.driver);
        c.nonconservative = re_fun(&c.nonconservative);
        for l in &mut c.loads {
            l.dof = re(l.dof);
        }
        c.impactor.dof = re(c.impactor.dof);
        c.impactor.dofs = c.impactor.dofs.iter().map(|&d| re(d)).collect();
    }
    if let Some(ex) = &mut m.excitation {
        for t in &mut ex.terms {
            t.dof = re(t.dof);
        }
    }
    for list in [&mut m.outputs.disp, &mut m.outputs.velo] {
        for (_, s) in list.iter_mut() {
            if let Source::Dof(i) = *s {
                *s = map[i].map_or(Source::Inert, Source::Dof);
            }
        }
    }
    m.inert_dofs = model.inert_dofs + (model.n() - next);
    let reduced = sys.restricted(&map, next);
    Some((m, reduced))
}

fn keep<T: Clone>(v: &[T], live: &[bool]) -> Vec<T> {
    v.iter().zip(live).filter(|(_, &l)| l).map(|(x, _)| x.clone()).collect()
}
