//! Variations of a model for verification and stability cases: scaled impact
//! velocity, contact stiffness or impactor mass, and an initial gap or overlap.

use super::Model;
use crate::elements::mass::PointMass;
use serde::Deserialize;

/// Why a modification cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModifyError {
    /// The model has no contact.
    #[error("the model has no contact to modify")]
    NoContact,
    /// A scale factor is not positive.
    #[error("{name} must be a positive number, not {value}")]
    NotPositive {
        /// The modification's name.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The gap is not finite.
    #[error("initial_gap must be finite, not {0}")]
    Gap(f64),
    /// α does not depend on the impactor.
    #[error("the indentation does not depend on the impactor's DOF")]
    Indentation,
}

/// What to change; every field defaults to "no change".
#[derive(Debug, Clone, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Modify {
    /// Multiplies the impactor's initial velocity.
    pub velocity_scale: Option<f64>,
    /// Multiplies the Hertz stiffness K and every NOLIN3 scale with it.
    pub contact_stiffness_scale: Option<f64>,
    /// Multiplies the impactor's mass and inertia.
    pub impactor_mass_scale: Option<f64>,
    /// Initial indentation α(0) = −gap (negative: the impactor starts inside).
    pub initial_gap: Option<f64>,
}

impl Modify {
    /// True when nothing changes.
    pub fn is_empty(&self) -> bool {
        *self == Modify::default()
    }

    /// The modified model, or why it cannot be made.
    pub fn apply(&self, model: &Model) -> Result<Model, ModifyError> {
        let mut m = model.clone();
        if self.is_empty() {
            return Ok(m);
        }
        let Some(c) = m.contact.as_mut() else {
            return Err(ModifyError::NoContact);
        };
        for (name, s) in [
            ("velocity_scale", self.velocity_scale),
            ("contact_stiffness_scale", self.contact_stiffness_scale),
            ("impactor_mass_scale", self.impactor_mass_scale),
        ] {
            if let Some(s) = s {
                if !(s.is_finite() && s > 0.0) {
                    return Err(ModifyError::NotPositive { name, value: s });
                }
            }
        }
        if let Some(s) = self.velocity_scale {
            for &d in &c.impactor.dofs {
                m.v0[d] *= s;
            }
        }
        if let Some(s) = self.contact_stiffness_scale {
            c.stiffness *= s;
            c.loads.iter_mut().for_each(|l| l.scale *= s);
            c.nonconservative.iter_mut().for_each(|t| t.1 *= s);
        }
        if let Some(s) = self.impactor_mass_scale {
            c.impactor.mass *= s;
            let grid = c.impactor.grid;
            for e in std::sync::Arc::make_mut(&mut m.elements)
                .iter_mut()
                .filter(|e| e.grids == [grid])
            {
                if let Some(p) = e.kind_mut::<PointMass>() {
                    p.mass *= s;
                    p.inertia.iter_mut().for_each(|i| *i *= s);
                }
            }
        }
        if let Some(gap) = self.initial_gap {
            if !gap.is_finite() {
                return Err(ModifyError::Gap(gap));
            }
            let d = c.impactor.dof;
            let coef = c.driver.iter().find(|t| t.0 == d).map(|t| t.1).unwrap_or(0.0);
            if coef == 0.0 {
                return Err(ModifyError::Indentation);
            }
            let alpha0 = crate::model::apply(&c.driver, &m.u0);
            m.u0[d] += (-gap - alpha0) / coef;
        }
        Ok(m)
    }
}
