//! The energy ledger (paper Eq. 13-17), momentum, and the energy error.
//!
//! Per state:
//! - KE_i = ½ vᵀMv over the impactor's DOFs (Eq. 14: ½ m v_i²);
//! - SE_i = V(α) = K/(A+1) α^(A+1), the integral of the contact law (Eq. 15: 2/5 K α^(5/2));
//!   for a contact that unloads along another curve ([`crate::integrate::law`]) what
//!   the unloading curve from the current state would return;
//! - KE_t = ½ vᵀMv over the target's DOFs — the exact kinetic energy of the lumped model;
//! - KE_t(Eq. 16) = Σ_e ½ m_e v̄_e², v̄_e the mean of the element's nodal velocities, as
//!   the paper computes it for rods (applied to shells likewise, over four corners). It is not the model's kinetic energy: it drops the energy
//!   of the velocity difference across each element, ½ m_e (Δv/2)²;
//! - SE_t = ½ uᵀKu, summed element by element through the element interface
//!   ([`crate::elements::Element::strain_energy`]), so every element kind is in it by
//!   construction; rods compute it from relative displacements (exactly Eq. 17,
//!   Σ ½ k_j (δ_j − δ_{j+1})²), so that the rigid-body drift of a free-free target
//!   adds no round-off;
//! - U_t = KE_i + SE_i + KE_t + SE_t (Eq. 13);
//! - W_ext: work of the loads that derive from no potential (the non-conservative
//!   remainder of the NOLIN3 loads), accumulated with the scheme's own step load, and
//!   of the deck's dynamic load (DLOAD), as the scheme books it;
//! - D: the energy the structure's viscous damping has dissipated, ∫ vᵀCv dt, as the
//!   scheme books it (its own energy identity's damping term, so that the balance
//!   closes as tightly as without damping); present only for a damped structure;
//! - D_c: the energy the contact has dissipated (the work done on it beyond SE_i, its
//!   hysteresis); present only for such a contact;
//! - error = (U_t + D + D_c − U_0 − W_ext)/U_0; for a structure that starts at rest (U_0 = 0,
//!   loaded by a DLOAD) the balance over the largest |W_ext| of the whole run, set
//!   when the run ends ([`Ledger::finish`]): its energies at the first steps are
//!   round-off of the later ones, and a balance over the work done so far is noise
//!   there (a second-order scheme's O(Δt²) at a load's kink is 25 % of the first
//!   step's work in NASTRAN-95's t09071a);
//! - energy ratio = (U_t + D + D_c)/(U_0 + W_ext), as LS-DYNA's GLSTAT prints it (1 when balanced);
//! - momentum: Σ (Mv)_i over the DOFs of the impact direction (each weighted by
//!   the cosine of its axis with it where grids are displaced in other frames).

use crate::assembly::System;
use crate::integrate::StepState;
use crate::model::Model;

/// One row of the ledger.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EnergyRow {
    /// Time.
    pub time: f64,
    /// KE_i = ½mv², Eq. 14.
    pub ke_impactor: f64,
    /// SE_i = K/(A+1)·α^(A+1), the contact potential, Eq. 15.
    pub se_impactor: f64,
    /// KE_t = ½vᵀMv over the target's DOFs.
    pub ke_target: f64,
    /// KE_t by the paper's Eq. 16 (mean nodal velocity of each element).
    pub ke_target_eq16: f64,
    /// SE_t = ½uᵀKu = Σ element strain energies, Eq. 17.
    pub se_target: f64,
    /// U_t = KE_i + SE_i + KE_t + SE_t, Eq. 13.
    pub total: f64,
    /// Work of the non-conservative loads so far.
    pub external_work: f64,
    /// Energy dissipated by viscous damping so far (0 for an undamped structure).
    pub dissipated_damping: f64,
    /// Energy dissipated by the contact's hysteresis so far (0 for an elastic one).
    pub dissipated_contact: f64,
    /// (U_t + D + D_c − U_0 − W)/U_0.
    pub error: f64,
    /// (U_t + D + D_c)/(U_0 + W).
    pub energy_ratio: f64,
    /// Σ(Mv) over the DOFs of the impact direction.
    pub momentum: f64,
}

