//! The modal engine: the target reduced to its lowest modes and residual vectors,
//! then stepped by the same schemes, contact and loads as the direct engine.
//!
//! The reduction (a Ritz basis, as MSC's modal transient response with residual
//! vectors, PARAM RESVEC):
//! - Modes Φ: the structure (every solved DOF but the impactor's) by shift-and-invert
//!   Lanczos ([`crate::eigen::lanczos`]), every root up to a cutoff frequency, its
//!   rigid-body modes included; M-orthonormal.
//! - Residual vectors Ψ: for each DOF the contact or a dynamic load acts on (the
//!   boundary DOFs), the static response to a unit load there with the modes' share of
//!   the load taken out first, ψ = (K − σM)⁻¹(I − MΦΦᵀ)e_b (σ = 0 unless the structure
//!   is free, [`crate::eigen::lanczos_factored`]), then M-orthogonalised against the modes and
//!   each other: the static flexibility there that the modes miss.
//! - Coordinates: the basis V = [Φ Ψ] is changed by Gauss-Jordan elimination on its
//!   boundary rows (the largest entry as pivot) into T, whose boundary rows are
//!   [I 0]: each boundary DOF is one coordinate and every other column vanishes there.
//!   The contact and the dynamic loads then act on coordinates exactly as on the direct
//!   engine's DOFs, and the impactor keeps its own. The span, and so the answer, is
//!   V's whatever the pivots.
//! - The interior columns (those vanishing on the boundary) are then turned into the
//!   reduced model's own modes with the boundary held (K_II X = M_II X Λ, XᵀM_II X =
//!   I), again without changing the span. The reduced system K_r = TᵀKT, M_r = TᵀMT
//!   is then an arrowhead: Λ and I on the interior, full only in the boundary's rows
//!   and columns, so that a step costs O(p·nb), p coordinates and nb boundary DOFs
//!   (the paper's plate: 3000 steps in 0.04 s, against 0.24 s dense). It is stepped by
//!   the scheme asked for. M_r is not diagonal (the boundary's rows): central
//!   differences, which need a lumped mass, are refused.
//! - The ledger is the reduced system's (½q̇ᵀM_r q̇, ½qᵀK_r q, momentum through
//!   M_r⁻¹TᵀMw): exact for the reduced model, so it closes as the direct ledger does.
//!   The history's outputs are linear in (u, v): each is a row over the coordinates
//!   (the outputs of each basis vector), so that a row costs outputs × p operations,
//!   not n × p. Snapshots are expanded, u = T q.
//!
//! What the truncation costs is reported ([`Truncation`]): the modal effective mass
//! captured along the impact direction, and the static flexibility at the contact DOF
//! captured by the modes alone and by the reduced model, modes and residual vectors
//! (from the reduced model's own eigenpairs, not assumed).

use super::direct::{record, Fields};
use super::{linear_outputs, Engine, RunError, RunOptions, RunResult};
use crate::assembly::System;
use crate::eigen::{
    lanczos_factored, orthogonalise_columns, remove_block, tall_gram, tall_update, Columns, Extracted, LanczosParams,
    Roots,
};
use crate::integrate::Scheme;
use crate::ledger::Ledger;
use crate::model::{Contact, DofLabel, Model};
use crate::numerics::{column, dot};
use faer::linalg::matmul::matmul;
use nalgebra::{DMatrix, DVector};

/// How the modal engine reduces a model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalParams {
    /// Keep the modes up to this frequency (cycles per the deck's time unit); `None`:
    /// [`CYCLES_PER_CONTACT`] cycles over the contact time estimated by Hertz.
    pub cutoff: Option<f64>,
    /// Add residual vectors (on by default; off only to see what they add).
    pub residual_vectors: bool,
}

impl Default for ModalParams {
    fn default() -> Self {
        ModalParams {
            cutoff: None,
            residual_vectors: true,
        }
    }
}

/// The default cutoff's cycles per contact time: modes up to f = this / t_H, t_H the
/// Hertz contact time of the impactor on a rigid target at its speed
/// ([`crate::physics::analytic::rigid_target`]), a lower bound of the contact time
/// on a flexible target. At 4 (with [`RESIDUAL_ORDER`] 8), the paper's plate's
/// contact duration and peak force are within 1e-3 of the direct engine's
/// (measured 2.5e-4 and 5.6e-4, 163 modes; tests/modal.rs).
pub const CYCLES_PER_CONTACT: f64 = 4.0;

/// Residual vectors per boundary DOF: the static one, ψ₁ = F(I − MΦΦᵀ)e_b with
/// F = (K − σM)⁻¹, then ψ_{k+1} = F M ψ_k, each M-orthogonalised against the modes and
/// the vectors before it: a Krylov chain whose span holds the truncated modes'
/// response to a load at b to order (ω/ω_j)^(2k) below their frequencies ω_j (the
/// static vector alone: order 0). Measured on the paper's plate (tests/modal.rs).
pub const RESIDUAL_ORDER: usize = 8;

