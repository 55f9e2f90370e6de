//! Scenes: an impact described directly ("a 5/8 in steel ball at 62.1 in/s on a 36 in
//! aluminium rod") in TOML. A scene is turned into the NASTRAN deck it stands for and
//! read back through the deck reader, so a scene and its deck build the same model by
//! the same code (`impactlab scene S.toml --to-deck F` writes that deck).
//!
//! Effects are off unless asked for or needed, and the run says which were simulated
//! and which skipped, and why. Effects the model cannot represent (rotary inertia,
//! gravity) are an error when asked for, never silently ignored. Damping
//! (`damping = { ratio, at }`) is the deck's structural damping turned viscous:
//! PARAM G = 2·ratio at W3 = 2π·at.

use crate::deck::number::format_real;
use crate::integrate::Scheme;
use crate::model::Model;
use crate::physics;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

mod strike;
use strike::{deck_bulk, direction_of};

pub use strike::{strike, Strike};

/// A scene file: a target, an impactor and a contact law, described by what they are rather than by cards.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Title, as the deck's TITLE.
    #[serde(default)]
    pub title: String,
    /// Unit names (never converted).
    pub units: Units,
    /// The struck structure.
    pub target: Target,
    /// The impactor.
    pub impactor: Impactor,
    /// The contact law.
    pub contact: Contact,
    /// The effects asked for.
    #[serde(default)]
    pub effects: Effects,
    /// What is written.
    #[serde(default)]
    pub output: Output,
    /// The `[run]` table: scheme, step and end.
    pub run: RunResult,
    /// The directory of the scene file: a deck target's path is relative to it.
    #[serde(skip)]
    pub dir: std::path::PathBuf,
}

/// The scene's unit names.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    /// Length unit.
    pub length: String,
    /// Force unit.
    pub force: String,
    /// Time unit.
    pub time: String,
}

/// An isotropic material.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Isotropic {
    /// Young's modulus E.
    pub e: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
    /// Mass density ρ (0 when not given).
    #[serde(default)]
    pub rho: f64,
}

/// The struck structure (`kind = "rod"`, `"plate"` or `"deck"`).
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Target {
    /// A uniform rod struck at one end along its axis.
    Rod {
        /// Length.
        length: f64,
        /// Cross-section area.
        area: f64,
        /// Number of CRODs (even).
        elements: usize,
        /// The rod's material.
        material: Isotropic,
        /// "free" or "fixed", struck end first.
        ends: [String; 2],
    },
    /// A square plate struck at its centre.
    Plate {
        /// Side of the square plate (the generator meshes squares).
        a: f64,
        /// Side along y (equal to `a`: the plate is square).
        b: f64,
        /// Thickness T.
        thickness: f64,
        /// Elements per side (odd: an element sits under the impactor).
        mesh: usize,
        /// Membrane stress–strain matrix G (upper triangle G11 G12 G13 G22 G23 G33).
        membrane: [f64; 6],
        /// Bending matrix (D = this · T³/12), same layout.
        bending: [f64; 6],
        /// Mass density ρ.
        rho: f64,
        /// Transverse modulus E33, for Eq. 18.
        e33: Option<f64>,
        /// Transverse shear moduli [G11, G12, G22] (the PSHELL MID3 material a MAT2
        /// gives, TS/T = 5/6): given, the plate is shear-deformable (MITC4); absent,
        /// thin (Kirchhoff, DKQ).
        #[serde(default)]
        transverse_shear: Option<[f64; 3]>,
        /// Per edge (y = −b/2, x = +a/2, y = +b/2, x = −a/2): "clamped" or "free".
        edges: [String; 4],
    },
    /// The structure of a deck (any deck `impactlab check` takes: its SOL, loads and
    /// transient cards are left out), struck where `impactor.at` or `impactor.grid`
    /// says.
    Deck {
        /// The deck's path, relative to the scene file.
        deck: String,
    },
}

/// The impactor: a rigid mass.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Impactor {
    /// Mass.
    pub mass: f64,
    /// Radius of the contact (sphere radius, or the rod end's contact radius).
    pub radius: Option<f64>,
    /// Material, for Eq. 5.
    pub material: Option<Isotropic>,
    /// Impact velocity.
    pub velocity: f64,
    /// A deck target's struck point (basic coordinates), on the surface of one of
    /// its shells.
    #[serde(default)]
    pub at: Option<[f64; 3]>,
    /// A deck target's struck grid, instead of `at`.
    #[serde(default)]
    pub grid: Option<i64>,
    /// A deck target: the impactor's travel, a vector (basic components) or
    /// "normal" (along the struck element's normal; at a grid, the mean of its
    /// shells' normals).
    #[serde(default)]
    pub direction: Option<toml::Value>,
}

