//! The check kinds that judge one run, one function each. The kinds that need a
//! family of runs (Δt and mesh convergence) are evaluated by the study stage
//! ([`crate::study::cases`]); [`check`] returns `None` for them.

use super::case::{rel, Case, CheckSpec, RodQuantity, Tol};
use super::{external, gold, Bound, CheckResult};
use crate::ledger::EnergyRow;
use crate::model::Model;
use crate::numerics::argmax;
use crate::physics::analytic;
use crate::physics::references::{
    infinite_plate, rod_critical_step, rod_params, semi_infinite, two_rigid_bodies, ReferenceError,
};
use crate::run::convolution::{engine_difference, Scale};
use crate::run::{run_model, Column, Engine, RunOptions, RunResult};

/// A check that cannot be evaluated on its run.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// A reference does not apply to the case's model.
    #[error("case {case}: {check}: {source}")]
    Reference {
        /// The case.
        case: String,
        /// The check.
        check: &'static str,
        /// Why.
        #[source]
        source: ReferenceError,
    },
    /// A run the check makes failed.
    #[error("case {case}: {source}")]
    Solve {
        /// The case.
        case: String,
        /// What failed.
        #[source]
        source: crate::integrate::SolveError,
    },
    /// The check needs a plate.
    #[error("case {case}: {check} needs a plate model with bending stiffness")]
    NoPlate {
        /// The case.
        case: String,
        /// The check.
        check: &'static str,
    },
    /// The check could not be computed.
    #[error("case {case}: {check}: {message}")]
    Failed {
        /// The case.
        case: String,
        /// The check.
        check: &'static str,
        /// Why.
        message: String,
    },
    /// The check needs a contact.
    #[error("case {case}: {check} needs a model with a contact")]
    NoContact {
        /// The case.
        case: String,
        /// The check.
        check: &'static str,
    },
    /// The run has no such history column.
    #[error("case {case}: the run has no history column {column}")]
    NoColumn {
        /// The case.
        case: String,
        /// The column asked for.
        column: String,
    },
    /// An external solver's file could not be read.
    #[error("case {case}: {source}")]
    External {
        /// The case.
        case: String,
        /// What failed.
        #[source]
        source: gold::CsvError,
    },
    /// A summary key names no number.
    #[error("case {case}: {source}")]
    Summary {
        /// The case.
        case: String,
        /// The key.
        #[source]
        source: crate::run::summary::UnknownKey,
    },
}

/// What every check reads: the case, its model and its run.
struct Cx<'a> {
    case: &'a Case,
    model: &'a Model,
    run: &'a RunResult,
}

impl Cx<'_> {
    fn energy(&self) -> &[EnergyRow] {
        &self.run.energy
    }
    /// Time in units of L/C for a rod target, else as it is.
    fn tcl(&self, t: f64) -> f64 {
        self.model.rod.map_or(t, |r| t / (r.length / r.wave_speed))
    }
    fn result(
        &self,
        check: String,
        value: f64,
        reference: Option<f64>,
        bound: Bound,
        passed: bool,
        detail: String,
    ) -> CheckResult {
        CheckResult::new(self.case, check, value, reference, bound, passed, detail)
    }
    fn reference<T>(&self, check: &'static str, r: Result<T, ReferenceError>) -> Result<T, CheckError> {
        r.map_err(|source| CheckError::Reference {
            case: self.case.name.clone(),
            check,
            source,
        })
    }
}

