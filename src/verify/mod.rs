//! The verification layer: cases (`verification/*.toml`), their checks and
//! tolerances, gold-file comparison, and the verdicts as a table, JSON and JUnit.
//!
//! A case names a model (a deck, or the generated plate on an n×n mesh), how to run
//! it, and a list of checks. Each check yields one [`CheckResult`]: the value it
//! measured, the reference it compared with, the tolerance, and the verdict. The
//! analytic references live in [`analytic`] and share no code with the solver core.

pub mod audit;
pub mod gold;

use crate::elements::quad4::Quad4;
use crate::error::Error;
use crate::integrate::Scheme;
use crate::ledger::EnergyRow;
use crate::model::{Model, Modify};
use crate::run::{run_model, Column, Run, RunOptions, Summary};
use crate::numerics::{argmax, slope};
use crate::physics::analytic::{self, HertzDashpot};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One verification case, as written in `verification/<name>.toml`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// A deck, relative to the case file.
    pub deck: Option<PathBuf>,
    /// Or the paper's plate on a generated n×n mesh.
    pub plate_mesh: Option<usize>,
    #[serde(default = "default_scheme")]
    pub scheme: Scheme,
    pub dt: Option<f64>,
    pub steps: Option<usize>,
    /// Output every step (for strain checks), instead of the deck's TSTEP rate.
    #[serde(default)]
    pub every_step: bool,
    #[serde(default)]
    pub modify: Modify,
    #[serde(rename = "check", default)]
    pub checks: Vec<CheckSpec>,
    /// The file the case was read from (set by [`read_case`]).
    #[serde(skip)]
    pub path: PathBuf,
}

fn default_scheme() -> Scheme {
    Scheme::Newmark
}

/// A tolerance on a value: relative to the reference, or absolute.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Tol {
    #[serde(default)]
    pub rel: f64,
    #[serde(default)]
    pub abs: f64,
}

impl Tol {
    fn accepts(&self, value: f64, reference: f64) -> bool {
        let d = (value - reference).abs();
        d <= self.abs || d <= self.rel * reference.abs()
    }
    fn text(&self) -> String {
        match (self.rel > 0.0, self.abs > 0.0) {
            (true, true) => format!("rel {:.1e} or abs {:.1e}", self.rel, self.abs),
            (true, false) => format!("rel {:.1e}", self.rel),
            _ => format!("abs {:.1e}", self.abs),
        }
    }
}

/// The checks a case can ask for.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CheckSpec {
    /// max |U_t − U_0 − W_ext| / U_0 ≤ max.
    EnergyBalance { max: f64 },
    /// max |p − p_0| / |m v0| ≤ max along the impact direction (free targets).
    Momentum { max: f64 },
    /// F ≥ 0 always, F > 0 exactly when α > 0, and SE_i > 0 exactly when α > 0.
    ContactComplementarity,
    /// max |KE_t − SE_t| / U_0 over from_tcl..to_tcl (a travelling rod pulse) ≤ max.
    KineticEqualsStrain { from_tcl: f64, to_tcl: f64, max: f64 },
    /// The minimum of SE_t within ±half_width of near_tcl: its time within the window
    /// and its depth (fraction of SE_t at the end of contact) in [min_fraction, max_fraction].
    StrainEnergyDip {
        near_tcl: f64,
        half_width: f64,
        min_fraction: f64,
        max_fraction: f64,
    },
    /// The paper's Eq. 16 KE_t against ½vᵀMv after contact: the relative deficit
    /// (½vᵀMv − Eq16)/½vᵀMv lies in [min, max].
    Eq16Deficit { after_tcl: f64, min: f64, max: f64 },
    /// A summary value against a number, with its source.
    Summary {
        key: String,
        reference: f64,
        tol: Tol,
        source: String,
    },
    /// A quantity of the ball on a semi-infinite rod (analytic::HertzDashpot with
    /// c = ρCA): contact_end_tcl, velocity_zero_tcl, peak_force, peak_force_tcl,
    /// rebound_velocity, transferred_fraction.
    SemiInfiniteRod { quantity: RodQuantity, tol: Tol },
    /// Strain of `element` (centre at x from the struck end) against d'Alembert's
    /// −F(t − x/C)/EA with the semi-infinite-rod force, while t < until_tcl;
    /// max |difference| / peak strain ≤ max.
    DalembertStrain {
        element: i64,
        x: f64,
        until_tcl: f64,
        max: f64,
    },
    /// Contact force against the infinite orthotropic plate (Zener/Olsson) over
    /// 0..until_s: max |difference| / analytic peak ≤ max.
    InfinitePlate { until_s: f64, max: f64 },
    /// Contact duration and peak force against the rigid-target closed form with the
    /// reduced mass of impactor and target.
    RigidTarget { tol: Tol },
    /// Halving Δt: fit the order of `quantity` (energy_error: the error itself;
    /// contact_duration, peak_force: successive differences) over `runs` step sizes.
    DtConvergence {
        quantity: Quantity,
        runs: usize,
        expected_order: f64,
        tol: f64,
    },
    /// Plate mesh refinement: `quantity` (contact_duration, peak_force_time) on each
    /// mesh; the change between the last two meshes, relative, ≤ max and smaller
    /// than the change before.
    MeshConvergence {
        meshes: Vec<usize>,
        quantity: Quantity,
        max: f64,
    },
    /// The run's history against a stored gold CSV, every column with the same
    /// relative tolerance and a floor relative to the column's peak.
    Gold { file: PathBuf, tol: gold::GoldTol },
}