/// The contact law.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// "hertz" (F = K α^1.5 loading and unloading), the default; or "yang-sun"
    /// (loading as Hertz, unloading along Yang and Sun's curve,
    /// [`crate::integrate::law`]).
    #[serde(default = "hertz")]
    pub law: String,
    /// A number, "eq5" (sphere on an isotropic flat) or "eq18" (k_t = E33).
    pub k: toml::Value,
    /// Yang and Sun's critical indentation α_cr, in the scene's length unit
    /// (law = "yang-sun"; `inf`: no permanent indentation).
    #[serde(default)]
    pub alpha_cr: Option<f64>,
    /// Yang and Sun's unloading exponent q (law = "yang-sun"; default 2.5, the value
    /// of their tests).
    #[serde(default)]
    pub q: Option<f64>,
}

/// Yang and Sun's unloading exponent, from their indentation tests (ASTM STP 787).
pub const YANG_SUN_Q: f64 = 2.5;

/// How the scene's contact unloads.
pub fn unloading(s: &Scene) -> crate::model::Unloading {
    match (s.contact.law.as_str(), s.contact.alpha_cr) {
        ("yang-sun", Some(critical)) => crate::model::Unloading::YangSun(crate::model::YangSun {
            critical,
            power: s.contact.q.unwrap_or(YANG_SUN_Q),
        }),
        _ => crate::model::Unloading::Elastic,
    }
}

/// Whether the scene has a NASTRAN deck twin: not when its contact unloads along
/// another curve than it loads on, which NOLIN cards cannot express.
pub fn deck_twin(s: &Scene) -> Result<(), SceneIssue> {
    if s.contact.law == "hertz" {
        return Ok(());
    }
    Err(SceneIssue(format!(
        "contact.law = \"{}\" has no NASTRAN deck twin: NOLIN cards give one curve for loading and unloading, \
         so the deck would run Hertz's law both ways; run the scene itself",
        s.contact.law
    )))
}

/// Effects asked for: each is off unless asked for or needed; the ledger is on unless
/// turned off.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Effects {
    /// Solve the plate's membrane DOFs.
    #[serde(default)]
    pub membrane: bool,
    /// Rotary inertia (not representable: an error when asked for).
    #[serde(default)]
    pub rotary_inertia: bool,
    /// Damping: a ratio of critical damping at a frequency.
    #[serde(default)]
    pub damping: Option<SceneDamping>,
    /// Gravity (not representable: an error when asked for).
    #[serde(default)]
    pub gravity: bool,
    /// Book the energy ledger (default on).
    #[serde(default = "yes")]
    pub ledger: bool,
}

/// A scene's damping: the structure damped at `ratio` of critical at the frequency
/// `at` (cycles per the scene's time unit), as NASTRAN's structural damping G = 2·ratio
/// turned viscous at W3 = 2π·at: C = (G/W3)·K, so that a mode's ratio is
/// ratio·f/at, exactly `ratio` at `at` and proportional to its frequency elsewhere.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDamping {
    /// The ratio of critical damping at `at` (0 < ratio < 1).
    pub ratio: f64,
    /// The frequency it holds at, cycles per the scene's time unit.
    pub at: f64,
}

fn yes() -> bool {
    true
}

impl Default for Effects {
    /// A scene without an `[effects]` table: nothing asked for, the ledger booked.
    fn default() -> Self {
        Effects {
            membrane: false,
            rotary_inertia: false,
            damping: None,
            gravity: false,
            ledger: true,
        }
    }
}

fn hertz() -> String {
    "hertz".into()
}

/// What a scene's run writes.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// Grid ids whose displacement history is written.
    #[serde(default)]
    pub points: Vec<i64>,
    /// Element ids whose stress and strain history is written.
    #[serde(default)]
    pub gages: Vec<i64>,
    /// Write every n-th step (default 1).
    pub every: Option<usize>,
}

