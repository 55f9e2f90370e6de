//! A run on the convolution engine ([`crate::integrate::convolution`]): the kernel
//! pass, the contact history, then the requested outputs rebuilt as history sums.
//!
//! What it computes, and how:
//! - contact force, indentation, impactor displacement and velocity: every step,
//!   exactly as the direct scheme defines them;
//! - every `history.csv` column: its own kernel, recorded in the one linear pass,
//!   convolved with the loads at the rows written (plus the impactor's part);
//! - the ledger: the impactor's KE_i and SE_i exactly, the target's total from the
//!   discrete work identity, the external work of a non-conservative contact and the
//!   momentum from their kernels; KE_t, its Eq. 16 form and SE_t are not computed
//!   (NaN): they need the whole field.
//!
//! Field snapshots need the whole field too: this engine refuses them.

use super::{
    history_columns, history_row, linear_outputs, summarize, Engine, GuardTrip, RowHead, RunError, RunOptions,
    RunResult, Series,
};
use crate::assembly::System;
use crate::integrate::convolution::{contact_history, convolve_at, unit_response, ConvStep, RunFailure};
use crate::integrate::{ContactForm, RunStats, Scheme};
use crate::ledger::EnergyRow;
use crate::model::{apply, Model};
use indicatif::ProgressBar;

impl From<RunFailure> for RunError {
    fn from(e: RunFailure) -> Self {
        match e {
            RunFailure::Model(m) => RunError::Engine(m.to_string()),
            RunFailure::Solve(s) => RunError::Solve(s),
        }
    }
}