/// The verdict of one check.
#[derive(Debug, Clone, Serialize)]
pub struct CheckResult {
    pub case: String,
    pub check: String,
    pub value: f64,
    pub reference: f64,
    pub tolerance: String,
    pub passed: bool,
    pub detail: String,
    pub time_s: f64,
}

/// Reads and validates a case file.
pub fn read_case(path: &Path) -> Result<Case, Error> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Usage(format!("{}: {e}", path.display())))?;
    let mut case: Case = toml::from_str(&text).map_err(|e| Error::Usage(format!("{}: {e}", path.display())))?;
    if case.deck.is_some() == case.plate_mesh.is_some() {
        return Err(Error::Usage(format!(
            "{}: give exactly one of `deck` and `plate_mesh`",
            path.display()
        )));
    }
    for spec in &case.checks {
        if let CheckSpec::Summary { key, .. } = spec {
            if let Err(e) = Summary::check_key(key) {
                let line = text
                    .lines()
                    .position(|l| l.contains(&format!("\"{key}\"")))
                    .map_or(String::new(), |i| format!(":{}", i + 1));
                return Err(Error::Usage(format!("{}{line}: summary check: {e}", path.display())));
            }
        }
    }
    case.path = path.to_path_buf();
    Ok(case)
}

/// The case files named on the command line: files as given, directories expanded
/// to their `*.toml` (sorted).
pub fn case_files(args: &[PathBuf]) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    for a in args {
        if a.is_dir() {
            let mut v: Vec<PathBuf> = std::fs::read_dir(a)
                .map_err(|e| Error::Usage(format!("{}: {e}", a.display())))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .collect();
            v.sort();
            out.extend(v);
        } else if a.exists() {
            out.push(a.clone());
        } else {
            return Err(Error::Usage(format!("{}: no such case file", a.display())));
        }
    }
    Ok(out)
}

/// The cases named by files or directories; none named means `verification/`.
pub fn load_cases(args: &[PathBuf]) -> Result<Vec<Case>, Error> {
    let default = [PathBuf::from("verification")];
    let args = if args.is_empty() { &default[..] } else { args };
    case_files(args)?.iter().map(|p| read_case(p)).collect()
}

fn rel(case: &Case, p: &Path) -> PathBuf {
    case.path.parent().unwrap_or(Path::new(".")).join(p)
}

/// The case's model, modifications applied.
pub fn case_model(case: &Case) -> Result<Model, Error> {
    let mut m = match (&case.deck, case.plate_mesh) {
        (Some(d), _) => crate::load_deck(&rel(case, d), Default::default())?.0,
        (None, Some(n)) => crate::mesh::plate_model(n)?,
        _ => unreachable!("checked by read_case"),
    };
    if case.every_step {
        m.time.every = 1;
    }
    case.modify.apply(&m).map_err(Error::Usage)
}

