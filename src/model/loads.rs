//! The static loads of a linear static deck (SOL 101): the set the case control's
//! `LOAD = n` selects (FORCE, MOMENT, PLOAD4 and GRAV cards of set n, or a LOAD card
//! combining such sets), as each grid's six components in its displacement frame.
//!
//! - FORCE and MOMENT: F·(N1, N2, N3) in system CID (for a cylindrical or spherical
//!   CID, its axes at the grid), on the grid's translations or rotations.
//! - PLOAD4 (and PLOAD2, read as one) on a shell: the consistent nodal forces ∫ Nᵢ p dA of the pressure p
//!   interpolated from the corners (P1..P4) by the element's own shape functions over
//!   its mean plane ([`nodal_integrals`]), along the element's normal (G1→G2→G3, right-handed; positive
//!   pressure pushes along it, as NASTRAN's does) or along CID's (N1, N2, N3). The
//!   forces go to the grids' translations; a corner that stands off its grid (ZOFFS,
//!   a grid tied whole by an RBE2, a warped quadrilateral's corner projected onto its
//!   mean plane) gives its grid the force and its moment about the grid, Λᵀ f
//!   ([`crate::elements::Placement`]).
//! - PLOAD on three or four grids: a triangle's P·A/3 at each grid along +r12 × r13,
//!   a quadrilateral as its four corner triangles of P/2 (NASTRAN's rule).
//! - GRAV: the inertia load M·a of every element's mass matrix on the rigid
//!   acceleration a = A·(N1, N2, N3) in rectangular system CID (NASTRAN's gravity: a
//!   mass is pushed along a).
//! - LOAD: S·Σ Sᵢ·(set Lᵢ); a set it names may not itself be a LOAD.
//! - TEMPERATURE(LOAD) = n: the bars' end loads for their TEMPRB temperatures of set
//!   n, in every SUBCASE (the bar kernel's thermal load, turned to the grids).

use super::{ModelError, Structure};
use crate::deck::cards::CardRef;
use crate::deck::cards::CoordKind;
use crate::deck::case::Selection;
use crate::deck::{Deck, Diagnostic};
use crate::elements::Family;
use nalgebra::{Matrix3, Vector3};
use std::collections::{BTreeMap, HashMap};

/// Each loaded grid's six load components (T1..R3) in its displacement frame.
pub type GridLoads = BTreeMap<i64, [f64; 6]>;

/// The static load the case control's LOAD selects (see the module's doc).
pub fn static_load(deck: &Deck, s: &Structure) -> Result<GridLoads, ModelError> {
    static_load_of(deck, s, deck.case.load.as_ref())
}

