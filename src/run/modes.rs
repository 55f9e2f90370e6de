//! Normal modes (NASTRAN-95's SOL 3, MSC's SOL 103): the real eigenvalues and
//! eigenvectors of K φ = λ M φ on the structure's assembly, extracted by
//! shift-and-invert Lanczos ([`crate::eigen::lanczos`]) as the case control's METHOD
//! selects them (an EIGR or EIGRL). M is the elements' own mass matrices (impactlab's
//! shells and rods lump theirs, as NASTRAN does by default). A free DOF that no
//! element stiffens and none gives mass is held (NASTRAN's AUTOSPC); one with mass
//! and no stiffness is kept, and has a zero root.
//!
//! Which roots, by METHOD (BULK.TXT, EIGR): every method gives the lowest roots at or
//! above F1, at most ND of them: INV, DET, UINV and UDET ND (default 3·NE) lowest
//! (NASTRAN-95's inverse power method, asked for 3 roots in 0.89-2.4 Hz in d03011a,
//! prints the third at 4.53 Hz); GIV, MGIV, HOU, MHOU, AHOU and AGIV the ND lowest
//! "positive roots" when ND > 0, else every root from F1 to F2; FEER the ND lowest
//! (NASTRAN's FEER finds those nearest F1, and as many more as it takes to make one
//! accurate: the roots impactlab gives are among them when F1 is below the lowest);
//! EIGRL (LAN) those from V1 to V2, at most ND.
//!
//! Each root's modal effective mass in the six rigid-body directions of the basic
//! system is the base-excitation participation of the solved DOFs: (φᵀMD)² for a
//! mass-normalised φ, D the rigid-body motion (about the basic origin for the
//! rotations); over all roots they sum to DᵀMD, which the running sums are fractions
//! of.

use super::statics::{displacements, GridDisplacement, StaticError};
use super::UnitSystem;
use crate::assembly::assemble_elements;
use crate::deck::cards::{Eigr, Norm};
use crate::deck::{Deck, Diagnostic};
use crate::eigen::{lanczos, LanczosParams, Roots, INACCURATE};
use crate::model::{build_structure, DofLabel, ModelError};
use serde::Serialize;

/// One root.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mode {
    /// Its number, from 1 in ascending order.
    pub mode: usize,
    /// λ = ω².
    pub eigenvalue: f64,
    /// ω = √λ (radians per unit time).
    pub radians: f64,
    /// ω/2π (cycles per unit time).
    pub cycles: f64,
    /// φᵀMφ of the eigenvector as normalised.
    pub generalized_mass: f64,
    /// φᵀKφ = λ φᵀMφ.
    pub generalized_stiffness: f64,
    /// Its backward error, ‖Kφ − λMφ‖ / ((‖K‖ + |λ|‖M‖)‖φ‖) (see
    /// [`crate::eigen::Eigenpairs::residuals`]).
    pub residual: f64,
    /// Its modal effective mass in each rigid-body direction of the basic system
    /// (T1, T2, T3; R1, R2, R3 about the basic origin): (φᵀMD)²/(φᵀMφ), D the
    /// rigid-body motion over the solved DOFs. Mass units for T, mass·length² for R.
    pub effective_mass: [f64; 6],
    /// The running sum of the effective masses, modes 1 to this one, as a fraction
    /// of DᵀMD (the mass the solved DOFs move with in that direction).
    pub effective_mass_sum: [f64; 6],
}