/// What the reduction kept and what it misses, in `summary.json` (`run.modal`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
pub struct Truncation {
    /// The cutoff frequency (cycles per the deck's time unit).
    pub cutoff_frequency: f64,
    /// Where the cutoff came from.
    pub cutoff_from: String,
    /// Modes kept, rigid-body modes included.
    pub modes: usize,
    /// Of which rigid-body modes (eigenvalue below 1e-12 of the largest K_ii/M_ii).
    pub rigid_modes: usize,
    /// The highest mode's frequency (cycles per the deck's time unit).
    pub highest_mode_frequency: f64,
    /// Residual vectors added.
    pub residual_vectors: usize,
    /// Coordinates of the reduced model, the impactor's included.
    pub coordinates: usize,
    /// The structure's solved DOFs it stands for.
    pub structure_dofs: usize,
    /// Σ (φᵀMw)² / wᵀMw over the modes, w the unit translation along the impact
    /// direction: the structure's mass the modes move along it.
    pub effective_mass_fraction: f64,
    /// The static flexibility at the contact DOF (its elastic part) the modes alone
    /// capture: Σ φ_c²/ω² over the elastic modes against that plus the residual
    /// flexibility (ψ_c of the residual vector's solve).
    pub flexibility_by_modes: f64,
    /// The same captured by the reduced model: Σ x_c²/λ over its own elastic
    /// eigenpairs (K_r x = λ M_r x), against the same whole.
    pub flexibility_reduced: f64,
    /// Lanczos vectors the modes took (a step of the block recurrence forms four; the
    /// key keeps its name from when a step formed one).
    pub lanczos_steps: usize,
    /// Seconds for the reduction: modes, residual vectors, the reduced system.
    pub reduction_s: f64,
    /// Of which seconds extracting the modes.
    pub modes_s: f64,
}

/// A model reduced for the modal engine.
pub struct Reduction {
    /// The reduced model: its DOFs the coordinates (the impactor's, the boundary DOFs,
    /// then the rest), its contact and loads on them, no elements.
    pub model: Model,
    /// The reduced system K_r, M_r.
    pub system: System,
    /// The momentum's weights on M_r q̇.
    pub(super) momentum: Vec<f64>,
    /// The structure's part, shared by the reductions of every model of the same
    /// structure ([`Reduction::for_point`]).
    basis: std::sync::Arc<Basis>,
    /// What the reduction kept.
    pub truncation: Truncation,
}

/// The structure's part of a reduction: its basis and what it maps.
struct Basis {
    /// The full model's solved DOFs.
    n: usize,
    /// The impactor's DOFs (the first coordinates, one each).
    own: Vec<usize>,
    /// The structure's DOFs, in the order of T's rows.
    structure: Vec<usize>,
    /// The coordinate of each of the full model's DOFs that is one: the impactor's and
    /// the boundary DOFs.
    map: Vec<Option<usize>>,
    /// T: the structure's basis vector of each coordinate after the impactor's.
    columns: Columns,
    /// The history's linear outputs of each coordinate's displacement and velocity:
    /// `outputs_u[c]` is the output vector of u = coordinate c's basis vector.
    outputs_u: Vec<Vec<f64>>,
    outputs_v: Vec<Vec<f64>>,
}

impl Reduction {
    /// The history's linear outputs at the reduced state (q, q̇).
    pub(super) fn outputs(&self, q: &[f64], qd: &[f64]) -> Vec<f64> {
        let b = &self.basis;
        let mut out = vec![0.0; b.outputs_u.first().map_or(0, Vec::len)];
        for (c, (ou, ov)) in b.outputs_u.iter().zip(&b.outputs_v).enumerate() {
            for (o, (a, b)) in out.iter_mut().zip(ou.iter().zip(ov)) {
                *o += a * q[c] + b * qd[c];
            }
        }
        out
    }

    /// The full model's field of reduced coordinates q: the impactor's DOFs as they
    /// are, the structure's T q.
    pub(super) fn expand(&self, q: &[f64]) -> Vec<f64> {
        let b = &self.basis;
        let mut u = vec![0.0; b.n];
        let o = b.own.len();
        for (&i, &x) in b.own.iter().zip(q) {
            u[i] = x;
        }
        let mut ts = vec![0.0; b.structure.len()];
        matmul(
            faer::MatMut::from_column_major_slice_mut(&mut ts, b.structure.len(), 1),
            faer::Accum::Replace,
            b.columns.mat(),
            faer::MatRef::from_column_major_slice(&q[o..], q.len() - o, 1),
            1.0,
            faer::Par::Seq,
        );
        for (&i, x) in b.structure.iter().zip(ts) {
            u[i] = x;
        }
        u
    }

    /// Runs `point` (a model of this reduction's structure: a sweep's or a threshold
    /// search's point) on the modal engine with this reduction:
    /// [`Reduction::for_point`] on its prepared system, then [`run_reduced`].
    pub fn run_point(&self, point: &Model, opts: &RunOptions) -> Result<RunResult, RunError> {
        let prepared = super::prepare(point, opts)?;
        let r = self.for_point(&prepared.model, &prepared.system)?;
        run_reduced(&prepared.model, &r, opts)
    }

