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
//! - TEMPERATURE(LOAD) = n (above the SUBCASEs or in one): the thermal load of
//!   temperature set n: each rod, bar and shell loaded by its free thermal
//!   deformation (see `thermal_load`).

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
    static_load_of(deck, s, deck.case.load.as_ref(), deck.case.temperature.as_ref())
}

/// [`static_load`] of the LOAD selection `sel` and the TEMPERATURE(LOAD) selection
/// `temperature` (a SUBCASE's).
pub fn static_load_of(
    deck: &Deck,
    s: &Structure,
    sel: Option<&Selection>,
    temperature: Option<&Selection>,
) -> Result<GridLoads, ModelError> {
    let mut errors = Vec::new();
    let mut out = GridLoads::new();
    if let Some(t) = temperature {
        thermal_load(deck, s, t, &mut out, &mut errors);
    }
    let Some(sel) = sel else {
        if temperature.is_none() {
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

/// The thermal load of temperature set `sel`, element by element, turned to the
/// grids' DOFs (Λᵀ f, offsets included). Every element that expands needs a
/// temperature in the set (`manual/BULK.TXT`, TEMP remark 3: "all elements must have a
/// temperature field defined either directly on a TEMPP1, TEMPP2, TEMPP3, or TEMPRB
/// card or indirectly as the average of the connected grid point temperatures
/// defined on the TEMP or TEMPD cards"):
/// - a bar (CBAR, CBEAM): its TEMPRB, or its grids' temperatures at its ends, no
///   gradient; its kernel's thermal load ([`crate::elements::bar::Bar::thermal_load`]);
/// - a shell: its TEMPP1 (T, T′), or the average of its grids' temperatures, no
///   gradient; a rod: the average of its grids' temperatures. Their load is K uₜ, uₜ
///   the free thermal deformation in the kernel's axes: the expansion α(T − TREF)·(x
///   − x̄) (MID1's α and TREF) and, for a shell, the curvature κ = α₂T′ (MID2's α),
///   w = −κ(x² + y²)/2, θx = ∂w/∂y, θy = −∂w/∂x, about its centroid x̄. Both are
///   fields the kernels reproduce exactly (constant strain and curvature: the patch
///   tests), so K uₜ is the consistent load ∫Bᵀ C εₜ dA, and a structure free to
///   deform so is left stress-free;
/// - springs, masses, general elements and bushings carry no thermal strain.
///
/// Refused with the reason: a shear panel, a laminate (PCOMP) or an anisotropic
/// material (MAT2) in a thermally loaded structure; a grid's temperature given twice.
/// The thermal strains are free strains: a static solution's ½uᵀKu is then not the
/// energy they store.
fn thermal_load(deck: &Deck, s: &Structure, sel: &Selection, out: &mut GridLoads, errors: &mut Vec<Diagnostic>) {
    use crate::elements::bar::{Bar, BarTemperature};
    let b = &deck.bulk;
    let selection = |message: String| {
        Diagnostic::error(Some(sel.pos.clone()), format!("(LOAD) = {}: {message}", sel.id)).card("TEMPERATURE")
    };
    let mut bar_cards: BTreeMap<i64, &crate::deck::cards::Temprb> = BTreeMap::new();
    for t in b.temprbs.iter().filter(|t| t.sid == sel.id) {
        for &e in &t.eids {
            if let Some(first) = bar_cards.insert(e, t) {
                errors.push(t.at.error(format!(
                    "TEMPRB {} gives element {e} a second temperature (the first at {})",
                    t.sid, first.at.pos
                )));
            }
        }
    }
    let mut plate_cards: BTreeMap<i64, &crate::deck::cards::Tempp1> = BTreeMap::new();
    for t in b.tempp1s.iter().filter(|t| t.sid == sel.id) {
        if let Some(first) = plate_cards.insert(t.eid, t) {
            errors.push(t.at.error(format!(
                "TEMPP1 {} gives element {} a second temperature (the first at {})",
                t.sid, t.eid, first.at.pos
            )));
        }
    }
    let mut grid_t: HashMap<i64, f64> = HashMap::new();
    let mut default = None;
    for t in b.temperatures.iter().filter(|t| t.sid == sel.id) {
        let twice = match t.grid {
            Some(g) => grid_t.insert(g, t.t).is_some(),
            None => default.replace(t.t).is_some(),
        };
        if twice {
            errors.push(t.at.error(match t.grid {
                Some(g) => format!("{} {} gives grid {g} a second temperature", t.at.name, t.sid),
                None => format!("{} {} is given twice", t.at.name, t.sid),
            }));
        }
    }
    if bar_cards.is_empty() && plate_cards.is_empty() && grid_t.is_empty() && default.is_none() {
        errors.push(selection(format!(
            "set {} has no TEMPRB, TEMPP1, TEMP or TEMPD card",
            sel.id
        )));
        return;
    }
    let grid_temperature = |g: &i64| grid_t.get(g).copied().or(default);
    let connections: HashMap<i64, &crate::deck::cards::Connection> = b.elements.iter().map(|c| (c.eid, c)).collect();
    let cards = Expansions::new(b);
    let mut taken = std::collections::BTreeSet::new();
    for e in &s.elements {
        let family = e.kernel.family();
        let expands = matches!(
            family,
            Family::Rod { .. } | Family::Shell(_) | Family::Beam { .. } | Family::Panel(_)
        );
        if !expands {
            continue;
        }
        let card = e.kernel.card();
        let no_temperature = |what: &str| {
            selection(format!(
                "{card} {} has no temperature in set {} ({what}): every element needs one (TEMP remark 3)",
                e.eid, sel.id
            ))
        };
        let average = || -> Option<f64> {
            let t: Option<Vec<f64>> = e.grids.iter().map(grid_temperature).collect();
            t.map(|t| t.iter().sum::<f64>() / t.len() as f64)
        };
        let local: Vec<f64> = match family {
            Family::Beam { .. } => {
                let bar = e.kind::<Bar>().expect("a beam's kernel is a Bar");
                let t = match bar_cards.get(&e.eid) {
                    Some(t) => t.temperature,
                    None => match (grid_temperature(&e.grids[0]), grid_temperature(&e.grids[1])) {
                        (Some(ta), Some(tb)) => BarTemperature {
                            average: [ta, tb],
                            gradient: [[0.0; 2]; 2],
                        },
                        _ => {
                            errors.push(no_temperature("no TEMPRB, and no TEMP or TEMPD for its grids"));
                            continue;
                        }
                    },
                };
                taken.insert(e.eid);
                bar.thermal_load(&t).to_vec()
            }
            Family::Panel(_) => {
                errors.push(selection(format!(
                    "{card} {} is a shear panel in a thermally loaded structure: impactlab takes thermal loads on \
                     rods, bars and shells",
                    e.eid
                )));
                continue;
            }
            _ => {
                let shell = matches!(family, Family::Shell(_));
                let (t, gradient) = match plate_cards.get(&e.eid).filter(|_| shell) {
                    Some(p) => (p.average, p.gradient),
                    None => match average() {
                        Some(t) => (t, 0.0),
                        None if shell => {
                            errors.push(no_temperature("no TEMPP1, and no TEMP or TEMPD for its grids"));
                            continue;
                        }
                        None => {
                            errors.push(no_temperature("no TEMP or TEMPD for its grids"));
                            continue;
                        }
                    },
                };
                let Some(c) = connections.get(&e.eid) else { continue };
                let Some((alpha, tref, alpha_bending)) = expansion(&cards, c, errors) else {
                    continue;
                };
                taken.insert(e.eid);
                free_deformation_load(e, alpha * (t - tref), alpha_bending * gradient)
            }
        };
        for (k, g) in e.grids.iter().enumerate() {
            let at_grid = e.load_at_grid(k, nalgebra::Vector6::from_column_slice(&local[6 * k..6 * k + 6]));
            let slot = out.entry(*g).or_insert([0.0; 6]);
            for (v, a) in slot.iter_mut().zip(at_grid.iter()) {
                *v += a;
            }
        }
    }
    for (eid, t) in bar_cards.iter().filter(|(e, _)| !taken.contains(e)) {
        errors.push(t.at.error(format!(
            "TEMPRB {} names element {eid}, which is not a CBAR or CBEAM of the deck",
            t.sid
        )));
    }
    for (eid, t) in plate_cards.iter().filter(|(e, _)| !taken.contains(e)) {
        errors.push(t.at.error(format!(
            "TEMPP1 {} names element {eid}, which is not a shell of the deck",
            t.sid
        )));
    }
}

/// The property and material cards by id, for the elements' thermal expansion.
struct Expansions<'b> {
    mat1: HashMap<i64, &'b crate::deck::cards::Mat1>,
    prod: HashMap<i64, &'b crate::deck::cards::Prod>,
    pshell: HashMap<(Option<&'static str>, i64), &'b crate::deck::cards::Pshell>,
}

impl<'b> Expansions<'b> {
    fn new(b: &'b crate::deck::cards::Bulk) -> Self {
        Expansions {
            mat1: b.mat1s.iter().map(|m| (m.mid, m)).collect(),
            prod: b.prods.iter().map(|p| (p.pid, p)).collect(),
            pshell: b
                .pshells
                .iter()
                .map(|p| ((None, p.pid), p))
                .chain(b.cosmic_plates.iter().map(|(card, p)| ((Some(*card), p.pid), p)))
                .collect(),
        }
    }
}

/// A rod's or shell's thermal expansion: (α, TREF) of its (membrane) MAT1 and the α of
/// a shell's bending MAT1 (MID2); refused for a laminate or a MAT2.
fn expansion(
    cards: &Expansions,
    c: &crate::deck::cards::Connection,
    errors: &mut Vec<Diagnostic>,
) -> Option<(f64, f64, f64)> {
    let mat1 = |mid: i64| cards.mat1.get(&mid).copied();
    let refuse = |errors: &mut Vec<Diagnostic>, why: &str| {
        errors.push(c.at.error(format!(
            "{} {} {why}: impactlab takes thermal loads on isotropic materials (MAT1)",
            c.kind.card, c.eid
        )));
    };
    if matches!(c.kind.card, "CROD" | "CONROD" | "CTUBE") {
        let p = c.rod.as_deref().or_else(|| cards.prod.get(&c.pid).copied())?;
        let m = mat1(p.mid)?;
        return Some((m.alpha, m.tref, 0.0));
    }
    let pshell = cards.pshell.get(&(c.property_card, c.pid));
    let Some(p) = pshell else {
        refuse(errors, "is a laminate (PCOMP) in a thermally loaded structure");
        return None;
    };
    let (membrane, bending) = (p.mid1.map(mat1), p.mid2.map(mat1));
    if matches!(membrane, Some(None)) || matches!(bending, Some(None)) {
        refuse(
            errors,
            "has an anisotropic material (MAT2) in a thermally loaded structure",
        );
        return None;
    }
    let (membrane, bending) = (membrane.flatten(), bending.flatten());
    let tref = membrane.or(bending).map_or(0.0, |m| m.tref);
    Some((
        membrane.map_or(0.0, |m| m.alpha),
        tref,
        bending.map_or(0.0, |m| m.alpha),
    ))
}

/// K uₜ in the kernel's axes, uₜ the free thermal deformation of `strain` (an
/// isotropic expansion) and, in a shell's plane, `curvature` (see [`thermal_load`]).
fn free_deformation_load(e: &crate::elements::Element, strain: f64, curvature: f64) -> Vec<f64> {
    let points = e.kernel.points();
    let n = points.len();
    let centre: [f64; 3] = std::array::from_fn(|i| points.iter().map(|p| p[i]).sum::<f64>() / n as f64);
    let mut u = vec![0.0; 6 * n];
    for (k, p) in points.iter().enumerate() {
        let d: [f64; 3] = std::array::from_fn(|i| p[i] - centre[i]);
        for i in 0..3 {
            u[6 * k + i] = strain * d[i];
        }
        let (x, y) = (d[0], d[1]);
        u[6 * k + 2] += -curvature * (x * x + y * y) / 2.0;
        u[6 * k + 3] = -curvature * y;
        u[6 * k + 4] = curvature * x;
    }
    let mut f = vec![0.0; 6 * n];
    for l in e.kernel.stiffness() {
        for (a, &(ga, ca)) in l.at.iter().enumerate() {
            for (bb, &(gb, cb)) in l.at.iter().enumerate() {
                f[6 * ga + ca] += l.values[(a, bb)] * u[6 * gb + cb];
            }
        }
    }
    f
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
