//! One run: model → [`prepare`] (preflight, the one assembly, the inert-DOF
//! reduction) → an engine ([`direct`] or [`convolution`]) → recorded history, ledger
//! and typed [`Summary`], made by the engine that ran. [`run_model`] is the one path;
//! sweeps and studies that drive the convolution engine's kernels themselves start
//! from [`prepare`] too. Plain data in, plain data out; writing files is
//! [`crate::output`]'s job.

use crate::assembly::{assemble, drop_inert, System};
use crate::integrate::{RunStats, Scheme, SolveError};
use crate::ledger::EnergyRow;
use crate::model::Model;
use crate::numerics::crossing;
use indicatif::ProgressBar;
pub use summary::{
    ContactSummary, EnergySummary, ImpactorSummary, ModelSummary, MomentumSummary, RodSummary, RunSummary, Summary,
    UnitSystem,
};

pub mod convolution;
pub mod direct;
pub mod history;
pub mod modal;
pub mod modes;
pub mod statics;
pub mod summary;

pub use history::{Column, Face, PlyAxis};

/// How to run a model; `None` means "as the deck says".
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The integration scheme.
    pub scheme: Scheme,
    /// Time step; `None`: the deck's TSTEP.
    pub dt: Option<f64>,
    /// Number of steps; `None`: the deck's TSTEP.
    pub steps: Option<usize>,
    /// The energy guard: stop when |relative energy error| exceeds this (like
    /// LS-DYNA's ENDENG or Radioss' /STOP Emax); `None` disables it. The run then
    /// fails with [`RunError::EnergyGuard`], which keeps what was recorded up to
    /// there. Default [`DEFAULT_ENERGY_GUARD`]. A run from rest (loaded by a DLOAD)
    /// is not guarded: its error's scale is known only when it ends
    /// ([`crate::ledger::Ledger::finish`]); the finite checks still stop it.
    pub max_energy_error: Option<f64>,
    /// A progress bar to advance, created and styled by the caller (the CLI); the run
    /// sets its length to the step count and clears it at the end.
    pub progress: Option<ProgressBar>,
    /// Solve only the live DOFs ([`crate::assembly::drop_inert`]); exact, so on by default.
    pub skip_inert: bool,
    /// Times at which to keep the whole displacement state (the nearest step).
    pub snapshot_times: Vec<f64>,
    /// Compute the energy ledger (on by default; a scene may leave it out).
    pub ledger: bool,
    /// Stop this long after the first separation (contact ended), if given.
    pub stop_after_separation: Option<f64>,
    /// How the run is computed.
    pub engine: Engine,
    /// How the modal engine reduces the model.
    pub modal: modal::ModalParams,
    /// Where the convolution engine keeps its kernels between runs
    /// ([`convolution::Kernels::cached`]); `None`: computed every time.
    pub kernel_cache: Option<std::path::PathBuf>,
    /// Refuse a run whose [`memory_estimate`] exceeds this many bytes, before
    /// allocating anything large; `None`: no limit. Default [`DEFAULT_MAX_MEMORY`].
    pub max_memory: Option<u64>,
    /// The interface's mode II fracture toughness G_IIc (force/length, the deck's
    /// units): the summary then gives the plate's delamination threshold
    /// ([`crate::damage`]) against the peak force. No card carries it.
    pub interlaminar_toughness: Option<f64>,
}

/// The default memory limit of a run: 4 GiB, a sixth of the project machine's 24 GiB,
/// so that two jobs (`--jobs 2`) stay well inside it; the paper's plate over 3000
/// steps is estimated at about 0.1 GiB.
pub const DEFAULT_MAX_MEMORY: u64 = 4 << 30;

/// Bytes a run of `steps` steps would hold beyond the model: the assembled system
/// (element triplets of K and M, and their compressed copies; the factor's fill is
/// not counted) and the records kept per step ([`record_bytes`]). For the model as
/// solved (its inert DOFs dropped, [`prepare`]) this is the run's estimate;
/// for the model as read it is an upper bound (the plate's membrane DOFs, inert under
/// a transverse impact, count there: 1.6-1.8× the measured peak).
pub fn memory_estimate(model: &Model, steps: usize, engine: Engine) -> u64 {
    system_bytes(model) + record_bytes(model, steps, engine)
}

/// Bytes of the assembled system of `model` (see [`memory_estimate`]).
fn system_bytes(model: &Model) -> u64 {
    model
        .elements
        .iter()
        .map(|e| {
            let d = e.dofs.iter().flatten().flatten().count() as u64;
            // K and M, as triplets (24 bytes) and compressed (about 16 bytes).
            2 * d * d * 40
        })
        .sum::<u64>()
        + model.n() as u64 * 8 * 16
}