/// The case's run options.
pub fn case_options(case: &Case) -> RunOptions {
    RunOptions {
        scheme: case.scheme,
        dt: case.dt,
        steps: case.steps,
        ..Default::default()
    }
}

/// Runs a case and all its checks.
pub fn run_case(case: &Case) -> Result<(Run, Vec<CheckResult>), Error> {
    let model = case_model(case)?;
    let run = run_model(&model, &case_options(case))?;
    let mut results = Vec::new();
    for spec in &case.checks {
        results.push(check(case, &model, &run, spec)?);
    }
    Ok((run, results))
}

/// A quantity of a run's summary that convergence checks follow; NaN where the run
/// has none (no contact, no ledger), which fails the check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    EnergyError,
    ContactDuration,
    PeakForce,
    PeakForceTime,
}

impl Quantity {
    /// The quantity's value in a summary.
    pub fn of(self, s: &Summary) -> f64 {
        match self {
            Quantity::EnergyError => s.energy.max_relative_error,
            Quantity::ContactDuration => s.contact.duration,
            Quantity::PeakForce => Some(s.contact.peak_force),
            Quantity::PeakForceTime => s.contact.peak_force_time,
        }
        .unwrap_or(f64::NAN)
    }

    /// The name a case file gives it.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::EnergyError => "energy_error",
            Quantity::ContactDuration => "contact_duration",
            Quantity::PeakForce => "peak_force",
            Quantity::PeakForceTime => "peak_force_time",
        }
    }
}

/// A quantity of the ball on a semi-infinite rod, for [`CheckSpec::SemiInfiniteRod`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RodQuantity {
    ContactEndTcl,
    VelocityZeroTcl,
    PeakForce,
    PeakForceTcl,
    ReboundVelocity,
    TransferredFraction,
}

impl RodQuantity {
    /// The name a case file gives it.
    pub fn name(self) -> &'static str {
        match self {
            RodQuantity::ContactEndTcl => "contact_end_tcl",
            RodQuantity::VelocityZeroTcl => "velocity_zero_tcl",
            RodQuantity::PeakForce => "peak_force",
            RodQuantity::PeakForceTcl => "peak_force_tcl",
            RodQuantity::ReboundVelocity => "rebound_velocity",
            RodQuantity::TransferredFraction => "transferred_fraction",
        }
    }
}