/// An optional summary value, NaN where the run has none (which fails any check).
fn or_nan(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// Evaluates one check of a case on its run; `None` for the kinds that need a family
/// of runs.
pub fn check(case: &Case, model: &Model, run: &RunResult, spec: &CheckSpec) -> Result<Option<CheckResult>, CheckError> {
    let cx = Cx { case, model, run };
    Ok(Some(match spec {
        CheckSpec::EnergyBalance { max } => energy_balance(&cx, *max),
        CheckSpec::Momentum { max } => momentum(&cx, *max)?,
        CheckSpec::ContactComplementarity => contact_complementarity(&cx),
        CheckSpec::KineticEqualsStrain { from_tcl, to_tcl, max } => {
            kinetic_equals_strain(&cx, *from_tcl, *to_tcl, *max)
        }
        CheckSpec::StrainEnergyDip {
            near_tcl,
            half_width,
            min_fraction,
            max_fraction,
        } => strain_energy_dip(&cx, *near_tcl, *half_width, [*min_fraction, *max_fraction]),
        CheckSpec::ShellRecoveryPatch { max } => shell_recovery_patch(&cx, *max),
        CheckSpec::Eq16Deficit {
            after_tcl,
            after,
            min,
            max,
        } => eq16_deficit(&cx, (*after_tcl, *after), *min, *max)?,
        CheckSpec::Summary {
            key,
            reference,
            tol,
            source,
        } => summary(&cx, key, *reference, tol, source)?,
        CheckSpec::SemiInfiniteRod { quantity, tol } => semi_infinite_rod(&cx, *quantity, tol)?,
        CheckSpec::DalembertStrain {
            element,
            x,
            until_tcl,
            max,
        } => dalembert_strain(&cx, *element, *x, *until_tcl, *max)?,
        CheckSpec::InfinitePlate { until_s, max } => infinite_plate_force(&cx, *until_s, *max)?,
        CheckSpec::RigidTarget { tol } => rigid_target(&cx, tol)?,
        CheckSpec::FreeDecay {
            column,
            omega,
            zeta,
            max,
            source,
        } => free_decay(&cx, column, (*omega, *zeta), *max, source)?,
        CheckSpec::CriticalStep { min_ratio } => critical_step(&cx, *min_ratio)?,
        CheckSpec::NavierFrequencies {
            meshes,
            modes,
            max,
            thickness,
        } => navier_frequencies(&cx, *meshes, *modes, *max, *thickness)?,
        CheckSpec::NavierStrains { mesh, until_s, max } => navier_strains(&cx, *mesh, *until_s, *max)?,
        CheckSpec::CylinderFrequencies {
            slenderness,
            meshes,
            min_order,
            max,
        } => cylinder_frequencies(&cx, slenderness, meshes, *min_order, *max)?,
        CheckSpec::Gold { file, tol } => {
            let path = rel(case, file);
            let out = gold::compare(&path, &run.history_names(), &run.history, tol);
            cx.result(
                format!("gold {}", file.display()),
                out.worst,
                None,
                tol.bound(),
                out.passed,
                out.detail,
            )
        }
        CheckSpec::External {
            file,
            solver,
            what,
            time,
            columns,
            max,
        } => external_history(&cx, file, solver, what, time, columns, *max)?,
        CheckSpec::Superposition { max } => superposition(&cx, *max)?,
        CheckSpec::ModalEngine { max, fractions } => modal_engine(&cx, *max, fractions)?,
        CheckSpec::RigidStrain { elements, max } => rigid_strain(&cx, elements, *max)?,
        CheckSpec::FailureIndices { allowables, sb } => failure_indices(&cx, *allowables, *sb),
        CheckSpec::DtConvergence { .. }
        | CheckSpec::MeshConvergence { .. }
        | CheckSpec::ConvergesToReference { .. } => return Ok(None),
        CheckSpec::StaticDeflection { .. }
        | CheckSpec::StaticOrder { .. }
        | CheckSpec::BeamFrequencies { .. }
        | CheckSpec::SameFrequencies { .. } => {
            return Err(CheckError::Failed {
                case: case.name.clone(),
                check: "static",
                message: "a static check judges a case's static decks, not a run".into(),
            })
        }
    }))
}

/// [`CheckSpec::FailureIndices`]: the summary's largest Tsai-Hill and bond indices
/// against the same recomputed from the history's columns by name.
fn failure_indices(cx: &Cx, allowables: [f64; 5], sb: f64) -> CheckResult {
    let [xt, xc, yt, yc, s] = allowables;
    let hill = |s1: f64, s2: f64, t: f64| {
        let x = if s1 >= 0.0 { xt } else { xc };
        let y = if s2 >= 0.0 { yt } else { yc };
        (s1 * s1 - s1 * s2) / (x * x) + (s2 / y).powi(2) + (t / s).powi(2)
    };
    let names = cx.run.history_names();
    let column = |name: &str| names.iter().position(|n| n == name);
    let (mut largest_hill, mut largest_bond, mut points, mut bonds) = (f64::NAN, f64::NAN, 0usize, 0usize);
    for (j, name) in names.iter().enumerate() {
        let Some(stem) = name.strip_prefix("ply_stress_") else {
            continue;
        };
        if let Some(point) = stem.strip_suffix("_11") {
            let (Some(j2), Some(j12)) = (
                column(&format!("ply_stress_{point}_22")),
                column(&format!("ply_stress_{point}_12")),
            ) else {
                continue;
            };
            points += 1;
            for row in &cx.run.history {
                largest_hill = largest_hill.max(hill(row[j], row[j2], row[j12]));
            }
        } else if stem.ends_with("_1z") || stem.ends_with("_2z") {
            bonds += 1;
            for row in &cx.run.history {
                largest_bond = largest_bond.max(row[j].abs() / sb);
            }
        }
    }
    let failure = cx.run.summary.failure.as_ref();
    let reported = [
        failure.map(|f| f.theory.largest),
        failure.and_then(|f| f.bond.as_ref()).map(|b| b.largest),
    ];
    let d = |r: Option<f64>, c: f64| r.map_or(f64::INFINITY, |r| (r - c).abs() / c.abs());
    let (dh, db) = (d(reported[0], largest_hill), d(reported[1], largest_bond));
    let value = dh.max(db);
    cx.result(
        "failure_indices HILL and BOND from the history".into(),
        value,
        None,
        Bound::at_most(1e-12),
        value <= 1e-12,
        format!(
            "{points} ply points: HILL {largest_hill:.6e} (summary {}); {} interface columns: BOND {largest_bond:.6e} \
             (summary {})",
            reported[0].map_or("none".into(), |v| format!("{v:.6e}")),
            bonds,
            reported[1].map_or("none".into(), |v| format!("{v:.6e}")),
        ),
    )
}

/// The direct run against the same case on the modal engine at rising cutoffs.
fn modal_engine(cx: &Cx, max: f64, fractions: &[f64]) -> Result<CheckResult, CheckError> {
    const CHECK: &str = "modal_engine";
    let failed = |message: String| CheckError::Failed {
        case: cx.case.name.clone(),
        check: CHECK,
        message,
    };
    if fractions.is_empty() || fractions.windows(2).any(|w| w[0] >= w[1]) || fractions[0] <= 0.0 {
        return Err(failed(format!(
            "fractions {fractions:?}: give positive fractions of the default cutoff, ascending"
        )));
    }
    let run = |cutoff: Option<f64>| {
        let opts = RunOptions {
            engine: Engine::Modal,
            snapshot_times: Vec::new(),
            modal: crate::run::modal::ModalParams {
                cutoff,
                ..Default::default()
            },
            ..super::case_options(cx.case)
        };
        run_model(cx.model, &opts).map_err(|e| failed(e.to_string()))
    };
    let direct = &cx.run.summary.contact;
    if direct.duration.is_none() {
        return Err(failed(
            "the direct run's contact does not end: no duration to compare".into(),
        ));
    }
    // The default cutoff, from the engine itself.
    let default = run(None)?;
    let cut = default
        .summary
        .run
        .modal
        .as_ref()
        .map(|t| t.cutoff_frequency)
        .ok_or_else(|| failed("the modal run reports no truncation".into()))?;
    let mut rows = Vec::new();
    for &f in fractions {
        let other;
        let r = if f == 1.0 {
            &default
        } else {
            other = run(Some(f * cut))?;
            &other
        };
        // A modal contact that does not end differs without bound.
        let (d, p) = r.summary.contact.relative_difference(direct);
        let d = d.unwrap_or(f64::INFINITY);
        let modes = r.summary.run.modal.as_ref().map_or(0, |t| t.modes);
        rows.push((f, modes, d.max(p), d, p));
    }
    let falls = rows.windows(2).all(|w| w[1].2 < w[0].2);
    let last = rows.last().expect("fractions are not empty");
    let detail = rows
        .iter()
        .map(|(f, m, _, d, p)| format!("{f} of {cut:.4e}: {m} modes, duration {d:.1e}, peak force {p:.1e}"))
        .collect::<Vec<_>>()
        .join("; ");
    Ok(cx.result(
        CHECK.into(),
        last.2,
        None,
        Bound::at_most(max),
        last.2 <= max && falls,
        if falls {
            detail
        } else {
            format!("the difference does not fall as modes are added: {detail}")
        },
    ))
}

/// The direct run against the same case on the convolution engine.
fn superposition(cx: &Cx, max: f64) -> Result<CheckResult, CheckError> {
    const CHECK: &str = "superposition";
    let opts = RunOptions {
        engine: Engine::Convolution,
        snapshot_times: Vec::new(),
        ..super::case_options(cx.case)
    };
    let conv = run_model(cx.model, &opts).map_err(|e| CheckError::Failed {
        case: cx.case.name.clone(),
        check: CHECK,
        message: e.to_string(),
    })?;
    let direct = cx.run;
    let units = &direct.summary.units;
    let worst = engine_difference(direct, &conv, Scale::Column).ok_or_else(|| CheckError::Failed {
        case: cx.case.name.clone(),
        check: CHECK,
        message: format!(
            "the engines ran {} and {} steps",
            direct.series.force.len() - 1,
            conv.series.force.len() - 1
        ),
    })?;
    let (v, what, t) = worst;
    Ok(cx.result(
        CHECK.into(),
        v,
        None,
        Bound::of_peak(max),
        v <= max,
        format!("largest: {what} at t = {t:.4e} {}", units.time),
    ))
}

/// The written strains of elements inside a rigid region against the largest written
/// strain (see [`CheckSpec::RigidStrain`]).
fn rigid_strain(cx: &Cx, elements: &[i64], max: f64) -> Result<CheckResult, CheckError> {
    let strain = |eid: Option<i64>| -> Vec<usize> {
        cx.run
            .history_columns
            .iter()
            .enumerate()
            .filter(|(_, c)| match c {
                Column::Element { eid: e, value } => {
                    value.measure == crate::elements::Measure::Strain && eid.is_none_or(|x| x == *e)
                }
                _ => false,
            })
            .map(|(j, _)| j)
            .collect()
    };
    let peak_of = |cols: &[usize]| {
        cx.run
            .history
            .iter()
            .flat_map(|row| cols.iter().map(move |&j| row[j].abs()))
            .fold(0.0f64, f64::max)
    };
    let inside: Vec<usize> = elements.iter().flat_map(|&e| strain(Some(e))).collect();
    if inside.is_empty() {
        return Err(CheckError::Failed {
            case: cx.case.name.clone(),
            check: "rigid_strain",
            message: format!("no strain of elements {elements:?} is written: add them to the deck's STRESS set"),
        });
    }
    let (peak, worst) = (peak_of(&strain(None)), peak_of(&inside));
    let value = if peak > 0.0 { worst / peak } else { 0.0 };
    Ok(cx.result(
        "rigid_strain".into(),
        value,
        None,
        Bound::of_peak(max),
        value <= max,
        format!("elements {elements:?}: largest |strain| {worst:.3e} against {peak:.3e} over the written elements"),
    ))
}

fn energy_balance(cx: &Cx, max: f64) -> CheckResult {
    let e = cx.energy();
    let (k, v) = argmax(e.iter().map(|r| r.error.abs()));
    cx.result(
        "energy_balance".into(),
        v,
        None,
        Bound::at_most(max),
        v <= max,
        format!("largest at t = {:.4e} {}", e[k].time, cx.run.summary.units.time),
    )
}

fn momentum(cx: &Cx, max: f64) -> Result<CheckResult, CheckError> {
    let e = cx.energy();
    let c = cx.model.contact.as_ref().ok_or_else(|| CheckError::NoContact {
        case: cx.case.name.clone(),
        check: "momentum",
    })?;
    let p_ref = (c.impactor.mass * cx.model.v0[c.impactor.dof]).abs();
    let (k, v) = argmax(e.iter().map(|r| (r.momentum - e[0].momentum).abs() / p_ref));
    Ok(cx.result(
        "momentum".into(),
        v,
        None,
        Bound::at_most(max),
        v <= max,
        format!("largest at t = {:.4e} {}", e[k].time, cx.run.summary.units.time),
    ))
}

fn contact_complementarity(cx: &Cx) -> CheckResult {
    let s = &cx.run.series;
    // α less the permanent indentation left so far: α itself for an elastic contact.
    let closure = cx
        .model
        .contact
        .as_ref()
        .map_or_else(|| s.alpha.clone(), |c| c.closure(&s.alpha));
    let mut bad = 0usize;
    let mut first = None;
    for (k, row) in cx.energy().iter().enumerate() {
        let (a, f) = (closure[k], s.force[k]);
        let ok =
            f >= 0.0 && ((f > 0.0) == (a > 0.0)) && ((row.se_impactor > 0.0) == (a > 0.0)) && row.se_impactor >= 0.0;
        if !ok {
            bad += 1;
            first.get_or_insert(s.time[k]);
        }
    }
    cx.result(
        "contact_complementarity".into(),
        bad as f64,
        None,
        Bound::within(0.0, "0 violations".into()),
        bad == 0,
        first.map_or("F ≥ 0, F > 0 and SE_i > 0 exactly when α > α0".into(), |t| {
            format!("first violation at t = {t:.4e} {}", cx.run.summary.units.time)
        }),
    )
}

fn kinetic_equals_strain(cx: &Cx, from_tcl: f64, to_tcl: f64, max: f64) -> CheckResult {
    let e = cx.energy();
    let u0 = e.first().map_or(1.0, |r| r.total);
    let (k, v) = argmax(e.iter().map(|r| {
        let t = cx.tcl(r.time);
        if t >= from_tcl && t <= to_tcl {
            (r.ke_target - r.se_target).abs() / u0
        } else {
            0.0
        }
    }));
    cx.result(
        format!("kinetic_equals_strain tC/L {from_tcl}..{to_tcl}"),
        v,
        None,
        Bound::at_most(max),
        v <= max,
        format!("largest at tC/L = {:.4}", cx.tcl(e[k].time)),
    )
}

fn strain_energy_dip(cx: &Cx, near_tcl: f64, half_width: f64, [lo, hi]: [f64; 2]) -> CheckResult {
    let e = cx.energy();
    let end = or_nan(cx.run.summary.contact.intervals.first().map(|i| i[1]));
    let plateau = e.iter().find(|r| r.time >= end).map_or(f64::NAN, |r| r.se_target);
    let (k, v) = argmax(e.iter().map(|r| {
        if (cx.tcl(r.time) - near_tcl).abs() <= half_width {
            -r.se_target
        } else {
            f64::NEG_INFINITY
        }
    }));
    let frac = -v / plateau;
    let at = cx.tcl(e[k].time);
    let ok = frac >= lo && frac <= hi && (at - near_tcl).abs() < half_width;
    cx.result(
        format!("strain_energy_dip near tC/L {near_tcl}"),
        frac,
        Some(0.5 * (lo + hi)),
        Bound::within(0.5 * (hi - lo), format!("depth in [{lo}, {hi}] within ±{half_width}")),
        ok,
        format!("minimum SE_t = {frac:.4} of its plateau at tC/L = {at:.4}"),
    )
}

/// The field of the shell patch, about a point (x0, y0): membrane strains (εx, εy, γxy)
/// and w = ½·a·x² + ½·b·y² + c·x·y, so that κ = (−a, −b, −2c) and, Kirchhoff's fibre
/// strain being ε(z) = ε_m + z·κ, ε(z) = (εx − a·z, εy − b·z, γxy − 2c·z).
const PATCH_MEMBRANE: [f64; 3] = [2e-4, -1e-4, 3e-4];
const PATCH_CURVATURE: [f64; 3] = [1.0e-2, -6.0e-3, 3.5e-3];

/// See [`CheckSpec::ShellRecoveryPatch`]. Nodal values per grid (T1, T2, T3, R1, R2,
/// R3) from the field with NASTRAN's rotations R1 = ∂w/∂y, R2 = −∂w/∂x; the expected
/// strains come from the field and the section's thickness alone, not from the element.
fn shell_recovery_patch(cx: &Cx, max: f64) -> CheckResult {
    let [ex, ey, gxy] = PATCH_MEMBRANE;
    let [a, b, c] = PATCH_CURVATURE;
    let (mut worst, mut count, mut at) = (0.0f64, 0, 0);
    let mut cards: Vec<&str> = Vec::new();
    for e in cx.model.elements.iter() {
        let Some(section) = e.kernel.family().shell() else {
            continue;
        };
        if !cards.contains(&e.kernel.card()) {
            cards.push(e.kernel.card());
        }
        let xy = e.kernel.points();
        let (x0, y0) = (xy[0][0], xy[0][1]);
        let mut ue = Vec::with_capacity(24);
        for p in &xy {
            let (x, y) = (p[0] - x0, p[1] - y0);
            let w = 0.5 * a * x * x + 0.5 * b * y * y + c * x * y;
            let (wx, wy) = (a * x + c * y, b * y + c * x);
            ue.extend([ex * x + 0.5 * gxy * y, ey * y + 0.5 * gxy * x, w, wy, -wx, 0.0]);
        }
        let got = e.kernel.recover(&ue, crate::elements::Output::Strain);
        let h = 0.5 * section.thickness;
        let want: Vec<f64> = [-h, h]
            .iter()
            .flat_map(|&z| [ex - a * z, ey - b * z, gxy - 2.0 * c * z])
            .collect();
        let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let d = got
            .iter()
            .zip(&want)
            .map(|(g, w)| (g - w).abs() / scale)
            .fold(if got.len() == want.len() { 0.0 } else { f64::INFINITY }, f64::max);
        if d > worst || d.is_nan() {
            (worst, at) = (d, e.eid);
        }
        count += 1;
    }
    cx.result(
        "shell_recovery_patch".into(),
        worst,
        None,
        Bound::of_peak(max),
        count > 0 && worst <= max,
        if count == 0 {
            "no shell element in the model".into()
        } else {
            format!(
                "{count} {}s, fibre strains at ∓T/2 of constant strain and curvature; largest at element {at}",
                cards.join("s and ")
            )
        },
    )
}

/// `from`: (tC/L, time in the deck's unit); exactly one is given, tC/L for a rod only.
fn eq16_deficit(cx: &Cx, from: (Option<f64>, Option<f64>), min: f64, max: f64) -> Result<CheckResult, CheckError> {
    let failed = |message: String| CheckError::Failed {
        case: cx.case.name.clone(),
        check: "eq16_deficit",
        message,
    };
    let (start, said) = match from {
        (Some(tcl), None) if cx.model.rod.is_some() => (tcl, format!("tC/L = {tcl}")),
        (None, Some(t)) => (cx.tcl(t), format!("t = {t:e} {}", cx.run.summary.units.time)),
        (Some(_), None) => return Err(failed("after_tcl needs a rod target; give `after` (a time)".into())),
        _ => return Err(failed("give one of after_tcl (a rod's tC/L) or after (a time)".into())),
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for r in cx
        .energy()
        .iter()
        .filter(|r| cx.tcl(r.time) >= start && r.ke_target > 0.0)
    {
        let d = (r.ke_target - r.ke_target_eq16) / r.ke_target;
        lo = lo.min(d);
        hi = hi.max(d);
    }
    Ok(cx.result(
        "eq16_deficit".into(),
        hi,
        Some(0.5 * (min + max)),
        Bound::within(0.5 * (max - min), format!("in [{min:.1e}, {max:.1e}]")),
        lo >= min && hi <= max,
        format!("(½vᵀMv − Eq.16)/½vᵀMv ranges {lo:.3e}..{hi:.3e} after {said}"),
    ))
}

fn summary(cx: &Cx, key: &str, reference: f64, tol: &Tol, source: &str) -> Result<CheckResult, CheckError> {
    let v = cx.run.summary.number(key).map_err(|source| CheckError::Summary {
        case: cx.case.name.clone(),
        source,
    })?;
    let v = or_nan(v);
    Ok(cx.result(
        key.to_string(),
        v,
        Some(reference),
        tol.bound(),
        tol.accepts(v, reference),
        source.to_string(),
    ))
}

fn semi_infinite_rod(cx: &Cx, quantity: RodQuantity, tol: &Tol) -> Result<CheckResult, CheckError> {
    let (_, ev, lc) = cx.reference("semi_infinite_rod", semi_infinite(cx.model))?;
    let s = &cx.run.summary;
    let rod = s.rod.as_ref();
    let (v, r) = match quantity {
        RodQuantity::ContactEndTcl => (or_nan(rod.and_then(|r| r.contact_end_tcl)), ev.contact_end / lc),
        RodQuantity::VelocityZeroTcl => (
            or_nan(rod.and_then(|r| r.velocity_zero_time_tcl)),
            ev.velocity_zero / lc,
        ),
        RodQuantity::PeakForce => (s.contact.peak_force, ev.peak_force),
        RodQuantity::PeakForceTcl => (or_nan(s.contact.peak_force_time) / lc, ev.peak_time / lc),
        RodQuantity::ReboundVelocity => (or_nan(s.impactor.rebound_velocity), ev.rebound_velocity),
        RodQuantity::TransferredFraction => (
            or_nan(s.energy.transferred_fraction),
            1.0 - (ev.rebound_velocity / s.impactor.initial_velocity).powi(2),
        ),
    };
    Ok(cx.result(
        format!("semi_infinite_rod {}", quantity.name()),
        v,
        Some(r),
        tol.bound(),
        tol.accepts(v, r),
        "ball on a semi-infinite rod, RK4 h = L/C/2e5".into(),
    ))
}

fn dalembert_strain(cx: &Cx, element: i64, x: f64, until_tcl: f64, max: f64) -> Result<CheckResult, CheckError> {
    let (tr, _, lc) = cx.reference("dalembert_strain", semi_infinite(cx.model))?;
    let rod = cx.reference("dalembert_strain", rod_params(cx.model))?;
    let column = Column::rod_strain(element);
    let j = cx.run.column(&column).ok_or_else(|| CheckError::NoColumn {
        case: cx.case.name.clone(),
        column: column.name(),
    })?;
    let peak = tr.force.iter().fold(0.0f64, |a, &f| a.max(f)) / rod.ea;
    let h = &cx.run.history;
    let (k, v) = argmax(h.iter().map(|h| {
        if h[0] / lc < until_tcl {
            (h[j] - analytic::dalembert_strain(&tr, x, rod.wave_speed, rod.ea, h[0])).abs() / peak
        } else {
            0.0
        }
    }));
    Ok(cx.result(
        format!("dalembert_strain element {element}"),
        v,
        None,
        Bound::of_peak(max),
        v <= max,
        format!("largest at tC/L = {:.4}", h[k][0] / lc),
    ))
}

fn infinite_plate_force(cx: &Cx, until: f64, max: f64) -> Result<CheckResult, CheckError> {
    let (p, z) = cx.reference("infinite_plate", infinite_plate(cx.model))?;
    let tr = p.integrate(until, until / 2.0e4);
    let peak = tr.force.iter().fold(0.0f64, |a, &f| a.max(f));
    let sr = &cx.run.series;
    let (k, v) = argmax(sr.time.iter().zip(&sr.force).map(|(&t, &f)| {
        if t <= until {
            (f - analytic::force_at(&tr, t)).abs() / peak
        } else {
            0.0
        }
    }));
    Ok(cx.result(
        format!("infinite_plate force to {:.0} us", until * 1e6),
        v,
        None,
        Bound::of_peak(max),
        v <= max,
        format!(
            "impedance 8√(ρh D*) = {z:.4e}; largest at t = {:.4e} {}",
            sr.time[k], cx.run.summary.units.time
        ),
    ))
}

fn rigid_target(cx: &Cx, tol: &Tol) -> Result<CheckResult, CheckError> {
    let model = cx.model;
    let c = model.contact.as_ref().ok_or_else(|| CheckError::NoContact {
        case: cx.case.name.clone(),
        check: "rigid_target",
    })?;
    let (_, mu) = cx.reference("rigid_target", two_rigid_bodies(model))?;
    let (_, f, dur) = analytic::rigid_target(mu, model.v0[c.impactor.dof], c.stiffness);
    let s = &cx.run.summary;
    let (vd, vf) = (or_nan(s.contact.duration), s.contact.peak_force);
    Ok(cx.result(
        "rigid_target duration".into(),
        vd,
        Some(dur),
        tol.bound(),
        tol.accepts(vd, dur) && tol.accepts(vf, f),
        format!("peak force {vf:.5e} vs {f:.5e}; reduced mass {mu:.4e}"),
    ))
}

/// A damped structure's free decay against the damped oscillator's closed form (see
/// [`CheckSpec::FreeDecay`]), with the dissipated energy never decreasing.
fn free_decay(
    cx: &Cx,
    column: &str,
    (omega, zeta): (f64, f64),
    max: f64,
    source: &str,
) -> Result<CheckResult, CheckError> {
    let j = cx
        .run
        .history_names()
        .iter()
        .position(|x| x == column)
        .ok_or_else(|| CheckError::NoColumn {
            case: cx.case.name.clone(),
            column: column.into(),
        })?;
    let rows = &cx.run.history;
    let u0 = rows.first().map_or(f64::NAN, |r| r[j]);
    let (s, wd) = (zeta * omega, omega * (1.0 - zeta * zeta).sqrt());
    let exact = |t: f64| u0 * (-s * t).exp() * ((wd * t).cos() + s / wd * (wd * t).sin());
    let (k, v) = argmax(rows.iter().map(|r| (r[j] - exact(r[0])).abs() / u0.abs()));
    let monotone = cx
        .energy()
        .windows(2)
        .all(|w| w[1].dissipated_damping >= w[0].dissipated_damping);
    let dissipated = cx.energy().last().map_or(0.0, |r| r.dissipated_damping);
    Ok(cx.result(
        format!("free_decay {column}"),
        v,
        None,
        Bound::at_most(max),
        v <= max && monotone && dissipated > 0.0,
        format!(
            "largest at t = {:.4e} {}; ω = {omega:e}, ζ = {zeta:e} ({source}); dissipated {dissipated:.4e}{}",
            rows.get(k).map_or(f64::NAN, |r| r[0]),
            cx.run.summary.units.time,
            if monotone { "" } else { ", decreasing somewhere" }
        ),
    ))
}

/// The run's history against another solver's CSV, column by column.
fn external_history(
    cx: &Cx,
    file: &std::path::Path,
    solver: &str,
    what: &str,
    time: &str,
    columns: &std::collections::BTreeMap<String, String>,
    max: f64,
) -> Result<CheckResult, CheckError> {
    let case = || cx.case.name.clone();
    let series = external::load(&rel(cx.case, file), solver, time, columns)
        .map_err(|source| CheckError::External { case: case(), source })?;
    let name = format!("external {solver}: {what}");
    let bound = Bound::of_peak(max);
    Ok(
        match external::compare(&series, &cx.run.history_names(), &cx.run.history, cx.run.dt) {
            Ok(diffs) => {
                let (k, worst) = argmax(diffs.iter().map(|d| d.worst));
                let w = &diffs[k];
                let per_column: Vec<String> = diffs.iter().map(|d| format!("{} {:.2e}", d.ours, d.worst)).collect();
                let detail = format!(
                    "{}: worst {} at t = {:.6e} {} ({} times compared); {}",
                    file.display(),
                    w.ours,
                    w.at,
                    cx.run.summary.units.time,
                    w.compared,
                    per_column.join(", ")
                );
                cx.result(name, worst, None, bound, worst <= max, detail)
            }
            Err(e) => cx.result(name, f64::INFINITY, None, bound, false, e.to_string()),
        },
    )
}

fn critical_step(cx: &Cx, min_ratio: f64) -> Result<CheckResult, CheckError> {
    let exact = cx.reference("critical_step", rod_critical_step(cx.model))?;
    let sys = crate::assembly::assemble(cx.model);
    let used = crate::integrate::central::critical_step(cx.model, &sys).map_err(|source| CheckError::Solve {
        case: cx.case.name.clone(),
        source,
    })?;
    let ratio = used / exact;
    Ok(cx.result(
        "critical_step central".into(),
        used,
        Some(exact),
        Bound {
            rtol: Some(1.0 - min_ratio),
            atol: None,
            text: format!("in [{min_ratio}, 1] × L_e/C"),
        },
        ratio <= 1.0 && ratio >= min_ratio,
        format!(
            "Gershgorin bound 2/ω_max = {used:.5e} = {ratio:.4} × L_e/C = {exact:.5e} {}; the run's Δt = {:.5e}",
            cx.run.summary.units.time, cx.run.dt
        ),
    ))
}

/// The files the run writes (`history.csv`, `energy.csv`, `summary.json`, made by
/// [`crate::output::run_files`] and read back): the headers carry the deck's units;
/// row k of `history.csv` is at k·(output interval)·Δt and of `energy.csv` at k·Δt;
/// every number reads back to the run's own; `summary.json` reads back to the run's
/// summary, its peak force is the largest force written, and its contact intervals
/// hold exactly the written rows with a positive indentation.
pub fn written_files(case: &Case, model: &Model, run: &RunResult) -> CheckResult {
    let problems = file_problems(model, run);
    CheckResult::new(
        case,
        "written_files".into(),
        problems.len() as f64,
        None,
        Bound::within(0.0, "0 problems".into()),
        problems.is_empty(),
        if problems.is_empty() {
            "history.csv, energy.csv, summary.json read back: times, units, values and summary agree".into()
        } else {
            problems.join("; ")
        },
    )
}

/// The ledger's fields by the name and unit `energy.csv` must give each, from the
/// deck's units and each field of [`crate::ledger::EnergyRow`] read by name (not by
/// the writer's column order); `dissipated_damping` for a damped structure only,
/// `dissipated_contact` for a hysteretic contact only.
fn ledger_columns(
    units: &crate::deck::Units,
    run: &RunResult,
    booked: crate::ledger::Dissipations,
) -> Vec<(String, Vec<f64>)> {
    use crate::ledger::EnergyRow;
    let energy = format!("{}*{}", units.force, units.length);
    // Name, unit, and the field itself.
    type Field = (&'static str, String, fn(&EnergyRow) -> f64);
    let mut fields: Vec<Field> = vec![
        ("time", units.time.clone(), |r| r.time),
        ("ke_impactor", energy.clone(), |r| r.ke_impactor),
        ("se_impactor", energy.clone(), |r| r.se_impactor),
        ("ke_target", energy.clone(), |r| r.ke_target),
        ("ke_target_eq16", energy.clone(), |r| r.ke_target_eq16),
        ("se_target", energy.clone(), |r| r.se_target),
        ("total", energy.clone(), |r| r.total),
        ("external_work", energy.clone(), |r| r.external_work),
        ("error", "-".into(), |r| r.error),
        ("energy_ratio", "-".into(), |r| r.energy_ratio),
        ("momentum", format!("{}*{}", units.force, units.time), |r| r.momentum),
    ];
    fields.extend(booked.booked().into_iter().map(|d| (d.column, energy.clone(), d.value)));
    fields
        .into_iter()
        .map(|(name, unit, f)| (format!("{name} [{unit}]"), run.energy.iter().map(f).collect()))
        .collect()
}

/// A written CSV against the run's own columns, each found by its header (name and
/// unit), never by position: a column named as no expected one, one written twice or
/// missing, and one whose values are not the run's to the last bit (NaN where the run
/// has NaN) are problems.
fn columns_by_name(file: &str, header: &[String], rows: &[Vec<f64>], expected: &[(String, Vec<f64>)]) -> Vec<String> {
    let mut bad = Vec::new();
    for (k, h) in header.iter().enumerate() {
        if header[..k].contains(h) {
            bad.push(format!("{file}: column {h:?} is written twice"));
        }
        match expected.iter().find(|(name, _)| name == h) {
            None => bad.push(format!(
                "{file}: column {h:?} is no column of the run (by that name and unit)"
            )),
            Some((_, values)) => {
                let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
                let column: Vec<f64> = rows.iter().map(|r| r.get(k).copied().unwrap_or(f64::NAN)).collect();
                if column.len() != values.len() || !column.iter().zip(values).all(|(a, b)| same(*a, *b)) {
                    bad.push(format!("{file}: column {h:?} does not read back to the run's {h}"));
                }
            }
        }
    }
    for (name, _) in expected {
        if !header.contains(name) {
            bad.push(format!("{file}: the run's {name:?} is not written"));
        }
    }
    bad
}

fn file_problems(model: &Model, run: &RunResult) -> Vec<String> {
    let mut bad = Vec::new();
    let files = crate::output::run_files(model, run);
    let file = |name: &str| {
        files
            .iter()
            .find(|f| f.0 == name)
            .map(|f| f.1.as_slice())
            .unwrap_or_default()
    };
    let read = |name: &str| crate::verify::gold::read_from(file(name), name);
    // The deck's units, not the summary's: a writer that relabels is caught.
    let units = &model.units;
    let dt = run.dt;
    let on_time = |t: f64, k: usize, per: usize| (t - (k * per) as f64 * dt).abs() <= 1e-9 * dt;
    match read("history.csv") {
        Err(e) => bad.push(e.to_string()),
        Ok((header, rows)) => {
            if header.first().map(String::as_str) != Some(&format!("time [{}]", units.time)) {
                bad.push(format!(
                    "history.csv: time header {:?}, the deck's time unit is {}",
                    header.first(),
                    units.time
                ));
            }
            if header.get(1).map(String::as_str) != Some(&format!("contact_force [{}]", units.force)) {
                bad.push(format!(
                    "history.csv: force header {:?}, the deck's force unit is {}",
                    header.get(1),
                    units.force
                ));
            }
            let every = model.time.every.max(1);
            if let Some(k) = (0..rows.len()).find(|&k| !on_time(rows[k][0], k, every)) {
                bad.push(format!(
                    "history.csv: row {} at t = {:e}, expected {:e} (every {every} steps of {dt:e})",
                    k + 1,
                    rows[k][0],
                    (k * every) as f64 * dt
                ));
            }
            let u = crate::run::UnitSystem::of(units);
            let expected: Vec<(String, Vec<f64>)> = run
                .history_columns
                .iter()
                .enumerate()
                .map(|(j, c)| (c.header(&u), run.history.iter().map(|r| r[j]).collect()))
                .collect();
            bad.extend(columns_by_name("history.csv", &header, &rows, &expected));
            let fmax = rows.iter().map(|r| r[1]).fold(0.0, f64::max);
            let peak = run.summary.contact.peak_force;
            if fmax > peak || (every == 1 && fmax != peak) {
                bad.push(format!("summary peak force {peak:e}, history.csv's largest {fmax:e}"));
            }
            let inside = |t: f64| run.summary.contact.intervals.iter().any(|i| t >= i[0] && t <= i[1]);
            // A row's force and indentation (columns 1 and 2).
            let closed = |r: &Vec<f64>| model.contact.as_ref().is_some_and(|c| c.closed(r[2], r[1]));
            if let Some(r) = rows.iter().find(|r| closed(r) != inside(r[0]) && r[0] > 0.0) {
                bad.push(format!(
                    "history.csv: indentation {:e} at t = {:e} disagrees with the summary's contact intervals",
                    r[2], r[0]
                ));
            }
        }
    }
    match read("energy.csv") {
        Err(e) => bad.push(e.to_string()),
        Ok((header, rows)) => {
            if header.first().map(String::as_str) != Some(&format!("time [{}]", units.time)) {
                bad.push(format!("energy.csv: time header {:?}", header.first()));
            }
            if !run.energy.is_empty() && rows.len() != run.summary.run.steps_done + 1 {
                bad.push(format!(
                    "energy.csv: {} rows for {} steps",
                    rows.len(),
                    run.summary.run.steps_done
                ));
            }
            if let Some(k) = (0..rows.len()).find(|&k| !on_time(rows[k][0], k, 1)) {
                bad.push(format!(
                    "energy.csv: row {} at t = {:e}, expected {:e}",
                    k + 1,
                    rows[k][0],
                    k as f64 * dt
                ));
            }
            bad.extend(columns_by_name(
                "energy.csv",
                &header,
                &rows,
                &ledger_columns(units, run, crate::ledger::Dissipations::of(model)),
            ));
        }
    }
    match serde_json::from_slice::<crate::run::Summary>(file("summary.json")) {
        Err(e) => bad.push(format!("summary.json: {e}")),
        Ok(s) if s != run.summary => bad.push("summary.json does not read back to the run's summary".into()),
        Ok(_) => {}
    }
    bad
}

/// Recovered stresses against the material law applied to the recovered strains, for
/// every element whose stresses are written, by its kind's law
/// ([`crate::elements::Kernel::material_law`]: a rod's σ = E·ε, a shell's
/// σ(z) = G_m·ε_m + G_b·κz from its two written fibres), a kind that recovers
/// stresses and answers no law failing the check; a laminate's ply stresses σ = Q·ε
/// in each ply's axes (Q of its MAT8), from the ply strains written beside them; on a
/// plate flexible in transverse shear, each ply interface's (τ1z, τ2z) as the
/// equilibrium distribution of the element's written shear forces
/// ([`crate::laminate::Interface::stresses`]), columns matched by name. Value: the
/// largest difference relative to the peak |stress|; round-off passes (≤ 1e-10), a
/// wrong sign, scale or component fails.
pub fn material_law(case: &Case, model: &Model, run: &RunResult) -> CheckResult {
    use crate::elements::{Measure, Recovered, Transverse};
    let (mut worst, mut peak, mut elements) = (0.0f64, 0.0f64, 0usize);
    let mut at = String::new();
    let mut unanswered = Vec::new();
    for e in model.elements.iter() {
        // Every value the kind recovers with stresses, written: its stresses against
        // its law (Kernel::material_law) applied to its written strains.
        let names = e.kernel.recovered(crate::elements::Output::Stress);
        let Some(cols) = names
            .iter()
            .map(|r| run.column(&Column::Element { eid: e.eid, value: *r }))
            .collect::<Option<Vec<usize>>>()
        else {
            continue;
        };
        let of = |m: Measure| -> Vec<usize> {
            names
                .iter()
                .zip(&cols)
                .filter(|(r, _)| r.measure == m)
                .map(|(_, &j)| j)
                .collect()
        };
        let (stresses, strains) = (of(Measure::Stress), of(Measure::Strain));
        if stresses.is_empty() {
            continue;
        }
        elements += 1;
        for row in &run.history {
            let Some(law) = e
                .kernel
                .material_law(&strains.iter().map(|&j| row[j]).collect::<Vec<_>>())
            else {
                unanswered.push(format!("element {} ({})", e.eid, e.kernel.card()));
                break;
            };
            let mut d = 0.0f64;
            for (&j, l) in stresses.iter().zip(&law) {
                peak = peak.max(row[j].abs());
                d = d.max((row[j] - l).abs());
            }
            if d > worst {
                (worst, at) = (d, format!("element {} at t = {:e}", e.eid, row[0]));
            }
        }
    }
    if !unanswered.is_empty() {
        return CheckResult::new(
            case,
            "material_law stress = law(strain)".into(),
            f64::INFINITY,
            None,
            Bound::of_peak(1e-10),
            false,
            format!("{} recover stresses and answer no material law", unanswered.join(", ")),
        );
    }
    // Ply stresses: the ply's own Q (its axes) times its written strain, at both faces.
    for (e, plies) in &model.outputs.plies {
        let eid = model.elements[*e].eid;
        let cols = Column::plies(eid, plies.len());
        let j: Vec<usize> = cols.iter().filter_map(|c| run.column(c)).collect();
        if j.len() != cols.len() {
            continue;
        }
        elements += 1;
        for row in &run.history {
            let values: Vec<f64> = j.iter().map(|&c| row[c]).collect();
            for (k, p, _, strain, stress) in crate::run::ply_points(plies, &values) {
                peak = peak.max(stress.amax());
                let d = (stress - p.q * strain).amax();
                if d > worst {
                    (worst, at) = (d, format!("element {eid} ply {} at t = {:e}", k + 1, row[0]));
                }
            }
        }
        // Interlaminar shear: each bond's equilibrium stresses from the element's
        // written transverse shear forces, matched by the columns' names.
        let bonds = Column::interlaminar(eid, plies);
        let forces = [Transverse::Qx, Transverse::Qy].map(|t| {
            run.column(&Column::Element {
                eid,
                value: Recovered {
                    measure: Measure::ShearForce(t),
                    at: None,
                },
            })
        });
        let (Some(qx), Some(qy)) = (forces[0], forces[1]) else {
            continue;
        };
        for (c, bond) in bonds.chunks(2).zip(plies.iter().filter_map(|p| p.interface.as_ref())) {
            let (Some(j1), Some(j2)) = (run.column(&c[0]), run.column(&c[1])) else {
                continue;
            };
            for row in &run.history {
                let law = bond.stresses([row[qx], row[qy]]);
                let d = (row[j1] - law[0]).abs().max((row[j2] - law[1]).abs());
                peak = peak.max(law.amax());
                if d > worst {
                    (worst, at) = (d, format!("element {eid} {} at t = {:e}", c[0].name(), row[0]));
                }
            }
        }
    }
    let value = if peak > 0.0 { worst / peak } else { 0.0 };
    CheckResult::new(
        case,
        "material_law stress = law(strain)".into(),
        value,
        None,
        Bound::of_peak(1e-10),
        value <= 1e-10,
        if elements == 0 {
            "no element stresses written".into()
        } else {
            format!("{elements} elements; largest difference at {at}")
        },
    )
}

fn navier_frequencies(
    cx: &Cx,
    meshes: [usize; 2],
    modes: usize,
    max: f64,
    thickness: Option<f64>,
) -> Result<CheckResult, CheckError> {
    let check = "navier_frequencies";
    let case = || cx.case.name.clone();
    let shells: Vec<_> = cx
        .model
        .elements
        .iter()
        .filter(|e| e.kernel.family().shell().is_some())
        .collect();
    let section = shells
        .first()
        .and_then(|e| e.kernel.family().shell().cloned())
        .filter(|s| s.g_bending.is_some())
        .ok_or_else(|| CheckError::NoPlate { case: case(), check })?;
    let g = section.g_bending.expect("filtered");
    // The case's element: a mesh of triangles when its shells are CTRIA3.
    let cells = if shells
        .iter()
        .all(|e| e.kernel.card() == crate::mesh::Cells::Tria3.card())
    {
        crate::mesh::Cells::Tria3
    } else {
        crate::mesh::Cells::Quad4
    };
    let xs = shells.iter().flat_map(|e| e.points().into_iter().map(|p| p[0]));
    let side = xs.clone().fold(f64::NEG_INFINITY, f64::max) - xs.fold(f64::INFINITY, f64::min);
    let t = thickness.unwrap_or(section.thickness);
    let scale = t / section.thickness;
    let mass_per_area = section.mass_per_area * scale;
    let d = |x: f64| x * t.powi(3) / 12.0;
    // G13 and G23 (the paper's are 1e-9 of G11) are left out of the closed form.
    let dd = [d(g[(0, 0)]), d(g[(1, 1)]), d(g[(0, 1)]), d(g[(2, 2)])];
    // A shear-deformable section: Mindlin's Navier solution (K12 left out, as D16).
    let shear = section.shear.map(|k| [k[(0, 0)] * scale, k[(1, 1)] * scale]);
    let exact = match shear {
        None => analytic::navier_frequencies(side, mass_per_area, dd, modes),
        Some(k) => analytic::mindlin_navier_frequencies(side, mass_per_area, dd, k, modes),
    };
    let g6 = [g[(0, 0)], g[(0, 1)], g[(0, 2)], g[(1, 1)], g[(1, 2)], g[(2, 2)]];
    let mut fem = Vec::new();
    for n in meshes {
        let rho = mass_per_area / t;
        let plate = crate::mesh::navier_plate(n, side, t, g6, rho, shear, cells);
        let m = plate.map_err(|e| CheckError::Failed {
            case: case(),
            check,
            message: e.to_string(),
        })?;
        fem.push(
            crate::eigen::lowest_frequencies(&m, modes).map_err(|e| CheckError::Failed {
                case: case(),
                check,
                message: format!("the {n}x{n} plate: {e}"),
            })?,
        );
    }
    let r2 = (meshes[1] as f64 / meshes[0] as f64).powi(2);
    let mut worst = 0.0f64;
    let mut detail = Vec::new();
    for k in 0..exact.len() {
        // CQUAD4 converges at order 2: Richardson-extrapolated. CTRIA3's DKMT converges
        // faster in this range (its thin-plate and shear errors have opposite signs, so
        // no one order holds): its finest mesh, as it is.
        let extrapolated = match cells {
            crate::mesh::Cells::Quad4 => fem[1][k] + (fem[1][k] - fem[0][k]) / (r2 - 1.0),
            crate::mesh::Cells::Tria3 => fem[1][k],
        };
        let rel = (extrapolated - exact[k]).abs() / exact[k];
        worst = worst.max(rel);
        detail.push(format!(
            "mode {}: {:.6e} ({}) {:.6e} ({}) → {:.6e}, Navier{} {:.6e}",
            k + 1,
            fem[0][k],
            meshes[0],
            fem[1][k],
            meshes[1],
            extrapolated,
            if shear.is_some() { " (Mindlin)" } else { "" },
            exact[k]
        ));
    }
    Ok(cx.result(
        match thickness {
            None => format!("navier_frequencies {modes} modes"),
            Some(t) => format!("navier_frequencies {modes} modes, t = {t}"),
        },
        worst,
        None,
        Bound::at_most(max),
        worst <= max,
        detail.join("; "),
    ))
}

fn cylinder_frequencies(
    cx: &Cx,
    slenderness: &[f64],
    meshes: &[[usize; 2]],
    min_order: f64,
    max: f64,
) -> Result<CheckResult, CheckError> {
    use analytic::{cylinder_lowest_frequency, ShellTheory};
    let check = "cylinder_frequencies";
    let failed = |message: String| CheckError::Failed {
        case: cx.case.name.clone(),
        check,
        message,
    };
    if meshes.len() < 3 {
        return Err(failed(
            "three meshes at least: the order is read from the last three".into(),
        ));
    }
    let nu = 0.3;
    let (mut worst, mut passed, mut detail) = (0.0f64, true, Vec::new());
    for &slender in slenderness {
        let t = 1.0 / slender;
        let (sanders, mode) = cylinder_lowest_frequency(1.0, 2.0, t, nu, ShellTheory::Sanders);
        let (donnell, _) = cylinder_lowest_frequency(1.0, 2.0, t, nu, ShellTheory::Donnell);
        let mut w = Vec::new();
        for &[around, along] in meshes {
            let m = crate::mesh::cylinder_model(t, around, along).map_err(|e| failed(e.to_string()))?;
            let f = crate::eigen::lowest_frequencies(&m, 4)
                .map_err(|e| failed(format!("the {around}×{along} cylinder: {e}")))?;
            // The lowest nonzero frequency, as Ω = √(ρ(1 − ν²)/E)·Rω with R = E = ρ = 1.
            let omega = f.iter().copied().find(|&x| x > 1e-6).unwrap_or(f64::NAN);
            w.push(omega * (1.0 - nu * nu).sqrt());
        }
        // Order and extrapolation on the last three meshes (h ∝ 1/around); falling
        // frequencies make the changes' ratio positive.
        let k = meshes.len() - 3;
        let h = [0, 1, 2].map(|i| 1.0 / meshes[k + i][0] as f64);
        let (p, extrapolated) = crate::numerics::three_mesh_order(h, [w[k], w[k + 1], w[k + 2]]);
        let error = (extrapolated / sanders - 1.0).abs();
        let falling = w.windows(2).all(|x| x[1] < x[0]);
        let apart = donnell - extrapolated > 0.5 * (donnell - sanders);
        passed &= falling && p >= min_order && error <= max && apart;
        worst = worst.max(error);
        detail.push(format!(
            "R/t {slender}: Ω {} ({}), order {p:.2}, extrapolated {extrapolated:.5}; Sanders {sanders:.5} at (m, n) = \
             {mode:?}, Donnell {donnell:.5}{}{}",
            w.iter().map(|x| format!("{x:.5}")).collect::<Vec<_>>().join(", "),
            meshes
                .iter()
                .map(|m| format!("{}×{}", m[0], m[1]))
                .collect::<Vec<_>>()
                .join(", "),
            if falling { "" } else { "; not falling" },
            if apart { "" } else { "; nearer to Donnell's" },
        ));
    }
    Ok(cx.result(
        format!("cylinder_frequencies R/t {slenderness:?}"),
        worst,
        None,
        Bound {
            text: format!("≤ {max:.1e}, order ≥ {min_order}, falling"),
            ..Bound::at_most(max)
        },
        passed,
        detail.join("; "),
    ))
}

fn navier_strains(cx: &Cx, n: usize, until: f64, max: [f64; 2]) -> Result<CheckResult, CheckError> {
    use crate::mesh::{Edges, PlateMesh, PLATE_SIDE};
    let check = "navier_strains";
    let failed = |message: String| CheckError::Failed {
        case: cx.case.name.clone(),
        check,
        message,
    };
    let mesh = PlateMesh::new(n).map_err(|e| failed(e.to_string()))?;
    let deck = crate::mesh::plate_deck_with(n, Edges::SimplySupported, crate::mesh::Cells::Quad4)
        .map_err(|e| failed(e.to_string()))?;
    let model =
        crate::model_from_text(&format!("plate-{n}x{n}-simply-supported"), &deck).map_err(|e| failed(e.to_string()))?;
    let mut o = super::case_options(cx.case);
    let dt = o.dt.unwrap_or(model.time.dt);
    o.dt = Some(dt);
    o.steps = Some((until / dt).round() as usize);
    o.snapshot_times = Vec::new();
    let run = run_model(&model, &o).map_err(|e| failed(e.to_string()))?;
    let section = model
        .elements
        .iter()
        .find_map(|e| e.kernel.family().shell())
        .and_then(|s| s.d().map(|d| (d, s.mass_per_area, s.thickness)));
    let (d, mass_per_area, t) = section.ok_or_else(|| CheckError::NoPlate {
        case: cx.case.name.clone(),
        check,
    })?;
    let plate = analytic::NavierPlate {
        side: PLATE_SIDE,
        mass_per_area,
        d: [d[(0, 0)], d[(1, 1)], d[(0, 1)], d[(2, 2)]],
    };
    // Plate coordinates from a corner: the centre element's corners carry the load,
    // the gage elements' centres are on the y axis through the plate's centre.
    let (centre, h) = (PLATE_SIDE / 2.0, PLATE_SIDE / n as f64);
    let loads =
        [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0]].map(|[a, b]| [centre + a * h / 2.0, centre + b * h / 2.0]);
    let gages = mesh.gage_elements();
    let c = n.div_ceil(2);
    let gauges = gages.map(|e| [centre, centre + ((e / mesh.base) as f64 - c as f64) * h]);
    let exact = plate.fibre_strains(&loads, &run.series.force, dt, &gauges, t / 2.0);
    let names = run.history_names();
    let mut worst = 0.0f64;
    let mut detail = Vec::new();
    for (g, e) in gages.iter().enumerate() {
        let name = format!("strain_{e}_z2_yy");
        let j = names
            .iter()
            .position(|x| *x == name)
            .ok_or_else(|| CheckError::NoColumn {
                case: cx.case.name.clone(),
                column: name.clone(),
            })?;
        let (mut num, mut den) = (0.0, 0.0);
        for row in run.history.iter().filter(|r| r[0] <= until * (1.0 + 1e-9)) {
            let k = (row[0] / dt).round() as usize;
            let reference = exact[k][g][1];
            num += (row[j] - reference).powi(2);
            den += reference * reference;
        }
        let rel = (num / den).sqrt();
        worst = worst.max(rel / max[g]);
        detail.push(format!(
            "gage {} {name} (y = {:.4}): {rel:.4e} (≤ {:.1e})",
            ["A", "B"][g],
            gauges[g][1] - centre,
            max[g]
        ));
    }
    Ok(cx.result(
        format!("navier_strains {n}x{n} simply supported"),
        worst,
        None,
        Bound {
            text: "≤ 1 (difference / its bound)".into(),
            ..Bound::at_most(1.0)
        },
        worst <= 1.0,
        format!("relative L2 difference until {until:e}: {}", detail.join("; ")),
    ))
}

/// A static case's deflection at `point` along `direction`, deck by deck: the
/// translation of the grid there in the basic system (a grid within 1e-6 of the
/// model's size of the point, in every deck).
fn static_deflections(
    case: &Case,
    solutions: &[crate::run::statics::StaticSolution],
    point: [f64; 3],
    direction: [f64; 3],
    rotation: bool,
) -> Result<Vec<f64>, CheckError> {
    let d = nalgebra::Vector3::from(direction);
    if d.norm() == 0.0 {
        return Err(CheckError::Failed {
            case: case.name.clone(),
            check: "static",
            message: "the direction is zero".into(),
        });
    }
    let d = d.normalize();
    solutions
        .iter()
        .map(|s| {
            let size = s
                .grids
                .iter()
                .flat_map(|g| g.position)
                .fold(0.0f64, |m, x| m.max(x.abs()))
                .max(1.0);
            let g = s.grid_at(point, 1e-6 * size).ok_or_else(|| CheckError::Failed {
                case: case.name.clone(),
                check: "static",
                message: format!("{}: no grid at {point:?}", s.deck),
            })?;
            Ok(nalgebra::Vector3::from(if rotation { g.rotation } else { g.basic }).dot(&d))
        })
        .collect()
}

/// A static deck's structure and all its natural frequencies, or why not.
fn structure_frequencies(deck: &crate::deck::Deck) -> Result<(crate::model::Structure, Vec<f64>), String> {
    let (s, _) = crate::model::build_structure(deck).map_err(|e| e.to_string())?;
    let f = crate::assembly::frequencies_of(&s.elements, s.dofs.len(), usize::MAX)
        .ok_or_else(|| format!("{}: the massless DOFs' stiffness is singular", deck.name))?;
    Ok((s, f))
}

/// The lowest natural frequencies of a static case's decks against its first deck's
/// (see [`CheckSpec::SameFrequencies`]).
fn same_frequencies(
    case: &Case,
    decks: &[crate::deck::Deck],
    modes: usize,
    max: f64,
) -> Result<CheckResult, CheckError> {
    let failed = |message: String| CheckError::Failed {
        case: case.name.clone(),
        check: "same_frequencies",
        message,
    };
    if decks.len() < 2 {
        return Err(failed(
            "needs two decks or more: the first and those compared with it".into(),
        ));
    }
    let mut all = Vec::new();
    for deck in decks {
        let (_, mut f) = structure_frequencies(deck).map_err(failed)?;
        f.sort_by(f64::total_cmp);
        if f.len() < modes {
            return Err(failed(format!(
                "{}: {} frequencies, fewer than {modes}",
                deck.name,
                f.len()
            )));
        }
        f.truncate(modes);
        all.push((deck.name.clone(), f));
    }
    let (first, base) = &all[0];
    let worst = all[1..]
        .iter()
        .flat_map(|(_, f)| f.iter().zip(base).map(|(a, b)| (a / b - 1.0).abs()))
        .fold(0.0f64, f64::max);
    Ok(CheckResult::new(
        case,
        format!("same_frequencies {modes} modes"),
        worst,
        None,
        Bound::at_most(max),
        worst <= max,
        format!(
            "{} against {first} ({:.6e} … {:.6e})",
            all[1..].iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", "),
            base[0],
            base[modes - 1]
        ),
    ))
}

/// The natural frequencies of a static case's beams against their closed forms (see
/// [`CheckSpec::BeamFrequencies`]).
fn beam_frequencies(
    case: &Case,
    decks: &[crate::deck::Deck],
    modes: usize,
    max: f64,
    min_order: f64,
) -> Result<CheckResult, CheckError> {
    let failed = |message: String| CheckError::Failed {
        case: case.name.clone(),
        check: "beam_frequencies",
        message,
    };
    let mut errors: Vec<Vec<f64>> = Vec::new();
    let mut names = Vec::new();
    for deck in decks {
        let (s, fem) = structure_frequencies(deck).map_err(failed)?;
        let beams: Vec<_> = s
            .elements
            .iter()
            .filter_map(|e| match e.kernel.family() {
                crate::elements::Family::Beam { section, length } => Some((*section, length)),
                _ => None,
            })
            .collect();
        let Some(&(sec, _)) = beams.first() else {
            return Err(failed(format!("{}: no CBAR or CBEAM", deck.name)));
        };
        let l: f64 = beams.iter().map(|b| b.1).sum();
        let m = sec.rho * sec.area + sec.nsm;
        let mut exact = Vec::new();
        for k in 1..=modes {
            let kl = k as f64 * std::f64::consts::PI / l;
            exact.push(("plane 1", k, kl * kl * (sec.e * sec.i1 / m).sqrt()));
            exact.push(("plane 2", k, kl * kl * (sec.e * sec.i2 / m).sqrt()));
            if sec.torsional_inertia > 0.0 {
                exact.push(("torsion", k, kl * (sec.g * sec.j / sec.torsional_inertia).sqrt()));
            }
        }
        errors.push(
            exact
                .iter()
                .map(|&(_, _, w)| fem.iter().map(|f| (f / w - 1.0).abs()).fold(f64::INFINITY, f64::min))
                .collect(),
        );
        if names.is_empty() {
            names = exact.iter().map(|(p, k, _)| format!("{p} {k}")).collect();
        }
    }
    let finest = errors.last().cloned().unwrap_or_default();
    let worst = finest.iter().fold(0.0f64, |m, &e| m.max(e));
    let orders: Vec<f64> = match &errors[..] {
        [.., a, b] => a.iter().zip(b).map(|(a, b)| (a / b).log2()).collect(),
        _ => Vec::new(),
    };
    let lowest = orders.iter().fold(f64::INFINITY, |m, &p| m.min(p));
    let list = |v: &[f64], f: &dyn Fn(f64) -> String| {
        names
            .iter()
            .zip(v)
            .map(|(n, x)| format!("{n}: {}", f(*x)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    Ok(CheckResult::new(
        case,
        format!("beam_frequencies {modes} modes a family"),
        worst,
        None,
        Bound {
            text: format!("≤ {max:.1e}, every order ≥ {min_order}"),
            ..Bound::at_most(max)
        },
        worst <= max && lowest >= min_order,
        format!(
            "finest deck's relative errors {}; orders {}",
            list(&finest, &|x| format!("{x:.2e}")),
            list(&orders, &|x| format!("{x:.2}"))
        ),
    ))
}

/// Judges a static case's check on its decks and their solutions (in the case's
/// order).
pub fn static_check(
    case: &Case,
    decks: &[crate::deck::Deck],
    solutions: &[crate::run::statics::StaticSolution],
    spec: &CheckSpec,
) -> Result<CheckResult, CheckError> {
    let list = |v: &[f64]| v.iter().map(|x| format!("{x:.6e}")).collect::<Vec<_>>().join(", ");
    let names = solutions.iter().map(|s| s.deck.as_str()).collect::<Vec<_>>().join(", ");
    match spec {
        CheckSpec::StaticDeflection {
            point,
            direction,
            reference,
            source,
            max,
            falling: sequence,
            rotation,
        } => {
            let w = static_deflections(case, solutions, *point, *direction, *rotation)?;
            let err: Vec<f64> = w.iter().map(|x| (x / reference - 1.0).abs()).collect();
            let (value, falling, text) = if *sequence {
                let finest = *err.last().unwrap_or(&f64::NAN);
                let falling = err.windows(2).all(|p| p[1] < p[0]);
                (finest, falling, format!("≤ {max:.1e} of the reference, falling"))
            } else {
                let worst = err.iter().fold(0.0f64, |m, &e| if e.is_nan() { e } else { m.max(e) });
                (worst, true, format!("≤ {max:.1e} of the reference, every deck"))
            };
            Ok(CheckResult::new(
                case,
                "static_deflection".into(),
                value,
                None,
                Bound {
                    text,
                    ..Bound::at_most(*max)
                },
                value <= *max && falling,
                format!(
                    "{names}: {} against {reference:e} ({source}); relative errors {}{}",
                    list(&w),
                    list(&err),
                    if falling { "" } else { ": not falling mesh by mesh" }
                ),
            ))
        }
        CheckSpec::StaticOrder {
            point,
            direction,
            reference,
            min,
        } => {
            let w = static_deflections(case, solutions, *point, *direction, false)?;
            let [a, b, c] = w[w.len() - 3..] else {
                unreachable!("read_case asks for three decks at least")
            };
            let ratio = (a - b) / (b - c);
            let (p, extrapolated) = crate::numerics::three_mesh_order([4.0, 2.0, 1.0], [a, b, c]);
            Ok(CheckResult::new(
                case,
                "static_order".into(),
                p,
                None,
                Bound {
                    text: format!("≥ {min}"),
                    ..Bound::at_most(f64::INFINITY)
                },
                p >= *min && ratio > 0.0,
                format!(
                    "{names}: {}; Richardson's extrapolation {extrapolated:.6e}, {:.2e} from {reference:e}{}",
                    list(&w),
                    (extrapolated / reference - 1.0).abs(),
                    if ratio > 0.0 {
                        ""
                    } else {
                        "; the last changes alternate in sign"
                    }
                ),
            ))
        }
        CheckSpec::BeamFrequencies { modes, max, min_order } => beam_frequencies(case, decks, *modes, *max, *min_order),
        CheckSpec::SameFrequencies { modes, max } => same_frequencies(case, decks, *modes, *max),
        _ => Err(CheckError::Failed {
            case: case.name.clone(),
            check: "static",
            message: "a transient check judges a run, not static decks".into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::columns_by_name;

    /// Goal: written columns are judged by name and unit, not position: two labels
    /// swapped, a unit misnamed, a column written twice or left out are each a problem;
    /// the columns in another order are not.
    #[test]
    fn written_columns_are_matched_by_name_and_unit() {
        let expected = vec![
            ("time [s]".to_string(), vec![0.0, 1.0]),
            ("ke_target [lbf*in]".to_string(), vec![3.0, 4.0]),
            ("ke_target_eq16 [lbf*in]".to_string(), vec![5.0, f64::NAN]),
        ];
        let h = |names: &[&str]| names.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let rows = vec![vec![0.0, 5.0, 3.0], vec![1.0, f64::NAN, 4.0]];
        let reordered = h(&["time [s]", "ke_target_eq16 [lbf*in]", "ke_target [lbf*in]"]);
        assert!(columns_by_name("energy.csv", &reordered, &rows, &expected).is_empty());
        let swapped = h(&["time [s]", "ke_target [lbf*in]", "ke_target_eq16 [lbf*in]"]);
        let p = columns_by_name("energy.csv", &swapped, &rows, &expected);
        assert_eq!(p.len(), 2, "{p:?}");
        assert!(p[0].contains("\"ke_target [lbf*in]\" does not read back"), "{p:?}");
        let unit = h(&["time [ms]", "ke_target_eq16 [lbf*in]", "ke_target [lbf*in]"]);
        let p = columns_by_name("energy.csv", &unit, &rows, &expected);
        assert!(
            p.iter().any(|m| m.contains("\"time [ms]\" is no column of the run")),
            "{p:?}"
        );
        assert!(
            p.iter().any(|m| m.contains("the run's \"time [s]\" is not written")),
            "{p:?}"
        );
        let twice = h(&["time [s]", "time [s]", "ke_target [lbf*in]"]);
        let p = columns_by_name("energy.csv", &twice, &rows, &expected);
        assert!(p.iter().any(|m| m.contains("written twice")), "{p:?}");
        assert!(
            p.iter().any(|m| m.contains("ke_target_eq16 [lbf*in]\" is not written")),
            "{p:?}"
        );
    }
}