/// [`static_load`] of the LOAD selection `sel` (a SUBCASE's), with the thermal load
/// of the deck's TEMPERATURE(LOAD) selection when it has one.
pub fn static_load_of(deck: &Deck, s: &Structure, sel: Option<&Selection>) -> Result<GridLoads, ModelError> {
    let mut errors = Vec::new();
    let mut out = GridLoads::new();
    if let Some(t) = &deck.case.temperature {
        thermal_load(deck, s, t, &mut out, &mut errors);
    }
    let Some(sel) = sel else {
        if deck.case.temperature.is_none() {
            errors.push(Diagnostic::error(
                deck.case.at.clone(),
                "a static deck needs a load: LOAD = n in case control, selecting FORCE, MOMENT, PLOAD4, GRAV or \
                 LOAD cards of set n, or TEMPERATURE(LOAD) = n, selecting TEMPRB cards",
            ));
        }
        return if errors.is_empty() {
            Ok(out)
        } else {
            Err(ModelError { diagnostics: errors })
        };
    };
    let b = &deck.bulk;
    let combos: Vec<_> = b.load_combinations.iter().filter(|l| l.sid == sel.id).collect();
    let terms: Vec<(f64, i64, Option<&CardRef>)> = match combos.as_slice() {
        [] => vec![(1.0, sel.id, None)],
        [l] => l
            .terms
            .iter()
            .map(|&(si, li)| (l.scale * si, li, Some(&l.at)))
            .collect(),
        [first, second, ..] => {
            errors.push(second.at.error(format!(
                "LOAD {} is defined twice (first at {})",
                second.sid, first.at.pos
            )));
            Vec::new()
        }
    };
    let cx = Loads {
        structure: s,
        elements: s.elements.iter().map(|e| (e.eid, e)).collect(),
    };
    for (factor, set, by) in terms {
        if let Some(at) = by.filter(|_| b.load_combinations.iter().any(|l| l.sid == set)) {
            errors.push(at.error(format!(
                "LOAD {} names set {set}, which is itself a LOAD: a LOAD combines FORCE, MOMENT, PLOAD4 and GRAV sets",
                sel.id
            )));
            continue;
        }
        let before = errors.len();
        let found = cx.apply(deck, set, factor, &mut out, &mut errors);
        if !found && errors.len() == before {
            let message = format!("set {set} has no FORCE, MOMENT, PLOAD, PLOAD2, PLOAD4 or GRAV card");
            errors.push(match by {
                Some(at) => at.error(format!("LOAD {} names {message}", sel.id)),
                None => Diagnostic::error(Some(sel.pos.clone()), format!("LOAD = {}: {message}", sel.id)).card("LOAD"),
            });
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(ModelError { diagnostics: errors })
    }
}

/// The thermal load of temperature set `sel`: each CBAR's and CBEAM's end loads for
/// its TEMPRB ([`crate::elements::bar::Bar::thermal_load`]), turned to its grids'
/// DOFs (Λᵀ f, offsets included). As NASTRAN requires (TEMPRB remark 4), every element
/// needs a temperature in the set; impactlab takes them from TEMPRB, on bars, only (a
/// deck's TEMP, TEMPD and TEMPP1 cards are refused as unknown), so another element
/// kind in a thermally loaded structure is an error. The bars' thermal strains are
/// free strains: a static solution's ½uᵀKu is then not the energy they store.
fn thermal_load(deck: &Deck, s: &Structure, sel: &Selection, out: &mut GridLoads, errors: &mut Vec<Diagnostic>) {
    use crate::elements::bar::Bar;
    let b = &deck.bulk;
    let mut of: BTreeMap<i64, &crate::deck::cards::Temprb> = BTreeMap::new();
    for t in b.temprbs.iter().filter(|t| t.sid == sel.id) {
        for &e in &t.eids {
            if let Some(first) = of.insert(e, t) {
                errors.push(t.at.error(format!(
                    "TEMPRB {} gives element {e} a second temperature (the first at {})",
                    t.sid, first.at.pos
                )));
            }
        }
    }
    let selection = |message: String| {
        Diagnostic::error(Some(sel.pos.clone()), format!("(LOAD) = {}: {message}", sel.id)).card("TEMPERATURE")
    };
    if of.is_empty() {
        errors.push(selection(format!(
            "set {} has no TEMPRB card (impactlab takes thermal loads on bars, from TEMPRB)",
            sel.id
        )));
        return;
    }
    if let Some(c) = b.elements.iter().find(|c| !matches!(c.kind.card, "CBAR" | "CBEAM")) {
        errors.push(selection(format!(
            "{} {} needs a temperature, and impactlab takes thermal loads on CBAR and CBEAM (TEMPRB) only",
            c.kind.card, c.eid
        )));
        return;
    }
    let mut bars = std::collections::BTreeSet::new();
    for e in &s.elements {
        let Some(bar) = e.kind::<Bar>() else { continue };
        bars.insert(e.eid);
        let Some(t) = of.get(&e.eid) else {
            errors.push(selection(format!(
                "{} {} has no TEMPRB in set {}: every element needs a temperature (TEMPRB remark 4)",
                bar.card, e.eid, sel.id
            )));
            continue;
        };
        let f = bar.thermal_load(&t.temperature);
        for (k, g) in e.grids.iter().enumerate() {
            let at_grid = e.load_at_grid(k, nalgebra::Vector6::from_column_slice(&f[6 * k..6 * k + 6]));
            let slot = out.entry(*g).or_insert([0.0; 6]);
            for (v, a) in slot.iter_mut().zip(at_grid.iter()) {
                *v += a;
            }
        }
    }
    for (eid, t) in of.iter().filter(|(e, _)| !bars.contains(e)) {
        errors.push(t.at.error(format!(
            "TEMPRB {} names element {eid}, which is not a CBAR or CBEAM of the deck (impactlab takes thermal loads \
             on bars only)",
            t.sid
        )));
    }
}

/// What applying a load set needs.
struct Loads<'s> {
    structure: &'s Structure,
    elements: HashMap<i64, &'s crate::elements::Element>,
}