/// Bytes of the records a run of `steps` steps keeps (contact series, ledger rows,
/// history rows; the convolution engine's kernels besides): what a run's length
/// costs, whatever its DOFs.
pub fn record_bytes(model: &Model, steps: usize, engine: Engine) -> u64 {
    let (steps, columns) = (steps as u64 + 1, history_columns(model).len() as u64);
    let rows = steps / model.time.every.max(1) as u64 + 1;
    // Series (5 values) and ledger row (11) per step, history rows as vectors.
    let records = steps * 16 * 8 + rows * (columns * 8 + 24);
    let kernels = match engine {
        Engine::Direct | Engine::Modal => 0,
        Engine::Convolution => steps * (columns + 4) * 8 * 2,
    };
    records + kernels
}

/// When [`preflight`] runs: before the assembly (the model as read: refuse what no
/// reduction can save: a bad Δt, records alone over the limit, or an assembly of every
/// DOF, which comes before the inert ones are dropped, over it) or on the model as
/// solved (refuse a run over its memory limit).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Preflight {
    AsRead,
    AsSolved,
}

/// Refuses a run that cannot be computed sensibly, before anything large is made: a
/// step whose 4/Δt² overflows, or a run over its memory limit.
fn preflight(model: &Model, opts: &RunOptions, stage: Preflight) -> Result<(), RunError> {
    let dt = opts.dt.unwrap_or(model.time.dt);
    let steps = opts.steps.unwrap_or(model.time.steps);
    if !(dt > 0.0 && dt.is_finite() && (4.0 / (dt * dt)).is_finite()) {
        return Err(RunError::Input(format!(
            "time step {dt:e} (the deck's TSTEP DT, or --dt): it must be positive and large enough \
             that 4/Δt² is finite (Δt ≥ 2e-154)"
        )));
    }
    if let Some(limit) = opts.max_memory {
        let need = memory_estimate(model, steps, opts.engine);
        let over = match stage {
            Preflight::AsRead => record_bytes(model, steps, opts.engine) > limit || system_bytes(model) > limit,
            Preflight::AsSolved => need > limit,
        };
        if over {
            let gib = |b: u64| b as f64 / (1u64 << 30) as f64;
            let source = match (opts.steps, &model.time_card) {
                (None, Some(card)) => format!(" from {card}"),
                (Some(_), _) => " as asked".to_string(),
                (None, None) => String::new(),
            };
            return Err(RunError::Input(format!(
                "the run would need about {:.1} GiB ({steps} steps{source}, {} solved DOFs, {} elements), over the \
                 limit of {:.1} GiB: lower the step count or raise --max-memory",
                gib(need),
                model.n(),
                model.elements.len(),
                gib(limit)
            )));
        }
    }
    Ok(())
}

/// How a run is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// Step by step, every DOF (the reference).
    #[default]
    Direct,
    /// The target's response to a unit contact load computed once, the contact by an
    /// exact history sum ([`crate::integrate::convolution`]): the direct run to
    /// round-off, for `newmark` and `energy`, with the requested outputs only.
    Convolution,
    /// The target reduced to its lowest modes and residual vectors
    /// ([`modal`]), stepped by the same schemes and contact.
    Modal,
}

impl Engine {
    /// True for the direct engine.
    pub fn is_direct(&self) -> bool {
        *self == Engine::Direct
    }

    /// Its name, as `--engine` takes it.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Direct => "direct",
            Engine::Convolution => "convolution",
            Engine::Modal => "modal",
        }
    }
}

impl RunOptions {
    /// How a scene asks to be run: its scheme, the membrane DOFs solved only when it
    /// asks for them, the ledger as it says, and its stop after separation.
    pub fn for_scene(s: &crate::scene::Scene) -> Self {
        RunOptions {
            scheme: s.run.scheme,
            skip_inert: !s.effects.membrane,
            ledger: s.effects.ledger,
            stop_after_separation: s.run.after_separation,
            ..Default::default()
        }
    }
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            scheme: Scheme::Newmark,
            dt: None,
            steps: None,
            max_energy_error: Some(DEFAULT_ENERGY_GUARD),
            progress: None,
            skip_inert: true,
            snapshot_times: Vec::new(),
            ledger: true,
            stop_after_separation: None,
            engine: Engine::Direct,
            modal: Default::default(),
            max_memory: Some(DEFAULT_MAX_MEMORY),
            kernel_cache: None,
            interlaminar_toughness: None,
        }
    }
}

/// The default energy guard: a run whose relative energy error exceeds 5 % has
/// stopped being a simulation of the model (every scheme here stays below 1e-3 on the
/// verification cases).
pub const DEFAULT_ENERGY_GUARD: f64 = 5e-2;

