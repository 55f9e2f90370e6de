//! Verification cases (`verification/*.toml`): what to run and which checks to
//! apply, read and validated with file and line.

use super::gold::GoldTol;
use super::Bound;
use crate::integrate::Scheme;
use crate::model::{Model, Modify};
use crate::run::{RunOptions, Summary};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A case file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum CaseError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Read {
        /// The case file.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
    /// There is no such case file.
    #[error("{path}: no such case file")]
    Missing {
        /// The case file asked for.
        path: String,
    },
    /// The case is not valid.
    #[error("{path}{}: {message}", line.map_or(String::new(), |l| format!(":{l}")))]
    Invalid {
        /// The case file.
        path: String,
        /// The line, where the TOML reader gives one.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
    /// Its deck could not be loaded.
    #[error("{0}")]
    Load(#[from] crate::model::LoadError),
    /// Its generated mesh could not be made.
    #[error("{0}")]
    Mesh(#[from] crate::mesh::MeshError),
    /// Its modification could not be made.
    #[error("{0}")]
    Modify(#[from] crate::model::ModifyError),
    /// Its scene could not be made into a model.
    #[error("{0}")]
    Scene(#[from] crate::scene::SceneError),
}

/// One verification case, as written in `verification/<name>.toml`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// The case's name (the file stem).
    pub name: String,
    /// What the case shows.
    #[serde(default)]
    pub description: String,
    /// A deck, relative to the case file.
    pub deck: Option<PathBuf>,
    /// Or a scene, relative to the case file (for what a deck cannot express, such as
    /// a contact that unloads along another curve).
    pub scene: Option<PathBuf>,
    /// Or the paper's plate on a generated n×n mesh.
    pub plate_mesh: Option<usize>,
    /// Or linear static decks (SOL 101), relative to the case file: one problem on a
    /// sequence of meshes, coarse to fine, each halving the element size. Such a case
    /// takes the static check kinds alone ([`CheckSpec::is_static`]).
    #[serde(default)]
    pub statics: Vec<PathBuf>,
    /// The generated plate's elements (default CQUAD4).
    #[serde(default)]
    pub plate_cells: crate::mesh::Cells,
    /// The generated plate's PSHELL names MID3 ([`crate::mesh::MID3`]): the
    /// shear-deformable plate (default: the paper's thin plate).
    #[serde(default)]
    pub plate_mid3: bool,
    /// The scheme (default `newmark`).
    #[serde(default = "default_scheme")]
    pub scheme: Scheme,
    /// Time step; `None`: the deck's.
    pub dt: Option<f64>,
    /// Steps; `None`: the deck's.
    pub steps: Option<usize>,
    /// Output every step (for strain checks), instead of the deck's TSTEP rate.
    #[serde(default)]
    pub every_step: bool,
    /// A change to the model before the run (velocity, contact stiffness, mass, gap).
    #[serde(default)]
    pub modify: Modify,
    /// Times (deck units) at which the run keeps the whole displacement field, for
    /// the report's field figures.
    #[serde(default)]
    pub snapshots: Vec<f64>,
    /// The interface's mode II toughness G_IIc (deck units), given to the run: the
    /// summary and the force figure then carry the plate's delamination threshold.
    pub g_iic: Option<f64>,
    /// The checks (`[[check]]` tables).
    #[serde(rename = "check", default)]
    pub checks: Vec<CheckSpec>,
    /// The file the case was read from (set by [`read_case`]).
    #[serde(skip)]
    pub path: PathBuf,
}

fn yes() -> bool {
    true
}

fn default_scheme() -> Scheme {
    Scheme::Newmark
}

/// A tolerance on a value: relative to the reference, or absolute.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Tol {
    /// Relative to the reference.
    #[serde(default)]
    pub rel: f64,
    /// Absolute.
    #[serde(default)]
    pub abs: f64,
}

impl Tol {
    /// True when `value` is within the tolerance of `reference`.
    pub fn accepts(&self, value: f64, reference: f64) -> bool {
        let d = (value - reference).abs();
        d <= self.abs || d <= self.rel * reference.abs()
    }
    /// The tolerance as numbers and in words.
    pub fn bound(&self) -> Bound {
        let given = |x: f64| (x > 0.0).then_some(x);
        Bound {
            rtol: given(self.rel),
            atol: given(self.abs),
            text: match (self.rel > 0.0, self.abs > 0.0) {
                (true, true) => format!("rel {:.1e} or abs {:.1e}", self.rel, self.abs),
                (true, false) => format!("rel {:.1e}", self.rel),
                _ => format!("abs {:.1e}", self.abs),
            },
        }
    }
}

/// The checks a case can ask for.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum CheckSpec {
    /// max |U_t − U_0 − W_ext| / U_0 ≤ max.
    EnergyBalance {
        /// Largest relative error allowed.
        max: f64,
    },
    /// max |p − p_0| / |m v0| ≤ max along the impact direction (free targets).
    Momentum {
        /// Largest relative change allowed.
        max: f64,
    },
    /// F ≥ 0 always, F > 0 exactly when α > 0, and SE_i > 0 exactly when α > 0.
    ContactComplementarity,
    /// max |KE_t − SE_t| / U_0 over from_tcl..to_tcl (a travelling rod pulse) ≤ max.
    KineticEqualsStrain {
        /// Start of the window, tC/L.
        from_tcl: f64,
        /// End of the window, tC/L.
        to_tcl: f64,
        /// Largest difference allowed, relative to U_0.
        max: f64,
    },
    /// The minimum of SE_t within ±half_width of near_tcl: its time within the window
    /// and its depth (fraction of SE_t at the end of contact) in [min_fraction, max_fraction].
    StrainEnergyDip {
        /// Expected time of the dip, tC/L.
        near_tcl: f64,
        /// Half the width of the window searched, tC/L.
        half_width: f64,
        /// Shallowest depth allowed.
        min_fraction: f64,
        /// Deepest depth allowed.
        max_fraction: f64,
    },
    /// The paper's Eq. 16 KE_t against ½vᵀMv after contact: the relative deficit
    /// (½vᵀMv − Eq16)/½vᵀMv lies in [min, max].
    Eq16Deficit {
        /// Compared from this time on, tC/L (a rod); or
        #[serde(default)]
        after_tcl: Option<f64>,
        /// compared from this time on, in the deck's time unit (any target).
        #[serde(default)]
        after: Option<f64>,
        /// Smallest deficit allowed.
        min: f64,
        /// Largest deficit allowed.
        max: f64,
    },
    /// A summary value against a number, with its source.
    Summary {
        /// Dotted summary key (`contact.peak_force`).
        key: String,
        /// The reference number.
        reference: f64,
        /// The tolerance.
        tol: Tol,
        /// Where the reference comes from.
        source: String,
    },
    /// A quantity of the ball on a semi-infinite rod (analytic::HertzDashpot with
    /// c = ρCA): contact_end_tcl, velocity_zero_tcl, peak_force, peak_force_tcl,
    /// rebound_velocity, transferred_fraction.
    SemiInfiniteRod {
        /// The quantity.
        quantity: RodQuantity,
        /// The tolerance.
        tol: Tol,
    },
    /// Strain of `element` (centre at x from the struck end) against d'Alembert's
    /// −F(t − x/C)/EA with the semi-infinite-rod force, while t < until_tcl;
    /// max |difference| / peak strain ≤ max.
    DalembertStrain {
        /// The rod element.
        element: i64,
        /// Its centre's distance from the struck end.
        x: f64,
        /// Compared until this time, tC/L.
        until_tcl: f64,
        /// Largest difference allowed, relative to the peak strain.
        max: f64,
    },
    /// Contact force against the infinite orthotropic plate (Zener/Olsson) over
    /// 0..until_s: max |difference| / analytic peak ≤ max.
    InfinitePlate {
        /// Compared until this time.
        until_s: f64,
        /// Largest difference allowed, relative to the analytic peak.
        max: f64,
    },
    /// Contact duration and peak force against the rigid-target closed form with the
    /// reduced mass of impactor and target.
    RigidTarget {
        /// The tolerance on both.
        tol: Tol,
    },
    /// A static case's deflection at `point` along `direction` (the translation of the
    /// grid there, in the basic system), deck by deck: the finest mesh's relative
    /// error against `reference` ≤ max, and the error falling mesh by mesh; or, for a
    /// patch test (`falling = false`), every deck's error ≤ max.
    StaticDeflection {
        /// The grid's location (basic coordinates; the grid nearest to it, which must
        /// lie within 1e-6 of the model's size).
        point: [f64; 3],
        /// The direction read (normalised).
        direction: [f64; 3],
        /// The reference deflection.
        reference: f64,
        /// Where it comes from and why it is held to.
        source: String,
        /// Largest relative error of the finest mesh (of every deck when not `falling`).
        max: f64,
        /// The decks are a mesh sequence whose error falls (default); `false`: each
        /// deck is exact up to round-off (a patch test).
        #[serde(default = "yes")]
        falling: bool,
        /// Read the grid's rotation (basic components) rather than its translation.
        #[serde(default)]
        rotation: bool,
    },
    /// A static case's observed order of convergence at `point` along `direction`
    /// from its last three meshes (h halving): p = log₂(|w₁ − w₂| / |w₂ − w₃|) ≥ min;
    /// the detail gives the Richardson extrapolation and its error against `reference`.
    StaticOrder {
        /// The grid's location, as for [`CheckSpec::StaticDeflection`].
        point: [f64; 3],
        /// The direction read.
        direction: [f64; 3],
        /// The reference deflection the extrapolation is compared with.
        reference: f64,
        /// Smallest order accepted.
        min: f64,
    },
    /// A static case's beams (its decks: one straight line of CBARs or CBEAMs of one
    /// section, simply supported, on a sequence of meshes each halving the element):
    /// their lowest `modes` frequencies of bending in plane 1 and in plane 2 and, for a
    /// CBEAM (which has torsional inertia), of torsion, against the closed forms
    /// ω = (kπ/L)² √(EI/m′) and ω = (kπ/L) √(GJ/ρ(I1 + I2)), each matched to the nearest
    /// computed frequency: the finest deck's largest relative error ≤ max, and each
    /// mode's order of convergence from the last two decks ≥ min_order.
    BeamFrequencies {
        /// Modes of each family.
        modes: usize,
        /// Largest relative error on the finest deck.
        max: f64,
        /// Smallest order of convergence of any mode.
        min_order: f64,
    },
    /// A static case's decks are one structure modelled alike but for parts that must
    /// not change its dynamics (an RBE3 that only reads motion): the lowest `modes`
    /// natural frequencies of each deck against the first deck's, largest relative
    /// difference ≤ max.
    SameFrequencies {
        /// How many of the lowest frequencies are compared.
        modes: usize,
        /// Largest relative difference.
        max: f64,
    },
    /// The lowest `modes` natural frequencies of a simply supported square plate of the
    /// case's size and shell section (bending), on two meshes (n × n, the second
    /// twice as fine), Richardson-extrapolated at order 2, against Navier's closed form:
    /// max relative difference ≤ max. Gates the element's bending stiffness and mass
    /// without any gold file.
    NavierFrequencies {
        /// The two meshes, elements a side.
        meshes: [usize; 2],
        /// Number of modes.
        modes: usize,
        /// Largest relative difference allowed.
        max: f64,
        /// The section thickened (or thinned) to this thickness, its materials as they
        /// are: D ∝ t³, the transverse shear stiffness and the mass ∝ t. A thick plate
        /// brings its shear into the lower modes, where a fault of the shear
        /// interpolation (a spurious mode among them) shows.
        thickness: Option<f64>,
    },
    /// Curved-shell dynamics, independent of the case's model: the lowest natural
    /// frequency of a simply supported closed cylinder (R = 1, L = 2, ν = 0.3;
    /// [`crate::mesh::cylinder_model`]) at each R/t of `slenderness`, on the `meshes`
    /// (around × along, refined by one factor in both), against Sanders' thin-shell
    /// theory ([`crate::physics::analytic::cylinder_lowest_frequency`]): the frequency
    /// falling mesh by mesh, the order observed on the last three meshes ≥ `min_order`,
    /// its Richardson extrapolation within `max` of Sanders' value and nearer to it than
    /// to Donnell-Mushtari's. The value is the largest such error.
    CylinderFrequencies {
        /// The radius-to-thickness ratios.
        slenderness: Vec<f64>,
        /// The meshes, elements around × along, coarse to fine (three at least).
        meshes: Vec<[usize; 2]>,
        /// Smallest observed order accepted.
        min_order: f64,
        /// Largest relative error of the extrapolation.
        max: f64,
    },
    /// The plate's gage strains against the Navier series: the paper's plate on a
    /// `mesh` × `mesh` mesh with its edges simply supported, run with the case's scheme
    /// and Δt until `until_s`, against the exact Kirchhoff response of the same plate
    /// (Navier, [`crate::physics::analytic::NavierPlate`]) to the run's own contact
    /// force, shared by the centre element's four corners as the deck loads them. Each
    /// gage's radial fibre strain (yy at z = +T/2: the gages lie on the y axis through
    /// the impact) as the relative L2 norm of the difference over 0..until_s, each
    /// within its own bound (the farther gage sees more of the mesh's dispersion); the
    /// value is the larger ratio of difference to bound. Gates the plate's bending
    /// stiffness, mass and strain recovery through the whole run path against a
    /// reference no gold file carries.
    NavierStrains {
        /// Elements a side.
        mesh: usize,
        /// Compared until this time.
        until_s: f64,
        /// Largest relative L2 difference allowed at gage A and at gage B.
        max: [f64; 2],
    },
    /// The critical step central differences use (2/ω_max from the Gershgorin bound)
    /// against the exact one of a uniform lumped-mass rod, L_e/C: safe (not above it)
    /// and not over-conservative (at least `min_ratio` of it).
    CriticalStep {
        /// Smallest fraction of the exact critical step allowed.
        min_ratio: f64,
    },
    /// Halving Δt: fit the order of `quantity` (energy_error: the error itself;
    /// contact_duration, peak_force: successive differences) over `runs` step sizes.
    DtConvergence {
        /// The quantity followed.
        quantity: Quantity,
        /// Number of step sizes.
        runs: usize,
        /// The order expected.
        expected_order: f64,
        /// Allowed difference from it.
        tol: f64,
    },
    /// The shell recovery on an exact field: every CQUAD4 of the model given the
    /// nodal values of constant membrane strain and constant curvature (w quadratic),
    /// its recovered fibre strains against the field's own at z = ∓T/2, to `max` of
    /// their largest magnitude.
    ShellRecoveryPatch {
        /// Largest difference allowed, relative.
        max: f64,
    },
    /// The scheme converges to the semi-discrete model's own solution, not to another
    /// limit: the contact force at Δt and at Δt/2 against a converged run of an
    /// independent scheme (`energy` at Δt/8; `newmark` when the case runs `energy`),
    /// each as the relative L2 norm of F − F_ref over the reference's first contact;
    /// the observed order log₂(e(Δt)/e(Δt/2)) within `tol` of `expected_order`.
    ConvergesToReference {
        /// The order expected.
        expected_order: f64,
        /// Allowed difference from it.
        tol: f64,
    },
    /// Plate mesh refinement: `quantity` (contact_duration, peak_force_time, ...) on each
    /// mesh of the paper's plate, or of the case's plate scene; the change between the last
    /// two meshes, relative, ≤ max and smaller than the change before.
    MeshConvergence {
        /// Elements a side of each mesh, coarse to fine.
        meshes: Vec<usize>,
        /// The quantity followed.
        quantity: Quantity,
        /// Largest relative change allowed between the last two meshes.
        max: f64,
    },
    /// The failure indices the summary reports against the Tsai-Hill index (NASTRAN's
    /// FT = HILL: X by the sign of σ1, Y by that of σ2) and the bond index
    /// max(|τ1z|, |τ2z|)/SB, recomputed here from the history's ply stress columns
    /// (found by name) with the allowables the case states: the largest of each over
    /// every written ply point and row against `failure.theory` and `failure.bond`.
    /// Value: the larger relative difference; round-off passes (≤ 1e-12).
    FailureIndices {
        /// Xt, Xc, Yt, Yc, S.
        allowables: [f64; 5],
        /// The bond allowable SB.
        sb: f64,
    },
    /// The case run again on the convolution engine ([`crate::run::Engine`]): the
    /// contact force at every step and every history column within `max` of its peak
    /// (a column below 1e-8 of the peak of the columns in its unit vanishes in exact
    /// arithmetic, as the shear on the plate's centre lines by symmetry: its own peak
    /// is round-off, and it is compared with that larger peak).
    Superposition {
        /// Largest difference allowed, relative to the peak.
        max: f64,
    },
    /// The case run again on the modal engine ([`crate::run::modal`]) with its modes
    /// up to each of `fractions` of the default cutoff (ascending; the last is
    /// usually 1, the default itself): the contact duration and the peak force
    /// against the direct run's. Value: the larger relative difference at the last
    /// cutoff, at most `max`; the difference must also fall at every cutoff raised
    /// (modes added), or the reduction does not converge to the direct answer.
    ModalEngine {
        /// Largest relative difference allowed at the last cutoff.
        max: f64,
        /// The cutoffs, as fractions of the default one.
        fractions: Vec<f64>,
    },
    /// A structure released at rest from a displacement, damped viscously: the history
    /// column `column` against the damped oscillator's closed form
    /// u0 e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t), ω_d = ω√(1 − ζ²), u0 its first
    /// value; max |difference| / |u0| ≤ max, and the ledger's dissipated energy never
    /// decreasing.
    FreeDecay {
        /// The history column (`disp_1`, `disp_2_T1`).
        column: String,
        /// The undamped circular frequency ω (radians per the deck's time unit).
        omega: f64,
        /// The damping ratio ζ (below 1).
        zeta: f64,
        /// Largest difference allowed, relative to |u0|.
        max: f64,
        /// Where ω and ζ come from.
        source: String,
    },
    /// A rigid region stores no strain: the written strains of `elements` (every
    /// corner tied to one grid by an RBE2) stay below `max` of the largest written
    /// strain of any element, at every output time.
    RigidStrain {
        /// The elements inside the rigid region.
        elements: Vec<i64>,
        /// Largest |strain| allowed there, relative to the largest written strain.
        max: f64,
    },
    /// The run's history against a stored gold CSV, every column with the same
    /// relative tolerance and a floor relative to the column's peak.
    Gold {
        /// The gold CSV, relative to the case file.
        file: PathBuf,
        /// Its tolerances.
        tol: GoldTol,
    },
    /// The run's history against another solver's results ([`super::external`]):
    /// `columns` maps each history column (name without unit) to the external file's
    /// column; at every time both have, |ours − theirs| ≤ max · (the external
    /// column's peak). `time` names the external time column, `solver` who computed
    /// it, `what` the columns compared (the check's name).
    External {
        /// The external CSV, relative to the case file.
        file: PathBuf,
        /// Who computed it.
        solver: String,
        /// The check's name.
        what: String,
        /// The external time column.
        time: String,
        /// History column (without unit) → external column.
        columns: BTreeMap<String, String>,
        /// Largest difference allowed, relative to the external column's peak.
        max: f64,
    },
}

/// Reads and validates a case file.
///
/// ```
/// let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("verification");
/// let case = impactlab::verify::read_case(&dir.join("rod.toml"))?;
/// assert_eq!(case.name, "rod");
/// assert!(!case.checks.is_empty());
/// # Ok::<(), impactlab::verify::CaseError>(())
/// ```
pub fn read_case(path: &Path) -> Result<Case, CaseError> {
    let file = || path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| CaseError::Read { path: file(), source })?;
    let mut case: Case = toml::from_str(&text).map_err(|e| CaseError::Invalid {
        path: file(),
        line: e.span().map(|s| text[..s.start].lines().count().max(1)),
        message: e.message().to_string(),
    })?;
    if [
        case.deck.is_some(),
        case.scene.is_some(),
        case.plate_mesh.is_some(),
        !case.statics.is_empty(),
    ]
    .iter()
    .filter(|&&b| b)
    .count()
        != 1
    {
        return Err(CaseError::Invalid {
            path: file(),
            line: None,
            message: "give exactly one of `deck`, `scene`, `plate_mesh` and `statics`".into(),
        });
    }
    if case.checks.iter().any(|c| c.is_static() == case.statics.is_empty()) {
        return Err(CaseError::Invalid {
            path: file(),
            line: None,
            message: "static_deflection and static_order judge static decks (a case with `statics`), every other \
                      check a transient run: this case mixes them"
                .into(),
        });
    }
    if case.statics.len() < 3 && case.checks.iter().any(|c| matches!(c, CheckSpec::StaticOrder { .. })) {
        return Err(CaseError::Invalid {
            path: file(),
            line: None,
            message: "static_order reads an order from the last three meshes: `statics` needs at least three decks"
                .into(),
        });
    }
    if case.deck.is_some() && case.plate_mid3 {
        return Err(CaseError::Invalid {
            path: file(),
            line: None,
            message: "`plate_mid3` applies to a generated plate (`plate_mesh`), not to a deck".into(),
        });
    }
    for spec in &case.checks {
        if let CheckSpec::Summary { key, .. } = spec {
            if let Err(e) = Summary::check_key(key) {
                return Err(CaseError::Invalid {
                    path: file(),
                    line: text
                        .lines()
                        .position(|l| l.contains(&format!("\"{key}\"")))
                        .map(|i| i + 1),
                    message: format!("summary check: {e}"),
                });
            }
        }
    }
    case.path = path.to_path_buf();
    Ok(case)
}

impl CheckSpec {
    /// True for the kinds that judge a case's static decks.
    pub fn is_static(&self) -> bool {
        matches!(
            self,
            CheckSpec::StaticDeflection { .. }
                | CheckSpec::StaticOrder { .. }
                | CheckSpec::BeamFrequencies { .. }
                | CheckSpec::SameFrequencies { .. }
        )
    }
}

/// The case files named on the command line: files as given, directories expanded
/// to their `*.toml` (sorted).
pub fn case_files(args: &[PathBuf]) -> Result<Vec<PathBuf>, CaseError> {
    let mut out = Vec::new();
    for a in args {
        if a.is_dir() {
            let mut v: Vec<PathBuf> = std::fs::read_dir(a)
                .map_err(|source| CaseError::Read {
                    path: a.display().to_string(),
                    source,
                })?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .collect();
            v.sort();
            out.extend(v);
        } else if a.exists() {
            out.push(a.clone());
        } else {
            return Err(CaseError::Missing {
                path: a.display().to_string(),
            });
        }
    }
    Ok(out)
}

/// The cases named by files or directories; none named means `verification/`.
pub fn load_cases(args: &[PathBuf]) -> Result<Vec<Case>, CaseError> {
    let default = [PathBuf::from("verification")];
    let args = if args.is_empty() { &default[..] } else { args };
    case_files(args)?.iter().map(|p| read_case(p)).collect()
}

impl Case {
    /// True when the case runs a model file (a deck or a scene): such a case has a
    /// report.
    pub fn reported(&self) -> bool {
        self.deck.is_some() || self.scene.is_some()
    }
}

/// A path of a case file, relative to the case file.
pub fn rel(case: &Case, p: &Path) -> PathBuf {
    case.path.parent().unwrap_or(Path::new(".")).join(p)
}

/// The case's model, modifications applied.
pub fn case_model(case: &Case) -> Result<Model, CaseError> {
    let mut m = match (&case.deck, case.plate_mesh) {
        (Some(d), _) => crate::load_deck(&rel(case, d), Default::default())?.0,
        (None, None) if case.scene.is_some() => {
            crate::scene::load(&rel(case, case.scene.as_ref().expect("a scene")))?.1
        }
        (None, Some(n)) if case.plate_mid3 => crate::mesh::plate_model_mid3(n, case.plate_cells)?,
        (None, Some(n)) => crate::mesh::plate_model_with(n, case.plate_cells)?,
        (None, None) => {
            return Err(CaseError::Invalid {
                path: case.path.display().to_string(),
                line: None,
                message: "a static case (`statics`) has no transient model".into(),
            })
        }
    };
    if case.every_step {
        m.time.every = 1;
    }
    Ok(case.modify.apply(&m)?)
}

/// The case's run options.
pub fn case_options(case: &Case) -> RunOptions {
    RunOptions {
        scheme: case.scheme,
        dt: case.dt,
        steps: case.steps,
        snapshot_times: case.snapshots.clone(),
        interlaminar_toughness: case.g_iic,
        ..Default::default()
    }
}

/// A quantity of a run's summary that convergence checks follow; NaN where the run
/// has none (no contact, no ledger), which fails the check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// The largest relative energy error.
    EnergyError,
    /// The first contact's duration.
    ContactDuration,
    /// The largest contact force.
    PeakForce,
    /// Its time.
    PeakForceTime,
    /// The energy a hysteretic contact dissipated.
    ContactDissipation,
}

impl Quantity {
    /// The quantity's value in a summary.
    pub fn of(self, s: &Summary) -> f64 {
        match self {
            Quantity::EnergyError => s.energy.max_relative_error,
            Quantity::ContactDuration => s.contact.duration,
            Quantity::PeakForce => Some(s.contact.peak_force),
            Quantity::PeakForceTime => s.contact.peak_force_time,
            Quantity::ContactDissipation => s.energy.contact.as_ref().map(|c| c.dissipated),
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
            Quantity::ContactDissipation => "contact_dissipation",
        }
    }
}

/// A quantity of the ball on a semi-infinite rod, for [`CheckSpec::SemiInfiniteRod`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RodQuantity {
    /// End of contact, tC/L.
    ContactEndTcl,
    /// Impactor at rest, tC/L.
    VelocityZeroTcl,
    /// Largest contact force.
    PeakForce,
    /// Its time, tC/L.
    PeakForceTcl,
    /// Impactor velocity after contact.
    ReboundVelocity,
    /// 1 − (v_rebound/v0)².
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