/// The scene's `[run]` table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunResult {
    /// The scheme (default `newmark`).
    #[serde(default = "newmark")]
    pub scheme: Scheme,
    /// A step in the scene's time unit, or "auto".
    pub dt: toml::Value,
    /// The run ends at this time at the latest.
    pub end: f64,
    /// ... or this long after the impactor separates, if sooner.
    pub after_separation: Option<f64>,
}

fn newmark() -> Scheme {
    Scheme::Newmark
}

/// What is wrong with a scene: its one error type.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct SceneIssue(pub String);

impl From<crate::mesh::MeshError> for SceneIssue {
    fn from(e: crate::mesh::MeshError) -> Self {
        SceneIssue(e.to_string())
    }
}

/// A scene file that cannot be used, with its path (and line, where the TOML
/// reader gives one).
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Read {
        /// The scene file.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
    /// The scene is not valid.
    #[error("{path}{}: {issue}", line.map_or(String::new(), |l| format!(":{l}")))]
    Invalid {
        /// The scene file.
        path: String,
        /// The line, where the TOML reader gives one.
        line: Option<usize>,
        /// What is wrong.
        issue: SceneIssue,
    },
    /// The scene's deck could not be made into a model.
    #[error("{0}")]
    Load(#[from] crate::model::LoadError),
}

/// The error of the scene at `path`.
pub fn invalid(path: &Path, issue: SceneIssue) -> SceneError {
    SceneError::Invalid {
        path: path.display().to_string(),
        line: None,
        issue,
    }
}

/// Reads a scene file.
pub fn read(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
        path: path.display().to_string(),
        source,
    })?;
    parse(path, &text)
}

/// Reads a scene from its text; `path` names it in errors.
pub fn parse(path: &Path, text: &str) -> Result<Scene, SceneError> {
    let s: Scene = toml::from_str(text).map_err(|e| SceneError::Invalid {
        path: path.display().to_string(),
        line: e.span().map(|r| text[..r.start].lines().count().max(1)),
        issue: SceneIssue(e.message().to_string()),
    })?;
    validate(&s).map_err(|e| invalid(path, e))?;
    Ok(Scene {
        dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        ..s
    })
}

/// A positive finite number, or why not.
fn pos(name: &str, v: f64) -> Result<(), SceneIssue> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneIssue(format!("{name} must be positive, not {v}")))
    }
}

/// The impactor, contact law, run and effects of a scene, then its target.
fn validate(s: &Scene) -> Result<(), SceneIssue> {
    pos("impactor.mass", s.impactor.mass)?;
    pos("run.end", s.run.end)?;
    if !s.impactor.velocity.is_finite() || s.impactor.velocity == 0.0 {
        return Err(SceneIssue("impactor.velocity must be a nonzero number".into()));
    }
    validate_contact(&s.contact)?;
    if s.effects.rotary_inertia {
        return Err(SceneIssue(
            "effects.rotary_inertia is asked for, but the elements lump mass to translations only \
             (NASTRAN's default); the model cannot represent it"
                .into(),
        ));
    }
    if let Some(d) = s.effects.damping {
        if !(d.ratio > 0.0 && d.ratio < 1.0) {
            return Err(SceneIssue(format!(
                "effects.damping.ratio = {}: a ratio of critical damping is above 0 and below 1",
                d.ratio
            )));
        }
        if !(d.at > 0.0 && d.at.is_finite()) {
            return Err(SceneIssue(format!(
                "effects.damping.at = {}: the frequency the ratio holds at must be positive",
                d.at
            )));
        }
    }
    if s.effects.gravity {
        return Err(SceneIssue(
            "effects.gravity is asked for, but body forces are not implemented".into(),
        ));
    }
    validate_target(s)
}

