//! Rigid elements (RBE2, RBE3), applied by constraint elimination: a dependent DOF is
//! not solved; it is a linear combination of independent grids' DOFs, and every
//! element, mass and load on it is carried over to those.
//!
//! - **RBE2**: the components CM of each dependent grid m follow the independent grid
//!   n as a rigid body, `[u; θ]_m = Λ [u; θ]_n` with
//!   `Λ = [Tₘᵀ Tₙ, −Tₘᵀ[d]× Tₙ; 0, Tₘᵀ Tₙ]` ([`crate::elements::Placement::turn_of`]),
//!   d = xₘ − xₙ and T each grid's displacement frame; the components not in CM stay
//!   the grid's own.
//! - **RBE3**: the components REFC of the reference grid r move as the weighted
//!   least-squares rigid fit of its independent grids' components Ci (MSC Nastran's
//!   definition). With q the rigid motion of r (basic), each grid i's rigid motion in
//!   its frame is `Sᵢ q`, `Sᵢ` = `turn_of(Tᵢ, I, xᵢ − x_r)`; with `Eᵢ` selecting its
//!   components Ci and `Wᵢ` weighting translations by WTi and rotations by WTi·Lc²
//!   (Lc the mean distance of the independent grids from r, 1 when they all sit on
//!   it), `q = A⁻¹ Σ Sᵢᵀ Eᵢᵀ Wᵢ Eᵢ uᵢ`, `A = Σ Sᵢᵀ Eᵢᵀ Wᵢ Eᵢ Sᵢ`. The grids must fix
//!   all six rigid motions (A regular). The fit reads motion and adds no stiffness; a
//!   load on r reaches the grids as the transpose, which for translations alone is
//!   the classic split `fᵢ = wᵢ F/Σw + wᵢ (J⁻¹M) × r̃ᵢ` about the weighted centroid.
//!
//! A dependent grid's motion is a sum of terms `Σ Mₕ uₕ` over independent grids h (a
//! partly dependent grid's own components are a term on itself); chains (an
//! independent grid itself dependent on another rigid element) are followed to the
//! grids that are independent. An element or mass on a dependent grid is attached to
//! those grids, which is Tᵀ K T of the constraint elimination element by element; a
//! load on it goes over as Mₕᵀ f; its displacement is recovered as Σ Mₕ uₕ. A rigid
//! element stores no energy and has no mass: the ledger needs nothing of it.
//!
//! Rigid elements tying disjoint components of one grid are joined. A cycle of
//! dependencies, or a component made dependent by two rigid elements, is an error
//! naming both cards.

use crate::deck::cards::{Bulk, CardRef};
use crate::deck::Diagnostic;
use crate::elements::{Element, Placement};
use crate::geometry::Geometry;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use std::collections::BTreeMap;

/// Every component of a grid.
const ALL: u8 = 0b11_1111;

/// The smallest eigenvalue of an RBE3's A against its largest below which its grids
/// and components are taken not to fix the reference grid's rigid motion.
const RBE3_RANK: f64 = 1e-10;

/// A dependent grid's tie to the independent grids whose motion it follows.
#[derive(Debug, Clone)]
pub struct Tie {
    /// The components made dependent (bit c − 1 for component c).
    pub dependent: u8,
    /// The grid's six components (in its frame) are `Σ M uₕ` over these terms (h, M),
    /// uₕ grid h's six components in its frame; h is the grid itself for the
    /// components it keeps. Sorted by grid.
    pub terms: Vec<(i64, Matrix6<f64>)>,
    /// The rigid element that makes the grid dependent, and its name ("RBE3 7").
    pub at: CardRef,
    /// See `at`.
    pub name: String,
}