/// Where the energy guard stopped a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuardTrip {
    /// The step that tripped it.
    pub step: usize,
    /// Its time.
    pub time: f64,
    /// The relative energy error there.
    pub error: f64,
    /// The limit it exceeded.
    pub limit: f64,
}

impl std::fmt::Display for GuardTrip {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "energy guard: relative energy error {:.3e} at step {} (t = {:.4e}) exceeds {:.3e}",
            self.error, self.step, self.time, self.limit
        )?;
        if self.error.is_nan() {
            write!(
                f,
                " (the energy itself is not a finite number: a velocity, mass or stiffness of the \
                 deck is too large for double precision, or the state overflowed)"
            )?;
        }
        Ok(())
    }
}

/// A run that did not complete.
#[derive(Debug, Clone, thiserror::Error)]
pub enum RunError {
    /// The solver failed.
    #[error("numerical failure: {0}")]
    Solve(#[from] SolveError),
    /// The convolution engine cannot run this model or these options.
    #[error("{0}")]
    Engine(String),
    /// The run cannot be made as asked (its step, its size): nothing was computed.
    #[error("{0}")]
    Input(String),
    /// A ply's failure index is not a finite number: the run's stresses cannot be
    /// divided by its allowables in double precision. Nothing is kept.
    #[error("{0}")]
    FailureIndex(String),
    /// The energy guard stopped the run; `partial` holds everything recorded up to
    /// and including the step that tripped it, its summary marked incomplete.
    #[error("{trip}")]
    EnergyGuard {
        /// Where and why it stopped.
        trip: GuardTrip,
        /// Everything recorded up to and including the tripping step, its summary marked incomplete.
        partial: Box<RunResult>,
    },
}

/// Per-step contact quantities, the basis of the summary.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Time of each state, from 0.
    pub time: Vec<f64>,
    /// Indentation α.
    pub alpha: Vec<f64>,
    /// Contact force magnitude K φ(α) (the force on the impactor).
    pub force: Vec<f64>,
    /// Impactor displacement along the impact direction.
    pub impactor_u: Vec<f64>,
    /// Impactor velocity along the impact direction.
    pub impactor_v: Vec<f64>,
}

/// Everything a run produced.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The scheme run.
    pub scheme: Scheme,
    /// Its time step.
    pub dt: f64,
    /// Steps planned.
    pub steps: usize,
    /// Counts and wall-clock times of the run's stages (assembly, factorisation,
    /// solves, the whole loop).
    pub stats: RunStats,
    /// Per-step contact quantities.
    pub series: Series,
    /// The energy ledger, every step.
    pub energy: Vec<EnergyRow>,
    /// The columns of `history.csv`.
    pub history_columns: Vec<Column>,
    /// The rows of `history.csv` (every TSTEP output interval).
    pub history: Vec<Vec<f64>>,
    /// The summary (`summary.json`).
    pub summary: Summary,
    /// The solved DOFs of the run (inert DOFs dropped), for reading snapshots.
    pub dofs: Vec<crate::model::DofLabel>,
    /// States at the requested snapshot times.
    pub snapshots: Vec<Snapshot>,
}

/// The state of a run at one snapshot time, over the run's solved DOFs
/// ([`RunResult::dofs`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Time of the state.
    pub time: f64,
    /// Displacements.
    pub u: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
}

impl RunResult {
    /// Index of a history column.
    pub fn column(&self, c: &Column) -> Option<usize> {
        self.history_columns.iter().position(|x| x == c)
    }

    /// The header of `history.csv`: each column's name with its unit.
    pub fn history_header(&self) -> Vec<String> {
        self.history_columns
            .iter()
            .map(|c| c.header(&self.summary.units))
            .collect()
    }

    /// The names of the history's columns (headers without units).
    pub fn history_names(&self) -> Vec<String> {
        self.history_columns.iter().map(Column::name).collect()
    }

    /// The values of a history column.
    pub fn column_values(&self, c: &Column) -> Option<Vec<f64>> {
        let j = self.column(c)?;
        Some(self.history.iter().map(|r| r[j]).collect())
    }
}