/// The contact law and its parameters.
fn validate_contact(c: &Contact) -> Result<(), SceneIssue> {
    match c.law.as_str() {
        "hertz" => {
            if c.alpha_cr.is_some() || c.q.is_some() {
                return Err(SceneIssue(
                    "contact.alpha_cr and contact.q are Yang and Sun's unloading law's: give them with law = \"yang-sun\""
                        .into(),
                ));
            }
        }
        "yang-sun" => {
            match c.alpha_cr {
                None => {
                    return Err(SceneIssue(
                        "contact.law = \"yang-sun\" needs contact.alpha_cr, the critical indentation above which the \
                         contact leaves a permanent one (a property of the laminate: measured, or stated as assumed)"
                            .into(),
                    ))
                }
                Some(a) if a.is_nan() || a <= 0.0 => {
                    return Err(SceneIssue(format!(
                        "contact.alpha_cr = {a}: the critical indentation must be positive (inf: never permanent)"
                    )))
                }
                Some(_) => {}
            }
            if let Some(q) = c.q {
                if !(q.is_finite() && q >= 1.5) {
                    return Err(SceneIssue(format!(
                        "contact.q = {q}: the unloading exponent must be at least the loading exponent 1.5 (below it \
                         the unloading curve lies above the loading curve and the contact would return more than it took)"
                    )));
                }
            }
        }
        other => {
            return Err(SceneIssue(format!(
                "contact.law '{other}' is not supported (\"hertz\" or \"yang-sun\")"
            )))
        }
    }
    Ok(())
}

/// The target: a rod or a square plate the generators can mesh, or a deck struck at
/// a point or grid along a direction.
fn validate_target(s: &Scene) -> Result<(), SceneIssue> {
    let i = &s.impactor;
    let deck = matches!(s.target, Target::Deck { .. });
    if !deck && (i.at.is_some() || i.grid.is_some() || i.direction.is_some()) {
        return Err(SceneIssue(
            "impactor.at, impactor.grid and impactor.direction are for a deck target (kind = \"deck\"); a rod \
             is struck at its end, a plate at its centre"
                .into(),
        ));
    }
    match &s.target {
        Target::Deck { .. } => {
            match (i.at, i.grid) {
                (Some(_), Some(_)) => {
                    return Err(SceneIssue("impactor: give `at` or `grid`, not both".into()));
                }
                (None, None) => {
                    return Err(SceneIssue(
                        "impactor: a deck target needs the struck point, `at = [x, y, z]`, or a grid, `grid = id`"
                            .into(),
                    ));
                }
                (Some(p), None) if p.iter().any(|v| !v.is_finite()) => {
                    return Err(SceneIssue(format!("impactor.at = {p:?} must be three finite numbers")));
                }
                _ => {}
            }
            direction_of(i.direction.as_ref())?;
            if s.effects.membrane {
                return Err(SceneIssue(
                    "effects.membrane is for a generated plate; a deck's membrane is solved wherever it is live".into(),
                ));
            }
        }
        Target::Rod {
            length,
            area,
            elements,
            material,
            ends,
        } => {
            pos("target.length", *length)?;
            pos("target.area", *area)?;
            pos("target.material.e", material.e)?;
            pos("target.material.rho", material.rho)?;
            // Grids 1..=elements+1; 999 is the impactor and EPOINT 10001 the indentation.
            if *elements < 2 || elements % 2 != 0 || *elements > 996 {
                return Err(SceneIssue(format!(
                    "target.elements must be even, from 2 to 996 (grid 999 is the impactor), not {elements}"
                )));
            }
            for e in ends {
                if e != "free" && e != "fixed" {
                    return Err(SceneIssue(format!(
                        "target.ends: '{e}' is neither \"free\" nor \"fixed\""
                    )));
                }
            }
            if s.effects.membrane {
                return Err(SceneIssue(
                    "effects.membrane applies to plates; this target is a rod".into(),
                ));
            }
        }
        Target::Plate {
            a,
            b,
            thickness,
            mesh,
            rho,
            edges,
            transverse_shear,
            ..
        } => {
            if let Some([g11, g12, g22]) = transverse_shear {
                if !(*g11 > 0.0 && *g22 > 0.0 && g11 * g22 > g12 * g12) {
                    return Err(SceneIssue(format!(
                        "target.transverse_shear = [{g11}, {g12}, {g22}]: [G11 G12; G12 G22] must be positive \
                         definite"
                    )));
                }
            }
            pos("target.a", *a)?;
            pos("target.thickness", *thickness)?;
            pos("target.rho", *rho)?;
            if a != b {
                return Err(SceneIssue(format!(
                    "target: the plate generator meshes square plates; a = {a} but b = {b}"
                )));
            }
            if *mesh < 3 || mesh % 2 == 0 || *mesh > crate::mesh::PlateMesh::MAX_N {
                return Err(SceneIssue(format!(
                    "target.mesh must be odd, from 3 to {}, not {mesh}",
                    crate::mesh::PlateMesh::MAX_N
                )));
            }
            for e in edges {
                if e != "clamped" && e != "free" {
                    return Err(SceneIssue(format!(
                        "target.edges: '{e}' is neither \"clamped\" nor \"free\""
                    )));
                }
            }
        }
    }
    Ok(())
}