impl Tie {
    /// Component `c` (0-5) of the grid, when dependent, as a functional of the solved
    /// DOFs: the row c of each term over its grid's solved DOFs (`dofs_of`; a term on
    /// a DOF not solved drops out, it being held at zero).
    pub fn functional(&self, c: usize, dofs_of: &impl Fn(i64) -> [Option<usize>; 6]) -> Vec<(usize, f64)> {
        let mut f = Vec::new();
        for (h, m) in &self.terms {
            let dofs = dofs_of(*h);
            f.extend((0..6).filter_map(|k| Some((dofs[k]?, m[(c, k)])).filter(|&(_, a)| a != 0.0)));
        }
        f
    }

    /// True when component `c` (0-5) is dependent.
    pub fn ties(&self, c: usize) -> bool {
        self.dependent & (1 << c) != 0
    }

    /// The independent grid and Λ when the whole grid follows one other grid (an RBE2
    /// of all six components, or a chain of them).
    pub fn whole(&self) -> Option<(i64, &Matrix6<f64>)> {
        match self.terms.as_slice() {
            [(g, m)] if self.dependent == ALL => Some((*g, m)),
            _ => None,
        }
    }
}

/// Every dependent grid of the deck's rigid elements, by grid id.
#[derive(Debug, Clone, Default)]
pub struct Rigid {
    /// Dependent grid → its tie.
    pub ties: BTreeMap<i64, Tie>,
}

/// A grid's dependency as its card writes it, before chains are followed.
struct Def<'b> {
    name: String,
    at: &'b CardRef,
    dependent: u8,
    terms: BTreeMap<i64, Matrix6<f64>>,
}

/// The selector of components `mask` (bit c − 1 for component c).
fn select(mask: u8) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| if i == j && mask & (1 << i) != 0 { 1.0 } else { 0.0 })
}

/// The rigid elements of a deck resolved (see the module's doc); errors for what
/// cannot be.
pub fn resolve(b: &Bulk, geo: &Geometry, errors: &mut Vec<Diagnostic>) -> Rigid {
    // Reports each grid a card names that does not exist; true when every one is
    // located (a grid whose location did not resolve has its error from the geometry).
    let usable = |name: &str, at: &CardRef, grids: &mut dyn Iterator<Item = i64>, errors: &mut Vec<Diagnostic>| {
        let mut ok = true;
        for g in grids.filter(|g| !geo.positions.contains_key(g)) {
            ok = false;
            if !b.grids.iter().any(|x| x.id == g) {
                errors.push(at.error(format!("{name} references grid {g}, which does not exist")));
            }
        }
        ok
    };
    let mut defs: BTreeMap<i64, Def> = BTreeMap::new();
    for r in &b.rbe2s {
        let name = format!("{} {}", r.card, r.eid);
        if !usable(
            &name,
            &r.at,
            &mut std::iter::once(r.gn).chain(r.gm.iter().copied()),
            errors,
        ) {
            continue;
        }
        let xn = Vector3::from(geo.positions[&r.gn]);
        for &gm in &r.gm {
            let d = Vector3::from(geo.positions[&gm]) - xn;
            let lambda = Placement::turn_of(&geo.frame(gm), &geo.frame(r.gn), d.into());
            let mut terms = BTreeMap::from([(r.gn, select(r.cm.0) * lambda)]);
            if r.cm.0 != ALL {
                terms.insert(gm, select(!r.cm.0 & ALL));
            }
            let def = Def {
                name: name.clone(),
                at: &r.at,
                dependent: r.cm.0,
                terms,
            };
            define(gm, def, &mut defs, errors);
        }
    }
    for r in &b.rbe3s {
        let name = format!("RBE3 {}", r.eid);
        let mut grids = std::iter::once(r.refgrid).chain(r.groups.iter().flat_map(|g| g.grids.iter().copied()));
        if !usable(&name, &r.at, &mut grids, errors) {
            continue;
        }
        match rbe3_terms(r, geo) {
            Ok(mut terms) => {
                if r.refc.0 != ALL {
                    terms.insert(r.refgrid, select(!r.refc.0 & ALL));
                }
                let def = Def {
                    name,
                    at: &r.at,
                    dependent: r.refc.0,
                    terms,
                };
                define(r.refgrid, def, &mut defs, errors);
            }
            Err(why) => errors.push(r.at.error(format!("{name}: {why}"))),
        }
    }

    let mut rigid = Rigid::default();
    let mut failed: Vec<i64> = Vec::new();
    let mut cycles_said: Vec<[String; 2]> = Vec::new();
    for &g in defs.keys() {
        let mut stack = Vec::new();
        match expand(g, &defs, &mut rigid, &mut stack) {
            Ok(()) => {}
            Err(cycle) => {
                failed.extend(cycle.iter().copied());
                let r = &defs[&g];
                let by = cycle
                    .iter()
                    .map(|c| &defs[c])
                    .find(|c| c.name != r.name)
                    .unwrap_or(&defs[&cycle[cycle.len() - 1]]);
                let mut pair = [r.name.clone(), by.name.clone()];
                pair.sort();
                if !cycles_said.contains(&pair) {
                    cycles_said.push(pair);
                    errors.push(r.at.error(format!(
                        "{} and {} (at {}) make a cycle of dependent grids ({}): no grid of it is independent",
                        r.name,
                        by.name,
                        by.at.pos,
                        cycle.iter().map(|g| g.to_string()).collect::<Vec<_>>().join(" → ")
                    )));
                }
            }
        }
    }
    for g in failed {
        rigid.ties.remove(&g);
    }
    rigid
}