    /// The reduction of `point` (prepared, with its system `sys`): a model of the same
    /// structure, contact DOFs and outputs as this reduction's, whose impactor, contact
    /// law or impactor's initial state differ (a sweep's point). The structure's basis,
    /// K_r and M_r are this reduction's; the impactor's block of the system, the
    /// contact and the initial state are the point's. The same as reducing `point`
    /// at this reduction's cutoff, without the extraction.
    pub fn for_point(&self, point: &Model, sys: &System) -> Result<Reduction, RunError> {
        let b = &self.basis;
        let o = b.own.len();
        let differs = |what: &str| {
            RunError::Engine(format!(
                "the modal reduction of one model serves another only with the same structure: {what} differs"
            ))
        };
        if point.n() != b.n || point.target_mask().iter().filter(|&&t| !t).count() != o {
            return Err(differs("the solved DOFs"));
        }
        // The structure starts at rest in both (as in a sweep).
        let point_moves = b.structure.iter().any(|&i| point.u0[i] != 0.0 || point.v0[i] != 0.0);
        let own_moves = self.model.u0[o..].iter().chain(&self.model.v0[o..]).any(|&x| x != 0.0);
        if point_moves || own_moves {
            return Err(differs("the structure's initial state (a point's must be at rest)"));
        }
        // The point's impactor block (its entries on the impactor's DOFs), then this
        // reduction's structure block (its coordinates from `o` on).
        type Entries = [faer::sparse::Triplet<usize, usize, f64>];
        let own_index = |i: usize| b.own.iter().position(|&j| j == i);
        let entries = |point: &Entries, reduced: &Entries| -> Vec<(usize, usize, f64)> {
            let own = point
                .iter()
                .filter_map(|t| Some((own_index(t.row)?, own_index(t.col)?, t.val)));
            let structure = reduced
                .iter()
                .filter(|t| t.row >= o && t.col >= o)
                .map(|t| (t.row, t.col, t.val));
            own.chain(structure).collect()
        };
        let system = System::from_entries(
            self.system.n,
            entries(&sys.k, &self.system.k),
            entries(&sys.m, &self.system.m),
            entries(&sys.c, &self.system.c),
        );
        let mut model = self.model.clone();
        for (k, &i) in b.own.iter().enumerate() {
            model.u0[k] = point.u0[i];
            model.v0[k] = point.v0[i];
        }
        model.contact = point
            .contact
            .as_ref()
            .map(|c| on_coordinates(c, &b.map).map_err(|_| differs("the DOFs the contact acts on")))
            .transpose()?;
        Ok(Reduction {
            model,
            system,
            momentum: self.momentum.clone(),
            basis: self.basis.clone(),
            truncation: self.truncation.clone(),
        })
    }
}

/// Runs a prepared model ([`super::prepare`]) on the modal engine.
pub fn run(model: &Model, sys: &System, opts: &RunOptions) -> Result<RunResult, RunError> {
    if opts.scheme == Scheme::Central {
        return Err(RunError::Engine(
            "the modal engine's reduced mass is not diagonal: central differences need a lumped mass; use \
             newmark, energy or nastran"
                .into(),
        ));
    }
    let budget = opts.max_memory.map(|limit| {
        let steps = opts.steps.unwrap_or(model.time.steps);
        limit.saturating_sub(super::memory_estimate(model, steps, Engine::Modal))
    });
    let t0 = std::time::Instant::now();
    // The reduction is most of a large model's run, all before its first step (the
    // 199 × 199 panel's: 45 s of 49 s): the run's bar says so meanwhile.
    let bar = opts.progress.clone();
    let label = bar.as_ref().map(|b| {
        let label = b.message();
        b.set_message(format!("{label}, reducing to modes and residual vectors"));
        b.enable_steady_tick(std::time::Duration::from_millis(250));
        label
    });
    // Then what it is at: the Lanczos vectors and modes so far, the residual vectors.
    let say = |detail: &str| {
        if let (Some(b), Some(label)) = (&bar, &label) {
            b.set_message(format!("{label}, reducing to modes and residual vectors: {detail}"));
        }
    };
    let reduced = reduce(model, sys, &opts.modal, budget, &say);
    if let (Some(b), Some(label)) = (&bar, label) {
        b.disable_steady_tick();
        b.set_message(label);
    }
    let r = reduced?;
    // The run's wall time includes its reduction.
    super::amended(run_reduced(model, &r, opts), |run| {
        run.stats.total_time = t0.elapsed();
        run.summary.run.wall_s = run.stats.total_time.as_secs_f64();
    })
}

/// Runs a prepared model on the modal engine with its reduction `r` ([`reduce`], or
/// [`Reduction::for_point`] of another model's).
pub fn run_reduced(model: &Model, r: &Reduction, opts: &RunOptions) -> Result<RunResult, RunError> {
    let ledger = opts
        .ledger
        .then(|| Ledger::reduced(&r.model, &r.system, r.momentum.clone()));
    let result = record(
        model,
        &r.model,
        &r.system,
        ledger,
        Fields::Reduced(r),
        opts,
        Engine::Modal,
    )
    .map_err(|e| match e {
        // A reduced coordinate is no DOF of the deck: "constrain it" would mislead.
        RunError::Solve(crate::integrate::SolveError::Mechanism { dof }) if dof.starts_with("point -") => {
            RunError::Engine(format!(
                "the modal engine's reduced system is singular along one of its {} basis vectors ({dof}): they are \
                 nearly dependent, as when the modes and residual vectors ({} and {} here) span nearly every DOF \
                 with mass; lower the cutoff (--modes-up-to)",
                r.truncation.coordinates, r.truncation.modes, r.truncation.residual_vectors
            ))
        }
        e => e,
    });
    super::amended(result, |run| run.summary.run.modal = Some(r.truncation.clone()))
}

