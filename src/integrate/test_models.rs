//! Named one-degree-of-freedom test models with exact solutions; every scheme is run
//! on each of them alone, without the rest of the pipeline (as diffsol tests its
//! solvers on its test models).
//!
//! - [`oscillator`]: a mass on a linear spring, u = (v0/ω) sin ωt.
//! - [`forced_oscillator`]: the same from rest under P0 sin Ωt (a TLOAD2):
//!   u = P0/(k(1 − r²)) (sin Ωt − r sin ωt), r = Ω/ω.
//! - [`damped_oscillator`]: the oscillator with a viscous damper to ground (ζ = 0.1)
//!   released from u0 at rest, u = u0 e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t),
//!   ω_d = ω√(1 − ζ²); or with the same damping as the model's proportional
//!   damping, C = a₁M + a₂K.
//! - [`hertz_wall`]: a mass striking a rigid wall through a Hertz spring F = Kα^1.5:
//!   α_max = (5mv0²/4K)^(2/5), F_max = Kα_max^1.5, contact time
//!   (4/5)·B(2/5, 1/2)·α_max/v0 = 2.9432752 α_max/v0, rebound at −v0 (restitution 1).
//! - [`yang_sun_wall`]: the same mass and wall through Yang and Sun's law (q = 2.5):
//!   loading as the Hertz wall to α_max, unloading to α0, rebound at −e·v0 with
//!   e² = (α_max − α0)/(1.4 α_max) (loading work 0.4 K α_max^2.5, returned work
//!   F_max(α_max − α0)/3.5).

use super::{integrate, Observer, Scheme, SolveError, StepState};
use crate::assembly::assemble;
use crate::deck::{cards::CardRef, diag::Pos, Units};
use crate::elements::{mass::PointMass, rod::Rod, rod::RodSection, Element};
use crate::model::{Contact, DofLabel, Impactor, Model, NonlinearLoad, OutputPlan, TimeControl};

/// A model of one solved DOF (T1 of grid 2): `mass` there, a spring `spring` to a
/// clamped grid 1 (none if 0), and, if `hertz` is given, a Hertz contact with a rigid
/// wall at u = 0 (α = u).
fn one_dof(mass: f64, spring: f64, v0: f64, hertz: Option<f64>) -> Model {
    let label = DofLabel { point: 2, comp: 1 };
    let free = [Some(0), None, None, None, None, None];
    let mut elements = vec![Element::new(
        2,
        vec![2],
        vec![free],
        PointMass {
            x: [1.0, 0.0, 0.0],
            mass,
            inertia: [0.0; 6],
        },
    )];
    if spring > 0.0 {
        let section = RodSection {
            e: spring,
            g: 0.0,
            area: 1.0,
            torsion: 0.0,
            rho: 0.0,
            nsm: 0.0,
            coupled_mass: false,
        };
        let x = [[0.0; 3], [1.0, 0.0, 0.0]];
        elements.push(Element::new(
            1,
            vec![1, 2],
            vec![[None; 6], free],
            Rod {
                card: "CROD",
                x,
                section,
            },
        ));
    }
    let contact = hertz.map(|k| {
        let at = CardRef {
            name: "NOLIN3".into(),
            pos: Pos {
                file: "test model".into(),
                line: 0,
                column: 0,
            },
            source: String::new(),
        };
        Contact {
            driver: vec![(0, 1.0)],
            driver_label: label,
            loads: vec![NonlinearLoad {
                dof: 0,
                label,
                scale: -k,
                at,
            }],
            exponent: 1.5,
            stiffness: k,
            impactor: Impactor {
                grid: 2,
                dof: 0,
                mass,
                dofs: vec![0],
            },
            nonconservative: Vec::new(),
            unloading: Default::default(),
        }
    });
    Model {
        name: "one-dof".into(),
        title: String::new(),
        units: Units::default(),
        deck_sha256: String::new(),
        dofs: vec![label],
        dependent: Vec::new(),
        elements: elements.into(),
        contact,
        excitation: None,
        damping: None,
        u0: vec![0.0],
        v0: vec![v0],
        time: TimeControl {
            dt: 1.0,
            steps: 1,
            every: 1,
        },
        outputs: OutputPlan::default(),
        rod: None,
        inert_dofs: 0,
        time_card: None,
        frames: Default::default(),
    }
}

/// Mass 2 on a spring of stiffness 8 (ω = 2), starting at u = 0 with v0 = 3.
pub struct Oscillator {
    pub model: Model,
    pub mass: f64,
    pub stiffness: f64,
    pub omega: f64,
    pub v0: f64,
}

pub fn oscillator() -> Oscillator {
    let (mass, stiffness, v0) = (2.0, 8.0, 3.0);
    Oscillator {
        model: one_dof(mass, stiffness, v0, None),
        mass,
        stiffness,
        omega: (stiffness / mass).sqrt(),
        v0,
    }
}

