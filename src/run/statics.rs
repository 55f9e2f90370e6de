//! A linear static solution (SOL 101): K u = f on the structure's assembly
//! ([`crate::assembly::assemble_elements`]) and the sparse Cholesky factorisation the
//! implicit schemes use ([`crate::integrate::linear::Factor`]), f the static load the
//! case control's LOAD selects ([`crate::model::loads`]), over the DOFs the selected
//! SPCs leave free but those no element stiffens and no load reaches, which are held
//! as NASTRAN's AUTOSPC holds them (a flat shell's rotation about its normal). Exact
//! up to the factorisation's round-off, which the residual ‖K u − f‖ / ‖f‖ reports.
//! A deck's SUBCASEs are its load cases ([`solve_subcases`]): one factorisation, one
//! solve for each. Enforced displacements (an SPC's D ≠ 0, the SPCDs of the LOAD set)
//! are prescribed DOFs u_e: K_kk u_k = f_k − K_ke u_e, exact.

use super::UnitSystem;
use crate::assembly::assemble_elements;
use crate::deck::{Deck, Diagnostic};
use crate::integrate::linear::Factor;
use crate::integrate::SolveError;
use crate::model::loads::{resultant, static_load_of};
use crate::model::{build_structure, ModelError, Structure};
use serde::Serialize;

/// A static (or normal modes) solution that could not be had.
#[derive(Debug, thiserror::Error)]
pub enum StaticError {
    /// The structure or its load could not be built.
    #[error("{0}")]
    Model(#[from] ModelError),
    /// The stiffness could not be factorised (a mechanism).
    #[error("{0}")]
    Solve(#[from] SolveError),
}

/// One grid's displacement, in its displacement (CD) frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridDisplacement {
    /// The grid.
    pub grid: i64,
    /// Its displacement frame's system (0: basic).
    pub cd: i64,
    /// T1, T2, T3, R1, R2, R3 (zero where constrained).
    pub u: [f64; 6],
    /// Its basic position.
    pub position: [f64; 3],
    /// Its translation in the basic system.
    pub basic: [f64; 3],
    /// Its rotation in the basic system.
    #[serde(skip)]
    pub rotation: [f64; 3],
}

/// What a static solution gives.
#[derive(Debug, Clone, Serialize)]
pub struct StaticSolution {
    /// The deck's name.
    pub deck: String,
    /// SHA-256 of the deck's bytes.
    pub deck_sha256: String,
    /// The deck's units.
    pub units: UnitSystem,
    /// The SUBCASE solved, when the deck has several.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subcase: Option<i64>,
    /// The LOAD set solved for.
    pub load_set: i64,
    /// Solved DOFs.
    pub dofs: usize,
    /// Free DOFs no element stiffens and no load reaches, held (NASTRAN's AUTOSPC);
    /// prescribed DOFs (enforced displacements) are not among them.
    pub autospc: usize,
    /// The resultant of the applied load (constrained components too) in the basic
    /// system: force, then moment about the basic origin.
    pub applied: [f64; 6],
    /// ½ uᵀ K u.
    pub strain_energy: f64,
    /// ‖K u − f‖ / ‖f‖ (0 for no load).
    pub residual: f64,
    /// The largest translation's magnitude and its grid.
    pub largest_translation: (f64, i64),
    /// Every grid, in id order.
    pub grids: Vec<GridDisplacement>,
    /// The element results case control's STRESS, STRAIN and FORCE ask for, in the
    /// order asked (written to `elements.csv`).
    #[serde(skip)]
    pub elements: Vec<ElementValues>,
}

/// One element's recovered values in a static solution (see
/// [`crate::elements::Kernel::recover`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementValues {
    /// The element.
    pub eid: i64,
    /// Its card.
    pub card: &'static str,
    /// Each value's name without the element's id: `stress_a_c`, `force_axial`.
    pub names: Vec<String>,
    /// The values.
    pub values: Vec<f64>,
}