/// What a model dissipates, each a column of `energy.csv` only when present.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dissipations {
    /// Viscous damping ([`Model::damped`]).
    pub damping: bool,
    /// A contact's hysteresis ([`Model::hysteretic`]).
    pub contact: bool,
}

impl Dissipations {
    /// Every column.
    pub const ALL: Dissipations = Dissipations {
        damping: true,
        contact: true,
    };

    /// What `model` dissipates.
    pub fn of(model: &Model) -> Self {
        Dissipations {
            damping: model.damped(),
            contact: model.hysteretic(),
        }
    }

    /// The dissipations booked, in column order.
    pub fn booked(self) -> Vec<Dissipated> {
        [
            (
                self.damping,
                Dissipated {
                    column: "dissipated_damping",
                    symbol: "D",
                    what: "dissipated by damping",
                    value: |r| r.dissipated_damping,
                },
            ),
            (
                self.contact,
                Dissipated {
                    column: "dissipated_contact",
                    symbol: "D_c",
                    what: "dissipated by the contact",
                    value: |r| r.dissipated_contact,
                },
            ),
        ]
        .into_iter()
        .filter_map(|(on, d)| on.then_some(d))
        .collect()
    }
}

/// One dissipation of the ledger: its `energy.csv` column, its symbol, what it is,
/// and its value in a row.
#[derive(Debug, Clone, Copy)]
pub struct Dissipated {
    /// The column of `energy.csv`.
    pub column: &'static str,
    /// The symbol in tables (D, D_c).
    pub symbol: &'static str,
    /// What it is, for legends.
    pub what: &'static str,
    /// Its value in a row.
    pub value: fn(&EnergyRow) -> f64,
}

/// The columns of `energy.csv`, in the order of [`EnergyRow::values`]:
/// `dissipated_damping` and `dissipated_contact` only where `booked` has them.
pub fn columns(booked: Dissipations) -> Vec<&'static str> {
    let mut c = vec![
        "time",
        "ke_impactor",
        "se_impactor",
        "ke_target",
        "ke_target_eq16",
        "se_target",
        "total",
        "external_work",
    ];
    c.extend(booked.booked().iter().map(|d| d.column));
    c.extend(["error", "energy_ratio", "momentum"]);
    c
}

impl EnergyRow {
    /// The row's values in the order of [`columns`].
    pub fn values(&self, booked: Dissipations) -> Vec<f64> {
        let mut v = vec![
            self.time,
            self.ke_impactor,
            self.se_impactor,
            self.ke_target,
            self.ke_target_eq16,
            self.se_target,
            self.total,
            self.external_work,
        ];
        v.extend(booked.booked().iter().map(|d| (d.value)(self)));
        v.extend([self.error, self.energy_ratio, self.momentum]);
        v
    }
}

/// Books the energies of each state of a run.
pub struct Ledger<'a> {
    model: &'a Model,
    sys: &'a System,
    target: Vec<bool>,
    direction: Vec<f64>,
    mv: Vec<f64>,
    /// K u, for the strain energy in reduced coordinates (empty otherwise).
    ku: Vec<f64>,
    u_prev: Vec<f64>,
    /// The Eq. 16 sums; `None` in reduced coordinates, which have no elements.
    eq16: Option<Eq16Elements>,
    external_work: f64,
    initial: Option<f64>,
}

impl<'a> Ledger<'a> {
    /// A ledger for a model and its assembled system.
    pub fn new(model: &'a Model, sys: &'a System) -> Self {
        let n = model.n();
        Ledger {
            model,
            sys,
            target: model.target_mask(),
            direction: model.momentum_weights(),
            mv: vec![0.0; n],
            ku: Vec::new(),
            u_prev: model.u0.clone(),
            eq16: Some(Eq16Elements::new(model)),
            external_work: 0.0,
            initial: None,
        }
    }