/// Hertz K as the scene gives it, when it gives a number (which must be positive).
fn given_k(s: &Scene) -> Option<Result<(f64, String), SceneIssue>> {
    let k = &s.contact.k;
    let v = k.as_float().or(k.as_integer().map(|i| i as f64))?;
    Some(if v > 0.0 {
        Ok((v, "given".into()))
    } else {
        Err(SceneIssue(format!("contact.k must be positive, not {v}")))
    })
}

/// Hertz K of the scene: given, Eq. 5 or Eq. 18 (with the formula's inputs).
pub fn contact_stiffness(s: &Scene) -> Result<(f64, String), SceneIssue> {
    if let Target::Deck { .. } = &s.target {
        let st = strike(s)?;
        return Ok((st.k, st.how));
    }
    if let Some(given) = given_k(s) {
        return given;
    }
    let which = s.contact.k.as_str().unwrap_or("");
    let r = s
        .impactor
        .radius
        .ok_or_else(|| SceneIssue("contact.k = \"eq5\"/\"eq18\" needs impactor.radius".into()))?;
    let mi = s
        .impactor
        .material
        .ok_or_else(|| SceneIssue("contact.k = \"eq5\"/\"eq18\" needs impactor.material".into()))?;
    let ki = physics::plane_strain_modulus(mi.e, mi.nu);
    let (kt, eq) = match (which, &s.target) {
        ("eq5", Target::Rod { material, .. }) => (physics::plane_strain_modulus(material.e, material.nu), "Eq. 5"),
        ("eq18", Target::Plate { e33: Some(e33), .. }) => (*e33, "Eq. 18 (k_t = E33)"),
        ("eq18", Target::Plate { e33: None, .. }) => {
            return Err(SceneIssue("contact.k = \"eq18\" needs target.e33".into()))
        }
        ("eq5", Target::Plate { .. }) => {
            return Err(SceneIssue(
                "contact.k = \"eq5\" is for an isotropic target; a plate uses \"eq18\"".into(),
            ))
        }
        ("eq18", Target::Rod { .. }) => {
            return Err(SceneIssue(
                "contact.k = \"eq18\" is for a composite plate; a rod uses \"eq5\"".into(),
            ))
        }
        (_, Target::Deck { .. }) => unreachable!("a deck target's K is its strike's"),
        (w, _) => {
            return Err(SceneIssue(format!(
                "contact.k must be a number, \"eq5\" or \"eq18\", not '{w}'"
            )))
        }
    };
    let kk = physics::hertz_stiffness(r, ki, kt);
    Ok((
        kk,
        format!("{eq}: 4/3 √r k_i k_t/(k_i + k_t), r = {r}, k_i = {ki:.4e}, k_t = {kt:.4e}"),
    ))
}

/// Δt: given, or "auto": 1/400 of the rigid-target Hertz contact time estimate
/// (2.94328 α_max/v0 with the impactor's mass), i.e. about the paper's resolution
/// (its rod contact took 372 steps); the accuracy study shows Newmark at this
/// resolution within 0.1 % in contact duration and peak force.
pub fn time_step(s: &Scene, k: f64) -> Result<f64, SceneIssue> {
    if let Some(v) = s.run.dt.as_float() {
        return if v > 0.0 {
            Ok(v)
        } else {
            Err(SceneIssue(format!("run.dt must be positive, not {v}")))
        };
    }
    if s.run.dt.as_str() == Some("auto") {
        let (_, _, t) = physics::analytic::rigid_target(s.impactor.mass, s.impactor.velocity, k);
        return Ok(t / 400.0);
    }
    Err(SceneIssue("run.dt must be a number or \"auto\"".into()))
}

fn mat2_line(w: &mut String, id: i64, g: &[f64; 6], rho: Option<f64>) {
    let f: Vec<String> = g.iter().map(|x| format_real(*x)).collect();
    let _ = writeln!(
        w,
        "MAT2,{id},{}{}",
        f.join(","),
        rho.map_or(String::new(), |r| format!(",{}", format_real(r)))
    );
}

