//! Deck → model, in named stages over the deck's cards: the constraints and the
//! solved DOFs ([`dofs`]), the properties and materials ([`properties`]), the
//! elements ([`elements`]), the contact ([`contact`]) and the output requests
//! ([`outputs`]); here, the stages in order for a transient model
//! ([`build_model`]), a structure alone ([`build_structure`]) and its survey
//! ([`survey_structure`]).

use super::*;
use crate::deck::cards::Connection;
use crate::deck::cards::{BarOrientation, Orientation};
use crate::deck::case::{OutputSet, Selection};
use crate::deck::{Deck, Diagnostic};
use crate::elements::{drill::Drill, mass::PointMass, rod::RodSection, BadShape, Build, Family, Placement};
use crate::geometry::{FrameError, Geometry};
use nalgebra::{Matrix2, Matrix3, Vector3};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::{BTreeMap, HashMap};

mod bush;
mod contact;
mod damping;
mod dofs;
mod elements;
mod excitation;
mod outputs;
mod properties;

use bush::*;
use contact::*;
use damping::*;
use dofs::*;
use elements::*;
use excitation::*;
pub(crate) use outputs::element_requests;
use outputs::*;
use properties::*;

/// Building the model failed: every problem found, each tied to its card.
#[derive(Debug, Clone)]
pub struct ModelError {
    /// Every problem found, each tied to its card.
    pub diagnostics: Vec<Diagnostic>,
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let errors: Vec<_> = self.diagnostics.iter().filter(|d| d.is_error()).collect();
        let max = crate::deck::diag::MAX_ERRORS;
        for d in errors.iter().take(max) {
            writeln!(f, "{d}")?;
        }
        if errors.len() > max {
            writeln!(f, "... and {} more errors", errors.len() - max)?;
        }
        write!(f, "{} error(s) in model", errors.len())
    }
}

impl std::error::Error for ModelError {}

#[derive(Default)]
struct Ctx {
    diags: Vec<Diagnostic>,
    /// The text of every error recorded, to report each once in linear time.
    seen: std::collections::HashSet<String>,
}

impl Ctx {
    /// Records an error once: the same message at the same place (a property used by
    /// many elements) is reported once.
    fn err(&mut self, d: Diagnostic) {
        if self.seen.insert(d.to_string()) {
            self.diags.push(d);
        }
    }

    /// Records a warning once, as [`Ctx::err`] an error (a PCOMP's note, laminated
    /// again for each material axis its elements turn it to, is said once).
    fn warn(&mut self, mut d: Diagnostic) {
        d.severity = crate::deck::Severity::Warning;
        self.err(d);
    }

    /// Cards of one kind selected by a case-control set id. Warns about cards whose
    /// set is not selected; errors when a selection matches no card.
    fn select<'c, T>(
        &mut self,
        kind: &str,
        keyword: &str,
        sel: &Option<Selection>,
        cards: &'c [T],
        sid: impl Fn(&T) -> i64,
        at: impl Fn(&T) -> &CardRef,
    ) -> Vec<&'c T> {
        let chosen: Vec<&T> = match sel {
            Some(s) => cards.iter().filter(|c| sid(c) == s.id).collect(),
            None => Vec::new(),
        };
        if let Some(s) = sel {
            if chosen.is_empty() {
                self.err(
                    Diagnostic::error(
                        Some(s.pos.clone()),
                        format!(
                            "case control {keyword} = {} selects no {kind} card (no {kind} has SID {})",
                            s.id, s.id
                        ),
                    )
                    .card(keyword),
                );
            }
        }
        let ignored: Vec<&T> = cards
            .iter()
            .filter(|c| sel.as_ref().is_none_or(|s| sid(c) != s.id))
            .collect();
        if let Some(first) = ignored.first() {
            let why = match sel {
                Some(s) => format!("case control selects {keyword} = {}", s.id),
                None => format!("case control has no {keyword} request"),
            };
            self.warn(at(first).error(format!(
                "{} {kind} card(s) not selected ({why}); ignored",
                ignored.len()
            )));
        }
        chosen
    }
}

/// The cards the case control selects.
struct Selected<'d> {
    spcs: Vec<&'d crate::deck::cards::Spc1>,
    tfs: Vec<&'d crate::deck::cards::Tf>,
    nolins: Vec<&'d crate::deck::cards::Nolin3>,
    tics: Vec<&'d crate::deck::cards::Tic>,
    tsteps: Vec<&'d crate::deck::cards::Tstep>,
}