/// The columns of `history.csv`, in the order the recorder writes its rows.
pub fn history_columns(m: &Model) -> Vec<Column> {
    let mut cols = FIXED_COLUMNS.to_vec();
    let cd = |d: &crate::model::DofLabel| m.frames.get(&d.point).map_or(0, |f| f.cd);
    cols.extend(m.outputs.disp.iter().map(|(d, _)| Column::Disp(*d, cd(d))));
    cols.extend(m.outputs.velo.iter().map(|(d, _)| Column::Velo(*d, cd(d))));
    if let Some(c) = &m.contact {
        cols.extend(
            m.outputs
                .nlload
                .iter()
                .map(|&k| Column::NlLoad(c.loads[k].label, cd(&c.loads[k].label))),
        );
    }
    for (e, what) in m.outputs.written() {
        let e = &m.elements[e];
        cols.extend(
            e.kernel
                .recovered(what)
                .into_iter()
                .map(|value| Column::Element { eid: e.eid, value }),
        );
    }
    for (e, plies) in &m.outputs.plies {
        cols.extend(Column::plies(m.elements[*e].eid, plies.len()));
        cols.extend(Column::interlaminar(m.elements[*e].eid, plies));
    }
    cols
}

/// The columns every history has, first, before what case control requests.
pub const FIXED_COLUMNS: [Column; 5] = [
    Column::Time,
    Column::ContactForce,
    Column::Indentation,
    Column::ImpactorDisp,
    Column::ImpactorVelo,
];

/// The history outputs that are linear in the state, in column order: DISP, VELO,
/// then the recovered element values.
fn linear_outputs(m: &Model, u: &[f64], v: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    for (_, src) in &m.outputs.disp {
        out.push(m.value(*src, u));
    }
    for (_, src) in &m.outputs.velo {
        out.push(m.value(*src, v));
    }
    for (e, what) in m.outputs.written() {
        out.extend(m.elements[e].recover(u, what));
    }
    for (e, plies) in &m.outputs.plies {
        ply_outputs(&m.elements[*e], plies, u, &mut out);
    }
    out
}

/// The largest failure index of the theory its PCOMP names (FT) over a laminate
/// element's plies, bottom and top, at displacements `u` (NaN when its plies have no
/// criterion).
pub fn largest_failure_index(e: &crate::elements::Element, plies: &[crate::laminate::PlyLayer], u: &[f64]) -> f64 {
    let mut values = Vec::new();
    ply_outputs(e, plies, u, &mut values);
    ply_points(plies, &values)
        .flat_map(|(_, p, _, strain, stress)| {
            p.criteria
                .iter()
                .filter(|c| c.theory != crate::damage::Theory::MaxStress)
                .map(move |c| c.index(&strain, &stress))
        })
        .fold(f64::NAN, f64::max)
}

/// The points of a laminate element's plies from its ply values in [`Column::plies`]
/// order: each ply (from 0) with its layer, bottom then top, and the strain and
/// stress there in the ply's axes.
pub fn ply_points<'a>(
    plies: &'a [crate::laminate::PlyLayer],
    values: &'a [f64],
) -> impl Iterator<
    Item = (
        usize,
        &'a crate::laminate::PlyLayer,
        Face,
        nalgebra::Vector3<f64>,
        nalgebra::Vector3<f64>,
    ),
> + 'a {
    plies.iter().enumerate().flat_map(move |(k, p)| {
        [Face::Bottom, Face::Top].into_iter().enumerate().map(move |(f, face)| {
            let v = |o: usize| {
                let b = 12 * k + 6 * f + o;
                nalgebra::Vector3::new(values[b], values[b + 1], values[b + 2])
            };
            (k, p, face, v(0), v(3))
        })
    })
}

/// The ply strains and stresses of a laminate element, in [`Column::plies`] order:
/// its mid-plane strain and curvature from the fibre strains its kernel recovers at
/// z = ∓T/2 (ε⁰ = (ε₁ + ε₂)/2, κ = (ε₂ − ε₁)/T), then each ply's
/// [`crate::laminate::PlyLayer::at`] its bottom and top; then, in
/// [`Column::interlaminar`] order, the interlaminar shear stresses from the
/// transverse shear forces the kernel recovers
/// ([`crate::laminate::Interface::stresses`]).
fn ply_outputs(e: &crate::elements::Element, plies: &[crate::laminate::PlyLayer], u: &[f64], out: &mut Vec<f64>) {
    use crate::elements::{Fibre, Measure, Plane, Recovered, Transverse};
    // One recovery: the fibre strains, and with interfaces also the shear forces,
    // which come with the stresses.
    let bonded = plies.iter().any(|p| p.interface.is_some());
    let what = if bonded {
        crate::elements::Output::Stress
    } else {
        crate::elements::Output::Strain
    };
    let names = e.kernel.recovered(what);
    let values = e.recover(u, what);
    let value = |r: Recovered| {
        let k = names
            .iter()
            .position(|n| *n == r)
            .unwrap_or_else(|| panic!("a laminate element recovers {r:?}"));
        values[k]
    };
    let fibre = |f: Fibre| {
        nalgebra::Vector3::from_fn(|i, _| {
            value(Recovered {
                measure: Measure::Strain,
                at: Some(crate::elements::At::Fibre(f, [Plane::Xx, Plane::Yy, Plane::Xy][i])),
            })
        })
    };
    let (e1, e2) = (fibre(Fibre::Z1), fibre(Fibre::Z2));
    let thickness = plies.last().map_or(0.0, |p| p.z[1]) - plies.first().map_or(0.0, |p| p.z[0]);
    let (e0, k) = ((e1 + e2) * 0.5, (e2 - e1) / thickness);
    for p in plies {
        for z in p.z {
            let (strain, stress) = p.at(&e0, &k, z);
            out.extend(strain.iter().chain(stress.iter()));
        }
    }
    if bonded {
        let q = [Transverse::Qx, Transverse::Qy].map(|t| {
            value(Recovered {
                measure: Measure::ShearForce(t),
                at: None,
            })
        });
        for bond in plies.iter().filter_map(|p| p.interface.as_ref()) {
            out.extend(bond.stresses(q).iter());
        }
    }
}

