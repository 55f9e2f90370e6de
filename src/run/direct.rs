//! The direct engine: the scheme steps the whole system, and the recorder books the
//! contact series, the ledger, the history rows and the snapshots at every step.

use super::{
    history_columns, history_row, linear_outputs, summarize, Engine, GuardTrip, RowHead, RunError, RunOptions,
    RunResult, Series, Snapshot, Summary,
};
use crate::assembly::System;
use crate::integrate::{integrate, Observer, SolveError, StepState};
use crate::ledger::{EnergyRow, Ledger};
use crate::model::Model;
use indicatif::ProgressBar;

/// Runs a prepared model ([`super::prepare`]) step by step.
pub fn run(model: &Model, sys: &System, opts: &RunOptions) -> Result<RunResult, RunError> {
    let ledger = opts.ledger.then(|| Ledger::new(model, sys));
    record(model, model, sys, ledger, Fields::Stepped, opts, Engine::Direct)
}

/// Where a recorder reads the history's outputs and the snapshots' fields from.
pub(super) enum Fields<'a> {
    /// The stepped state: the model's own DOFs.
    Stepped,
    /// A reduced state, through the reduction's basis ([`super::modal`]).
    Reduced(&'a super::modal::Reduction),
}

/// Steps `stepped` (its system `sys`) and records the run of `model`: the same model,
/// or the model a reduced one stands for (`fields` says which).
pub(super) fn record(
    model: &Model,
    stepped: &Model,
    sys: &System,
    ledger: Option<Ledger>,
    fields: Fields,
    opts: &RunOptions,
    engine: Engine,
) -> Result<RunResult, RunError> {
    let dt = opts.dt.unwrap_or(model.time.dt);
    let steps = opts.steps.unwrap_or(model.time.steps);
    let bar = opts.progress.clone().unwrap_or_else(ProgressBar::hidden);
    bar.set_length(steps as u64);
    bar.set_position(0);
    // The bar's clock (its rate and estimate) starts with the stepping.
    bar.reset_elapsed();
    let mut rec = Recorder {
        model,
        stepped,
        fields,
        ledger,
        stop_after_separation: opts.stop_after_separation,
        separated_at: None,
        in_contact: false,
        every: model.time.every.max(1),
        energy: Vec::with_capacity(steps + 1),
        series: Series::default(),
        history: Vec::new(),
        max_energy_error: opts.max_energy_error,
        tripped: None,
        bar,
        snapshot_steps: opts.snapshot_times.iter().map(|t| (t / dt).round() as usize).collect(),
        snapshots: Vec::new(),
    };
    let stats = integrate(stepped, sys, opts.scheme, dt, steps, &mut rec)?;
    rec.bar.finish_and_clear();
    if let Some(ledger) = &rec.ledger {
        ledger.finish(&mut rec.energy);
    }
    let mut run = RunResult {
        scheme: opts.scheme,
        dt,
        steps,
        stats,
        series: rec.series,
        energy: rec.energy,
        history_columns: history_columns(model),
        history: rec.history,
        summary: Summary::default(),
        dofs: model.dofs.clone(),
        snapshots: rec.snapshots,
    };
    run.summary = summarize(model, &run, rec.tripped, opts, engine)?;
    match rec.tripped {
        None => Ok(run),
        Some(trip) => Err(RunError::EnergyGuard {
            trip,
            partial: Box::new(run),
        }),
    }
}

struct Recorder<'a> {
    model: &'a Model,
    stepped: &'a Model,
    fields: Fields<'a>,
    ledger: Option<Ledger<'a>>,
    stop_after_separation: Option<f64>,
    separated_at: Option<f64>,
    in_contact: bool,
    every: usize,
    energy: Vec<EnergyRow>,
    series: Series,
    history: Vec<Vec<f64>>,
    max_energy_error: Option<f64>,
    tripped: Option<GuardTrip>,
    bar: ProgressBar,
    snapshot_steps: Vec<usize>,
    snapshots: Vec<Snapshot>,
}

impl Observer for Recorder<'_> {
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError> {
        let m = self.model;
        if let Some(ledger) = &mut self.ledger {
            let row = ledger.record(s);
            // A run from rest is judged at its end (see `Ledger::finish`).
            if let Some(limit) = self.max_energy_error.filter(|_| ledger.judged_online()) {
                if row.error.abs() > limit || row.error.is_nan() {
                    self.tripped = Some(GuardTrip {
                        step: s.step,
                        time: s.time,
                        error: row.error,
                        limit,
                    });
                }
            }
            self.energy.push(row);
        }
        if self
            .stepped
            .contact
            .as_ref()
            .is_some_and(|c| c.closed(s.alpha, s.load_factor))
        {
            self.in_contact = true;
        } else if self.in_contact && self.separated_at.is_none() {
            self.separated_at = Some(s.time);
        }
        // Without a contact there is no impactor: its series are zero.
        let (force, iu, iv) = match &self.stepped.contact {
            Some(c) => (c.stiffness * s.load_factor, s.u[c.impactor.dof], s.v[c.impactor.dof]),
            None => (0.0, 0.0, 0.0),
        };
        self.series.time.push(s.time);
        self.series.alpha.push(s.alpha);
        self.series.force.push(force);
        self.series.impactor_u.push(iu);
        self.series.impactor_v.push(iv);
        if s.step % self.every == 0 {
            let head = RowHead {
                time: s.time,
                force,
                alpha: s.alpha,
                impactor_u: iu,
                impactor_v: iv,
                load_factor: s.load_factor,
            };
            let linear = match self.fields {
                Fields::Stepped => linear_outputs(m, s.u, s.v),
                Fields::Reduced(r) => r.outputs(s.u, s.v),
            };
            self.history.push(history_row(m, &head, &linear));
        }
        if self.snapshot_steps.contains(&s.step) {
            let field = |x: &[f64]| match self.fields {
                Fields::Stepped => x.to_vec(),
                Fields::Reduced(r) => r.expand(x),
            };
            self.snapshots.push(Snapshot {
                time: s.time,
                u: field(s.u),
                v: field(s.v),
            });
        }
        if s.step % 64 == 0 {
            self.bar.set_position(s.step as u64);
        }
        let done = matches!((self.separated_at, self.stop_after_separation), (Some(t0), Some(w)) if s.time >= t0 + w);
        Ok(!done && self.tripped.is_none())
    }
}