impl Loads<'_> {
    /// Adds `factor` times load set `set` to `out`; false when the set has no card.
    fn apply(&self, deck: &Deck, set: i64, factor: f64, out: &mut GridLoads, errors: &mut Vec<Diagnostic>) -> bool {
        let b = &deck.bulk;
        let g = &self.structure.geometry;
        let mut found = false;
        for l in b.point_loads.iter().filter(|l| l.sid == set) {
            found = true;
            let Some(p) = g.positions.get(&l.g) else {
                errors.push(l.at.error(format!(
                    "{} {} loads grid {}, which does not exist",
                    l.at.name, l.sid, l.g
                )));
                continue;
            };
            let Some(axes) = self.axes(&l.at, l.cid, &Vector3::from(*p), errors) else {
                continue;
            };
            let v = g.frame(l.g).transpose() * (axes * Vector3::from(l.vector)) * factor;
            let slot = out.entry(l.g).or_default();
            let first = if l.moment { 3 } else { 0 };
            for c in 0..3 {
                slot[first + c] += v[c];
            }
        }
        for l in b.pload4s.iter().filter(|l| l.sid == set) {
            found = true;
            for eid in &l.eids {
                self.pressure(l, *eid, factor, out, errors);
            }
        }
        for l in b.ploads.iter().filter(|l| l.sid == set) {
            found = true;
            self.grid_pressure(l, factor, out, errors);
        }
        for l in b.gravs.iter().filter(|l| l.sid == set) {
            found = true;
            if g.systems.get(&l.cid).is_some_and(|s| s.kind != CoordKind::Rectangular) {
                errors.push(l.at.error(format!(
                    "GRAV {} is given in system {}, which is not rectangular: a uniform acceleration needs fixed axes",
                    l.sid, l.cid
                )));
                continue;
            }
            let Some(axes) = self.axes(&l.at, l.cid, &Vector3::zeros(), errors) else {
                continue;
            };
            let a = axes * Vector3::from(l.vector) * factor;
            for e in &self.structure.elements {
                let acc: Vec<Vector3<f64>> = e.grids.iter().map(|&id| g.frame(id).transpose() * a).collect();
                for m in e.mass() {
                    for (r, &(gr, cr)) in m.at.iter().enumerate() {
                        let f: f64 =
                            m.at.iter()
                                .enumerate()
                                .filter(|(_, &(_, cc))| cc < 3)
                                .map(|(c, &(gc, cc))| m.values[(r, c)] * acc[gc][cc])
                                .sum();
                        if f != 0.0 {
                            out.entry(e.grids[gr]).or_default()[cr] += f;
                        }
                    }
                }
            }
        }
        found
    }

    /// The axes of system `cid` at basic point `p`, or an error on `at`.
    fn axes(&self, at: &CardRef, cid: i64, p: &Vector3<f64>, errors: &mut Vec<Diagnostic>) -> Option<Matrix3<f64>> {
        let Some(sys) = self.structure.geometry.systems.get(&cid) else {
            errors.push(at.error(format!(
                "{} names coordinate system {cid}, which is not defined",
                at.name
            )));
            return None;
        };
        let axes = sys.frame_at(p);
        if axes.is_none() {
            errors.push(at.error(format!(
                "{} is directed in system {cid} at a point on its axis, where its axes are undefined",
                at.name
            )));
        }
        axes
    }

    /// A PLOAD's forces: a triangle's P·A/3 at each of its grids along +r12 × r13; a
    /// quadrilateral as its four corner triangles (G1G2G3, G2G3G4, G3G4G1, G4G1G2),
    /// each of P/2 (`manual/BULK.TXT`, PLOAD remarks 2 and 3).
    fn grid_pressure(
        &self,
        l: &crate::deck::cards::Pload,
        factor: f64,
        out: &mut GridLoads,
        errors: &mut Vec<Diagnostic>,
    ) {
        let g = &self.structure.geometry;
        let mut x = Vec::new();
        for id in &l.grids {
            match g.positions.get(id) {
                Some(p) => x.push(Vector3::from(*p)),
                None => {
                    errors.push(l.at.error(format!("PLOAD {} loads grid {id}, which does not exist", l.sid)));
                    return;
                }
            }
        }
        let (triangles, share): (&[[usize; 3]], f64) = if x.len() == 3 {
            (&[[0, 1, 2]], 1.0)
        } else {
            (&[[0, 1, 2], [1, 2, 3], [2, 3, 0], [3, 0, 1]], 0.5)
        };
        for t in triangles {
            // (r12 × r13)/6 is A/3 along the triangle's normal.
            let f = (x[t[1]] - x[t[0]]).cross(&(x[t[2]] - x[t[0]])) * (l.p * share * factor / 6.0);
            for &k in t {
                let v = g.frame(l.grids[k]).transpose() * f;
                let slot = out.entry(l.grids[k]).or_default();
                for c in 0..3 {
                    slot[c] += v[c];
                }
            }
        }
    }

    /// A PLOAD4's consistent nodal forces on shell `eid`.
    fn pressure(
        &self,
        l: &crate::deck::cards::Pload4,
        eid: i64,
        factor: f64,
        out: &mut GridLoads,
        errors: &mut Vec<Diagnostic>,
    ) {
        let Some(e) = self.elements.get(&eid) else {
            errors.push(l.at.error(format!(
                "{} {} loads element {eid}, which does not exist",
                l.at.name, l.sid
            )));
            return;
        };
        if !matches!(e.kernel.family(), Family::Shell(_)) {
            errors.push(l.at.error(format!(
                "{} {} loads element {eid}, which is not a shell (CQUAD4, CTRIA3)",
                l.at.name, l.sid
            )));
            return;
        }
        let points = e.points();
        let Ok(frame) = crate::geometry::shell_frame(&points) else {
            return; // the element's own build has refused it
        };
        let n = points.len();
        let centroid = points.iter().map(|&p| Vector3::from(p)).sum::<Vector3<f64>>() / n as f64;
        let direction = match l.direction {
            None => frame.axes.column(2).into_owned(),
            Some(d) => match self.axes(&l.at, l.cid, &centroid, errors) {
                Some(axes) => (axes * Vector3::from(d)).normalize(),
                None => return,
            },
        };
        let p = &l.p[..n];
        let weights = nodal_integrals(&frame.local, p);
        let g = &self.structure.geometry;
        for (k, &id) in e.grids.iter().enumerate() {
            let f = direction * (weights[k] * factor);
            let v = g.frame(id).transpose() * f;
            let slot = out.entry(id).or_default();
            match e.placement.as_ref().filter(|p| !p.rotates_only(k)) {
                // The corner stands off its grid (ZOFFS, a rigid tie): the grid takes
                // the force and its moment, Λᵀ of the corner's force in the kernel's
                // axes, which Λ's rotation block (Rᵀ T) gives from the grid's frame.
                Some(p) => {
                    let local = p.turn[k].fixed_view::<3, 3>(0, 0) * v;
                    let at_grid =
                        e.load_at_grid(k, nalgebra::Vector6::new(local[0], local[1], local[2], 0.0, 0.0, 0.0));
                    for c in 0..6 {
                        slot[c] += at_grid[c];
                    }
                }
                None => {
                    for c in 0..3 {
                        slot[c] += v[c];
                    }
                }
            }
        }
    }
}