/// Records grid `g`'s dependency. Rigid elements that tie disjoint components of one
/// grid are joined (each card's rows, and the grid keeps what neither ties); a
/// component tied twice is an error naming both cards.
fn define<'b>(g: i64, def: Def<'b>, defs: &mut BTreeMap<i64, Def<'b>>, errors: &mut Vec<Diagnostic>) {
    match defs.get_mut(&g) {
        Some(other) if other.dependent & def.dependent != 0 => errors.push(def.at.error(format!(
            "{} makes grid {g} dependent, which {} (at {}) already makes dependent: a DOF can be dependent once",
            def.name, other.name, other.at.pos
        ))),
        Some(other) => {
            other.terms.remove(&g);
            for (h, m) in def.terms.into_iter().filter(|(h, _)| *h != g) {
                *other.terms.entry(h).or_insert_with(Matrix6::zeros) += m;
            }
            other.dependent |= def.dependent;
            if other.dependent != ALL {
                other.terms.insert(g, select(!other.dependent & ALL));
            }
            other.name = format!("{} and {}", other.name, def.name);
        }
        None => {
            defs.insert(g, def);
        }
    }
}

/// Grid `g`'s tie with its chains followed, into `rigid`; on a cycle, the grids of
/// the cycle from `g`.
fn expand(g: i64, defs: &BTreeMap<i64, Def>, rigid: &mut Rigid, stack: &mut Vec<i64>) -> Result<(), Vec<i64>> {
    if rigid.ties.contains_key(&g) {
        return Ok(());
    }
    if let Some(k) = stack.iter().position(|&s| s == g) {
        return Err(stack[k..].to_vec());
    }
    stack.push(g);
    let def = &defs[&g];
    let mut terms: BTreeMap<i64, Matrix6<f64>> = BTreeMap::new();
    for (&h, m) in &def.terms {
        if h == g || !defs.contains_key(&h) {
            *terms.entry(h).or_insert_with(Matrix6::zeros) += m;
            continue;
        }
        expand(h, defs, rigid, stack)?;
        for (k, mk) in &rigid.ties[&h].terms {
            *terms.entry(*k).or_insert_with(Matrix6::zeros) += m * mk;
        }
    }
    stack.pop();
    rigid.ties.insert(
        g,
        Tie {
            dependent: def.dependent,
            terms: terms.into_iter().filter(|(_, m)| m.iter().any(|&v| v != 0.0)).collect(),
            at: def.at.clone(),
            name: def.name.clone(),
        },
    );
    Ok(())
}