/// What a normal modes solution gives.
#[derive(Debug, Clone, Serialize)]
pub struct ModalSolution {
    /// The deck's name.
    pub deck: String,
    /// SHA-256 of the deck's bytes.
    pub deck_sha256: String,
    /// The deck's units.
    pub units: UnitSystem,
    /// The EIGR or EIGRL the case control's METHOD selects: its card, set and method.
    pub method: String,
    /// The roots asked for, in words.
    pub roots_asked: String,
    /// How the eigenvectors are normalised.
    pub normalised: String,
    /// Solved DOFs.
    pub dofs: usize,
    /// Free DOFs with neither stiffness nor mass, held (NASTRAN's AUTOSPC).
    pub autospc: usize,
    /// The Lanczos shift σ of the roots found (0, or below the rigid-body roots).
    pub shift: f64,
    /// Lanczos vectors formed (a step of the block recurrence forms four; the key keeps
    /// its name from when a step formed one), in both extractions where a free
    /// structure's was made again from a second shift.
    pub lanczos_steps: usize,
    /// The roots found, ascending.
    pub modes: Vec<Mode>,
    /// Each mode's grid displacements.
    #[serde(skip)]
    pub shapes: Vec<Vec<GridDisplacement>>,
    /// Where the time went (not written: outputs repeat to the byte).
    #[serde(skip)]
    pub timing: ModalTiming,
}

/// Where a normal modes solution's time goes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ModalTiming {
    /// Building the structure and assembling K and M.
    pub build: std::time::Duration,
    /// Factorising K − σM.
    pub factor: std::time::Duration,
    /// Solves with the factor.
    pub solves: std::time::Duration,
    /// The Lanczos extraction in all (factorisation, solves, re-orthogonalisation,
    /// tridiagonal eigenproblems, Ritz vectors).
    pub lanczos: std::time::Duration,
}

/// Component `l` of the rigid-body motion `d` of the basic system (0-2: a unit
/// translation along X, Y, Z; 3-5: a unit rotation about X, Y, Z through the basic
/// origin), in the grid's displacement frame; 0 on a scalar point.
fn rigid_body(geo: &crate::geometry::Geometry, l: &DofLabel, d: usize) -> f64 {
    use nalgebra::Vector3;
    let Some(x) = geo.positions.get(&l.point).filter(|_| l.comp > 0) else {
        return 0.0;
    };
    let axis = Vector3::ith(d % 3, 1.0);
    let (u, theta) = if d < 3 {
        (axis, Vector3::zeros())
    } else {
        (axis.cross(&Vector3::from(*x)), axis)
    };
    let t = geo.frame(l.point).transpose();
    let c = usize::from(l.comp) - 1;
    if c < 3 {
        (t * u)[c]
    } else {
        (t * theta)[c - 3]
    }
}

/// A deck refused for one reason.
fn refuse(d: Diagnostic) -> StaticError {
    StaticError::Model(ModelError { diagnostics: vec![d] })
}

/// The roots an EIGR or EIGRL asks for.
fn roots_of(e: &Eigr) -> Result<(Roots, String), StaticError> {
    let w = |f: f64| (2.0 * std::f64::consts::PI * f).powi(2);
    let [f1, f2] = e.range;
    // From F1 > 0; from F1 = 0 or blank every root, rigid-body roots (λ = 0 to
    // round-off, of either sign) included.
    let above = f1.filter(|&f| f > 0.0).map_or(f64::NEG_INFINITY, w);
    let from = f1.map(|f| format!(" from {f}")).unwrap_or_default();
    let up_to = |f: f64| format!(" up to {f}");
    let (count, below) = match e.method.as_str() {
        "INV" | "DET" | "UINV" | "UDET" | "SINV" => {
            (e.nd.or(e.ne.filter(|&n| n > 0).map(|n| n.saturating_mul(3))), None)
        }
        "GIV" | "MGIV" | "HOU" | "MHOU" | "AHOU" | "AGIV" => match e.nd {
            Some(n) => (Some(n), None),
            None => (None, f2.map(w)),
        },
        m if m.starts_with("FEER") => (Some(e.nd.unwrap_or(1)), None),
        _ => (e.nd, f2.map(w)),
    };
    if count.is_none() && below.is_none() {
        return Err(refuse(e.at.error(format!(
            "{} {} asks for no number of roots (ND) and no upper frequency: say how many roots or up to which \
             frequency",
            e.at.name, e.sid
        ))));
    }
    let words = match (count, below) {
        (Some(n), None) => format!("the {n} lowest roots{from} (cycles per unit time)"),
        (Some(n), Some(_)) => format!(
            "at most {n} roots{from}{} (cycles per unit time)",
            up_to(f2.unwrap_or_default())
        ),
        _ => format!(
            "every root{from}{} (cycles per unit time)",
            up_to(f2.unwrap_or_default())
        ),
    };
    Ok((
        Roots {
            above,
            below,
            count: count.map(|n| n as usize),
        },
        words,
    ))
}