/// The cutoff frequency of a model's reduction and where it came from: as asked, or
/// [`CYCLES_PER_CONTACT`] cycles over the Hertz contact time of its impactor.
pub fn cutoff(model: &Model, params: &ModalParams) -> Result<(f64, String), RunError> {
    if let Some(f) = params.cutoff {
        if !(f > 0.0 && f.is_finite()) {
            return Err(RunError::Input(format!(
                "modal cutoff frequency {f:e}: it must be positive"
            )));
        }
        return Ok((f, "as asked".into()));
    }
    let Some(c) = &model.contact else {
        return Err(RunError::Input(
            "the modal engine takes its default cutoff from the contact time, and this run has no contact: give \
             the cutoff frequency (--modes-up-to)"
                .into(),
        ));
    };
    let v0 = model.v0[c.impactor.dof].abs();
    if v0 == 0.0 {
        return Err(RunError::Input(
            "the modal engine takes its default cutoff from the contact time, and the impactor starts at rest: \
             give the cutoff frequency (--modes-up-to)"
                .into(),
        ));
    }
    let (_, _, t_h) = crate::physics::analytic::rigid_target(c.impactor.mass, v0, c.stiffness);
    Ok((
        CYCLES_PER_CONTACT / t_h,
        format!(
            "{CYCLES_PER_CONTACT} cycles over {t_h:.4e}, the Hertz contact time (A = 3/2) of the impactor on a \
             rigid target at its speed"
        ),
    ))
}

/// Reduces a prepared model (see the module's text), in at most `budget` bytes
/// besides the run's system and records. Its storage is vectors over the structure's
/// DOFs: j Lanczos vectors (over its DOFs with mass alone), with the m modes as they
/// are formed (j + m), then T as it is reordered and turned, two copies at a time (2p,
/// p = m + residual vectors, m ≤ j); so the extraction may form as many Lanczos
/// vectors as half the budget holds vectors over the structure's DOFs. It tells `say`
/// what it is at, for a progress bar: the factorisation, the Lanczos vectors and the
/// modes converged at each convergence test, the modes' vectors, the residual vector
/// it is forming, the reduced matrices.
pub fn reduce(
    model: &Model,
    sys: &System,
    params: &ModalParams,
    budget: Option<u64>,
    say: &dyn Fn(&str),
) -> Result<Reduction, RunError> {
    reduce_at(model, sys, params, cutoff(model, params)?, budget, say)
}