impl Oscillator {
    /// The exact displacement and velocity.
    pub fn exact(&self, t: f64) -> (f64, f64) {
        let w = self.omega;
        (self.v0 / w * (w * t).sin(), self.v0 * (w * t).cos())
    }
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.omega
    }
    pub fn energy(&self, u: f64, v: f64) -> f64 {
        0.5 * self.mass * v * v + 0.5 * self.stiffness * u * u
    }
}

/// The oscillator (m = 2, k = 8, ω = 2) with viscous damping c = 0.8
/// (ζ = c/(2mω) = 0.1), released at rest from u0 = 1.5.
pub struct DampedOscillator {
    pub model: Model,
    pub mass: f64,
    pub stiffness: f64,
    pub damping: f64,
    pub u0: f64,
}

/// How the damped oscillator is damped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DampedBy {
    /// A scalar damper (CDAMP) to ground.
    Element,
    /// The model's proportional damping, half on M and half on K.
    Proportional,
}

pub fn damped_oscillator(by: DampedBy) -> DampedOscillator {
    use crate::elements::scalar::{Scalar, ScalarKind};
    let (mass, stiffness, damping, u0) = (2.0, 8.0, 0.8, 1.5);
    let mut model = one_dof(mass, stiffness, 0.0, None);
    model.u0 = vec![u0];
    match by {
        DampedBy::Element => {
            let mut elements = model.elements.to_vec();
            elements.push(Element::new(
                3,
                vec![2],
                vec![[Some(0), None, None, None, None, None]],
                Scalar {
                    card: "CDAMP2",
                    kind: ScalarKind::Damper(damping),
                    slots: vec![(0, 0)],
                    points: vec![Some([1.0, 0.0, 0.0])],
                },
            ));
            model.elements = elements.into();
        }
        DampedBy::Proportional => {
            model.damping = Some(crate::model::Damping {
                mass: 0.5 * damping / mass,
                stiffness: 0.5 * damping / stiffness,
                from: vec!["the test model".into()],
            })
        }
    }
    DampedOscillator {
        model,
        mass,
        stiffness,
        damping,
        u0,
    }
}

impl DampedOscillator {
    pub fn omega(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }
    pub fn zeta(&self) -> f64 {
        self.damping / (2.0 * self.mass * self.omega())
    }
    /// The damped circular frequency ω√(1 − ζ²).
    pub fn omega_d(&self) -> f64 {
        self.omega() * (1.0 - self.zeta().powi(2)).sqrt()
    }
    /// The damped period 2π/ω_d.
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.omega_d()
    }
    /// The exact displacement.
    pub fn exact(&self, t: f64) -> f64 {
        let (s, wd) = (self.zeta() * self.omega(), self.omega_d());
        self.u0 * (-s * t).exp() * ((wd * t).cos() + s / wd * (wd * t).sin())
    }
    pub fn energy(&self, u: f64, v: f64) -> f64 {
        0.5 * self.mass * v * v + 0.5 * self.stiffness * u * u
    }
}

/// The states of a damped run: (time, u, v, D, W), D the energy dissipated so far
/// and W the work of the scheme's own loads (the three-point scheme's start loads).
#[derive(Default)]
pub struct Dissipating(pub Vec<(f64, f64, f64, f64, f64)>);

impl Observer for Dissipating {
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError> {
        self.0.push((s.time, s.u[0], s.v[0], s.dissipated, s.applied_work));
        Ok(true)
    }
}

/// Runs `scheme` on a damped one-DOF model.
pub fn run_damped(model: &Model, scheme: Scheme, dt: f64, steps: usize) -> Dissipating {
    let sys = assemble(model);
    let mut rec = Dissipating::default();
    integrate(model, &sys, scheme, dt, steps, &mut rec).expect("the test model runs");
    rec
}

/// The oscillator's mass and spring (m = 2, k = 8, ω = 2) from rest under
/// P(t) = P0 sin Ωt, P0 = 3, Ω = 1: a TLOAD2 with F = Ω/2π and P = −90°.
pub struct ForcedOscillator {
    pub model: Model,
    pub mass: f64,
    pub stiffness: f64,
    pub omega: f64,
    pub forcing: f64,
    pub p0: f64,
}

pub fn forced_oscillator() -> ForcedOscillator {
    use crate::model::excitation::{Excitation, LoadTerm, TimeFunction};
    let (mass, stiffness, p0, forcing) = (2.0, 8.0, 3.0, 1.0);
    let mut model = one_dof(mass, stiffness, 0.0, None);
    model.excitation = Some(Excitation {
        terms: vec![LoadTerm {
            dof: 0,
            scale: p0,
            delay: 0.0,
            function: 0,
        }],
        functions: vec![TimeFunction::Formula(crate::deck::cards::Formula {
            t1: 0.0,
            t2: 1e9,
            f: forcing / (2.0 * std::f64::consts::PI),
            p: -90.0,
            c: 0.0,
            b: 0.0,
        })],
        source: "TLOAD2 of the test model".into(),
    });
    ForcedOscillator {
        model,
        mass,
        stiffness,
        omega: (stiffness / mass).sqrt(),
        forcing,
        p0,
    }
}

