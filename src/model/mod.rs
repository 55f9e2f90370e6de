//! The model: DOF numbering, constraints, elements, masses, the contact definition,
//! initial conditions and the output plan, built from a deck.
//!
//! DOFs are numbered over the *solved* DOFs: grid components left free by PS and
//! the selected SPC1 cards, and scalar points that are not defined by a TF. A scalar
//! point defined by a TF (the paper's indentation EPOINT) is algebraic: it is kept as
//! a linear functional of the solved DOFs, not as an unknown.

mod build;
pub mod check;
pub mod excitation;
pub mod loads;
mod modify;
pub mod rigid;
mod weight;

pub(crate) use build::element_requests;
pub use build::{build_model, build_structure, survey_structure, ModelError, Structure, Survey};
pub use modify::{Modify, ModifyError};
pub use weight::{mass_properties, MassProperties};

/// Loading a model from a deck failed: the deck's or the model builder's problems,
/// or (for an embedded deck) the files it is read from could not be written.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The deck could not be read.
    #[error("{0}")]
    Deck(#[from] crate::deck::DeckError),
    /// The model could not be built.
    #[error("{0}")]
    Model(#[from] ModelError),
    /// An embedded deck could not be written where it is read from.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The path being written.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
}

use crate::deck::{CardRef, Units};
pub use crate::elements::shell::ShellSection;
pub use crate::elements::Element;
use std::fmt;

/// A DOF of the deck: point id and component (1-6 for grids, 0 for scalar points).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DofLabel {
    /// Grid or scalar point id.
    pub point: i64,
    /// Component: 1-6 for a grid, 0 for a scalar point.
    pub comp: u8,
}

impl fmt::Display for DofLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const NAMES: [&str; 7] = ["", "T1", "T2", "T3", "R1", "R2", "R3"];
        if self.comp == 0 {
            write!(f, "point {}", self.point)
        } else {
            write!(f, "grid {} {}", self.point, NAMES[self.comp as usize])
        }
    }
}

/// A linear functional Σ c_j u_j of solved DOFs.
pub type Functional = Vec<(usize, f64)>;

/// The functional's value at `u`.
pub fn apply(f: &Functional, u: &[f64]) -> f64 {
    f.iter().map(|&(j, c)| c * u[j]).sum()
}

/// A scalar point defined by a transfer function (B0 u_dep + Σ A0_j u_j = 0).
#[derive(Debug, Clone)]
pub struct DependentPoint {
    /// The point.
    pub label: DofLabel,
    /// Its value as a functional of the solved DOFs.
    pub functional: Functional,
    /// The card defining it (a TF, or an RBE2 for a dependent grid's component).
    pub at: CardRef,
    /// An RBE2-dependent grid's component, read for output requests only: the contact
    /// and the inert-DOF grouping do not see it.
    pub tied: bool,
}

/// One NOLIN3 load: P = S·x^A on a solved DOF.
#[derive(Debug, Clone)]
pub struct NonlinearLoad {
    /// The loaded solved DOF.
    pub dof: usize,
    /// Its label.
    pub label: DofLabel,
    /// The scale factor S.
    pub scale: f64,
    /// The NOLIN3 card.
    pub at: CardRef,
}

/// The rigid impactor: a point mass loaded by the contact and attached to no element.
#[derive(Debug, Clone)]
pub struct Impactor {
    /// The impactor's grid.
    pub grid: i64,
    /// The solved DOF the contact load acts on (the impact direction).
    pub dof: usize,
    /// Its mass.
    pub mass: f64,
    /// All solved DOFs of the impactor grid.
    pub dofs: Vec<usize>,
}

