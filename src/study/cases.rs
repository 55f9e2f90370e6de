//! Running verification cases: each case's run, the checks that judge it
//! ([`crate::verify::check`]) and those that need a family of runs (Δt and mesh
//! convergence, here), in parallel over cases. The result is a [`CaseOutcome`] per
//! case, which `verify` judges and `report` draws without running anything again.

use super::StudyError;
use crate::integrate::Scheme;
use crate::mesh::plate_model;
use crate::model::Model;
use crate::numerics::slope;
use crate::run::{run_model, RunResult};
use crate::verify::{
    case_model, case_options, check, Bound, Case, CaseOutcome, CheckResult, CheckSpec, Quantity, Solved,
};
use std::time::Instant;

/// Runs a case and evaluates all its checks, timing each check on its own (a
/// convergence check's time includes its runs).
///
/// ```
/// let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("verification");
/// let case = impactlab::verify::read_case(&dir.join("rod-rigid.toml"))?;
/// let outcome = impactlab::study::cases::evaluate(&case)?;
/// for c in &outcome.checks {
///     assert!(c.passed, "{}: {} ({})", c.check, c.value, c.detail);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn evaluate(case: &Case) -> Result<CaseOutcome, StudyError> {
    if !case.statics.is_empty() {
        return evaluate_static(case);
    }
    let model = case_model(case)?;
    let t0 = Instant::now();
    let run = run_model(&model, &case_options(case))?;
    let wall_s = t0.elapsed().as_secs_f64();
    let mut checks = Vec::new();
    for spec in &case.checks {
        let t = Instant::now();
        let mut r = match check(case, &model, &run, spec)? {
            Some(r) => r,
            None => convergence(case, &model, &run, spec)?,
        };
        r.time_s = t.elapsed().as_secs_f64();
        checks.push(r);
    }
    // Every case: what the run writes reads back to what it computed, and the stresses
    // it writes follow the material law from its strains.
    for always in [
        crate::verify::checks::written_files,
        crate::verify::checks::material_law,
    ] {
        let t = Instant::now();
        let mut r = always(case, &model, &run);
        r.time_s = t.elapsed().as_secs_f64();
        checks.push(r);
    }
    Ok(CaseOutcome {
        case: case.clone(),
        solved: Solved::Transient {
            model: Box::new(model),
            run: Box::new(run),
        },
        checks,
        wall_s,
    })
}

/// Solves a static case's decks (SOL 101, [`crate::run::statics::solve`]) and judges
/// its checks ([`crate::verify::checks::static_check`]).
fn evaluate_static(case: &Case) -> Result<CaseOutcome, StudyError> {
    let t0 = Instant::now();
    let mut solutions = Vec::new();
    let mut decks = Vec::new();
    for d in &case.statics {
        let deck = crate::deck::read_deck(&crate::verify::case::rel(case, d), Default::default())
            .map_err(crate::model::LoadError::from)?;
        solutions.push(crate::run::statics::solve(&deck)?.0);
        decks.push(deck);
    }
    let wall_s = t0.elapsed().as_secs_f64();
    let mut checks = Vec::new();
    for spec in &case.checks {
        let t = Instant::now();
        let mut r = crate::verify::checks::static_check(case, &decks, &solutions, spec)?;
        r.time_s = t.elapsed().as_secs_f64();
        checks.push(r);
    }
    Ok(CaseOutcome {
        case: case.clone(),
        solved: Solved::Static(solutions),
        checks,
        wall_s,
    })
}

/// Evaluates cases on up to `jobs` threads; outcomes in case order, each named.
pub fn evaluate_all(cases: &[Case], jobs: usize) -> Vec<(String, Result<CaseOutcome, StudyError>)> {
    super::in_parallel(jobs, cases.len(), |i| evaluate(&cases[i]))
        .into_iter()
        .zip(cases)
        .map(|(r, c)| (c.name.clone(), r))
        .collect()
}