/// ∫ Nᵢ p dA over a flat shell with corners `local` (in its plane, counter-clockwise)
/// and corner values `p`, by the element's own shape functions: bilinear over a
/// quadrilateral ([`crate::elements::quad4::pressure_loads`]), linear over a triangle
/// ([`crate::elements::tria3::pressure_loads`]).
pub fn nodal_integrals(local: &[[f64; 3]], p: &[f64]) -> Vec<f64> {
    let xy = |k: usize| [local[k][0], local[k][1]];
    match (local.len(), p.len()) {
        (3, 3) => crate::elements::tria3::pressure_loads(&[xy(0), xy(1), xy(2)], &[p[0], p[1], p[2]]).to_vec(),
        _ => crate::elements::quad4::pressure_loads(&[xy(0), xy(1), xy(2), xy(3)], &[p[0], p[1], p[2], p[3]]).to_vec(),
    }
}

/// The resultant of grid loads in the basic system: force and moment about the basic
/// origin.
pub fn resultant(loads: &GridLoads, s: &Structure) -> [f64; 6] {
    let g = &s.geometry;
    let (mut f, mut m) = (Vector3::zeros(), Vector3::zeros());
    for (id, l) in loads {
        let t = g.frame(*id);
        let x = Vector3::from(g.positions.get(id).copied().unwrap_or_default());
        let force = t * Vector3::new(l[0], l[1], l[2]);
        f += force;
        m += x.cross(&force) + t * Vector3::new(l[3], l[4], l[5]);
    }
    [f.x, f.y, f.z, m.x, m.y, m.z]
}