/// Points and the numbering of the solved DOFs.
struct Numbering<'d> {
    grids: BTreeMap<i64, &'d crate::deck::cards::Grid>,
    scalar: BTreeMap<i64, &'d CardRef>,
    dofs: Vec<DofLabel>,
    /// Each grid's solved DOFs: the index of its first and the components solved
    /// (bit c−1 for component c), numbered in component order from the first.
    grid_first: FxHashMap<i64, (usize, u8)>,
    /// Each scalar point's solved DOF.
    scalar_index: FxHashMap<i64, usize>,
    /// The rigid elements' dependent grids.
    rigid: &'d crate::model::rigid::Rigid,
}

impl Numbering<'_> {
    /// The solved DOF index of T1..R3 of a grid.
    fn grid_dofs(&self, id: i64) -> [Option<usize>; 6] {
        let mut d = [None; 6];
        if let Some(&(first, solved)) = self.grid_first.get(&id) {
            let mut next = first;
            for (k, slot) in d.iter_mut().enumerate() {
                if solved & (1 << k) != 0 {
                    *slot = Some(next);
                    next += 1;
                }
            }
        }
        d
    }

    /// The solved DOF index of a (point, component), if it is solved.
    fn index(&self, l: &DofLabel) -> Option<usize> {
        match l.comp {
            0 => self.scalar_index.get(&l.point).copied(),
            c => self.grid_dofs(l.point)[usize::from(c) - 1],
        }
    }

    /// A reference (point, component) to a solved DOF, with a clear error otherwise.
    fn lookup(&self, cx: &mut Ctx, at: &CardRef, what: &str, g: i64, c: usize) -> Option<usize> {
        let is_grid = self.grids.contains_key(&g);
        let is_scalar = self.scalar.contains_key(&g);
        if !is_grid && !is_scalar {
            cx.err(at.error(format!("{what} references point {g}, which does not exist")));
            return None;
        }
        if is_grid && c == 0 {
            cx.err(at.error(format!(
                "{what} names grid {g} with component 0: a grid needs a component 1-6"
            )));
            return None;
        }
        let l = DofLabel {
            point: g,
            comp: if is_scalar { 0 } else { c as u8 },
        };
        match (self.index(&l), self.rigid.ties.get(&g)) {
            (Some(i), _) => Some(i),
            (None, Some(t)) if is_grid && t.ties(c - 1) => {
                cx.err(at.error(match t.whole() {
                    Some((gn, _)) => format!(
                        "{what} uses {l}, a DOF {} makes dependent (its motion is grid {gn}'s): name grid {gn} \
                         instead",
                        t.name
                    ),
                    None => format!(
                        "{what} uses {l}, a DOF {} makes dependent: name an independent DOF instead",
                        t.name
                    ),
                }));
                None
            }
            (None, _) => {
                cx.err(at.error(format!("{what} uses {l}, which is constrained (SPC1 or PS)")));
                None
            }
        }
    }
}

/// The TF-defined scalar points, as functionals of the solved DOFs.
struct Dependent {
    points: Vec<DependentPoint>,
    index: HashMap<i64, usize>,
}

/// What a survey does with each element as it is built, with the grids' geometry.
type Surveyor<'s> = dyn FnMut(&Element, &Geometry) + 's;