/// The checks that need a family of runs.
fn convergence(case: &Case, model: &Model, run: &RunResult, spec: &CheckSpec) -> Result<CheckResult, StudyError> {
    let result = |check, value, reference, tolerance, passed, detail| {
        CheckResult::new(case, check, value, reference, tolerance, passed, detail)
    };
    let list = |values: &[f64]| values.iter().map(|v| format!("{v:.6e}")).collect::<Vec<_>>().join(", ");
    match spec {
        CheckSpec::DtConvergence {
            quantity,
            runs,
            expected_order,
            tol,
        } => {
            let (dts, values) = dt_family(case, model, run, *quantity, *runs)?;
            let p = fitted_order(*quantity, &dts, &values);
            Ok(result(
                format!("dt_convergence {}", quantity.name()),
                p,
                Some(*expected_order),
                Bound::within(*tol, format!("± {tol}")),
                (p - expected_order).abs() <= *tol,
                format!("values {}", list(&values)),
            ))
        }
        CheckSpec::ConvergesToReference { expected_order, tol } => {
            let (e, reference) = errors_to_reference(case, model, run)?;
            let p = (e[0] / e[1]).log2();
            Ok(result(
                "converges_to_reference".into(),
                p,
                Some(*expected_order),
                Bound::within(*tol, format!("± {tol}")),
                (p - expected_order).abs() <= *tol,
                format!(
                    "force error against {reference}: {:.3e} at Δt, {:.3e} at Δt/2",
                    e[0], e[1]
                ),
            ))
        }
        CheckSpec::MeshConvergence { meshes, quantity, max } => {
            let mut values = Vec::new();
            for &n in meshes {
                let m = match &case.scene {
                    Some(p) => crate::scene::load_with_mesh(&crate::verify::case::rel(case, p), n)?,
                    None => plate_model(n)?,
                };
                let r = run_model(&m, &case_options(case))?;
                values.push(quantity.of(&r.summary));
            }
            let ch: Vec<f64> = values.windows(2).map(|w| ((w[1] - w[0]) / w[1]).abs()).collect();
            let last = *ch.last().unwrap_or(&f64::NAN);
            let decreasing = ch.windows(2).all(|w| w[1] < w[0]);
            Ok(result(
                format!("mesh_convergence {}", quantity.name()),
                last,
                None,
                Bound {
                    text: format!("≤ {max:.1e}, decreasing"),
                    ..Bound::at_most(*max)
                },
                last <= *max && decreasing,
                format!("meshes {meshes:?}: {}", list(&values)),
            ))
        }
        _ => unreachable!("crate::verify::check judges every other kind"),
    }
}

/// The force errors of the case's scheme at its Δt and at Δt/2 against a converged run
/// of another scheme (`energy` at Δt/8, or `newmark` when the case runs `energy`): the
/// relative L2 norm of F − F_ref over the reference's first contact, every reference
/// step, the runs' forces interpolated linearly between their steps. Runs cover the
/// reference's contact and 5 % more, not the case's whole span. Returns the two errors
/// and what the reference was.
fn errors_to_reference(case: &Case, model: &Model, run: &RunResult) -> Result<([f64; 2], String), StudyError> {
    let dt0 = run.dt;
    let independent = if run.scheme == Scheme::Energy {
        Scheme::Newmark
    } else {
        Scheme::Energy
    };
    let with = |scheme: Scheme, dt: f64, t_end: f64| -> Result<RunResult, StudyError> {
        let mut o = case_options(case);
        o.scheme = scheme;
        o.dt = Some(dt);
        o.steps = Some((t_end / dt).ceil() as usize);
        o.snapshot_times = Vec::new();
        Ok(run_model(model, &o)?)
    };
    let t_run = dt0 * run.steps as f64;
    // The runs are causal: the reference needs no step past the case's first contact
    // and a margin (the two ends differ by O(Δt²), far below 10 %).
    let case_end = run.summary.contact.intervals.first().map_or(t_run, |i| i[1]);
    let reference = with(independent, dt0 / 8.0, (1.1 * case_end).min(t_run))?;
    let end = reference
        .summary
        .contact
        .intervals
        .first()
        .map_or(t_run, |i| i[1])
        .min(t_run);
    let half = with(run.scheme, dt0 / 2.0, (1.05 * end).min(t_run))?;
    let error = |r: &RunResult| {
        let (mut num, mut den) = (0.0, 0.0);
        let s = &reference.series;
        for (&t, &f) in s.time.iter().zip(&s.force).filter(|(t, _)| **t <= end) {
            let d = crate::numerics::interp(&r.series.time, &r.series.force, t) - f;
            num += d * d;
            den += f * f;
        }
        (num / den).sqrt()
    };
    Ok(([error(run), error(&half)], format!("{independent} at Δt/8")))
}

/// The case's run and `runs − 1` more, halving Δt over the same time span: the step
/// sizes and the quantity of each.
fn dt_family(
    case: &Case,
    model: &Model,
    run: &RunResult,
    quantity: Quantity,
    runs: usize,
) -> Result<(Vec<f64>, Vec<f64>), StudyError> {
    let (dt0, t_end) = (run.dt, run.dt * run.steps as f64);
    let (mut dts, mut values) = (vec![dt0], vec![quantity.of(&run.summary)]);
    for i in 1..runs.max(3) {
        let dt = dt0 / 2f64.powi(i as i32);
        let mut o = case_options(case);
        o.dt = Some(dt);
        o.steps = Some((t_end / dt).round() as usize);
        values.push(quantity.of(&run_model(model, &o)?.summary));
        dts.push(dt);
    }
    Ok((dts, values))
}

/// The observed order: of the quantity itself for an error (energy error), of the
/// successive differences for a converging value.
fn fitted_order(quantity: Quantity, dts: &[f64], values: &[f64]) -> f64 {
    let (xs, ys): (Vec<f64>, Vec<f64>) = if quantity == Quantity::EnergyError {
        (
            dts.iter().map(|d| d.ln()).collect(),
            values.iter().map(|v| v.abs().ln()).collect(),
        )
    } else {
        (
            dts[1..].iter().map(|d| d.ln()).collect(),
            values.windows(2).map(|w| (w[0] - w[1]).abs().ln()).collect(),
        )
    };
    slope(&xs, &ys)
}