/// What STRESS (or ELSTRESS), STRAIN and FORCE (or ELFORCE) ask of each element, as a
/// transient run writes it ([`crate::model::OutputPlan::written`]: STRESS, then STRAIN
/// of the elements STRESS does not already give, then FORCE), elements that recover
/// nothing of it (a mass) left out. A load case with a thermal load (`thermal`, the
/// first such) gets none, with a warning: the kernels recover from displacements
/// alone, and a thermal strain's free expansion would be counted as stress.
fn element_requests(
    deck: &Deck,
    s: &Structure,
    thermal: Option<&crate::deck::case::Selection>,
    warnings: &mut Vec<Diagnostic>,
) -> Vec<(usize, crate::elements::Output)> {
    if let Some(t) = thermal {
        let outputs = &deck.case.outputs;
        let asked = [
            ("STRESS", outputs.get("STRESS")),
            ("STRAIN", outputs.get("STRAIN")),
            ("FORCE", outputs.get("FORCE").or(outputs.get("ELFORCE"))),
        ];
        for (key, r) in asked.into_iter().filter_map(|(k, r)| Some((k, r?))) {
            warnings.push(Diagnostic::warning(
                Some(r.pos.clone()),
                format!(
                    "{key} output is not written under a thermal load (TEMPERATURE(LOAD) = {}): impactlab recovers \
                     element results from displacements alone, without the free thermal expansion; ignored where \
                     it applies",
                    t.id
                ),
            ));
        }
    }
    let [stress, strain, force] = crate::model::element_requests(&deck.case, &s.elements);
    let plan = crate::model::OutputPlan {
        stress,
        strain,
        force,
        ..Default::default()
    };
    plan.written()
        .filter(|&(i, what)| !s.elements[i].kernel.recovered(what).is_empty())
        .collect()
}

/// The requested elements' values at the displacements `u` of the solved DOFs.
fn element_values(s: &Structure, requests: &[(usize, crate::elements::Output)], u: &[f64]) -> Vec<ElementValues> {
    requests
        .iter()
        .map(|&(i, what)| {
            let e = &s.elements[i];
            let id = format!("_{}", e.eid);
            ElementValues {
                eid: e.eid,
                card: e.kernel.card(),
                names: e
                    .kernel
                    .recovered(what)
                    .iter()
                    .map(|r| r.name(e.eid).replacen(&id, "", 1))
                    .collect(),
                values: e.recover(u, what),
            }
        })
        .collect()
}

impl StaticSolution {
    /// The grid nearest to basic point `p`, if one lies within `tol` of it.
    pub fn grid_at(&self, p: [f64; 3], tol: f64) -> Option<&GridDisplacement> {
        let d2 = |g: &GridDisplacement| (0..3).map(|k| (g.position[k] - p[k]).powi(2)).sum::<f64>();
        self.grids
            .iter()
            .min_by(|a, b| d2(a).total_cmp(&d2(b)))
            .filter(|g| d2(g).sqrt() <= tol)
    }

    /// Grid `g`'s component `c` (1..6) in its displacement frame.
    pub fn displacement(&self, g: i64, c: usize) -> Option<f64> {
        let i = self.grids.binary_search_by_key(&g, |d| d.grid).ok()?;
        self.grids[i].u.get(c.checked_sub(1)?).copied()
    }
}

/// Solves a static deck (read with [`crate::deck::STATICS`] as its solution) for its
/// LOAD selection (its first SUBCASE's): the solution and the model builder's
/// warnings.
pub fn solve(deck: &Deck) -> Result<(StaticSolution, Vec<Diagnostic>), StaticError> {
    let (mut all, warnings) = solve_loads(deck, &[(None, deck.case.load.as_ref(), deck.case.temperature.as_ref())])?;
    Ok((all.remove(0), warnings))
}

/// Solves every SUBCASE of a static deck (the deck's one load case when it has one
/// SUBCASE or none): for each constraint set the SUBCASEs select, the structure built
/// and its stiffness factorised once, one solve for each of their LOADs; the solutions
/// in SUBCASE order.
pub fn solve_subcases(deck: &Deck) -> Result<(Vec<StaticSolution>, Vec<Diagnostic>), StaticError> {
    let subcases = &deck.case.subcases;
    if subcases.len() <= 1 {
        let (s, w) = solve(deck)?;
        return Ok((vec![s], w));
    }
    let spc_id = |s: &crate::deck::case::Subcase| s.spc.as_ref().map(|x| x.id);
    let mut sets: Vec<Option<i64>> = Vec::new();
    for s in subcases {
        if !sets.contains(&spc_id(s)) {
            sets.push(spc_id(s));
        }
    }
    if let [_] = sets.as_slice() {
        let cases: Vec<_> = subcases
            .iter()
            .map(|s| (Some(s.id), s.load.as_ref(), s.temperature.as_ref()))
            .collect();
        return solve_loads(deck, &cases);
    }
    // One structure (numbering, factorisation) a constraint set.
    let (mut all, mut warnings) = (Vec::new(), Vec::new());
    for set in sets {
        let group: Vec<_> = subcases.iter().filter(|s| spc_id(s) == set).cloned().collect();
        let mut d = deck.clone();
        d.case.spc = group[0].spc.clone();
        d.case.subcases = group;
        let cases: Vec<_> = d
            .case
            .subcases
            .iter()
            .map(|s| (Some(s.id), s.load.as_ref(), s.temperature.as_ref()))
            .collect();
        let (solutions, w) = solve_loads(&d, &cases)?;
        all.extend(solutions);
        for w in w {
            if !warnings.iter().any(|k: &Diagnostic| k.to_string() == w.to_string()) {
                warnings.push(w);
            }
        }
    }
    let order = |s: &StaticSolution| subcases.iter().position(|c| Some(c.id) == s.subcase);
    all.sort_by_key(order);
    Ok((all, warnings))
}