/// Builds the model of a deck, collecting every error: named stages, each reporting
/// its problems against the cards.
pub fn build_model(deck: &Deck) -> Result<(Model, Vec<Diagnostic>), ModelError> {
    let mut cx = Ctx::default();
    if deck.executive.sol == Some(crate::deck::STATICS) {
        cx.err(Diagnostic::error(
            deck.case.at.clone(),
            "a linear static deck (SOL 101): `impactlab run` solves it; this command takes a transient deck",
        ));
        return Err(ModelError { diagnostics: cx.diags });
    }
    no_static_loads(&mut cx, deck);
    let case = &deck.case;
    let sel = select_cards(&mut cx, deck);
    let (geo, geo_errors) = crate::geometry::resolve(&deck.bulk);
    for d in geo_errors {
        cx.err(d);
    }
    let constrained = constrained_grids(&mut cx, deck, &sel);
    for d in enforced_values(&sel) {
        cx.err(d);
    }
    let rigid = rigid_elements(&mut cx, deck, &geo, &sel);
    let tf_of = transfer_functions(&mut cx, &sel, deck);
    let num = number_dofs(deck, &constrained, &tf_of, &rigid);
    let mut dependent = dependent_points(&mut cx, &tf_of, &num);
    let elements = build_elements(&mut cx, deck, &num, &geo, &rigid, None);
    let tied = tied_points(&rigid, &num, &mut dependent);
    let time = time_control(&sel);
    let (u0, v0) = initial_conditions(&mut cx, &sel, &dependent, &num);
    let refs = ContactRefs {
        dependent: &dependent.points,
        dep_index: &dependent.index,
        elements: &elements.list,
        on_element: &elements.on_element,
        labels: &num.dofs,
    };
    let contact = build_contact(&mut cx, &sel.nolins, &refs, |cx, at, w, g, c| {
        num.lookup(cx, at, w, g, c)
    });
    let excitation = excitation(&mut cx, deck, &num);
    let damping = proportional_damping(&mut cx, deck, &elements.structurally_damped);
    let outputs = output_plan(&mut cx, deck, &num, (&dependent, &tied), &elements, contact.as_ref());
    let rod = rod_info(&elements.list);
    let model = Model {
        name: deck.name.clone(),
        title: case.title.clone(),
        units: deck.units.clone(),
        deck_sha256: deck.sha256.clone(),
        dofs: num.dofs,
        dependent: dependent.points,
        elements: elements.list.into(),
        contact,
        excitation,
        damping,
        u0,
        v0,
        time,
        outputs,
        rod,
        inert_dofs: 0,
        time_card: sel.tsteps.first().map(|t| format!("TSTEP {} at {}", t.sid, t.at.pos)),
        frames: std::sync::Arc::new(
            deck.bulk
                .grids
                .iter()
                .filter_map(|g| {
                    let axes = geo.frames.get(&g.id)?;
                    Some((
                        g.id,
                        GridFrame {
                            cd: crate::geometry::grid_systems(g, &deck.bulk).1,
                            axes: *axes,
                        },
                    ))
                })
                .collect(),
        ),
    };
    let errors = cx.diags.iter().any(|d| d.is_error());
    if errors {
        Err(ModelError { diagnostics: cx.diags })
    } else {
        Ok((model, cx.diags))
    }
}

/// A deck's structure alone, as `impactlab check` builds it: no time stepping, no
/// impactor and no contact are asked for.
#[derive(Debug, Clone)]
pub struct Structure {
    /// The grids, with their basic positions and displacement frames, and the
    /// coordinate systems.
    pub geometry: Geometry,
    /// The elements, CONM2 masses and drilling supports, as a run builds them.
    pub elements: Vec<Element>,
    /// The grid DOFs left free by PS, GRDSET and the selected SPC1/SPC cards.
    pub free_dofs: usize,
    /// The grid DOFs they constrain.
    pub constrained_dofs: usize,
    /// The grid DOFs RBE2s make dependent.
    pub dependent_dofs: usize,
    /// The RBE2s' dependent grids and their ties.
    pub rigid: crate::model::rigid::Rigid,
    /// Scalar points (EPOINT, SPOINT).
    pub scalar_points: usize,
    /// The solved DOFs, in the order the elements' DOF indices count them.
    pub dofs: Vec<DofLabel>,
    /// The solved DOFs whose values a static solution prescribes: the components a
    /// selected SPC holds at D ≠ 0 and those an SPCD names (they are numbered among
    /// [`Structure::dofs`], not constrained), each with its SPC's D (0 for an SPCD's
    /// component the SPC holds at zero; the SPCD of the solved LOAD set overrides it).
    pub prescribed: Vec<(usize, f64)>,
}

impl Structure {
    /// Its mass, centre of gravity and inertia (see [`super::mass_properties`]).
    pub fn mass_properties(&self) -> super::MassProperties {
        let g = &self.geometry;
        super::mass_properties(&self.elements, |id| g.positions.get(&id).copied(), |id| g.frame(id))
    }
}

/// Builds a deck's structure alone (see [`Structure`]): its coordinate systems and
/// grids, constraints (the case control's SPC, through SPCADD), elements with their
/// properties and materials, and masses, collecting every error as [`build_model`]
/// does. TSTEP, TF, NOLIN3 and TIC cards are read but not used.
pub fn build_structure(deck: &Deck) -> Result<(Structure, Vec<Diagnostic>), ModelError> {
    structure(deck, None)
}