/// Solves a normal modes deck (read with [`crate::deck::MODES`] as its solution): the
/// roots its METHOD's EIGR or EIGRL asks for, with the model builder's warnings.
pub fn solve(deck: &Deck) -> Result<(ModalSolution, Vec<Diagnostic>), StaticError> {
    let Some(sel) = &deck.case.method else {
        return Err(refuse(Diagnostic::error(
            deck.case.at.clone(),
            "a normal modes deck (SOL 103) needs METHOD = n in its case control, selecting an EIGR or EIGRL",
        )));
    };
    let Some(card) = deck.bulk.eigrs.iter().find(|e| e.sid == sel.id) else {
        return Err(refuse(
            Diagnostic::error(
                Some(sel.pos.clone()),
                format!("METHOD = {} selects no EIGR or EIGRL of that set", sel.id),
            )
            .card("METHOD"),
        ));
    };
    let (roots, roots_asked) = roots_of(card)?;
    let method = format!("{} {} ({})", card.at.name, card.sid, card.method);
    solve_for(deck, &roots, roots_asked, card.norm, method)
}

/// The `count` lowest roots of a deck's structure (rigid-body roots included),
/// normalised to unit generalised mass, whatever its solution sequence: what
/// `impactlab check --modes N` prints.
pub fn lowest(deck: &Deck, count: usize) -> Result<(ModalSolution, Vec<Diagnostic>), StaticError> {
    let roots = Roots {
        above: f64::NEG_INFINITY,
        below: None,
        count: Some(count),
    };
    let asked = format!("the {count} lowest roots");
    solve_for(deck, &roots, asked, Norm::Mass, "Lanczos (check --modes)".into())
}

/// What to warn of when some roots found have a backward error past
/// [`INACCURATE`]: the roots of a Krylov space that spans the whole space with mass are
/// all taken as exact, and on a free structure the highest come out so where the
/// extraction from a second shift ([`crate::eigen::lanczos`]) has not made them
/// accurate.
pub fn inaccurate_roots(modes: &[Mode]) -> Option<String> {
    let bad: Vec<&Mode> = modes.iter().filter(|m| m.residual > INACCURATE).collect();
    let worst = bad.iter().max_by(|a, b| a.residual.total_cmp(&b.residual))?;
    let (first, last) = (bad[0], bad[bad.len() - 1]);
    Some(format!(
        "{} of the {} roots found have a backward error above {INACCURATE:e} (modes {} to {}, {:.4e} to {:.4e} \
         cycles per unit time; the largest {:.1e}, mode {}): they are not accurate to the digits written; the \
         highest roots can come out so when most of a structure's roots are asked for: ask for fewer",
        bad.len(),
        modes.len(),
        first.mode,
        last.mode,
        first.cycles,
        last.cycles,
        worst.residual,
        worst.mode
    ))
}