/// [`reduce`] with the cutoff frequency and where it came from given: the cutoff of a
/// family of runs (a sweep's, from its shortest contact).
pub fn reduce_at(
    model: &Model,
    sys: &System,
    params: &ModalParams,
    (cut, cutoff_from): (f64, String),
    budget: Option<u64>,
    say: &dyn Fn(&str),
) -> Result<Reduction, RunError> {
    let t0 = std::time::Instant::now();
    let n = model.n();
    // The impactor's DOFs stay physical; the rest is the structure.
    let target = model.target_mask();
    let structure: Vec<usize> = (0..n).filter(|&i| target[i]).collect();
    let own: Vec<usize> = (0..n).filter(|&i| !target[i]).collect();
    let mut local = vec![None; n];
    for (k, &i) in structure.iter().enumerate() {
        local[i] = Some(k);
    }
    let ns = structure.len();
    // The boundary: every structure DOF the contact or a dynamic load touches.
    let mut boundary: Vec<usize> = Vec::new();
    if let Some(c) = &model.contact {
        boundary.extend(c.driver.iter().map(|&(j, _)| j));
        boundary.extend(c.loads.iter().map(|l| l.dof));
        boundary.extend(c.nonconservative.iter().map(|&(j, _)| j));
    }
    if let Some(x) = &model.excitation {
        boundary.extend(x.terms.iter().map(|t| t.dof));
    }
    boundary.retain(|&j| target[j]);
    boundary.sort_unstable();
    boundary.dedup();
    let s_sys = sys.restricted(&local, ns);
    let labels: Vec<DofLabel> = structure.iter().map(|&i| model.dofs[i]).collect();
    let omega_cut = 2.0 * std::f64::consts::PI * cut;
    let roots = Roots {
        above: f64::NEG_INFINITY,
        below: Some(omega_cut * omega_cut),
        count: None,
    };
    let lanczos_params = LanczosParams {
        max_vectors: budget.map(|b| (b / 2 / (8 * ns.max(1) as u64)) as usize),
        ..Default::default()
    };
    // K − σM, factorised for the extraction and kept for the residual vectors.
    say(&format!("factorising the structure's {ns} DOFs"));
    let extracted = |e: Extracted| {
        say(&if e.converged {
            format!(
                "{} modes from {} Lanczos vectors, forming their vectors",
                e.roots, e.vectors
            )
        } else {
            format!("{} Lanczos vectors, {} modes converged", e.vectors, e.roots)
        })
    };
    let (mut pairs, mut factor) =
        lanczos_factored(&s_sys, &labels, &roots, &lanczos_params, &extracted).map_err(|e| match e {
            crate::integrate::SolveError::Memory { what, .. } => RunError::Input(format!(
                "the modal reduction (modes up to {cut:.4e} cycles per the deck's time unit) is over the memory \
             limit: {what}; with as many modes over the structure's {ns} DOFs and the basis made of them, more \
             than the {:.2} GiB the limit leaves beside the system and the records; lower the cutoff \
             (--modes-up-to) or raise --max-memory",
                budget.unwrap_or(0) as f64 / (1u64 << 30) as f64
            )),
            e => e.into(),
        })?;
    let m_mul = |x: &[f64]| {
        let mut y = vec![0.0; ns];
        s_sys.m_mul(x, &mut y);
        y
    };
    let rigid_below = crate::eigen::rigid_below(&s_sys);
    let md = s_sys.m_diag();
    let rigid_modes = pairs.values.iter().filter(|&&l| l < rigid_below).count();
    // Residual vectors, and the residual flexibility at the contact DOF.
    let contact_dof = model
        .contact
        .as_ref()
        .and_then(|c| c.loads.iter().map(|l| l.dof).find(|&j| target[j]))
        .and_then(|j| local[j]);
    // Truncation: effective mass along the impact direction, flexibility at the
    // contact by the modes.
    let w = model.momentum_weights();
    let ws: Vec<f64> = structure.iter().map(|&i| w[i]).collect();
    let mw = m_mul(&ws);
    let total_mass = dot(&ws, &mw);
    let captured: f64 = pairs.vectors.iter().map(|phi| dot(phi, &mw).powi(2)).sum();
    let by_modes = contact_dof.map_or(f64::NAN, |c| {
        pairs
            .values
            .iter()
            .zip(&pairs.vectors)
            .filter(|(&l, _)| l >= rigid_below)
            .map(|(l, phi)| phi[c] * phi[c] / l)
            .sum::<f64>()
    });
    let mut residual_count = 0;
    let mut residual_flexibility = f64::NAN;
    // The basis, modes then residual vectors, as one matrix (the modes moved in).
    let mut kept = Columns::with_capacity(ns, pairs.vectors.len() + boundary.len() * RESIDUAL_ORDER);
    for phi in std::mem::take(&mut pairs.vectors) {
        kept.push(&phi);
    }
    // No more M-independent vectors than DOFs with mass: past them a residual vector
    // is round-off (the modes up to a cutoff above the mesh's highest span them all).
    let with_mass = md.iter().filter(|&&m| m > 0.0).count();
    let modes = kept.len();
    // The M-images of the residual vectors (the vectors are `kept`'s after the modes).
    let mut m_images: Vec<Vec<f64>> = Vec::new();
    {
        for &b in &boundary {
            let bl = local[b].expect("boundary DOFs are the structure's");
            // (I − MΦΦᵀ) e_b: the modes' share of the load taken out.
            let mut share = vec![0.0; ns];
            let phi = kept.mat().subcols(0, modes);
            matmul(
                faer::MatMut::from_column_major_slice_mut(&mut share, ns, 1),
                faer::Accum::Replace,
                phi,
                phi.row(bl).transpose().as_mat(),
                1.0,
                faer::Par::Seq,
            );
            let mut load: Vec<f64> = m_mul(&share).iter().map(|x| -x).collect();
            load[bl] += 1.0;
            for order in 0..if params.residual_vectors { RESIDUAL_ORDER } else { 1 } {
                say(&if params.residual_vectors {
                    format!(
                        "{modes} modes; residual vector {} of at most {}",
                        residual_count + 1,
                        boundary.len() * RESIDUAL_ORDER
                    )
                } else {
                    format!("{modes} modes; the static flexibility they leave out")
                });
                factor.solve_in_place(&mut load);
                let mut psi = load;
                if order == 0 && Some(bl) == contact_dof {
                    residual_flexibility = psi[bl];
                }
                if !params.residual_vectors || kept.len() >= with_mass {
                    break;
                }
                // M-orthogonal to the residual vectors before it, one after another
                // (a chain's next vector lies mostly along its last ones), then to the
                // modes and them all at once, where only round-off is left (F M ψ is
                // M-orthogonal to the modes when ψ is, to their accuracy): one pass of
                // the matrix products, where the Kahan test asked for a second for 30
                // of the paper's plate's 32 vectors without the first step.
                let mut m_psi = m_mul(&psi);
                let size = dot(&psi, &m_psi).max(0.0).sqrt();
                let residuals = kept.iter().skip(modes).zip(m_images.iter().map(Vec::as_slice));
                remove_block(&mut psi, &mut m_psi, residuals, |_, _| {});
                let m_psi = orthogonalise_columns(
                    faer::MatMut::from_column_major_slice_mut(&mut psi, ns, 1),
                    &kept,
                    &m_mul,
                );
                let left = dot(&psi, column(m_psi.as_ref(), 0)).max(0.0).sqrt();
                if left <= 1e-8 * size {
                    break;
                }
                psi.iter_mut().for_each(|p| *p /= left);
                // The next of the chain: the structure's response to this shape's inertia.
                load = column(m_psi.as_ref(), 0).iter().map(|x| x / left).collect();
                kept.push(&psi);
                m_images.push(load.clone());
                residual_count += 1;
            }
        }
    }
    say(&format!(
        "the reduced matrices over {} basis vectors",
        modes + residual_count
    ));
    // V = [Φ Ψ], then T: boundary rows [I 0].
    let mut columns = kept;
    let p = columns.len();
    let mut pivots: Vec<usize> = Vec::with_capacity(boundary.len());
    for &b in &boundary {
        let bl = local[b].expect("boundary DOFs are the structure's");
        let pick = (0..p)
            .filter(|j| !pivots.contains(j))
            .max_by(|&x, &y| columns.col(x)[bl].abs().total_cmp(&columns.col(y)[bl].abs()));
        // A pivot small against its own column's motion where there is mass (a
        // massless rotation held by little stiffness may move far more): the basis
        // hardly moves this DOF.
        let moved = |j: &usize| {
            let size = columns
                .col(*j)
                .iter()
                .zip(&md)
                .filter(|(_, &m)| m > 0.0)
                .fold(0.0f64, |a, (x, _)| a.max(x.abs()));
            columns.col(*j)[bl].abs() > 1e-10 * size
        };
        let Some(j) = pick.filter(moved) else {
            return Err(RunError::Input(format!(
                "the modal basis ({} modes, {} residual vectors) does not move {} (the contact or a dynamic load \
                 acts there): raise the cutoff frequency{}",
                modes,
                residual_count,
                model.dofs[b],
                if params.residual_vectors {
                    ""
                } else {
                    " or add residual vectors"
                }
            )));
        };
        let d = columns.col(j)[bl];
        columns.col_mut(j).iter_mut().for_each(|x| *x /= d);
        let pivot = columns.col(j).to_vec();
        for c in (0..p).filter(|&c| c != j) {
            let col = columns.col_mut(c);
            let f = col[bl];
            if f != 0.0 {
                col.iter_mut().zip(&pivot).for_each(|(x, y)| *x -= f * y);
                col[bl] = 0.0;
            }
        }
        pivots.push(j);
    }
    let order: Vec<usize> = pivots
        .iter()
        .copied()
        .chain((0..p).filter(|j| !pivots.contains(j)))
        .collect();
    let mut columns = {
        let v = columns;
        let mut t = Columns::with_capacity(ns, p);
        order.iter().for_each(|&j| t.push(v.col(j)));
        t
    };
    // The reduced coordinates: the impactor's DOFs, then T's columns.
    let nr = own.len() + p;
    let mut own_index: Vec<Option<usize>> = vec![None; n];
    for (k, &i) in own.iter().enumerate() {
        own_index[i] = Some(k);
    }
    let mut map = own_index.clone();
    for (k, &b) in boundary.iter().enumerate() {
        map[b] = Some(own.len() + k);
    }
    // K_r and M_r: the impactor's block as assembled, the structure's TᵀKT, TᵀMT.
    let own_block = |entries: &[faer::sparse::Triplet<usize, usize, f64>]| {
        let mut x = DMatrix::<f64>::zeros(nr, nr);
        for t in entries {
            if let (Some(a), Some(b)) = (own_index[t.row], own_index[t.col]) {
                x[(a, b)] += t.val;
            }
        }
        x
    };
    let (mut k_r, mut m_r, mut c_r) = (own_block(&sys.k), own_block(&sys.m), own_block(&sys.c));
    // TᵀKT and TᵀMT: the sparse products of a block of columns, then a matrix product
    // each for the lower triangle only (each half block's rows from its first column
    // down), mirrored: half the products of the whole, and symmetric. Blocks of 32
    // columns keep the products' storage small beside T's.
    let o = own.len();
    // TᵀCT likewise, for a damped structure (an empty p × 0 product otherwise).
    let damped = s_sys.damped();
    let (mut kt_t, mut mt_t) = (faer::Mat::<f64>::zeros(p, p), faer::Mat::<f64>::zeros(p, p));
    let mut ct_t = faer::Mat::<f64>::zeros(p, if damped { p } else { 0 });
    for first in (0..p).step_by(32) {
        let width = 32.min(p - first);
        // The block's sparse products, its second half's on a second thread.
        let products_of = |cs: std::ops::Range<usize>| {
            let x = columns.mat().subcols(cs.start, cs.len());
            let (mut kt, mut mt) = (faer::Mat::zeros(ns, cs.len()), faer::Mat::zeros(ns, cs.len()));
            let mut ct = faer::Mat::zeros(ns, if damped { cs.len() } else { 0 });
            s_sys.k_mul_columns(x, kt.as_mut());
            s_sys.m_mul_columns(x, mt.as_mut());
            if damped {
                s_sys.c_mul_columns(x, ct.as_mut());
            }
            [kt, mt, ct]
        };
        let half = first + width / 2;
        let (top, bottom) = crate::numerics::both(|| products_of(first..half), || products_of(half..first + width));
        let mut products = vec![(&mut kt_t, 0), (&mut mt_t, 1)];
        if damped {
            products.push((&mut ct_t, 2));
        }
        for (x, which) in products {
            for (at, xt) in [(first, &top[which]), (half, &bottom[which])] {
                if xt.ncols() == 0 {
                    continue;
                }
                let g = tall_gram(columns.mat().subcols(at, p - at), xt.as_ref());
                x.as_mut()
                    .submatrix_mut(at, at, p - at, xt.ncols())
                    .copy_from(g.as_ref());
            }
        }
    }
    let mut reduced = vec![(&mut k_r, &kt_t), (&mut m_r, &mt_t)];
    if damped {
        reduced.push((&mut c_r, &ct_t));
    }
    for (x_r, x) in reduced {
        for a in 0..p {
            for b in 0..=a {
                let v = x[(a, b)];
                x_r[(o + a, o + b)] = v;
                x_r[(o + b, o + a)] = v;
            }
        }
    }
    // The interior coordinates (those after the boundary's, whose vectors vanish on
    // the boundary DOFs) turned into the reduced model's own modes with the boundary
    // held: T_I ← T_I X, K_II X = M_II X Λ, XᵀM_II X = I. The span is unchanged; K_r and
    // M_r become arrowheads (diagonal but for the impactor's and the boundary's rows),
    // so that a step costs O(p·nb), not O(p²).
    let first = o + boundary.len();
    let massless_vector =
        || RunError::Engine("the reduced mass matrix is not positive definite: a basis vector carries no mass".into());
    let (lambda, x) = held_modes(
        &k_r.view((first, first), (nr - first, nr - first)).into_owned(),
        &m_r.view((first, first), (nr - first, nr - first)).into_owned(),
    )
    .ok_or_else(massless_vector)?;
    let ni = nr - first;
    {
        let mut turned = faer::Mat::<f64>::zeros(ns, ni);
        tall_update(
            turned.as_mut(),
            columns.mat().subcols(first - o, ni),
            faer::MatRef::from_column_major_slice(x.as_slice(), ni, ni),
            1.0,
        );
        for c in 0..ni {
            columns
                .col_mut(first - o + c)
                .iter_mut()
                .zip(turned.col(c).iter())
                .for_each(|(t, v)| *t = *v);
        }
    }
    let turn = |a: &mut DMatrix<f64>, interior: Option<DMatrix<f64>>| {
        let rows = a.view((0, first), (first, ni)) * &x;
        a.view_mut((0, first), (first, ni)).copy_from(&rows);
        a.view_mut((first, 0), (ni, first)).copy_from(&rows.transpose());
        let interior = interior.unwrap_or_else(|| {
            let b = x.transpose() * a.view((first, first), (ni, ni)) * &x;
            (&b + b.transpose()) * 0.5
        });
        a.view_mut((first, first), (ni, ni)).copy_from(&interior);
    };
    turn(&mut k_r, Some(DMatrix::from_diagonal(&DVector::from_vec(lambda))));
    turn(&mut m_r, Some(DMatrix::identity(ni, ni)));
    if damped {
        turn(&mut c_r, None);
    }
    let entries = |x: &DMatrix<f64>| -> Vec<(usize, usize, f64)> {
        (0..nr)
            .flat_map(|j| (0..nr).map(move |i| (i, j)))
            .filter(|&(i, j)| x[(i, j)] != 0.0)
            .map(|(i, j)| (i, j, x[(i, j)]))
            .collect()
    };
    let system = System::from_entries(nr, entries(&k_r), entries(&m_r), entries(&c_r));
    // A full vector x on the coordinates: the impactor's entries as they are (its
    // block is not coupled to the structure's), the structure's projected,
    // M_r⁻¹TᵀMx; zero stays zero.
    let ms = m_r
        .view((o, o), (p, p))
        .into_owned()
        .cholesky()
        .ok_or_else(massless_vector)?;
    let project = |x: &[f64]| -> Vec<f64> {
        let mut q: Vec<f64> = own.iter().map(|&i| x[i]).collect();
        let xs: Vec<f64> = structure.iter().map(|&i| x[i]).collect();
        if xs.iter().all(|&v| v == 0.0) {
            q.resize(nr, 0.0);
        } else {
            let mx = m_mul(&xs);
            let rhs = DVector::from_iterator(p, columns.iter().map(|c| dot(c, &mx)));
            q.extend(ms.solve(&rhs).iter());
        }
        q
    };
    let momentum = project(&w);
    let (u0, v0) = (project(&model.u0), project(&model.v0));
    // The reduced model: coordinates labelled by the DOF they are, or as points.
    let dofs: Vec<DofLabel> = own
        .iter()
        .map(|&i| model.dofs[i])
        .chain(boundary.iter().map(|&b| model.dofs[b]))
        .chain((boundary.len()..p).map(|k| DofLabel {
            point: -(k as i64) - 1,
            comp: 0,
        }))
        .collect();
    let remap = |j: usize| map[j].expect("the contact and the loads act on coordinates");
    let mut reduced = model.clone();
    reduced.dofs = dofs;
    reduced.dependent = Vec::new();
    reduced.elements = std::sync::Arc::new(Vec::new());
    reduced.u0 = u0;
    reduced.v0 = v0;
    reduced.rod = None;
    reduced.inert_dofs = 0;
    reduced.frames = Default::default();
    reduced.contact = model.contact.as_ref().map(|c| {
        on_coordinates(c, &map).unwrap_or_else(|j| panic!("the contact acts on coordinates, not on {}", model.dofs[j]))
    });
    if let Some(x) = &mut reduced.excitation {
        x.terms.iter_mut().for_each(|t| t.dof = remap(t.dof));
    }
    // The outputs of each coordinate, from its vector over the full model's DOFs.
    let zero = vec![0.0; n];
    let mut e = vec![0.0; n];
    let (mut outputs_u, mut outputs_v) = (Vec::with_capacity(nr), Vec::with_capacity(nr));
    for c in 0..nr {
        e.fill(0.0);
        if c < o {
            e[own[c]] = 1.0;
        } else {
            structure.iter().zip(columns.col(c - o)).for_each(|(&i, &x)| e[i] = x);
        }
        outputs_u.push(linear_outputs(model, &e, &zero));
        outputs_v.push(linear_outputs(model, &zero, &e));
    }
    let whole = by_modes + residual_flexibility;
    let reduced_flexibility = contact_dof.map_or(f64::NAN, |c| {
        let k = boundary
            .iter()
            .position(|&b| local[b] == Some(c))
            .expect("the contact DOF is a boundary DOF");
        reduced_flexibility(&k_r, &m_r, o, o + k, rigid_modes)
    });
    let truncation = Truncation {
        cutoff_frequency: cut,
        cutoff_from,
        modes: pairs.values.len(),
        rigid_modes,
        highest_mode_frequency: pairs.values.last().map_or(0.0, |l| l.max(0.0).sqrt()) / (2.0 * std::f64::consts::PI),
        residual_vectors: residual_count,
        coordinates: nr,
        structure_dofs: ns,
        effective_mass_fraction: if total_mass > 0.0 {
            captured / total_mass
        } else {
            f64::NAN
        },
        flexibility_by_modes: by_modes / whole,
        flexibility_reduced: reduced_flexibility / whole,
        lanczos_steps: pairs.lanczos_vectors,
        reduction_s: t0.elapsed().as_secs_f64(),
        modes_s: pairs.time.as_secs_f64(),
    };
    Ok(Reduction {
        model: reduced,
        system,
        momentum,
        basis: std::sync::Arc::new(Basis {
            n,
            own,
            structure,
            map,
            columns,
            outputs_u,
            outputs_v,
        }),
        truncation,
    })
}