/// What `impactlab check` needs of a structure: its elements counted and weighed as
/// they are built, none of them kept, so that a deck of any size is surveyed in the
/// memory its cards take. No drilling supports are added (they need the shells'
/// stiffness, which a survey does not compute).
#[derive(Debug, Clone, PartialEq)]
pub struct Survey {
    /// Elements by card (CONM2 masses included).
    pub elements: BTreeMap<&'static str, usize>,
    /// The grid DOFs left free (see [`Structure::free_dofs`]).
    pub free_dofs: usize,
    /// The grid DOFs constrained.
    pub constrained_dofs: usize,
    /// The grid DOFs rigid elements make dependent.
    pub dependent_dofs: usize,
    /// Scalar points (EPOINT, SPOINT).
    pub scalar_points: usize,
    /// Mass, centre of gravity and inertia (see [`super::mass_properties`]).
    pub mass: super::MassProperties,
}

/// Surveys a deck's structure (see [`Survey`]), with the errors [`build_structure`]
/// would report.
pub fn survey_structure(deck: &Deck) -> Result<(Survey, Vec<Diagnostic>), ModelError> {
    let mut elements: BTreeMap<&'static str, usize> = BTreeMap::new();
    let mut mass = super::weight::RigidBodyMass::default();
    let mut survey = |e: &Element, g: &Geometry| {
        *elements.entry(e.kernel.card()).or_default() += 1;
        mass.add(e, &|id| g.positions.get(&id).copied(), &|id| g.frame(id));
    };
    let (s, diags) = structure(deck, Some(&mut survey))?;
    let survey = Survey {
        elements,
        free_dofs: s.free_dofs,
        constrained_dofs: s.constrained_dofs,
        dependent_dofs: s.dependent_dofs,
        scalar_points: s.scalar_points,
        mass: mass.properties(),
    };
    Ok((survey, diags))
}

/// [`build_structure`], or with `survey` its elements handed to it as built.
fn structure<'s>(
    deck: &Deck,
    survey: Option<&'s mut Surveyor<'s>>,
) -> Result<(Structure, Vec<Diagnostic>), ModelError> {
    let mut cx = Ctx::default();
    let (geometry, geo_errors) = crate::geometry::resolve(&deck.bulk);
    for d in geo_errors {
        cx.err(d);
    }
    let sel = Selected {
        spcs: select_spcs(&mut cx, deck),
        tfs: Vec::new(),
        nolins: Vec::new(),
        tics: Vec::new(),
        tsteps: Vec::new(),
    };
    let mut constrained = constrained_grids(&mut cx, deck, &sel);
    let values = prescribed_values(&mut cx, deck, &sel, &constrained);
    // Prescribed components are solved DOFs whose values the solution sets.
    for l in values.keys() {
        if let Some(c) = constrained.get_mut(&l.point) {
            *c &= !(1 << (l.comp - 1));
        }
    }
    let rigid = rigid_elements(&mut cx, deck, &geometry, &sel);
    let num = number_dofs(deck, &constrained, &BTreeMap::new(), &rigid);
    let elements = build_elements(&mut cx, deck, &num, &geometry, &rigid, survey).list;
    let prescribed: Vec<(usize, f64)> = values.iter().filter_map(|(l, &d)| Some((num.index(l)?, d))).collect();
    let grid_dofs = num.dofs.iter().filter(|d| d.comp != 0).count() - prescribed.len();
    let structure = Structure {
        geometry,
        elements,
        free_dofs: grid_dofs,
        constrained_dofs: 6 * num.grids.len() - rigid.dependent_dofs() - grid_dofs,
        dependent_dofs: rigid.dependent_dofs(),
        scalar_points: num.scalar.len(),
        dofs: num.dofs,
        rigid,
        prescribed,
    };
    if cx.diags.iter().any(|d| d.is_error()) {
        Err(ModelError { diagnostics: cx.diags })
    } else {
        Ok((structure, cx.diags))
    }
}