/// The NASTRAN deck the scene stands for.
pub fn to_deck(s: &Scene) -> Result<String, SceneIssue> {
    validate(s)?;
    let (k, how) = contact_stiffness(s)?;
    let dt = time_step(s, k)?;
    let steps = (s.run.end / dt).ceil() as usize;
    let every = s.output.every.unwrap_or(1).max(1);
    let mut d = String::new();
    let w = &mut d;
    let _ = writeln!(w, "$ Generated by impactlab from a scene: {}", s.title);
    let _ = writeln!(w, "$ Hertz K = {} ({how})", format_real(k));
    let _ = writeln!(w, "$ Units: {}, {}, {}", s.units.length, s.units.force, s.units.time);
    let _ = writeln!(w, "ID SCENE,IMPACT\nSOL 27\nCEND");
    let _ = writeln!(w, "  TITLE = {}", if s.title.is_empty() { "SCENE" } else { &s.title });
    let steps_line = format!("TSTEP,1,{steps},{},{every}", format_real(dt));
    if let Target::Deck { .. } = &s.target {
        deck_bulk(w, s, &strike(s)?, &steps_line);
    } else {
        let _ = writeln!(w, "  SPC = 1\n  IC = 3\n  NONLINEAR = 5\n  TSTEP = 1\n  TFL = 111");
    }
    match &s.target {
        Target::Rod { .. } => rod_bulk(w, s, k, &steps_line),
        Target::Plate { .. } => plate_bulk(w, s, k, &steps_line)?,
        Target::Deck { .. } => {}
    }
    if let Some(dm) = s.effects.damping {
        let _ = writeln!(
            w,
            "$ Damping: ratio {} at {} cycles per {}: G = 2 ratio turned viscous at W3 = 2 pi at",
            dm.ratio, dm.at, s.units.time
        );
        let _ = writeln!(w, "PARAM,G,{}", format_real(2.0 * dm.ratio));
        let _ = writeln!(w, "PARAM,W3,{}", format_real(2.0 * std::f64::consts::PI * dm.at));
    }
    let _ = writeln!(w, "ENDDATA");
    Ok(d)
}

/// The rod's bulk data: grids, CRODs, the ball, its contact and initial velocity.
fn rod_bulk(w: &mut String, s: &Scene, k: f64, tstep: &str) {
    let v0 = s.impactor.velocity;
    let Target::Rod {
        length,
        area,
        elements: n,
        material,
        ends,
    } = &s.target
    else {
        unreachable!("called for a rod")
    };
    let mut pts = vec![999, 1];
    pts.extend(s.output.points.iter().copied());
    output_requests(w, &pts, &s.output.gages, 10001);
    let r = s.impactor.radius.unwrap_or(0.0);
    let _ = writeln!(w, "GRID,999,,{},0.0,0.0", format_real(-r));
    for i in 0..=*n {
        let _ = writeln!(
            w,
            "GRID,{},,{},0.0,0.0",
            i + 1,
            format_real(length * i as f64 / *n as f64)
        );
    }
    for i in 1..=*n {
        let _ = writeln!(w, "CROD,{i},1,{i},{}", i + 1);
    }
    let _ = writeln!(w, "CONM2,999999,999,0,{}", format_real(s.impactor.mass));
    let _ = writeln!(w, "PROD,1,11,{}", format_real(*area));
    let _ = writeln!(
        w,
        "MAT1,11,{},,{},{}",
        format_real(material.e),
        format_real(material.nu),
        format_real(material.rho)
    );
    let _ = writeln!(w, "SPC1,1,23456,1,THRU,{}\nSPC1,1,23456,999", n + 1);
    for (end, g) in ends.iter().zip([1, n + 1]) {
        if end == "fixed" {
            let _ = writeln!(w, "SPC1,1,1,{g}");
        }
    }
    let _ = writeln!(w, "{tstep}");
    let _ = writeln!(w, "NOLIN3,5,1,1,{},10001,0,1.5", format_real(k));
    let _ = writeln!(w, "NOLIN3,5,999,1,{},10001,0,1.5", format_real(-k));
    let _ = writeln!(
        w,
        "TF,111,10001,0,1.0,0.0,0.0,,,+TF-1\n+TF-1,999,1,-1.0,0.0,0.0,,,,+TF-2\n+TF-2,1,1,1.0,0.0,0.0"
    );
    let _ = writeln!(w, "TIC,3,999,1,0.0,{}", format_real(v0));
}