/// The plies' failure indices over a run's history: for each written laminate element
/// whose plies have criteria, every ply's bottom and top at every row, read from the
/// history's ply strain and stress columns; and the bond index of every interface
/// with an allowable, from its interlaminar columns. `None` when no written ply has a
/// criterion. An index that is not a finite number (allowables too small for the
/// stresses to be divided by them in double precision) is an error: the summary
/// would otherwise carry a null where it promises a number.
fn failure_summary(
    model: &Model,
    columns: &[Column],
    rows: &[Vec<f64>],
) -> Result<Option<summary::FailureSummary>, RunError> {
    use crate::damage::Theory;
    use summary::PlyIndex;
    // Per criterion slot (0: the FT theory, 1: maximum stress): its running result.
    let slot = |t: Theory| usize::from(t == Theory::MaxStress);
    let mut found: [Option<PlyIndex>; 2] = [None, None];
    let mut bond_found: Option<PlyIndex> = None;
    let mut names: [Vec<&str>; 2] = [Vec::new(), Vec::new()];
    for (e, plies) in &model.outputs.plies {
        let eid = model.elements[*e].eid;
        for c in plies.iter().flat_map(|p| &p.criteria) {
            let n = &mut names[slot(c.theory)];
            if !n.contains(&c.theory.name()) {
                n.push(c.theory.name());
            }
        }
        // The element's ply columns, contiguous in Column::plies order.
        let first = Column::plies(eid, 1)[0];
        let start = columns
            .iter()
            .position(|c| *c == first)
            .expect("a written laminate element has its ply columns");
        let end = start + 12 * plies.len();
        for row in rows {
            let time = row[0];
            for (k, p, face, strain, stress) in ply_points(plies, &row[start..end]) {
                for c in &p.criteria {
                    let index = c.index(&strain, &stress);
                    if !index.is_finite() {
                        return Err(RunError::FailureIndex(format!(
                            "the {} failure index of element {eid}, ply {} {}, is {index} at t = {time:e} (stresses \
                             σ1 {:e}, σ2 {:e}, τ12 {:e} in the ply's axes): its MAT8 allowables are too small for \
                             these stresses to be divided by them in double precision",
                            c.theory.name(),
                            k + 1,
                            face.name(),
                            stress[0],
                            stress[1],
                            stress[2]
                        )));
                    }
                    track(&mut found[slot(c.theory)], index, time, eid, k, face);
                }
            }
        }
        // The bonds: the element's interlaminar columns, in Column::interlaminar order.
        let first = Column::interlaminar(eid, plies).into_iter().next();
        let Some(start) = first.and_then(|f| columns.iter().position(|c| *c == f)) else {
            continue;
        };
        let bonds: Vec<(usize, &crate::laminate::Interface)> = plies
            .iter()
            .enumerate()
            .filter_map(|(k, p)| Some((k, p.interface.as_ref()?)))
            .collect();
        for row in rows {
            for (j, (k, bond)) in bonds.iter().enumerate() {
                let tau = nalgebra::Vector2::new(row[start + 2 * j], row[start + 2 * j + 1]);
                if let Some(index) = bond.bond_index(&tau) {
                    if !index.is_finite() {
                        return Err(RunError::FailureIndex(format!(
                            "the bond index of element {eid} above ply {} is {index} at t = {:e} (τ1z {:e}, τ2z {:e}): \
                             the PCOMP's SB is too small for these stresses to be divided by it in double precision",
                            k + 1,
                            row[0],
                            tau[0],
                            tau[1]
                        )));
                    }
                    track(&mut bond_found, index, row[0], eid, *k, Face::Top);
                }
            }
        }
    }
    let [theory, max_stress] = found;
    let name = |mut r: PlyIndex, n: &str| {
        r.name = n.into();
        r
    };
    Ok(theory.map(|theory| summary::FailureSummary {
        theory: name(theory, &names[0].join("+")),
        max_stress: max_stress.map(|r| name(r, &names[1].join("+"))),
        bond: bond_found.map(|r| name(r, "BOND")),
    }))
}