/// A load case: its SUBCASE, LOAD and TEMPERATURE(LOAD) selections.
type Case<'a> = (
    Option<i64>,
    Option<&'a crate::deck::case::Selection>,
    Option<&'a crate::deck::case::Selection>,
);

/// The solutions of the structure for each (SUBCASE, LOAD selection, TEMPERATURE(LOAD)
/// selection) of `cases`.
fn solve_loads(deck: &Deck, cases: &[Case]) -> Result<(Vec<StaticSolution>, Vec<Diagnostic>), StaticError> {
    let (s, mut warnings) = build_structure(deck)?;
    let thermal = cases.iter().find_map(|c| c.2);
    let requests = element_requests(deck, &s, thermal, &mut warnings);
    let element_keys = ["DISP", "STRESS", "STRAIN", "FORCE", "ELFORCE"];
    for (key, r) in deck
        .case
        .outputs
        .iter()
        .filter(|(k, _)| !element_keys.contains(&k.as_str()))
    {
        warnings.push(Diagnostic::warning(
            Some(r.pos.clone()),
            format!(
                "{key} output of a static solution is not written (displacements.csv holds every grid's \
                 displacement, elements.csv the element results asked for); ignored"
            ),
        ));
    }
    let n = s.dofs.len();
    let index: std::collections::HashMap<_, _> = s.dofs.iter().enumerate().map(|(i, l)| (*l, i)).collect();
    let mut loads = Vec::new();
    let mut forces = Vec::new();
    for (_, sel, temperature) in cases {
        let l = static_load_of(deck, &s, *sel, *temperature)?;
        let mut f = vec![0.0; n];
        for (g, l) in &l {
            // A load on a dependent grid is carried by the grids it follows.
            for (g, l) in s.rigid.carry(*g, *l) {
                for (c, v) in l.iter().enumerate() {
                    if let Some(&i) = index.get(&crate::model::DofLabel {
                        point: g,
                        comp: c as u8 + 1,
                    }) {
                        f[i] += v;
                    }
                }
            }
        }
        loads.push(l);
        forces.push(f);
    }
    // Each case's prescribed values: the SPCs' D, overridden by the SPCDs of the LOAD
    // set it selects (a LOAD combination does not select SPCDs: SPCD remark 3).
    let mut is_prescribed = vec![false; n];
    for &(i, _) in &s.prescribed {
        is_prescribed[i] = true;
    }
    let prescribed: Vec<Vec<f64>> = cases
        .iter()
        .map(|(_, sel, _)| {
            let mut u = vec![0.0; n];
            for &(i, d) in &s.prescribed {
                u[i] = d;
            }
            for p in deck.bulk.spcds.iter().filter(|p| sel.is_some_and(|l| l.id == p.sid)) {
                for comp in p.c.iter() {
                    let l = crate::model::DofLabel {
                        point: p.point,
                        comp: comp as u8,
                    };
                    if let Some(&i) = index.get(&l) {
                        u[i] = p.d;
                    }
                }
            }
            u
        })
        .collect();
    // AUTOSPC, as NASTRAN's statics does: a DOF no element stiffens (a flat shell's
    // rotation about its normal) is held, unless a load case loads it.
    let full = assemble_elements(&s.elements, n);
    let diag = full.k_diag();
    let mut map = vec![None; n];
    let mut kept = Vec::new();
    for i in (0..n).filter(|&i| !is_prescribed[i]) {
        if diag[i] != 0.0 || forces.iter().any(|f| f[i] != 0.0) {
            map[i] = Some(kept.len());
            kept.push(i);
        }
    }
    let sys = full.restricted(&map, kept.len());
    let labels: Vec<_> = kept.iter().map(|&i| s.dofs[i]).collect();
    let mut factor = Factor::new(&sys.k_csc, &labels)?;
    let mut out = Vec::new();
    for ((((subcase, sel, temperature), f), loads), ue) in cases.iter().zip(&forces).zip(&loads).zip(&prescribed) {
        // K_kk u_k = f_k − K_ke u_e, u_e the prescribed values.
        let mut kue = vec![0.0; n];
        if ue.iter().any(|&v| v != 0.0) {
            full.k_mul(ue, &mut kue);
        }
        let rhs: Vec<f64> = f.iter().zip(&kue).map(|(a, b)| a - b).collect();
        let mut uk: Vec<f64> = kept.iter().map(|&i| rhs[i]).collect();
        factor.solve_in_place(&mut uk);
        let mut u = ue.clone();
        for (k, &i) in kept.iter().enumerate() {
            u[i] = uk[k];
        }
        let mut ku = vec![0.0; n];
        full.k_mul(&u, &mut ku);
        // Over the DOFs not prescribed (a prescribed DOF's row holds its reaction).
        let free = |v: &[f64]| -> Vec<f64> { (0..n).filter(|&i| !is_prescribed[i]).map(|i| v[i]).collect() };
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let diff: Vec<f64> = ku.iter().zip(f).map(|(a, b)| a - b).collect();
        let (diff, rhs) = (free(&diff), free(&rhs));
        let residual = if norm(&rhs) > 0.0 {
            norm(&diff) / norm(&rhs)
        } else {
            0.0
        };
        let strain_energy = 0.5 * u.iter().zip(&ku).map(|(a, b)| a * b).sum::<f64>();
        let grids = displacements(deck, &s, &u);
        let largest_translation = grids
            .iter()
            .map(|d| (d.u[0].hypot(d.u[1]).hypot(d.u[2]), d.grid))
            .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
        out.push(StaticSolution {
            deck: deck.name.clone(),
            deck_sha256: deck.sha256.clone(),
            units: UnitSystem::of(&deck.units),
            subcase: *subcase,
            load_set: sel.map_or(0, |l| l.id),
            dofs: kept.len(),
            autospc: n - kept.len() - s.prescribed.len(),
            applied: resultant(loads, &s),
            strain_energy,
            residual,
            largest_translation,
            grids,
            // Under a thermal load the kernels' recovery would count the free expansion
            // as strain: nothing is written (element_requests warned).
            elements: match temperature {
                Some(_) => Vec::new(),
                None => element_values(&s, &requests, &u),
            },
        });
    }
    Ok((out, warnings))
}

