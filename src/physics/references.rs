//! The analytic references of a model's impact, from its plain numbers (impactor,
//! Hertz law, rod or shell section): the ball on a semi-infinite rod and the impactor
//! on an infinite plate. They read the model's data; they run no solver code.

use super::analytic::{self, Events, HertzDashpot, Trace};
use crate::model::Model;

/// A reference that does not apply to a model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// The model has no contact.
    #[error("the reference needs a model with a contact")]
    NoContact,
    /// The target is not one uniform rod.
    #[error("the reference needs a uniform rod target")]
    NoRod,
    /// The target is not a plate with bending stiffness.
    #[error("the infinite-plate reference needs a plate with bending stiffness")]
    NoPlate,
    /// The contact outlasts the first wave reflection.
    #[error("semi-infinite rod: contact does not end before 2L/C")]
    ContactDoesNotEnd,
}

/// The impactor and Hertz law of a model, on a dashpot of the given impedance.
fn dashpot(model: &Model, impedance: f64) -> Result<HertzDashpot, ReferenceError> {
    let c = model.contact.as_ref().ok_or(ReferenceError::NoContact)?;
    Ok(HertzDashpot {
        mass: c.impactor.mass,
        v0: model.v0[c.impactor.dof].abs(),
        stiffness: c.stiffness,
        exponent: c.exponent,
        impedance,
    })
}

/// A uniform rod target: wave speed C, length L, axial stiffness EA, impedance ρCA.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodParams {
    /// Bar wave speed C = √(E/ρ).
    pub wave_speed: f64,
    /// Length L.
    pub length: f64,
    /// Axial stiffness EA.
    pub ea: f64,
    /// Impedance ρCA.
    pub impedance: f64,
}

/// The rod target's parameters.
pub fn rod_params(model: &Model) -> Result<RodParams, ReferenceError> {
    let r = model.rod.ok_or(ReferenceError::NoRod)?;
    let rho = r.e / (r.wave_speed * r.wave_speed);
    Ok(RodParams {
        wave_speed: r.wave_speed,
        length: r.length,
        ea: r.e * r.area,
        impedance: rho * r.wave_speed * r.area,
    })
}

/// The exact critical step of explicit central differences on the model's uniform
/// lumped-mass rod: L_e/C. The chain of N elements with half masses at its free ends
/// has ω_k = (2C/L_e)·sin(kπ/2N), k = 0…N; the highest (adjacent nodes in antiphase)
/// is ω_max = 2C/L_e, and central differences are stable for Δt ≤ 2/ω_max = L_e/C.
/// The impactor and the contact are left out (a free mass adds no frequency; the
/// Hertz contact is nonlinear).
pub fn rod_critical_step(model: &Model) -> Result<f64, ReferenceError> {
    let r = rod_params(model)?;
    let n = model
        .elements
        .iter()
        .filter(|e| matches!(e.kernel.family(), crate::elements::Family::Rod { .. }))
        .count();
    Ok(r.length / n as f64 / r.wave_speed)
}

/// The model's ball on a semi-infinite rod, integrated over 2L/C (RK4, h = L/C/2e5):
/// its trace, its events and L/C.
pub fn semi_infinite(model: &Model) -> Result<(Trace, Events, f64), ReferenceError> {
    let r = rod_params(model)?;
    let p = dashpot(model, r.impedance)?;
    let lc = r.length / r.wave_speed;
    let tr = p.integrate(2.0 * lc, lc / 2.0e5);
    let ev = HertzDashpot::events(&tr).ok_or(ReferenceError::ContactDoesNotEnd)?;
    Ok((tr, ev, lc))
}

/// The model's impactor on the infinite plate (Zener/Olsson impedance 8√(ρh D*) of
/// its first shell section), and that impedance.
pub fn infinite_plate(model: &Model) -> Result<(HertzDashpot, f64), ReferenceError> {
    let s = plate_section(model)?;
    let d = s.d().ok_or(ReferenceError::NoPlate)?;
    let z = analytic::plate_impedance(s.mass_per_area, d[(0, 0)], d[(1, 1)], d[(0, 1)], d[(2, 2)]);
    Ok((dashpot(model, z)?, z))
}

/// The first shell section of the model's plate.
fn plate_section(model: &Model) -> Result<crate::elements::shell::ShellSection, ReferenceError> {
    model
        .elements
        .iter()
        .find_map(|e| e.kernel.family().shell().cloned())
        .ok_or(ReferenceError::NoPlate)
}

/// The bending stiffness matrix D of the model's plate (its first shell section).
pub fn plate_bending_stiffness(model: &Model) -> Result<nalgebra::Matrix3<f64>, ReferenceError> {
    plate_section(model)?.d().ok_or(ReferenceError::NoPlate)
}

/// The impactor and the whole target as two rigid bodies in Hertz contact: a dashpot
/// of infinite impedance (a rigid face) carrying the reduced mass μ = m M/(m + M),
/// M the target's mass along the impact direction. Exact when the target's
/// waves are fast next to the contact (a soft contact on a stiff rod). Returns it and μ.
pub fn two_rigid_bodies(model: &Model) -> Result<(HertzDashpot, f64), ReferenceError> {
    let c = model.contact.as_ref().ok_or(ReferenceError::NoContact)?;
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
    let d = HertzDashpot {
        mass: mu,
        v0: model.v0[c.impactor.dof].abs(),
        stiffness: c.stiffness,
        exponent: c.exponent,
        impedance: f64::INFINITY,
    };
    Ok((d, mu))
}