/// Runs a model whose system is assembled on the convolution engine.
pub fn run_convolution(model: &Model, sys: &System, opts: &RunOptions) -> Result<RunResult, RunError> {
    let t0 = std::time::Instant::now();
    let form = match opts.scheme {
        Scheme::Newmark => ContactForm::Endpoint,
        Scheme::Energy => ContactForm::DiscreteGradient,
        s => {
            return Err(RunError::Engine(format!(
                "the convolution engine runs the trapezoidal schemes (newmark, energy), not {s}"
            )))
        }
    };
    if !opts.snapshot_times.is_empty() {
        return Err(RunError::Engine(
            "field snapshots need the whole field: run them on the direct engine".into(),
        ));
    }
    let ct = model
        .contact
        .as_ref()
        .ok_or_else(|| RunError::Engine("the convolution engine needs a model with a contact".into()))?;
    let dt = opts.dt.unwrap_or(model.time.dt);
    let steps = opts.steps.unwrap_or(model.time.steps);
    let bar = opts.progress.clone().unwrap_or_else(ProgressBar::hidden);
    bar.set_length(2 * steps as u64);
    bar.set_position(0);

    // Functionals the ledger needs beyond the outputs, over the target's DOFs.
    let imp = ct.impactor.dof;
    let comp = model.dofs[imp].comp;
    let m_diag = sys.m_diag();
    let target = model.target_mask();
    let momentum_t: Vec<(usize, f64)> = (0..model.n())
        .filter(|&i| target[i] && model.dofs[i].comp == comp && m_diag[i] != 0.0)
        .map(|i| (i, m_diag[i]))
        .collect();
    let nc_t: Vec<(usize, f64)> = ct.nonconservative.iter().copied().filter(|&(j, _)| j != imp).collect();
    let nc_imp: f64 = ct
        .nonconservative
        .iter()
        .filter(|&&(j, _)| j == imp)
        .map(|&(_, r)| r)
        .sum();

    // The kernel pass: each step's outputs, then the two ledger functionals.
    let mut kernels: Vec<Vec<f64>> = Vec::with_capacity(steps);
    let kernel = unit_response(model, sys, dt, steps, &mut |u, v| {
        let mut k = linear_outputs(model, u, v);
        k.push(apply(&momentum_t, v));
        k.push(apply(&nc_t, u));
        kernels.push(k);
        if kernels.len() % 64 == 0 {
            bar.set_position(kernels.len() as u64);
        }
    })?;
    let width = kernels.first().map_or(2, Vec::len);
    // Kernels by column: columns[c][k − 1] is output c at step k.
    let columns: Vec<Vec<f64>> = (0..width).map(|c| kernels.iter().map(|k| k[c]).collect()).collect();
    drop(kernels);
    let (h_mom, h_nc) = (&columns[width - 2], &columns[width - 1]);

    // The contact history, with the ledger, the energy guard and the planned stop.
    let mass = m_diag[imp];
    let mut series = Series::default();
    let mut energy: Vec<EnergyRow> = Vec::with_capacity(steps + 1);
    let mut loads: Vec<f64> = Vec::with_capacity(steps);
    let mut heads: Vec<RowHead> = Vec::new();
    let every = model.time.every.max(1);
    let (mut target_energy, mut external, mut initial) = (0.0, 0.0, None);
    let (mut prev_w, mut prev_x, mut prev_nc) = (0.0, 0.0, 0.0);
    let (mut in_contact, mut separated_at, mut tripped) = (false, None::<f64>, None);
    let mut observe = |s: &ConvStep| {
        if s.step > 0 {
            loads.push(s.p);
        }
        let force = ct.stiffness * s.load_factor;
        series.time.push(s.time);
        series.alpha.push(s.alpha);
        series.force.push(force);
        series.impactor_u.push(s.x);
        series.impactor_v.push(s.xv);
        if opts.ledger {
            let nc = convolve_at(h_nc, &loads, s.step);
            if s.step > 0 {
                target_energy += (s.w - prev_w) * s.work_factor;
                external += (nc_imp * (s.x - prev_x) + (nc - prev_nc)) * s.work_factor;
            }
            (prev_w, prev_x, prev_nc) = (s.w, s.x, nc);
            let ke_i = 0.5 * mass * s.xv * s.xv;
            let se_i = ct.potential(s.alpha);
            let u0 = *initial.get_or_insert(ke_i + se_i + target_energy);
            let momentum = mass * s.xv + convolve_at(h_mom, &loads, s.step);
            let row = EnergyRow::with_target_total(s.time, ke_i, se_i, target_energy, external, u0, momentum);
            if let Some(limit) = opts.max_energy_error {
                if row.error.abs() > limit || row.error.is_nan() {
                    tripped = Some(GuardTrip {
                        step: s.step,
                        time: s.time,
                        error: row.error,
                        limit,
                    });
                }
            }
            energy.push(row);
        }
        if s.step % every == 0 {
            heads.push(RowHead {
                time: s.time,
                force,
                alpha: s.alpha,
                impactor_u: s.x,
                impactor_v: s.xv,
                load_factor: s.load_factor,
            });
        }
        if s.alpha > 0.0 {
            in_contact = true;
        } else if in_contact && separated_at.is_none() {
            separated_at = Some(s.time);
        }
        if s.step % 64 == 0 {
            bar.set_position((steps + s.step) as u64);
        }
        let done = matches!((separated_at, opts.stop_after_separation), (Some(t), Some(w)) if s.time >= t + w);
        Ok(!done && tripped.is_none())
    };
    let (p, iterations) = contact_history(model, sys, form, &kernel, steps, &mut observe)?;

    // The history rows: the impactor's part of each linear output plus the target's sum.
    let outputs = width - 2;
    let (mut u_imp, mut v_imp) = (model.u0.clone(), model.v0.clone());
    let history: Vec<Vec<f64>> = heads
        .iter()
        .map(|h| {
            let n = (h.time / dt).round() as usize;
            u_imp[imp] = h.impactor_u;
            v_imp[imp] = h.impactor_v;
            let mut linear = linear_outputs(model, &u_imp, &v_imp);
            for (c, y) in linear.iter_mut().enumerate().take(outputs) {
                *y += convolve_at(&columns[c], &p, n);
            }
            history_row(model, h, &linear)
        })
        .collect();
    bar.finish_and_clear();

    let stats = RunStats {
        steps: p.len(),
        factorizations: kernel.costs.factorizations,
        solves: kernel.costs.solves,
        contact_iterations: iterations,
        factor_time: kernel.costs.factor_time,
        solve_time: kernel.costs.solve_time,
        total_time: t0.elapsed(),
        assembly_time: Default::default(),
    };
    let mut run = RunResult {
        scheme: opts.scheme,
        dt,
        steps,
        stats,
        series,
        energy,
        history_columns: history_columns(model),
        history,
        summary: Default::default(),
        dofs: model.dofs.clone(),
        snapshots: Vec::new(),
    };
    run.summary = summarize(model, &run, tripped);
    run.summary.run.engine = Engine::Convolution;
    match tripped {
        None => Ok(run),
        Some(trip) => Err(RunError::EnergyGuard {
            trip,
            partial: Box::new(run),
        }),
    }
}