/// The Hertzian contact: NOLIN3 loads P_i = S_i·x^A driven by one scalar x (here the
/// indentation α), which is a linear functional of the solved DOFs.
///
/// The contact is conservative when the loads derive from the potential
/// V(α) = K/(A+1)·α^(A+1), i.e. when S_i = −K ∂α/∂u_i for every loaded DOF. K is
/// taken from the impactor's load. Any remainder `S_i + K ∂α/∂u_i` is a
/// non-conservative load whose work the ledger books separately.
#[derive(Debug, Clone)]
pub struct Contact {
    /// The indentation α as a functional of the solved DOFs.
    pub driver: Functional,
    /// The point holding α (the NOLIN3 cards' GJ, CJ).
    pub driver_label: DofLabel,
    /// The NOLIN3 loads.
    pub loads: Vec<NonlinearLoad>,
    /// The exponent A (1.5 for Hertz).
    pub exponent: f64,
    /// Hertz contact stiffness K of V(α) = K/(A+1) α^(A+1).
    pub stiffness: f64,
    /// The impactor.
    pub impactor: Impactor,
    /// Non-conservative remainder of the loads (DOF, S_i + K ∂α/∂u_i), nonzero entries.
    pub nonconservative: Functional,
    /// How the contact unloads: along its loading curve (NOLIN3's law, elastic) or
    /// along another ([`crate::integrate::law`]). A deck's contact is elastic: NOLIN
    /// cards cannot express hysteresis; a scene sets it.
    pub unloading: Unloading,
}

/// How a contact unloads.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Unloading {
    /// Along the loading curve: F = K α^A both ways, nothing dissipated.
    #[default]
    Elastic,
    /// Yang and Sun's law for laminates ([`crate::integrate::law`]).
    YangSun(YangSun),
}

/// The parameters of Yang and Sun's unloading law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YangSun {
    /// The critical indentation α_cr: below it the contact unloads to α0 = 0, above it
    /// to the permanent indentation α0 = α_m [1 − (α_cr/α_m)^(2/5)]. Infinite: never.
    pub critical: f64,
    /// The unloading exponent q (2.5 in Yang and Sun's tests), at least the loading
    /// exponent A (else unloading would return more than loading took).
    pub power: f64,
}

impl YangSun {
    /// The permanent indentation α0 after a largest indentation α_m:
    /// α_m [1 − (α_cr/α_m)^(2/5)] above α_cr, 0 up to it.
    pub fn permanent(&self, max: f64) -> f64 {
        if max > self.critical {
            max * (1.0 - (self.critical / max).powf(0.4))
        } else {
            0.0
        }
    }
}

impl Contact {
    /// Load factor φ(α) = max(α, 0)^A: the NOLIN3 law divided by S.
    pub fn law(&self, alpha: f64) -> f64 {
        if alpha > 0.0 {
            alpha.powf(self.exponent)
        } else {
            0.0
        }
    }

    /// Derivative of the law.
    pub fn law_slope(&self, alpha: f64) -> f64 {
        if alpha > 0.0 {
            self.exponent * alpha.powf(self.exponent - 1.0)
        } else {
            0.0
        }
    }

    /// W(α) = ∫φ = max(α,0)^(A+1)/(A+1); the contact potential is K·W.
    pub fn law_integral(&self, alpha: f64) -> f64 {
        if alpha > 0.0 {
            alpha.powf(self.exponent + 1.0) / (self.exponent + 1.0)
        } else {
            0.0
        }
    }

    /// Whether the contact is closed at a state of indentation `alpha` and contact
    /// load `load` (its force or load factor: only its sign counts): α > 0 for an
    /// elastic contact; for one that unloads along another curve, a load (α above
    /// the permanent indentation it has left).
    pub fn closed(&self, alpha: f64, load: f64) -> bool {
        match self.unloading {
            Unloading::Elastic => alpha > 0.0,
            Unloading::YangSun(_) => load > 0.0,
        }
    }

    /// The closure of each state of an indentation history `alpha` (every step, in
    /// order): α less the permanent indentation the history has left by then, so that
    /// the contact is closed exactly where it is positive. α itself for an elastic
    /// contact.
    pub fn closure(&self, alpha: &[f64]) -> Vec<f64> {
        match self.unloading {
            Unloading::Elastic => alpha.to_vec(),
            Unloading::YangSun(y) => {
                let mut max = 0.0f64;
                alpha
                    .iter()
                    .map(|&a| {
                        max = max.max(a);
                        a - y.permanent(max)
                    })
                    .collect()
            }
        }
    }

    /// Contact strain energy (Eq. 15): V = K/(A+1) α^(A+1) = 2/5 K α^(5/2) for A = 3/2.
    pub fn potential(&self, alpha: f64) -> f64 {
        self.stiffness * self.law_integral(alpha)
    }

    /// Contact force magnitude F = K α^A (the force on the impactor, Eq. 12).
    pub fn force(&self, alpha: f64) -> f64 {
        self.stiffness * self.law(alpha)
    }
}