/// An RBE3's terms on its independent grids: `P_REFC Tᵣᵀ A⁻¹ Sᵢᵀ Eᵢᵀ Wᵢ Eᵢ` each (see
/// the module's doc), or why the grids do not fix the reference grid's motion.
fn rbe3_terms(r: &crate::deck::cards::Rbe3, geo: &Geometry) -> Result<BTreeMap<i64, Matrix6<f64>>, String> {
    let xr = Vector3::from(geo.positions[&r.refgrid]);
    let all: Vec<i64> = r.groups.iter().flat_map(|g| g.grids.iter().copied()).collect();
    let lc = all
        .iter()
        .map(|g| (Vector3::from(geo.positions[g]) - xr).norm())
        .sum::<f64>()
        / all.len() as f64;
    let lc = if lc > 0.0 { lc } else { 1.0 };
    // Each grid's weighted selection Eᵀ W E (diagonal) and its rigid map S, summed over
    // the groups it is in.
    let mut weighted: BTreeMap<i64, Matrix6<f64>> = BTreeMap::new();
    for group in &r.groups {
        let w = Matrix6::from_fn(|i, j| {
            if i == j && group.c.contains(i + 1) {
                group.weight * if i < 3 { 1.0 } else { lc * lc }
            } else {
                0.0
            }
        });
        for g in &group.grids {
            *weighted.entry(*g).or_insert_with(Matrix6::zeros) += w;
        }
    }
    let s = |g: i64| {
        Placement::turn_of(
            &geo.frame(g),
            &Matrix3::identity(),
            (Vector3::from(geo.positions[&g]) - xr).into(),
        )
    };
    let a: Matrix6<f64> = weighted.iter().map(|(&g, w)| s(g).transpose() * w * s(g)).sum();
    let eig = crate::numerics::symmetric_eigenvalues(a);
    let (lo, hi) = (eig.min(), eig.max());
    if !(hi > 0.0 && lo > RBE3_RANK * hi) {
        return Err(
            "its independent grids and components do not fix the reference grid's six rigid motions (collinear \
             grids, or too few components): the weighted fit has no unique answer"
                .into(),
        );
    }
    let a_inv = a.try_inverse().ok_or("its weighted fit is singular")?;
    let to_ref = select(r.refc.0) * Placement::turn_of(&geo.frame(r.refgrid), &Matrix3::identity(), [0.0; 3]);
    Ok(weighted
        .iter()
        .map(|(&g, w)| (g, to_ref * a_inv * s(g).transpose() * w))
        .collect())
}

impl Rigid {
    /// The element attached through its dependent grids' ties (unchanged without any).
    /// When each tied grid follows one grid whole, that grid replaces it and its turn
    /// is composed with Λ; otherwise the element keeps its grids and each tied grid's
    /// components gain their terms as links ([`Element::links`]). `dofs_of` gives a
    /// grid's solved DOFs.
    pub fn attach(&self, mut e: Element, dofs_of: impl Fn(i64) -> [Option<usize>; 6]) -> Element {
        let ties: Vec<Option<&Tie>> = e.grids.iter().map(|g| self.ties.get(g)).collect();
        if ties.iter().all(Option::is_none) {
            return e;
        }
        if ties.iter().flatten().all(|t| t.whole().is_some()) {
            let n = e.grids.len();
            let mut p = match e.placement.take() {
                Some(p) => (*p).clone(),
                None => Placement {
                    turn: vec![Matrix6::identity(); n],
                    points: e.kernel.points(),
                },
            };
            for (k, t) in ties.iter().enumerate() {
                if let Some((gn, map)) = t.and_then(Tie::whole) {
                    p.turn[k] *= map;
                    e.grids[k] = gn;
                    e.dofs[k] = dofs_of(gn);
                }
            }
            return e.placed(p);
        }
        let links = ties
            .iter()
            .map(|t| {
                std::array::from_fn(|c| match t {
                    Some(t) if t.ties(c) => t.functional(c, &dofs_of),
                    _ => Vec::new(),
                })
            })
            .collect();
        e.linked(links)
    }