#[cfg(test)]
mod tests {
    use super::nodal_integrals;

    /// Goal: the consistent pressure forces carry the pressure's resultant and its first
    /// moments exactly (Σ Fᵢ = ∫p dA, Σ xᵢFᵢ = ∫x p dA, as Σ Nᵢ = 1 and Σ Nᵢxᵢ = x).
    /// Model: a rectangle a × b = 2 × 1 with corner pressures 5, 6, 7, 8 (bilinear p),
    /// and a triangle of the same corners' first three (linear p). Reference: the
    /// integrals by hand: ∫p dA = ab·mean(p); ∫x p dA = b/2·(a²/6·(p₁ + p₄) +
    /// a²/3·(p₂ + p₃)) on the rectangle; on the triangle (0,0), (2,0), (2,1): ∫p dA =
    /// A·mean(p), A = 1. Tolerance: 1e-14 relative (round-off).
    #[test]
    fn consistent_pressure_forces_carry_the_resultant_and_its_moment() {
        let (a, b) = (2.0, 1.0);
        let corners = [[0.0, 0.0, 0.0], [a, 0.0, 0.0], [a, b, 0.0], [0.0, b, 0.0]];
        let p = [5.0, 6.0, 7.0, 8.0];
        let f = nodal_integrals(&corners, &p);
        let total: f64 = f.iter().sum();
        assert!((total - a * b * 6.5).abs() < 1e-14 * total, "{f:?}");
        let moment: f64 = f.iter().zip(&corners).map(|(f, c)| f * c[0]).sum();
        let exact = b / 2.0 * (a * a / 6.0 * (p[0] + p[3]) + a * a / 3.0 * (p[1] + p[2]));
        assert!((moment - exact).abs() < 1e-14 * exact, "{moment} vs {exact}");
        let t = nodal_integrals(&corners[..3], &p[..3]);
        let total: f64 = t.iter().sum();
        assert!((total - 6.0).abs() < 1e-14 * 6.0, "{t:?}");
        let moment: f64 = t.iter().zip(&corners).map(|(f, c)| f * c[0]).sum();
        // ∫x p dA over the triangle: A/12·Σᵢ xᵢ(pᵢ + Σⱼ pⱼ) for linear x and p.
        let exact = 1.0 / 12.0 * (0.0 * (5.0 + 18.0) + 2.0 * (6.0 + 18.0) + 2.0 * (7.0 + 18.0));
        assert!((moment - exact).abs() < 1e-14 * exact, "{moment} vs {exact}");
    }
}