/// Time stepping as the deck's TSTEP gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeControl {
    /// Time step.
    pub dt: f64,
    /// Number of steps.
    pub steps: usize,
    /// Output every `every` steps.
    pub every: usize,
}

/// Where an output value comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// A solved DOF.
    Dof(usize),
    /// A TF-defined point (index into [`Model::dependent`]).
    Dependent(usize),
    /// A DOF dropped as inert (see [`crate::assembly::drop_inert`]): identically zero.
    Inert,
}

/// What the deck's case control asks to be written.
#[derive(Debug, Clone, Default)]
pub struct OutputPlan {
    /// DOFs requested by DISP, with where each value comes from.
    pub disp: Vec<(DofLabel, Source)>,
    /// DOFs requested by VELO.
    pub velo: Vec<(DofLabel, Source)>,
    /// NOLIN3 loads requested by NLLOAD (index into `Contact::loads`).
    pub nlload: Vec<usize>,
    /// Element indices (into `Model::elements`) requested by STRESS.
    pub stress: Vec<usize>,
    /// Element indices requested by STRAIN.
    pub strain: Vec<usize>,
    /// Element indices requested by FORCE (or ELFORCE).
    pub force: Vec<usize>,
    /// The laminate (PCOMP) elements among those, with their plies: their ply strains
    /// and stresses are written too.
    pub plies: Vec<(usize, PlyStack)>,
    /// Every laminate element whose plies have failure criteria (PCOMP FT), with its
    /// plies: the field output gives each its largest index.
    pub failure_fields: Vec<(usize, PlyStack)>,
    /// What case control asked for that impactlab does not write (SPCFORCES, OLOAD,
    /// ACCEL, …), in the order asked: each named once.
    pub not_written: Vec<String>,
}

impl OutputPlan {
    /// The elements whose results are recorded, with what of them: STRESS requests
    /// (stress and strain), then STRAIN requests not already there, then FORCE
    /// requests.
    pub fn written(&self) -> impl Iterator<Item = (usize, crate::elements::Output)> + '_ {
        use crate::elements::Output;
        self.stress
            .iter()
            .map(|&e| (e, Output::Stress))
            .chain(
                self.strain
                    .iter()
                    .filter(|e| !self.stress.contains(e))
                    .map(|&e| (e, Output::Strain)),
            )
            .chain(self.force.iter().map(|&e| (e, Output::Force)))
    }
}

/// A laminate's plies as its results need them, shared by the elements of one PCOMP.
pub type PlyStack = std::sync::Arc<Vec<crate::laminate::PlyLayer>>;

/// A uniform rod target, for results in units of tC/L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodInfo {
    /// Bar wave speed C = √(E/ρ).
    pub wave_speed: f64,
    /// Rod length L.
    pub length: f64,
    /// Young's modulus E.
    pub e: f64,
    /// Cross-section area A.
    pub area: f64,
}

/// The structure, impactor and contact a run integrates, built from a deck.
#[derive(Debug, Clone)]
pub struct Model {
    /// Name of the deck (its file stem).
    pub name: String,
    /// Its TITLE.
    pub title: String,
    /// The deck's units.
    pub units: Units,
    /// SHA-256 of the deck the model was built from (see [`crate::deck::Deck::sha256`]).
    pub deck_sha256: String,
    /// The solved DOFs, in solve order.
    pub dofs: Vec<DofLabel>,
    /// TF-defined points.
    pub dependent: Vec<DependentPoint>,
    /// The elements (CONM2 masses included).
    pub elements: std::sync::Arc<Vec<Element>>,
    /// The Hertzian contact, if the deck has NOLIN3 loads.
    pub contact: Option<Contact>,
    /// The dynamic load the case control's DLOAD selects, if any.
    pub excitation: Option<excitation::Excitation>,
    /// The structure's proportional viscous damping, if the deck asks for any (the
    /// damping elements' own is in their kernels).
    pub damping: Option<Damping>,
    /// Initial displacements (TIC).
    pub u0: Vec<f64>,
    /// Initial velocities (TIC).
    pub v0: Vec<f64>,
    /// Time stepping.
    pub time: TimeControl,
    /// What the case control asks to be written.
    pub outputs: OutputPlan,
    /// The rod, when the target is one uniform rod.
    pub rod: Option<RodInfo>,
    /// Solved DOFs dropped as inert (identically zero for the whole run).
    pub inert_dofs: usize,
    /// Where the time stepping comes from (`TSTEP 7 at rod.bdf:55:1`), for messages;
    /// `None` for a model not read from a deck.
    pub time_card: Option<String>,
    /// The displacement frame of each grid whose CD is not the basic system (a grid
    /// absent here is displaced along basic x, y, z).
    pub frames: std::sync::Arc<std::collections::BTreeMap<i64, GridFrame>>,
}