/// Keeps in `found` the largest of a running failure index and when it first
/// reached 1: `index` at `time` in ply `k` (from 0) of element `eid`, at `face`.
fn track(found: &mut Option<summary::PlyIndex>, index: f64, time: f64, eid: i64, k: usize, face: Face) {
    let r = found.get_or_insert_with(|| summary::PlyIndex {
        largest: f64::NEG_INFINITY,
        ..Default::default()
    });
    if index > r.largest {
        *r = summary::PlyIndex {
            largest: index,
            time,
            element: eid,
            ply: k as u16 + 1,
            face: face.name().into(),
            ..std::mem::take(r)
        };
    }
    if index >= 1.0 && r.first_reaches_one.is_none_or(|t| time < t) {
        r.first_reaches_one = Some(time);
    }
}

/// The contact quantities of a history row.
struct RowHead {
    time: f64,
    force: f64,
    alpha: f64,
    impactor_u: f64,
    impactor_v: f64,
    load_factor: f64,
}

/// A row of `history.csv` in [`history_columns`] order, from the contact quantities
/// and the [`linear_outputs`].
fn history_row(m: &Model, h: &RowHead, linear: &[f64]) -> Vec<f64> {
    let mut row = vec![h.time, h.force, h.alpha, h.impactor_u, h.impactor_v];
    let nodal = m.outputs.disp.len() + m.outputs.velo.len();
    row.extend_from_slice(&linear[..nodal]);
    if let Some(c) = &m.contact {
        for &k in &m.outputs.nlload {
            row.push(c.loads[k].scale * h.load_factor);
        }
    }
    row.extend_from_slice(&linear[nodal..]);
    row
}

/// A model ready for an engine: preflight passed, its system assembled (once), its
/// inert DOFs dropped when asked ([`drop_inert`]; the model is then a reduced copy).
pub struct Prepared<'m> {
    /// The model as solved.
    pub model: std::borrow::Cow<'m, Model>,
    /// Its assembled system.
    pub system: System,
    /// Wall-clock time of the assembly and reduction.
    pub assembly_time: std::time::Duration,
}

/// The one stage before any engine: the preflight on the model as read (a bad Δt,
/// records or an assembly of every DOF over the memory limit), the assembly,
/// refused when a DOF has neither stiffness nor mass (a mechanism, whether or not
/// anything loads it), the inert-DOF reduction of the assembled system when
/// `opts.skip_inert`, and the preflight on the model as solved (its memory limit).
pub fn prepare<'m>(model: &'m Model, opts: &RunOptions) -> Result<Prepared<'m>, RunError> {
    preflight(model, opts, Preflight::AsRead)?;
    let t0 = std::time::Instant::now();
    let sys = assemble(model);
    let (kd, md) = (sys.k_diag(), sys.m_diag());
    if let Some(i) = (0..sys.n).find(|&i| kd[i] <= 0.0 && md[i] <= 0.0) {
        return Err(SolveError::Mechanism {
            dof: model.dofs[i].to_string(),
        }
        .into());
    }
    let (model, system) = match opts.skip_inert.then(|| drop_inert(model, &sys)).flatten() {
        Some((m, s)) => (std::borrow::Cow::Owned(m), s),
        None => (std::borrow::Cow::Borrowed(model), sys),
    };
    preflight(&model, opts, Preflight::AsSolved)?;
    Ok(Prepared {
        model,
        system,
        assembly_time: t0.elapsed(),
    })
}

/// Runs a model: [`prepare`], then the engine `opts.engine` names, which summarises
/// the run as its own.
///
/// ```
/// use impactlab::run::{run_model, RunOptions};
/// let model = impactlab::paper::rod_model()?;
/// let run = run_model(&model, &RunOptions::default())?;
/// let s = &run.summary;
/// assert_eq!(s.contact.intervals.len(), 1);
/// assert!((s.rod.as_ref().unwrap().contact_end_tcl.unwrap() - 0.4134).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run_model(model: &Model, opts: &RunOptions) -> Result<RunResult, RunError> {
    let p = prepare(model, opts)?;
    let (model, sys) = (p.model.as_ref(), &p.system);
    let with_assembly = |run: &mut RunResult| {
        run.stats.assembly_time = p.assembly_time;
        run.summary.run.assembly_s = p.assembly_time.as_secs_f64();
    };
    let run = match opts.engine {
        Engine::Direct => direct::run(model, sys, opts),
        Engine::Convolution => convolution::run(model, sys, opts),
        Engine::Modal => modal::run(model, sys, opts),
    };
    amended(run, with_assembly)
}