/// An optional summary value, NaN where the run has none (which fails any check).
fn or_nan(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// The impactor and Hertz law of a model, on a dashpot of the given impedance.
fn dashpot(model: &Model, impedance: f64) -> Result<HertzDashpot, Error> {
    let c = model
        .contact
        .as_ref()
        .ok_or_else(|| Error::Usage("the check needs a model with a contact".into()))?;
    Ok(HertzDashpot {
        mass: c.impactor.mass,
        v0: model.v0[c.impactor.dof].abs(),
        stiffness: c.stiffness,
        exponent: c.exponent,
        impedance,
    })
}

/// Wave speed C, length L, axial stiffness EA and impedance ρCA of a rod target.
fn rod_params(model: &Model) -> Result<(f64, f64, f64, f64), Error> {
    let r = model
        .rod
        .ok_or_else(|| Error::Usage("the check needs a uniform rod target".into()))?;
    let rho = r.e / (r.wave_speed * r.wave_speed);
    Ok((r.wave_speed, r.length, r.e * r.area, rho * r.wave_speed * r.area))
}

/// The model's ball on a semi-infinite rod, integrated over 2L/C (RK4, h = L/C/2e5):
/// its trace, its events and L/C.
pub fn semi_infinite(model: &Model) -> Result<(analytic::Trace, analytic::Events, f64), Error> {
    let (c, l, _, z) = rod_params(model)?;
    let p = dashpot(model, z)?;
    let lc = l / c;
    let tr = p.integrate(2.0 * lc, lc / 2.0e5);
    let ev = HertzDashpot::events(&tr)
        .ok_or_else(|| Error::Usage("semi-infinite rod: contact does not end before 2L/C".into()))?;
    Ok((tr, ev, lc))
}

/// The model's impactor on the infinite plate (Zener/Olsson impedance 8√(ρh D*) of
/// its first shell section), and that impedance.
pub fn infinite_plate(model: &Model) -> Result<(HertzDashpot, f64), Error> {
    let s = model
        .elements
        .iter()
        .find_map(|e| e.kind::<Quad4>().map(|q| q.section.clone()))
        .ok_or_else(|| Error::Usage("infinite_plate needs a plate".into()))?;
    let d = s
        .d()
        .ok_or_else(|| Error::Usage("infinite_plate needs bending stiffness".into()))?;
    let z = analytic::plate_impedance(s.mass_per_area, d[(0, 0)], d[(1, 1)], d[(0, 1)], d[(2, 2)]);
    Ok((dashpot(model, z)?, z))
}

fn column(run: &Run, c: &Column) -> Result<usize, Error> {
    run.column(c)
        .ok_or_else(|| Error::Usage(format!("the run has no history column {}", c.name())))
}

/// Evaluates one check of a case on its run.
pub fn check(case: &Case, model: &Model, run: &Run, spec: &CheckSpec) -> Result<CheckResult, Error> {
    let e: &[EnergyRow] = &run.energy;
    let u0 = e.first().map(|r| r.total).unwrap_or(1.0);
    let lc = model.rod.map(|r| r.length / r.wave_speed);
    let tcl = |t: f64| lc.map_or(t, |lc| t / lc);
    let res =
        |check: String, value: f64, reference: f64, tolerance: String, passed: bool, detail: String| CheckResult {
            case: case.name.clone(),
            check,
            value,
            reference,
            tolerance,
            passed,
            detail,
            time_s: 0.0,
        };
    Ok(match spec {
        CheckSpec::EnergyBalance { max } => {
            let (k, v) = argmax(e.iter().map(|r| r.error.abs()));
            res(
                "energy_balance".into(),
                v,
                0.0,
                format!("≤ {max:.1e}"),
                v <= *max,
                format!("largest at t = {:.4e} s", e[k].time),
            )
        }
        CheckSpec::Momentum { max } => {
            let c = model
                .contact
                .as_ref()
                .ok_or_else(|| Error::Usage("momentum needs a contact".into()))?;
            let p_ref = (c.impactor.mass * model.v0[c.impactor.dof]).abs();
            let (k, v) = argmax(e.iter().map(|r| (r.momentum - e[0].momentum).abs() / p_ref));
            res(
                "momentum".into(),
                v,
                0.0,
                format!("≤ {max:.1e}"),
                v <= *max,
                format!("largest at t = {:.4e} s", e[k].time),
            )
        }
        CheckSpec::ContactComplementarity => {
            let s = &run.series;
            let mut bad = 0usize;
            let mut first = None;
            for (k, row) in e.iter().enumerate() {
                let (a, f) = (s.alpha[k], s.force[k]);
                let ok = f >= 0.0
                    && ((f > 0.0) == (a > 0.0))
                    && ((row.se_impactor > 0.0) == (a > 0.0))
                    && row.se_impactor >= 0.0;
                if !ok {
                    bad += 1;
                    first.get_or_insert(s.time[k]);
                }
            }
            res(
                "contact_complementarity".into(),
                bad as f64,
                0.0,
                "0 violations".into(),
                bad == 0,
                first.map_or("F ≥ 0, F > 0 and SE_i > 0 exactly when α > 0".into(), |t| {
                    format!("first violation at t = {t:.4e} s")
                }),
            )
        }
        CheckSpec::KineticEqualsStrain { from_tcl, to_tcl, max } => {
            let (k, v) = argmax(e.iter().map(|r| {
                if tcl(r.time) >= *from_tcl && tcl(r.time) <= *to_tcl {
                    (r.ke_target - r.se_target).abs() / u0
                } else {
                    0.0
                }
            }));
            res(
                format!("kinetic_equals_strain tC/L {from_tcl}..{to_tcl}"),
                v,
                0.0,
                format!("≤ {max:.1e}"),
                v <= *max,
                format!("largest at tC/L = {:.4}", tcl(e[k].time)),
            )
        }
        CheckSpec::StrainEnergyDip {
            near_tcl,
            half_width,
            min_fraction,
            max_fraction,
        } => {
            let end = or_nan(run.summary.contact.intervals.first().map(|i| i[1]));
            let plateau = e.iter().find(|r| r.time >= end).map_or(f64::NAN, |r| r.se_target);
            let (k, v) = argmax(e.iter().map(|r| {
                if (tcl(r.time) - near_tcl).abs() <= *half_width {
                    -r.se_target
                } else {
                    f64::NEG_INFINITY
                }
            }));
            let frac = -v / plateau;
            let at = tcl(e[k].time);
            let ok = frac >= *min_fraction && frac <= *max_fraction && (at - near_tcl).abs() < *half_width;
            res(
                format!("strain_energy_dip near tC/L {near_tcl}"),
                frac,
                0.0,
                format!("depth in [{min_fraction}, {max_fraction}] within ±{half_width}"),
                ok,
                format!("minimum SE_t = {frac:.4} of its plateau at tC/L = {at:.4}"),
            )
        }
        CheckSpec::Eq16Deficit { after_tcl, min, max } => {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for r in e.iter().filter(|r| tcl(r.time) >= *after_tcl && r.ke_target > 0.0) {
                let d = (r.ke_target - r.ke_target_eq16) / r.ke_target;
                lo = lo.min(d);
                hi = hi.max(d);
            }
            res(
                "eq16_deficit".into(),
                hi,
                0.0,
                format!("in [{min:.1e}, {max:.1e}]"),
                lo >= *min && hi <= *max,
                format!("(½vᵀMv − Eq.16)/½vᵀMv ranges {lo:.3e}..{hi:.3e} after tC/L = {after_tcl}"),
            )
        }
        CheckSpec::Summary {
            key,
            reference,
            tol,
            source,
        } => {
            let v = or_nan(run.summary.number(key).map_err(|e| Error::Usage(e.to_string()))?);
            res(
                key.clone(),
                v,
                *reference,
                tol.text(),
                tol.accepts(v, *reference),
                source.clone(),
            )
        }
        CheckSpec::SemiInfiniteRod { quantity, tol } => {
            let (_, ev, lc) = semi_infinite(model)?;
            let s = &run.summary;
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
            res(
                format!("semi_infinite_rod {}", quantity.name()),
                v,
                r,
                tol.text(),
                tol.accepts(v, r),
                "ball on a semi-infinite rod, RK4 h = L/C/2e5".into(),
            )
        }
        CheckSpec::DalembertStrain {
            element,
            x,
            until_tcl,
            max,
        } => {
            let (tr, _, lc) = semi_infinite(model)?;
            let (c, _, ea, _) = rod_params(model)?;
            let j = column(run, &Column::rod_strain(*element))?;
            let peak = tr.force.iter().fold(0.0f64, |a, &f| a.max(f)) / ea;
            let (k, v) = argmax(run.history.iter().map(|h| {
                if h[0] / lc < *until_tcl {
                    (h[j] - analytic::dalembert_strain(&tr, *x, c, ea, h[0])).abs() / peak
                } else {
                    0.0
                }
            }));
            res(
                format!("dalembert_strain element {element}"),
                v,
                0.0,
                format!("≤ {max:.1e} of peak"),
                v <= *max,
                format!("largest at tC/L = {:.4}", run.history[k][0] / lc),
            )
        }
        CheckSpec::InfinitePlate { until_s, max } => {
            let (p, z) = infinite_plate(model)?;
            let tr = p.integrate(*until_s, until_s / 2.0e4);
            let peak = tr.force.iter().fold(0.0f64, |a, &f| a.max(f));
            let sr = &run.series;
            let (k, v) = argmax(sr.time.iter().zip(&sr.force).map(|(&t, &f)| {
                if t <= *until_s {
                    (f - analytic::force_at(&tr, t)).abs() / peak
                } else {
                    0.0
                }
            }));
            res(
                format!("infinite_plate force to {:.0} us", until_s * 1e6),
                v,
                0.0,
                format!("≤ {max:.1e} of peak"),
                v <= *max,
                format!("impedance 8√(ρh D*) = {z:.4e}; largest at t = {:.4e} s", sr.time[k]),
            )
        }
        CheckSpec::RigidTarget { tol } => {
            let c = model
                .contact
                .as_ref()
                .ok_or_else(|| Error::Usage("rigid_target needs a contact".into()))?;
            let diag = crate::assembly::assemble(model).m_diag();
            let comp = model.dofs[c.impactor.dof].comp;
            let target: f64 = model
                .target_mask()
                .iter()
                .enumerate()
                .filter(|&(i, &t)| t && model.dofs[i].comp == comp)
                .map(|(i, _)| diag[i])
                .sum();
            let mu = c.impactor.mass * target / (c.impactor.mass + target);
            let (_, f, dur) = analytic::rigid_target(mu, model.v0[c.impactor.dof], c.stiffness);
            let (vd, vf) = (or_nan(run.summary.contact.duration), run.summary.contact.peak_force);
            let ok = tol.accepts(vd, dur) && tol.accepts(vf, f);
            res(
                "rigid_target duration".into(),
                vd,
                dur,
                tol.text(),
                ok,
                format!("peak force {vf:.5e} vs {f:.5e}; reduced mass {mu:.4e}"),
            )
        }
        CheckSpec::DtConvergence {
            quantity,
            runs,
            expected_order,
            tol,
        } => {
            let dt0 = run.dt;
            let t_end = dt0 * run.steps as f64;
            let mut values = Vec::new();
            let mut dts = Vec::new();
            for i in 0..(*runs).max(3) {
                let dt = dt0 / 2f64.powi(i as i32);
                let r = if i == 0 {
                    run.clone()
                } else {
                    let mut o = case_options(case);
                    o.dt = Some(dt);
                    o.steps = Some((t_end / dt).round() as usize);
                    run_model(model, &o)?
                };
                values.push(quantity.of(&r.summary));
                dts.push(dt);
            }
            let (xs, ys): (Vec<f64>, Vec<f64>) = if *quantity == Quantity::EnergyError {
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
            let p = slope(&xs, &ys);
            res(
                format!("dt_convergence {}", quantity.name()),
                p,
                *expected_order,
                format!("± {tol}"),
                (p - expected_order).abs() <= *tol,
                format!(
                    "values {}",
                    values.iter().map(|v| format!("{v:.6e}")).collect::<Vec<_>>().join(", ")
                ),
            )
        }
        CheckSpec::MeshConvergence { meshes, quantity, max } => {
            let mut values = Vec::new();
            for &n in meshes {
                let m = crate::mesh::plate_model(n)?;
                let r = run_model(&m, &case_options(case))?;
                values.push(quantity.of(&r.summary));
            }
            let ch: Vec<f64> = values.windows(2).map(|w| ((w[1] - w[0]) / w[1]).abs()).collect();
            let last = *ch.last().unwrap_or(&f64::NAN);
            let decreasing = ch.windows(2).all(|w| w[1] < w[0]);
            res(
                format!("mesh_convergence {}", quantity.name()),
                last,
                0.0,
                format!("≤ {max:.1e}, decreasing"),
                last <= *max && decreasing,
                format!(
                    "meshes {:?}: {}",
                    meshes,
                    values.iter().map(|v| format!("{v:.6e}")).collect::<Vec<_>>().join(", ")
                ),
            )
        }
        CheckSpec::Gold { file, tol } => {
            let path = rel(case, file);
            let out = gold::compare(&path, &run.history_names(), &run.history, tol);
            res(
                format!("gold {}", file.display()),
                out.worst,
                0.0,
                tol.text(),
                out.passed,
                out.detail,
            )
        }
    })
}

/// The verdicts of all cases.
#[derive(Debug, Clone, Serialize)]
pub struct Verdicts {
    pub results: Vec<CheckResult>,
    /// Cases that could not run at all, with why.
    pub errors: Vec<(String, String)>,
}

impl Verdicts {
    pub fn passed(&self) -> bool {
        self.errors.is_empty() && self.results.iter().all(|r| r.passed)
    }
}

/// Runs cases on up to `jobs` threads; results in case order.
pub fn verify(cases: &[Case], jobs: usize) -> Verdicts {
    let next = std::sync::atomic::AtomicUsize::new(0);
    type Slot = std::sync::Mutex<Option<Result<Vec<CheckResult>, String>>>;
    let slots: Vec<Slot> = cases.iter().map(|_| std::sync::Mutex::new(None)).collect();
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1).min(cases.len().max(1)) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                if i >= cases.len() {
                    break;
                }
                let t0 = std::time::Instant::now();
                let r = run_case(&cases[i]).map(|(_, mut v)| {
                    let t = t0.elapsed().as_secs_f64();
                    v.iter_mut()
                        .for_each(|c| c.time_s = t / cases[i].checks.len().max(1) as f64);
                    v
                });
                *slots[i].lock().expect("no poisoning") = Some(r.map_err(|e| e.to_string()));
            });
        }
    });
    let mut out = Verdicts {
        results: Vec::new(),
        errors: Vec::new(),
    };
    for (case, slot) in cases.iter().zip(slots) {
        match slot.into_inner().expect("no poisoning") {
            Some(Ok(v)) => out.results.extend(v),
            Some(Err(e)) => out.errors.push((case.name.clone(), e)),
            None => out.errors.push((case.name.clone(), "not run".into())),
        }
    }
    out
}