/// Viscous damping proportional to the whole structure's matrices, as NASTRAN's
/// direct transient solutions form it: C += a₁·M + a₂·K, a₁ = PARAM ALPHA1 and
/// a₂ = PARAM ALPHA2 + G/W3 (structural damping G turned viscous at the frequency
/// W3, radians per time unit: the force G·K·u̇/W3, equal to G·K·u at W3 for a
/// harmonic motion). The modal damping ratio this gives a mode of circular frequency
/// ω is a₁/(2ω) + a₂ω/2.
#[derive(Debug, Clone, PartialEq)]
pub struct Damping {
    /// a₁, of M.
    pub mass: f64,
    /// a₂, of K.
    pub stiffness: f64,
    /// The cards it comes from (`PARAM G 0.02 at plate.bdf:8:1`), for the summary.
    pub from: Vec<String>,
}

/// A grid's displacement frame other than the basic system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridFrame {
    /// Its coordinate system, the grid's CD.
    pub cd: i64,
    /// The frame's axes at the grid (T1/R1, T2/R2, T3/R3), in basic components, as
    /// columns.
    pub axes: nalgebra::Matrix3<f64>,
}

impl Model {
    /// Number of solved DOFs.
    pub fn n(&self) -> usize {
        self.dofs.len()
    }

    /// True when the structure is damped: proportional damping or a damping element.
    pub fn damped(&self) -> bool {
        self.damping.is_some() || self.elements.iter().any(|e| e.damps())
    }

    /// True when the contact unloads along another curve than it loads on, so that it
    /// dissipates energy.
    pub fn hysteretic(&self) -> bool {
        self.contact.as_ref().is_some_and(|c| c.unloading != Unloading::Elastic)
    }

    /// Active DOFs as NASTRAN counts them: solved DOFs plus TF-defined scalar points.
    pub fn active_dofs(&self) -> usize {
        self.dofs.len() + self.dependent.len() + self.inert_dofs
    }

    /// The value of an output source at `u`.
    pub fn value(&self, s: Source, u: &[f64]) -> f64 {
        match s {
            Source::Dof(i) => u[i],
            Source::Dependent(j) => apply(&self.dependent[j].functional, u),
            Source::Inert => 0.0,
        }
    }

    /// The weight of each solved DOF's (Mv) in the momentum along the impact
    /// direction (the axis of the impactor's DOF; T1 without a contact): when every
    /// grid is displaced in the basic system, 1 on the DOFs of that component and 0
    /// elsewhere; with grids in other frames, the cosine between each translation's
    /// axis and the impact direction.
    pub fn momentum_weights(&self) -> Vec<f64> {
        let imp = match &self.contact {
            Some(c) => self.dofs[c.impactor.dof],
            None => DofLabel { point: 0, comp: 1 },
        };
        let axis = |d: &DofLabel| -> Option<nalgebra::Vector3<f64>> {
            let k = (1..=3).contains(&d.comp).then(|| d.comp as usize - 1)?;
            Some(match self.frames.get(&d.point) {
                Some(f) => f.axes.column(k).into_owned(),
                None => nalgebra::Vector3::ith(k, 1.0),
            })
        };
        match axis(&imp) {
            Some(dir) if !self.frames.is_empty() => {
                self.dofs.iter().map(|d| axis(d).map_or(0.0, |a| a.dot(&dir))).collect()
            }
            _ => self
                .dofs
                .iter()
                .map(|d| if d.comp == imp.comp { 1.0 } else { 0.0 })
                .collect(),
        }
    }

    /// True for the solved DOFs of the target (everything but the impactor).
    pub fn target_mask(&self) -> Vec<bool> {
        let mut mask = vec![true; self.n()];
        if let Some(c) = &self.contact {
            for &d in &c.impactor.dofs {
                mask[d] = false;
            }
        }
        mask
    }
}