/// A run's result with `f` applied to what it recorded: the run, or the partial run
/// the energy guard stopped.
fn amended(run: Result<RunResult, RunError>, f: impl FnOnce(&mut RunResult)) -> Result<RunResult, RunError> {
    match run {
        Ok(mut run) => {
            f(&mut run);
            Ok(run)
        }
        Err(RunError::EnergyGuard { trip, mut partial }) => {
            f(&mut partial);
            Err(RunError::EnergyGuard { trip, partial })
        }
        Err(e) => Err(e),
    }
}

/// Contact intervals [start, end] from the indentation: contact while α > 0.
pub fn contact_intervals(t: &[f64], alpha: &[f64]) -> (Vec<[f64; 2]>, bool) {
    let mut out = Vec::new();
    let mut start = None;
    for k in 0..alpha.len() {
        let inside = alpha[k] > 0.0;
        match (start, inside) {
            (None, true) => start = Some(if k == 0 { t[0] } else { crossing(t, alpha, k) }),
            (Some(s), false) => {
                out.push([s, crossing(t, alpha, k)]);
                start = None;
            }
            _ => {}
        }
    }
    let open = start.is_some();
    if let Some(s) = start {
        out.push([s, *t.last().unwrap_or(&s)]);
    }
    (out, open)
}

/// What a hysteretic contact dissipated over the run, with its law and the permanent
/// indentation it leaves; `None` for an elastic contact.
fn contact_dissipation(model: &Model, run: &RunResult) -> Option<summary::ContactDissipation> {
    let crate::model::Unloading::YangSun(y) = model.contact.as_ref()?.unloading else {
        return None;
    };
    let max = run.series.alpha.iter().copied().fold(0.0, f64::max);
    Some(summary::ContactDissipation {
        dissipated: run.energy.last().map_or(0.0, |r| r.dissipated_contact),
        law: "yang-sun".into(),
        critical_indentation: y.critical,
        unloading_exponent: y.power,
        max_indentation: max,
        permanent_indentation: y.permanent(max),
    })
}

/// Where the energy the impactor lost went, for a run with an impactor that
/// dissipates (damping or a hysteretic contact); `None` otherwise or without a ledger.
fn impactor_loss(model: &Model, e: &[EnergyRow]) -> Option<summary::ImpactorLoss> {
    if model.contact.is_none() || !(model.damped() || model.hysteretic()) {
        return None;
    }
    let (first, last) = (e.first()?, e.last()?);
    // The target's energy as the total less the impactor's and the contact's: the
    // convolution engine knows it as a total only.
    let target = |r: &EnergyRow| r.total - r.ke_impactor - r.se_impactor;
    let lost = first.ke_impactor - last.ke_impactor;
    let gained = target(last) - target(first);
    let holds = last.se_impactor - first.se_impactor;
    // The convolution engine cannot split a damped target's energy from what its
    // damping took (D is NaN there): its gain holds both.
    let damping = last.dissipated_damping;
    Some(summary::ImpactorLoss {
        lost,
        target: gained,
        contact_holds: holds,
        damping,
        contact: last.dissipated_contact,
        external_work: last.external_work,
        residual: lost
            - (gained + holds + if damping.is_nan() { 0.0 } else { damping } + last.dissipated_contact
                - last.external_work),
    })
}