/// `c` with the DOFs it acts on renumbered to the coordinates `map` gives them, or the
/// first DOF that is no coordinate.
fn on_coordinates(c: &Contact, map: &[Option<usize>]) -> Result<Contact, usize> {
    let to = |j: usize| map[j].ok_or(j);
    let mut c = c.clone();
    for t in c.driver.iter_mut().chain(c.nonconservative.iter_mut()) {
        t.0 = to(t.0)?;
    }
    for l in &mut c.loads {
        l.dof = to(l.dof)?;
    }
    c.impactor.dof = to(c.impactor.dof)?;
    for d in &mut c.impactor.dofs {
        *d = to(*d)?;
    }
    Ok(c)
}

/// The reduced model's static flexibility at coordinate `c` (its structure's block
/// from `o` on): (K_r⁻¹)_cc when K_r is positive definite, else (a free structure with
/// `rigid` rigid-body modes) Σ x_c²/λ over the elastic eigenpairs of K_r x = λ M_r x,
/// M_r-normalised.
fn reduced_flexibility(k_r: &DMatrix<f64>, m_r: &DMatrix<f64>, o: usize, c: usize, rigid: usize) -> f64 {
    let p = k_r.nrows() - o;
    let k = k_r.view((o, o), (p, p)).into_owned();
    // A structure held in place: (K_r⁻¹)_cc.
    if let Some(f) = k.clone().cholesky() {
        return f.solve(&DVector::from_fn(p, |i, _| if i == c - o { 1.0 } else { 0.0 }))[c - o];
    }
    let Some((lambda, x)) = held_modes(&k, &m_r.view((o, o), (p, p)).into_owned()) else {
        return f64::NAN;
    };
    // The rigid-body roots are the lowest: zero to the round-off of the highest.
    lambda[rigid..]
        .iter()
        .zip(x.row(c - o).iter().skip(rigid))
        .map(|(lam, xc)| xc * xc / lam)
        .sum()
}

/// The eigenpairs of K x = λ M x (K symmetric, M symmetric positive definite, dense):
/// λ ascending and X with XᵀMX = I, XᵀKX = diag λ (by M = LLᵀ and the symmetric
/// eigenproblem of L⁻¹KL⁻ᵀ, [`crate::numerics::symmetric_eigen`]: with nalgebra's
/// pairing alone, the paper's free rod with every mode kept had two held modes
/// swapped, a reduced stiffness indefinite and a run 3e-3 from the direct run in
/// contact duration); `None` when M is not positive definite.
fn held_modes(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let n = k.nrows();
    let l = m.clone().cholesky()?.l();
    let lk = l.solve_lower_triangular(k)?;
    let a = l.solve_lower_triangular(&lk.transpose())?;
    let eig = crate::numerics::symmetric_eigen((&a + a.transpose()) * 0.5);
    let values = &eig.eigenvalues;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
    let y = DMatrix::from_fn(n, n, |r, c| eig.eigenvectors[(r, order[c])]);
    let x = l.transpose().solve_upper_triangular(&y)?;
    Some((order.iter().map(|&i| values[i]).collect(), x))
}