impl ForcedOscillator {
    /// The exact displacement.
    pub fn exact(&self, t: f64) -> f64 {
        let r = self.forcing / self.omega;
        self.amplitude() * ((self.forcing * t).sin() - r * (self.omega * t).sin())
    }
    /// P0/(k(1 − r²)).
    pub fn amplitude(&self) -> f64 {
        let r = self.forcing / self.omega;
        self.p0 / (self.stiffness * (1.0 - r * r))
    }
    /// The forcing period 2π/Ω.
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.forcing
    }
    pub fn energy(&self, u: f64, v: f64) -> f64 {
        0.5 * self.mass * v * v + 0.5 * self.stiffness * u * u
    }
}

/// The states of a run with the work of its dynamic load: (time, u, v, W).
#[derive(Default)]
pub struct Worked(pub Vec<(f64, f64, f64, f64)>);

impl Observer for Worked {
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError> {
        self.0.push((s.time, s.u[0], s.v[0], s.applied_work));
        Ok(true)
    }
}

/// Runs `scheme` on a one-DOF model with a dynamic load.
pub fn run_worked(model: &Model, scheme: Scheme, dt: f64, steps: usize) -> Worked {
    let sys = assemble(model);
    let mut rec = Worked::default();
    integrate(model, &sys, scheme, dt, steps, &mut rec).expect("the test model runs");
    rec
}

/// The paper's steel ball (m = 9.587e-5 lbf·s²/in, K = 6.24e6 lbf/in^1.5) at
/// 62.1 in/s on a rigid wall.
pub struct HertzWall {
    pub model: Model,
    pub mass: f64,
    pub stiffness: f64,
    pub v0: f64,
}

pub fn hertz_wall() -> HertzWall {
    let (mass, stiffness, v0) = (9.587e-5, 6.24e6, 62.1);
    HertzWall {
        model: one_dof(mass, 0.0, v0, Some(stiffness)),
        mass,
        stiffness,
        v0,
    }
}

/// The Hertz wall through Yang and Sun's law with unloading exponent `power` and
/// critical indentation `critical_over_max`·α_max.
pub struct YangSunWall {
    pub wall: HertzWall,
    pub critical: f64,
    pub power: f64,
}

pub fn yang_sun_wall(critical_over_max: f64, power: f64) -> YangSunWall {
    let mut wall = hertz_wall();
    let critical = critical_over_max * wall.alpha_max();
    wall.model.contact.as_mut().expect("a contact").unloading =
        crate::model::Unloading::YangSun(crate::model::YangSun { critical, power });
    YangSunWall { wall, critical, power }
}

impl YangSunWall {
    /// α0 of α_max.
    pub fn permanent(&self) -> f64 {
        let m = self.wall.alpha_max();
        // α0 written out, independently of the law's own.
        if m > self.critical {
            m * (1.0 - (self.critical / m).powf(0.4))
        } else {
            0.0
        }
    }
    /// e = √(returned/loading work) = √((A + 1)(α_max − α0)/((q + 1) α_max)).
    pub fn restitution(&self) -> f64 {
        let m = self.wall.alpha_max();
        (2.5 * (m - self.permanent()) / ((self.power + 1.0) * m)).sqrt()
    }
}

impl HertzWall {
    pub fn alpha_max(&self) -> f64 {
        (5.0 * self.mass * self.v0 * self.v0 / (4.0 * self.stiffness)).powf(0.4)
    }
    pub fn force_max(&self) -> f64 {
        self.stiffness * self.alpha_max().powf(1.5)
    }
    pub fn contact_time(&self) -> f64 {
        crate::physics::analytic::RIGID_DURATION_FACTOR * self.alpha_max() / self.v0
    }
}

/// The states of a run: (time, u, v, α).
#[derive(Default)]
pub struct Record(pub Vec<(f64, f64, f64, f64)>);

impl Observer for Record {
    fn observe(&mut self, s: &StepState) -> Result<bool, SolveError> {
        self.0.push((s.time, s.u[0], s.v[0], s.alpha));
        Ok(true)
    }
}

/// Runs `scheme` on a one-DOF model.
pub fn run(model: &Model, scheme: Scheme, dt: f64, steps: usize) -> Record {
    let sys = assemble(model);
    let mut rec = Record::default();
    integrate(model, &sys, scheme, dt, steps, &mut rec).expect("the test model runs");
    rec
}

/// The observed order: least-squares slope of log(error) against log(dt).
pub fn order(dts: &[f64], errors: &[f64]) -> f64 {
    crate::numerics::order(dts, errors, 0.0, 2)
}