    /// A load on grid `g` (its six components in its frame) as the grids that carry
    /// it: an independent grid's is its own; a dependent grid's goes to each grid h
    /// of its tie as Mₕᵀ f (its own kept components among them).
    pub fn carry(&self, g: i64, f: [f64; 6]) -> Vec<(i64, [f64; 6])> {
        match self.ties.get(&g) {
            None => vec![(g, f)],
            Some(t) => t
                .terms
                .iter()
                .map(|(h, m)| (*h, (m.transpose() * Vector6::from(f)).into()))
                .collect(),
        }
    }

    /// The components of grid `g` a rigid element makes dependent (bit c − 1 for
    /// component c); none for an independent grid.
    pub fn dependent(&self, g: i64) -> u8 {
        self.ties.get(&g).map_or(0, |t| t.dependent)
    }

    /// How many DOFs the rigid elements make dependent.
    pub fn dependent_dofs(&self) -> usize {
        self.ties.values().map(|t| t.dependent.count_ones() as usize).sum()
    }

    /// Every grid's six components from `own` (each grid's solved components, zero
    /// elsewhere): a dependent grid's through its tie.
    pub fn recover(&self, own: &impl Fn(i64) -> [f64; 6]) -> BTreeMap<i64, [f64; 6]> {
        self.ties
            .iter()
            .map(|(&g, t)| {
                let u = t
                    .terms
                    .iter()
                    .map(|(h, m)| m * Vector6::from(own(*h)))
                    .reduce(|a, b| a + b);
                (g, u.unwrap_or_default().into())
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: an RBE3 on translations alone splits a load as the textbook formula about
    /// the weighted centroid, fᵢ = wᵢF/Σw + wᵢ(J⁻¹M)×r̃ᵢ, and reads a rigid motion of
    /// its grids exactly. Model: four grids in a plane, weights 1-4, the reference
    /// grid above and off the centroid. Tolerance: round-off.
    #[test]
    fn rbe3_splits_a_load_about_the_weighted_centroid() {
        let deck = crate::deck::parse_deck_str(
            "rbe3",
            "SOL 101\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,4.,0.,0.\nGRID,3,,4.,3.,0.\nGRID,4,,0.,3.,0.\n\
             GRID,9,,1.,1.,2.\nRBE3,7,,9,123456,1.,123,1\n,2.,123,2,3.,123,3,4.,123\n,4\nENDDATA\n",
            crate::deck::ReadOptions::default(),
        )
        .unwrap();
        let (geo, _) = crate::geometry::resolve(&deck.bulk);
        let mut errors = Vec::new();
        let rigid = resolve(&deck.bulk, &geo, &mut errors);
        assert!(errors.is_empty(), "{errors:?}");
        let f = [30.0, -10.0, -100.0, 5.0, 7.0, -3.0];
        let got: BTreeMap<i64, [f64; 6]> = rigid.carry(9, f).into_iter().collect();
        let x = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [4.0, 3.0, 0.0], [0.0, 3.0, 0.0]].map(Vector3::from);
        let w = [1.0, 2.0, 3.0, 4.0];
        let sw: f64 = w.iter().sum();
        let c = x.iter().zip(&w).map(|(x, w)| x * *w).sum::<Vector3<f64>>() / sw;
        let force = Vector3::new(f[0], f[1], f[2]);
        let moment = Vector3::new(f[3], f[4], f[5]) + (Vector3::new(1.0, 1.0, 2.0) - c).cross(&force);
        let j: Matrix3<f64> = x
            .iter()
            .zip(&w)
            .map(|(x, w)| {
                let r = x - c;
                (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * *w
            })
            .sum();
        let k = j.try_inverse().unwrap() * moment;
        for (i, g) in (1..=4).enumerate() {
            let want = force * w[i] / sw + k.cross(&(x[i] - c)) * w[i];
            let have = got[&g];
            for a in 0..3 {
                assert!(
                    (have[a] - want[a]).abs() < 1e-12 * 100.0,
                    "grid {g} {a}: {} vs {}",
                    have[a],
                    want[a]
                );
            }
            assert!(have[3..].iter().all(|v| *v == 0.0));
        }
        // A rigid motion of the grids is read back exactly at the reference grid.
        let q = Vector6::new(0.1, -0.2, 0.3, 0.01, 0.02, -0.03);
        let own = |g: i64| -> [f64; 6] {
            if g == 9 {
                return [0.0; 6];
            }
            let s = Placement::turn_of(
                &Matrix3::identity(),
                &Matrix3::identity(),
                (x[g as usize - 1] - Vector3::new(1.0, 1.0, 2.0)).into(),
            );
            (s * q).into()
        };
        let u = rigid.recover(&own)[&9];
        for a in 0..6 {
            assert!((u[a] - q[a]).abs() < 1e-14, "{a}: {} vs {}", u[a], q[a]);
        }
    }

    /// Goal: two RBE2s on disjoint components of one grid join: its translations follow
    /// one grid, its rotations another, each with its lever arm. Model: grid 3 tied by
    /// CM = 123 to grid 1 and by CM = 456 to grid 2 (both off it). Reference: the
    /// rows of each card's Λ. Tolerance: exact. The same grid's translations tied by a
    /// third card is refused, naming both.
    #[test]
    fn rbe2s_on_disjoint_components_join() {
        let text = |extra: &str| {
            format!(
                "SOL 101\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,4.,1.,0.\nGRID,3,,1.,2.,3.\n\
                 RBE2,7,1,123,3\nRBE2,8,2,456,3\n{extra}ENDDATA\n"
            )
        };
        let resolved = |extra: &str| {
            let deck =
                crate::deck::parse_deck_str("joined", &text(extra), crate::deck::ReadOptions::default()).unwrap();
            let (geo, _) = crate::geometry::resolve(&deck.bulk);
            let mut errors = Vec::new();
            let rigid = resolve(&deck.bulk, &geo, &mut errors);
            (rigid, errors)
        };
        let (rigid, errors) = resolved("");
        assert!(errors.is_empty(), "{errors:?}");
        let t = &rigid.ties[&3];
        assert_eq!(t.dependent, ALL);
        assert_eq!(t.name, "RBE2 7 and RBE2 8");
        let lambda = |from: [f64; 3]| {
            let d = Vector3::new(1.0, 2.0, 3.0) - Vector3::from(from);
            Placement::turn_of(&Matrix3::identity(), &Matrix3::identity(), d.into())
        };
        let terms: BTreeMap<i64, Matrix6<f64>> = t.terms.iter().cloned().collect();
        assert_eq!(terms[&1], select(0b000111) * lambda([0.0; 3]));
        assert_eq!(terms[&2], select(0b111000) * lambda([4.0, 1.0, 0.0]));
        let (rigid, errors) = resolved("RBE2,9,2,1,3\n");
        assert!(rigid.ties.contains_key(&3));
        assert!(
            errors[0]
                .message
                .contains("RBE2 9 makes grid 3 dependent, which RBE2 7 and RBE2 8"),
            "{errors:?}"
        );
    }

    /// Goal: grids on one line do not fix a rotation: the RBE3 is refused with why.
    #[test]
    fn rbe3_on_collinear_translations_is_refused() {
        let deck = crate::deck::parse_deck_str(
            "rbe3",
            "SOL 101\nCEND\nBEGIN BULK\nGRID,1,,0.,0.,0.\nGRID,2,,4.,0.,0.\nGRID,3,,8.,0.,0.\nGRID,9,,1.,1.,2.\n\
             RBE3,7,,9,123,1.,123,1,2,3\nENDDATA\n",
            crate::deck::ReadOptions::default(),
        )
        .unwrap();
        let (geo, _) = crate::geometry::resolve(&deck.bulk);
        let mut errors = Vec::new();
        let rigid = resolve(&deck.bulk, &geo, &mut errors);
        assert!(rigid.ties.is_empty());
        assert!(errors[0].message.contains("do not fix"), "{errors:?}");
    }
}