/// The summary of a run by `engine`.
fn summarize(
    model: &Model,
    run: &RunResult,
    tripped: Option<GuardTrip>,
    opts: &RunOptions,
    engine: Engine,
) -> Result<Summary, RunError> {
    let s = &run.series;
    let closure = model
        .contact
        .as_ref()
        .map_or_else(|| s.alpha.clone(), |c| c.closure(&s.alpha));
    let (intervals, open) = contact_intervals(&s.time, &closure);
    let (kmax, fmax) = s
        .force
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |acc, (k, &f)| if f > acc.1 { (k, f) } else { acc });
    let v0 = s.impactor_v.first().copied().unwrap_or(0.0);
    let vzero = (1..s.impactor_v.len())
        .find(|&k| s.impactor_v[k] * v0.signum() <= 0.0 && s.impactor_v[k - 1] * v0.signum() > 0.0)
        .map(|k| crossing(&s.time, &s.impactor_v, k));
    let rebound = if open || intervals.is_empty() {
        None
    } else {
        s.impactor_v.last().copied()
    };
    // Without a ledger the energy and momentum entries are null, not zero.
    let e = &run.energy;
    let p0 = e.first().map(|r| r.momentum);
    let peak_force_time = s.time.get(kmax).copied();
    let rod = model.rod.map(|r| {
        let tau = r.length / r.wave_speed;
        let scale = |x: Option<f64>| x.map(|x| x / tau);
        RodSummary {
            wave_speed: r.wave_speed,
            length: r.length,
            transit_time: tau,
            contact_intervals_tcl: intervals.iter().map(|i| [i[0] / tau, i[1] / tau]).collect(),
            contact_end_tcl: scale(intervals.first().map(|i| i[1])),
            peak_force_time_tcl: scale(peak_force_time),
            velocity_zero_time_tcl: scale(vzero),
        }
    });
    let contact = model.contact.as_ref();
    Ok(Summary {
        schema_version: summary::SCHEMA_VERSION,
        impactlab_version: env!("CARGO_PKG_VERSION").to_string(),
        deck: model.name.clone(),
        deck_sha256: model.deck_sha256.clone(),
        title: model.title.clone(),
        units: UnitSystem::of(&model.units),
        model: ModelSummary {
            active_dofs: model.active_dofs(),
            solved_dofs: model.n(),
            inert_dofs_skipped: model.inert_dofs,
            elements: model.elements.len(),
            contact_stiffness: contact.map(|c| c.stiffness),
            contact_exponent: contact.map(|c| c.exponent),
            contact_conservative: contact.map(|c| c.nonconservative.is_empty()),
            transverse_shear_elements: Some(
                model
                    .elements
                    .iter()
                    .filter(|e| e.kernel.family().shell().is_some_and(|s| s.shear.is_some()))
                    .count(),
            )
            .filter(|&n| n > 0),
            not_written: model.outputs.not_written.clone(),
        },
        contact: ContactSummary {
            duration: intervals.first().map(|i| i[1] - i[0]),
            intervals,
            open_at_end: open,
            peak_force: fmax,
            peak_force_time,
        },
        impactor: ImpactorSummary {
            mass: contact.map(|c| c.impactor.mass),
            initial_velocity: v0,
            velocity_zero_time: vzero,
            rebound_velocity: rebound,
        },
        energy: EnergySummary {
            initial: e.first().map(|r| r.total),
            final_total: e.last().map(|r| r.total),
            external_work: e.last().map(|r| r.external_work),
            damping: model.damped().then(|| summary::DampingSummary {
                dissipated: e.last().map_or(0.0, |r| r.dissipated_damping),
                mass_coefficient: model.damping.as_ref().map_or(0.0, |d| d.mass),
                stiffness_coefficient: model.damping.as_ref().map_or(0.0, |d| d.stiffness),
                elements: model.elements.iter().filter(|e| e.damps()).count(),
                from: model.damping.as_ref().map_or_else(Vec::new, |d| d.from.clone()),
            }),
            contact: contact_dissipation(model, run),
            impactor_loss: impactor_loss(model, e),
            transferred_fraction: rebound.map(|vr| 1.0 - (vr / v0).powi(2)),
            max_relative_error: (!e.is_empty()).then(|| e.iter().map(|r| r.error.abs()).fold(0.0, f64::max)),
            final_relative_error: e.last().map(|r| r.error),
        },
        momentum: MomentumSummary {
            initial: p0,
            max_abs_change: p0.map(|p0| e.iter().map(|r| (r.momentum - p0).abs()).fold(0.0, f64::max)),
        },
        run: RunSummary {
            scheme: run.scheme,
            engine,
            kernel_cache: None,
            modal: None,
            dt: run.dt,
            steps: run.steps,
            steps_done: run.stats.steps,
            factorizations: run.stats.factorizations,
            solves: run.stats.solves,
            contact_iterations: run.stats.contact_iterations,
            factor_s: run.stats.factor_time.as_secs_f64(),
            solve_s: run.stats.solve_time.as_secs_f64(),
            assembly_s: run.stats.assembly_time.as_secs_f64(),
            wall_s: run.stats.total_time.as_secs_f64(),
            complete: tripped.is_none(),
            stopped_by: tripped.map(|t| t.to_string()),
        },
        rod,
        delamination: opts.interlaminar_toughness.and_then(|g| {
            let d = crate::physics::references::plate_bending_stiffness(model).ok()?;
            let onset = crate::damage::delamination_onset(&d, g);
            Some(summary::DelaminationSummary {
                peak_over_critical: fmax / onset.critical_force,
                onset,
            })
        }),
        // A run the energy guard stopped keeps the guard's error and its outputs so far;
        // an index its last rows cannot form (they may hold what tripped it) is left
        // out of that incomplete summary rather than put in the guard's place.
        failure: match failure_summary(model, &run.history_columns, &run.history) {
            Err(_) if tripped.is_some() => None,
            failure => failure?,
        },
        effects: None,
        contact_stiffness_source: None,
    })
}