/// Every grid's displacement from the solved DOFs' `u`.
pub(super) fn displacements(deck: &Deck, s: &Structure, u: &[f64]) -> Vec<GridDisplacement> {
    let mut out: Vec<GridDisplacement> = deck
        .bulk
        .grids
        .iter()
        .map(|g| GridDisplacement {
            grid: g.id,
            cd: crate::geometry::grid_systems(g, &deck.bulk).1,
            u: [0.0; 6],
            position: s.geometry.positions.get(&g.id).copied().unwrap_or_default(),
            basic: [0.0; 3],
            rotation: [0.0; 3],
        })
        .collect();
    out.sort_by_key(|d| d.grid);
    for (l, v) in s.dofs.iter().zip(u) {
        if l.comp == 0 {
            continue;
        }
        if let Ok(i) = out.binary_search_by_key(&l.point, |d| d.grid) {
            out[i].u[l.comp as usize - 1] = *v;
        }
    }
    // Dependent grids: the motion of the grids they follow, through their ties.
    let own = |g: i64| out.binary_search_by_key(&g, |d| d.grid).map_or([0.0; 6], |i| out[i].u);
    for (g, u) in s.rigid.recover(&own) {
        if let Ok(i) = out.binary_search_by_key(&g, |d| d.grid) {
            out[i].u = u;
        }
    }
    for d in &mut out {
        let t = s.geometry.frame(d.grid);
        d.basic = (t * nalgebra::Vector3::new(d.u[0], d.u[1], d.u[2])).into();
        d.rotation = (t * nalgebra::Vector3::new(d.u[3], d.u[4], d.u[5])).into();
    }
    out
}