/// The plate's bulk data: the mesh, its edges, the impactor, its contact on the centre
/// element's corners and its initial velocity.
fn plate_bulk(w: &mut String, s: &Scene, k: f64, tstep: &str) -> Result<(), SceneIssue> {
    let v0 = s.impactor.velocity;
    let Target::Plate {
        a,
        thickness,
        mesh: n,
        membrane,
        bending,
        rho,
        edges,
        transverse_shear,
        ..
    } = &s.target
    else {
        unreachable!("called for a plate")
    };
    let m = crate::mesh::PlateMesh::new(*n)?;
    let contact = m.contact_grids();
    let mut pts: Vec<i64> = vec![999];
    pts.extend(contact.iter().map(|&g| g as i64));
    pts.extend(s.output.points.iter().copied());
    let ep = m.indentation_point();
    output_requests(w, &pts, &s.output.gages, ep);
    let _ = writeln!(
        w,
        "GRID,999,,0.0,0.0,{}",
        format_real(-s.impactor.radius.unwrap_or(0.0))
    );
    let _ = writeln!(w, "CONM2,999999,999,0,{}", format_real(s.impactor.mass));
    let last = n + 1;
    m.write_grids_and_shells(w, *a, crate::mesh::Cells::Quad4);
    let mid3 = if transverse_shear.is_some() { ",301" } else { "" };
    let _ = writeln!(w, "PSHELL,1,101,{},201,1.0{mid3}", format_real(*thickness));
    mat2_line(w, 101, membrane, Some(*rho));
    mat2_line(w, 201, bending, None);
    if let Some([g11, g12, g22]) = transverse_shear {
        mat2_line(w, 301, &[*g11, *g12, 0.0, *g22, 0.0, 0.0], None);
    }
    // Edges: y = −b/2 (row 1), x = +a/2 (col last), y = +b/2 (row last), x = −a/2 (col 1).
    let sides: [Vec<usize>; 4] = [
        (1..=last).map(|c| m.grid(1, c)).collect(),
        (1..=last).map(|r| m.grid(r, last)).collect(),
        (1..=last).map(|c| m.grid(last, c)).collect(),
        (1..=last).map(|r| m.grid(r, 1)).collect(),
    ];
    for (edge, grids) in edges.iter().zip(&sides) {
        if edge == "clamped" {
            for g in grids {
                let _ = writeln!(w, "SPC1,1,123456,{g}");
            }
        }
    }
    let _ = writeln!(w, "SPC1,1,12456,999\nGRDSET,,,,,,,6");
    let _ = writeln!(w, "{tstep}");
    for g in contact {
        let _ = writeln!(w, "NOLIN3,5,{g},3,{},{ep},0,1.5", format_real(k / 4.0));
    }
    let _ = writeln!(w, "NOLIN3,5,999,3,{},{ep},0,1.5", format_real(-k));
    m.write_indentation_tf(w);
    let _ = writeln!(w, "TIC,3,999,3,0.0,{}", format_real(v0));
    Ok(())
}

/// Case control output requests (the contact points and `points` displaced, the
/// gages' stress and strain), then the start of the bulk data with the EPOINT.
fn output_requests(w: &mut String, points: &[i64], gages: &[i64], epoint: usize) {
    let _ = writeln!(w, "  SET 15 = {}", join(points));
    let _ = writeln!(w, "  NLLOAD = 15\n  DISP = 15");
    if !gages.is_empty() {
        let _ = writeln!(w, "  SET 20 = {}\n  STRESS = 20", join(gages));
    }
    let _ = writeln!(w, "BEGIN BULK\nEPOINT,{epoint}");
}

fn join<T: std::fmt::Display>(v: &[T]) -> String {
    let mut seen = Vec::new();
    for x in v {
        let s = x.to_string();
        if !seen.contains(&s) {
            seen.push(s);
        }
    }
    seen.join(",")
}

/// The scene's model (through its deck), its run options, and the computed K.
pub fn load(path: &Path) -> Result<(Scene, Model, String), SceneError> {
    model_of(path, read(path)?)
}

/// A plate scene's model on another mesh (`mesh` elements a side), for a mesh study.
pub fn load_with_mesh(path: &Path, elements: usize) -> Result<Model, SceneError> {
    let mut s = read(path)?;
    match &mut s.target {
        Target::Plate { mesh, .. } => *mesh = elements,
        _ => return Err(invalid(path, SceneIssue("a mesh study needs a plate target".into()))),
    }
    Ok(model_of(path, s)?.1)
}