/// A transient deck's static load cards and LOAD selection are errors: a transient
/// run applies none of them (its loads are the contact's NOLIN3 and the DLOAD), and
/// ignoring them would answer another question than the deck asks. The static load
/// sets that the LSEQ cards of the case control's LOADSET name (directly or through a
/// LOAD) are the dynamic loads' distributions: their cards are taken.
fn no_static_loads(cx: &mut Ctx, deck: &Deck) {
    let b = &deck.bulk;
    let mut named: FxHashSet<i64> = match &deck.case.loadset {
        Some(sel) => b.lseqs.iter().filter(|l| l.sid == sel.id).map(|l| l.lid).collect(),
        None => FxHashSet::default(),
    };
    let combined: Vec<i64> = b
        .load_combinations
        .iter()
        .filter(|c| named.contains(&c.sid))
        .flat_map(|c| c.terms.iter().map(|t| t.1))
        .collect();
    named.extend(combined);
    let free = |sid: &i64| !named.contains(sid);
    let why = "is a static load, which a transient run does not apply (it applies the contact's NOLIN3 and the \
               DLOAD's dynamic loads, and the static load sets a LOADSET's LSEQ names): remove it, or solve the \
               deck as SOL 101";
    let firsts = [
        b.point_loads.iter().find(|l| free(&l.sid)).map(|l| &l.at),
        b.pload4s.iter().find(|l| free(&l.sid)).map(|l| &l.at),
        b.ploads.iter().find(|l| free(&l.sid)).map(|l| &l.at),
        b.gravs.iter().find(|l| free(&l.sid)).map(|l| &l.at),
        b.spcds.first().map(|l| &l.at),
        b.load_combinations.iter().find(|l| free(&l.sid)).map(|l| &l.at),
    ];
    for at in firsts.into_iter().flatten() {
        cx.err(at.error(format!("{} {why}", at.name)));
    }
    if let Some(sel) = &deck.case.load {
        cx.err(Diagnostic::error(Some(sel.pos.clone()), format!("LOAD = {} {why}", sel.id)).card("LOAD"));
    }
    if let Some(sel) = &deck.case.temperature {
        cx.err(
            Diagnostic::error(Some(sel.pos.clone()), format!("TEMPERATURE(LOAD) = {} {why}", sel.id))
                .card("TEMPERATURE"),
        );
    }
}

/// The SPC1, TF, NOLIN3, TIC and TSTEP cards the case control selects.
fn select_cards<'d>(cx: &mut Ctx, deck: &'d Deck) -> Selected<'d> {
    let (b, case) = (&deck.bulk, &deck.case);
    let sel = Selected {
        spcs: select_spcs(cx, deck),
        tfs: cx.select("TF", "TFL", &case.tfl, &b.tfs, |c| c.sid, |c| &c.at),
        nolins: cx.select("NOLIN3", "NONLINEAR", &case.nonlinear, &b.nolin3s, |c| c.sid, |c| &c.at),
        tics: cx.select("TIC", "IC", &case.ic, &b.tics, |c| c.sid, |c| &c.at),
        tsteps: cx.select("TSTEP", "TSTEP", &case.tstep, &b.tsteps, |c| c.sid, |c| &c.at),
    };
    for t in &sel.tsteps {
        if let Some(f) = &t.further {
            cx.err(t.at.field_error(f, "more than one TSTEP interval is not supported"));
        }
    }
    if case.tstep.is_none() {
        cx.err(Diagnostic::error(
            case.at.clone(),
            "case control has no TSTEP request: a transient run needs one",
        ));
    }
    sel
}

/// The selected TSTEP (zero steps where there is none: already an error).
fn time_control(sel: &Selected) -> TimeControl {
    match sel.tsteps.first() {
        Some(t) => TimeControl {
            dt: t.dt,
            steps: t.n,
            every: t.every,
        },
        None => TimeControl {
            dt: 0.0,
            steps: 0,
            every: 1,
        },
    }
}

/// Initial displacements and velocities from the selected TICs.
fn initial_conditions(cx: &mut Ctx, sel: &Selected, dependent: &Dependent, num: &Numbering) -> (Vec<f64>, Vec<f64>) {
    let dep_index = &dependent.index;
    let n = num.dofs.len();
    let (mut u0, mut v0) = (vec![0.0; n], vec![0.0; n]);
    for t in &sel.tics {
        if dep_index.contains_key(&t.g) {
            cx.err(t.at.error(format!(
                "TIC on point {}, which a TF defines: it has no state of its own",
                t.g
            )));
            continue;
        }
        if let Some(i) = num.lookup(cx, &t.at, "TIC", t.g, t.c) {
            u0[i] = t.u0;
            v0[i] = t.v0;
        }
    }

    (u0, v0)
}

/// A target made of CRODs of one section along one line: wave speed and length.
fn rod_info(elements: &[Element]) -> Option<RodInfo> {
    let rods: Vec<(&RodSection, f64)> = elements
        .iter()
        .filter_map(|e| match e.kernel.family() {
            Family::Rod { section, length } => Some((section, length)),
            _ => None,
        })
        .collect();
    let s0 = rods.first()?.0;
    if rods.iter().any(|r| r.0 != s0) || s0.rho <= 0.0 {
        return None;
    }
    let length: f64 = rods.iter().map(|r| r.1).sum();
    Some(RodInfo {
        wave_speed: (s0.e / s0.rho).sqrt(),
        length,
        e: s0.e,
        area: s0.area,
    })
}