    /// A ledger in a reduced model's coordinates ([`crate::run::modal`]): its energies
    /// are ½q̇ᵀM_r q̇ and ½qᵀK_r q of the reduced system `sys` (the model has no
    /// elements), `direction` the momentum's weights on M_r q̇, and KE_t by Eq. 16 is
    /// not computed (NaN): it needs the elements' velocities.
    pub fn reduced(model: &'a Model, sys: &'a System, direction: Vec<f64>) -> Self {
        Ledger {
            direction,
            eq16: None,
            ku: vec![0.0; model.n()],
            ..Ledger::new(model, sys)
        }
    }

    /// Books a state; states must come in step order starting with step 0.
    pub fn record(&mut self, s: &StepState) -> EnergyRow {
        let m = self.model;
        self.sys.m_mul(s.v, &mut self.mv);
        // One pass: KE_t and KE_i, the momentum, and ½ u·Ku from the scheme's own K u
        // where it keeps one (the impactor has no stiffness: only the target
        // contributes), element by element otherwise.
        let (mut ke_t, mut ke_i, mut p, mut uf) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..m.n() {
            let k = 0.5 * s.v[i] * self.mv[i];
            if self.target[i] {
                ke_t += k;
            } else {
                ke_i += k;
            }
            let w = self.direction[i];
            if w == 1.0 {
                p += self.mv[i];
            } else if w != 0.0 {
                p += w * self.mv[i];
            }
            if let Some(f) = s.internal_force {
                uf += s.u[i] * f[i];
            }
        }
        let se_t = match (s.internal_force, &self.eq16) {
            (Some(_), _) => 0.5 * uf,
            (None, Some(_)) => strain_energy(m, s.u),
            (None, None) => {
                self.sys.k_mul(s.u, &mut self.ku);
                0.5 * crate::numerics::dot(s.u, &self.ku)
            }
        };
        let se_i = s.contact.stored;
        if let Some(c) = &m.contact {
            if s.step > 0 {
                let du: f64 = c
                    .nonconservative
                    .iter()
                    .map(|&(j, r)| r * (s.u[j] - self.u_prev[j]))
                    .sum();
                self.external_work += du * s.work_factor;
            }
            for &(j, _) in &c.nonconservative {
                self.u_prev[j] = s.u[j];
            }
        }
        let total = ke_i + se_i + ke_t + se_t;
        let u0 = *self.initial.get_or_insert(total);
        let external_work = self.external_work + s.applied_work;
        let held = total + s.dissipated + s.contact.dissipated;
        EnergyRow {
            time: s.time,
            ke_impactor: ke_i,
            se_impactor: se_i,
            ke_target: ke_t,
            ke_target_eq16: self.eq16.as_ref().map_or(f64::NAN, |e| e.kinetic_energy(s.v)),
            se_target: se_t,
            total,
            external_work,
            dissipated_damping: s.dissipated,
            dissipated_contact: s.contact.dissipated,
            error: relative_error(held, u0, external_work),
            energy_ratio: ratio(held, u0 + external_work),
            momentum: p,
        }
    }
}

impl Ledger<'_> {
    /// True when each row's error is final as recorded (U_0 > 0), so that a guard
    /// can judge it at once; false for a run from rest, whose rows
    /// [`Ledger::finish`] sets.
    pub fn judged_online(&self) -> bool {
        self.initial.is_some_and(|u0| u0 > 0.0)
    }

    /// Ends the ledger of a run: for a run from rest (U_0 = 0), each row's error is
    /// its balance over the largest |W_ext| of the run (left the balance itself when
    /// no work was done).
    pub fn finish(&self, rows: &mut [EnergyRow]) {
        if self.judged_online() {
            return;
        }
        let scale = rows.iter().fold(0.0f64, |m, r| m.max(r.external_work.abs()));
        if scale > 0.0 {
            for r in rows {
                r.error = (r.total + r.dissipated_damping + r.dissipated_contact - r.external_work) / scale;
            }
        }
    }
}