/// The verdicts as a plain-text table.
pub fn table(v: &Verdicts) -> String {
    let mut s = format!(
        "{:<10} {:<44} {:>13} {:>13} {:<28} {}\n",
        "case", "check", "value", "reference", "tolerance", "verdict"
    );
    for r in &v.results {
        s += &format!(
            "{:<10} {:<44} {:>13.6e} {:>13.6e} {:<28} {}\n",
            r.case,
            r.check,
            r.value,
            r.reference,
            r.tolerance,
            if r.passed { "pass" } else { "FAIL" }
        );
        if !r.passed {
            s += &format!("{:<10} {:<44} {}\n", "", "", r.detail);
        }
    }
    for (c, e) in &v.errors {
        s += &format!("{c:<10} {:<44} ERROR: {e}\n", "(case did not run)");
    }
    let failed = v.results.iter().filter(|r| !r.passed).count();
    s += &format!(
        "{} checks, {} passed, {} failed, {} cases in error\n",
        v.results.len(),
        v.results.len() - failed,
        failed,
        v.errors.len()
    );
    s
}

/// `verify.json`.
pub fn json(v: &Verdicts) -> Vec<u8> {
    let mut b = serde_json::to_vec_pretty(v).expect("plain data");
    b.push(b'\n');
    b
}