/// The roots of a deck's structure that `roots` asks for.
fn solve_for(
    deck: &Deck,
    roots: &Roots,
    roots_asked: String,
    norm: Norm,
    method: String,
) -> Result<(ModalSolution, Vec<Diagnostic>), StaticError> {
    let t0 = std::time::Instant::now();
    let (s, mut warnings) = build_structure(deck)?;
    for (key, r) in deck.case.outputs.iter().filter(|(k, _)| k.as_str() != "DISP") {
        warnings.push(Diagnostic::warning(
            Some(r.pos.clone()),
            format!(
                "{key} output of a normal modes solution is not written (shapes.csv holds every mode's shape); ignored"
            ),
        ));
    }
    let n = s.dofs.len();
    let full = assemble_elements(&s.elements, n);
    let (k_diag, m_diag) = (full.k_diag(), full.m_diag());
    let mut map = vec![None; n];
    let mut kept = Vec::new();
    for i in (0..n).filter(|&i| k_diag[i] != 0.0 || m_diag[i] != 0.0) {
        map[i] = Some(kept.len());
        kept.push(i);
    }
    let sys = full.restricted(&map, kept.len());
    let labels: Vec<DofLabel> = kept.iter().map(|&i| s.dofs[i]).collect();
    let build = t0.elapsed();
    let pairs = lanczos(&sys, &labels, roots, &LanczosParams::default())?;
    let point =
        |g: i64, c: usize| -> Option<usize> { labels.iter().position(|l| l.point == g && usize::from(l.comp) == c) };
    let normalised = match norm {
        Norm::Mass => "unit generalised mass".to_string(),
        Norm::Max => "unit largest component".to_string(),
        Norm::Point(g, c) => format!(
            "unit component {c} of point {g} (the largest component where it is zero: below 1e-8 of the largest)"
        ),
    };
    // The rigid-body motions over the solved DOFs, and M times each.
    let rigid: Vec<Vec<f64>> = (0..6)
        .map(|d| labels.iter().map(|l| rigid_body(&s.geometry, l, d)).collect())
        .collect();
    let m_rigid: Vec<Vec<f64>> = rigid
        .iter()
        .map(|r| {
            let mut y = vec![0.0; r.len()];
            sys.m_mul(r, &mut y);
            y
        })
        .collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let moved: Vec<f64> = rigid.iter().zip(&m_rigid).map(|(r, mr)| dot(r, mr)).collect();
    let mut running = [0.0; 6];
    let mut modes = Vec::new();
    let mut shapes = Vec::new();
    for (k, ((lambda, phi), residual)) in pairs
        .values
        .iter()
        .zip(&pairs.vectors)
        .zip(&pairs.residuals)
        .enumerate()
    {
        let largest = phi
            .iter()
            .copied()
            .fold(0.0_f64, |a, b| if b.abs() > a.abs() { b } else { a });
        let scale = match norm {
            Norm::Mass => 1.0,
            Norm::Max => largest,
            // "Defaults to MAX if defined component is zero": zero to round-off.
            Norm::Point(g, c) => match point(g, c).map(|i| phi[i]) {
                Some(v) if v.abs() > 1e-8 * largest.abs() => v,
                _ => largest,
            },
        };
        // φ has unit generalised mass here.
        let effective_mass: [f64; 6] = std::array::from_fn(|d| dot(phi, &m_rigid[d]).powi(2));
        let effective_mass_sum: [f64; 6] = std::array::from_fn(|d| {
            running[d] += effective_mass[d];
            if moved[d] > 0.0 {
                running[d] / moved[d]
            } else {
                0.0
            }
        });
        let phi: Vec<f64> = phi.iter().map(|v| v / scale).collect();
        let generalized_mass = 1.0 / (scale * scale);
        let radians = lambda.max(0.0).sqrt();
        modes.push(Mode {
            mode: k + 1,
            eigenvalue: *lambda,
            radians,
            cycles: radians / (2.0 * std::f64::consts::PI),
            generalized_mass,
            generalized_stiffness: lambda * generalized_mass,
            residual: *residual,
            effective_mass,
            effective_mass_sum,
        });
        let mut u = vec![0.0; n];
        for (v, &i) in phi.iter().zip(&kept) {
            u[i] = *v;
        }
        shapes.push(displacements(deck, &s, &u));
    }
    if let Some(w) = inaccurate_roots(&modes) {
        warnings.push(Diagnostic::warning(None, w));
    }
    Ok((
        ModalSolution {
            deck: deck.name.clone(),
            deck_sha256: deck.sha256.clone(),
            units: UnitSystem::of(&deck.units),
            method,
            roots_asked,
            normalised,
            dofs: kept.len(),
            autospc: n - kept.len(),
            shift: pairs.shift,
            lanczos_steps: pairs.lanczos_vectors,
            modes,
            shapes,
            timing: ModalTiming {
                build,
                factor: pairs.factor_time,
                solves: pairs.solve_time,
                lanczos: pairs.time,
            },
        },
        warnings,
    ))
}