impl EnergyRow {
    /// A row whose target energy is known as a total only (the convolution engine's
    /// discrete work identity): KE_t, its Eq. 16 form and SE_t are NaN, the balance
    /// the same as the direct ledger's. `initial` is U_0, the total at step 0.
    pub fn with_target_total(
        time: f64,
        ke_impactor: f64,
        contact: crate::integrate::ContactEnergy,
        target_total: f64,
        external_work: f64,
        initial: f64,
        momentum: f64,
    ) -> Self {
        let se_impactor = contact.stored;
        let total = ke_impactor + se_impactor + target_total;
        let held = total + contact.dissipated;
        EnergyRow {
            time,
            ke_impactor,
            se_impactor,
            ke_target: f64::NAN,
            ke_target_eq16: f64::NAN,
            se_target: f64::NAN,
            total,
            external_work,
            dissipated_damping: 0.0,
            dissipated_contact: contact.dissipated,
            error: relative_error(held, initial, external_work),
            energy_ratio: ratio(held, initial + external_work),
            momentum,
        }
    }
}

/// (U_t − U_0 − W)/U_0, or the balance itself when U_0 is not positive.
fn relative_error(total: f64, u0: f64, external_work: f64) -> f64 {
    let balance = total - u0 - external_work;
    if u0 > 0.0 {
        balance / u0
    } else {
        balance
    }
}

/// Strain energy ½uᵀKu of the target, element by element.
pub fn strain_energy(model: &Model, u: &[f64]) -> f64 {
    model.elements.iter().map(|e| e.strain_energy(u)).sum()
}

/// What the paper's Eq. 16 sums over, computed once per model: each element's mass,
/// the weight 1/corners of a corner in the mean velocity, and where its solved corner
/// translations end in `dofs`, which holds each element's x DOFs, then its y, then
/// its z, each in corner order. Where grids are displaced in frames other than the
/// basic system, `turned` instead holds each element's corners with their frames, and
/// the mean is taken of their basic velocities.
struct Eq16Elements {
    elements: Vec<(f64, f64, [usize; 3])>,
    dofs: Vec<u32>,
    turned: Vec<(f64, Vec<Corner>)>,
}

/// An element corner's solved translations and their frame (axes in basic, columns).
type Corner = ([Option<usize>; 3], nalgebra::Matrix3<f64>);

impl Eq16Elements {
    fn new(model: &Model) -> Self {
        let mut elements = Vec::new();
        let mut dofs = Vec::new();
        let mut turned = Vec::new();
        for e in model.elements.iter() {
            let Some(mass) = e.kernel.eq16_mass() else { continue };
            let corners = e.translations();
            if !model.frames.is_empty() {
                let axes = |g: &i64| model.frames.get(g).map_or_else(nalgebra::Matrix3::identity, |f| f.axes);
                turned.push((mass, corners.into_iter().zip(e.grids.iter().map(axes)).collect()));
                continue;
            }
            let ends = std::array::from_fn(|k| {
                dofs.extend(
                    corners
                        .iter()
                        .filter_map(|c| c[k])
                        .map(|i| u32::try_from(i).expect("fewer than 2³² DOFs (the memory check refuses far fewer)")),
                );
                dofs.len()
            });
            elements.push((mass, 1.0 / corners.len() as f64, ends));
        }
        Eq16Elements { elements, dofs, turned }
    }

    /// The paper's Eq. 16: element mass times the square of the mean nodal velocity.
    fn kinetic_energy(&self, v: &[f64]) -> f64 {
        let mut ke = 0.0;
        let mut start = 0;
        for &(mass, w, ends) in &self.elements {
            let [x, y, z] = ends.map(|end| {
                let mean = self.dofs[start..end]
                    .iter()
                    .fold(0.0, |acc, &i| acc + w * v[i as usize]);
                start = end;
                mean
            });
            ke += 0.5 * mass * (x * x + y * y + z * z);
        }
        for (mass, corners) in &self.turned {
            let mean = corners.iter().fold(nalgebra::Vector3::zeros(), |acc, (d, axes)| {
                let local = nalgebra::Vector3::from_fn(|k, _| d[k].map_or(0.0, |i| v[i]));
                acc + axes * local
            }) / corners.len() as f64;
            ke += 0.5 * mass * mean.norm_squared();
        }
        ke
    }
}

/// U_t/(U_0 + W_ext): 1 for a balanced ledger; 1 too when there is no energy at all.
fn ratio(total: f64, available: f64) -> f64 {
    if available != 0.0 {
        total / available
    } else if total == 0.0 {
        1.0
    } else {
        f64::INFINITY
    }
}