/// `junit.xml`: one test suite per case, one test case per check.
pub fn junit(v: &Verdicts) -> Vec<u8> {
    use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
    let mut report = Report::new("impactlab verify");
    let mut names: Vec<&str> = v.results.iter().map(|r| r.case.as_str()).collect();
    names.extend(v.errors.iter().map(|e| e.0.as_str()));
    names.dedup();
    for name in names {
        let mut suite = TestSuite::new(name);
        for r in v.results.iter().filter(|r| r.case == name) {
            let status = if r.passed {
                TestCaseStatus::success()
            } else {
                let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                s.set_message(format!(
                    "value {:e}, reference {:e}, tolerance {}",
                    r.value, r.reference, r.tolerance
                ));
                s.set_description(r.detail.clone());
                s
            };
            let mut tc = TestCase::new(r.check.clone(), status);
            tc.set_classname(format!("verify.{name}"));
            tc.set_time(std::time::Duration::from_secs_f64(r.time_s));
            suite.add_test_case(tc);
        }
        for (_, e) in v.errors.iter().filter(|e| e.0 == name) {
            let mut s = TestCaseStatus::non_success(NonSuccessKind::Error);
            s.set_message(e.clone());
            let mut tc = TestCase::new("run", s);
            tc.set_classname(format!("verify.{name}"));
            suite.add_test_case(tc);
        }
        report.add_test_suite(suite);
    }
    report.to_string().expect("serialisable report").into_bytes()
}

/// Writes the gold files of a case's `gold` checks from its run (by hand, never in CI).
pub fn bless(case: &Case, run: &Run) -> Result<Vec<PathBuf>, Error> {
    let mut written = Vec::new();
    for spec in &case.checks {
        if let CheckSpec::Gold { file, .. } = spec {
            let path = rel(case, file);
            let bytes = crate::output::csv_bytes(&run.history_header(), run.history.iter().cloned());
            crate::output::write_file_atomically(&path, &bytes).map_err(|source| Error::Io {
                path: path.display().to_string(),
                source,
            })?;
            written.push(path);
        }
    }
    Ok(written)
}