/// The model of a scene read from `path`, and its deck.
fn model_of(path: &Path, s: Scene) -> Result<(Scene, Model, String), SceneError> {
    let deck = to_deck(&s).map_err(|e| invalid(path, e))?;
    let name = path
        .file_stem()
        .map_or("scene".into(), |n| n.to_string_lossy().into_owned());
    let mut model = crate::model_from_text(&name, &deck)?;
    if let Some(c) = model.contact.as_mut() {
        c.unloading = unloading(&s);
    }
    Ok((s, model, deck))
}

/// A scene's effects, each with the reason it is in or out (`effects` in the summary).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct EffectReport {
    /// Effects simulated, with why.
    pub simulated: Vec<Effect>,
    /// Effects not simulated, with why.
    pub skipped: Vec<Effect>,
}

/// One effect and why it is simulated or skipped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Effect {
    /// The effect (`membrane`, `ledger`, ...).
    pub name: String,
    /// Why it is simulated or skipped.
    pub reason: String,
}

impl Effect {
    fn new(name: &str, reason: impl Into<String>) -> Self {
        Effect {
            name: name.into(),
            reason: reason.into(),
        }
    }
}

/// The effects of a scene, given how many DOFs the run left out as inert and how
/// many steps it did.
pub fn effects(s: &Scene, inert_dofs: usize, steps_done: usize) -> EffectReport {
    let mut sim = vec![Effect::new(
        "transverse bending and the Hertz contact",
        "the impact itself",
    )];
    if let crate::model::Unloading::YangSun(y) = unloading(s) {
        sim.push(Effect::new(
            "contact hysteresis",
            format!(
                "contact.law = \"yang-sun\": loading along Hertz's curve, unloading along Yang and Sun's (q = {}) with \
                 a permanent indentation above alpha_cr = {} {}; its energy is the ledger's dissipated_contact",
                y.power, y.critical, s.units.length
            ),
        ));
    }
    let mut skip = Vec::new();
    match (&s.target, s.effects.membrane) {
        (Target::Plate { .. }, true) => sim.push(Effect::new("membrane", "asked for")),
        (Target::Plate { .. }, false) => skip.push(Effect::new("membrane", format!(
            "not asked for; a transverse impact on a plate with no membrane-bending coupling leaves the in-plane DOFs at zero: {inert_dofs} DOFs not solved"))),
        (Target::Rod { .. }, _) => sim.push(Effect::new("axial waves", "the rod's response")),
        (Target::Deck { .. }, _) => sim.push(Effect::new(
            "the deck's structure",
            format!(
                "every DOF a load, initial condition or the contact reaches, its membrane wherever it is coupled to \
                 bending: {inert_dofs} DOFs nothing reaches not solved"
            ),
        )),
    }
    if let Target::Plate { transverse_shear, .. } = &s.target {
        match transverse_shear {
            Some(_) => sim.push(Effect::new(
                "transverse shear",
                "target.transverse_shear given: a shear-deformable plate (MITC4, TS/T = 5/6)",
            )),
            None => skip.push(Effect::new(
                "transverse shear",
                "target.transverse_shear not given: a thin (Kirchhoff) plate, rigid in transverse shear",
            )),
        }
    }
    if s.effects.ledger {
        sim.push(Effect::new("energy ledger", "asked for"));
    } else {
        skip.push(Effect::new("energy ledger", "not asked for: not computed"));
    }
    for name in ["rotary inertia", "damping", "gravity"] {
        match (name, s.effects.damping) {
            ("damping", Some(d)) => sim.push(Effect::new(
                name,
                format!(
                    "asked for: {} of critical at {} cycles per {}, proportional to frequency elsewhere (PARAM G \
                     {} turned viscous at W3 = 2π·{}); its energy is the ledger's dissipated_damping",
                    d.ratio,
                    d.at,
                    s.units.time,
                    2.0 * d.ratio,
                    d.at
                ),
            )),
            _ => skip.push(Effect::new(name, "not asked for")),
        }
    }
    if let Some(after) = s.run.after_separation {
        sim.push(Effect::new(
            "stop after separation",
            format!(
                "run ends {after} {} after the impactor separates (steps done: {steps_done})",
                s.units.time
            ),
        ));
    }
    EffectReport {
        simulated: sim,
        skipped: skip,
    }
}
