//! Deck → model.

use super::*;
use crate::deck::cards::Connection;
use crate::deck::cards::{BarOrientation, Orientation};
use crate::deck::case::{OutputSet, Selection};
use crate::deck::{Deck, Diagnostic};
use crate::elements::{drill::Drill, mass::PointMass, rod::RodSection, BadShape, Build, Family, Placement};
use crate::geometry::{FrameError, Geometry};
use nalgebra::{Matrix2, Matrix3, Vector3};
use std::collections::{BTreeMap, HashMap};

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
    grid_first: HashMap<i64, (usize, u8)>,
    /// Each scalar point's solved DOF.
    scalar_index: HashMap<i64, usize>,
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

/// The elements, and how many elements touch each grid.
struct Elements<'a, 's> {
    list: Vec<Element>,
    on_element: HashMap<i64, usize>,
    /// The plies of each laminate (PCOMP) element, by its index in `list`.
    plies: HashMap<usize, PlyStack>,
    /// The rigid elements, whose ties each element is attached through.
    rigid: &'a crate::model::rigid::Rigid,
    /// For a survey of the structure: each element is handed to it as it is built,
    /// with the grids' geometry, instead of kept in `list`.
    survey: Option<&'s mut Surveyor<'s>>,
    /// The grids' positions and frames.
    geo: &'a Geometry,
    /// Elements built so far.
    built: usize,
}

impl Elements<'_, '_> {
    /// An element built, on grids whose DOFs are `dofs(g)`: attached through the ties
    /// of the rigid elements (an independent grid that a grid follows whole carries
    /// that grid's elements), then kept or surveyed.
    fn push(&mut self, e: Element, dofs: impl Fn(i64) -> [Option<usize>; 6]) {
        let e = if self.rigid.ties.is_empty() {
            e
        } else {
            if !matches!(e.kernel.family(), Family::Point { .. }) {
                for (gn, _) in e.grids.iter().filter_map(|g| self.rigid.ties.get(g)?.whole()) {
                    *self.on_element.entry(gn).or_default() += 1;
                }
            }
            self.rigid.attach(e, dofs)
        };
        self.built += 1;
        match &mut self.survey {
            Some(survey) => survey(&e, self.geo),
            None => self.list.push(e),
        }
    }
}

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
/// run applies none of them (its load is the contact's NOLIN3), and ignoring them
/// would answer another question than the deck asks.
fn no_static_loads(cx: &mut Ctx, deck: &Deck) {
    let b = &deck.bulk;
    let why = "is a static load, which a transient run does not apply (its load is the contact's NOLIN3): \
               remove it, or solve the deck as SOL 101";
    let firsts = [
        b.point_loads.first().map(|l| &l.at),
        b.pload4s.first().map(|l| &l.at),
        b.ploads.first().map(|l| &l.at),
        b.gravs.first().map(|l| &l.at),
        b.spcds.first().map(|l| &l.at),
        b.load_combinations.first().map(|l| &l.at),
    ];
    for at in firsts.into_iter().flatten() {
        cx.err(at.error(format!("{} {why}", at.name)));
    }
    if let Some(sel) = &deck.case.load {
        cx.err(Diagnostic::error(Some(sel.pos.clone()), format!("LOAD = {} {why}", sel.id)).card("LOAD"));
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

/// The SPC1 (and SPC) cards the case control's SPC selects: those of its set, or of
/// every set an SPCADD of that id joins (an SPCADD naming an SPCADD, or a set no card
/// has, is an error).
fn select_spcs<'d>(cx: &mut Ctx, deck: &'d Deck) -> Vec<&'d crate::deck::cards::Spc1> {
    let (b, case) = (&deck.bulk, &deck.case);
    let Some(add) = case.spc.as_ref().and_then(|s| b.spcadds.iter().find(|a| a.sid == s.id)) else {
        return cx.select("SPC1", "SPC", &case.spc, &b.spc1s, |c| c.sid, |c| &c.at);
    };
    for &set in &add.sets {
        if b.spcadds.iter().any(|a| a.sid == set) {
            cx.err(add.at.error(format!(
                "SPCADD {} joins set {set}, itself an SPCADD: join SPC1/SPC sets only",
                add.sid
            )));
        } else if !b.spc1s.iter().any(|c| c.sid == set) {
            cx.err(add.at.error(format!(
                "SPCADD {} joins set {set}, which no SPC1 or SPC card has",
                add.sid
            )));
        }
    }
    let chosen: Vec<_> = b.spc1s.iter().filter(|c| add.sets.contains(&c.sid)).collect();
    let ignored = b.spc1s.len() - chosen.len();
    if ignored > 0 {
        let first = b
            .spc1s
            .iter()
            .find(|c| !add.sets.contains(&c.sid))
            .expect("one is ignored");
        cx.warn(first.at.error(format!(
            "{ignored} SPC1 card(s) not selected (case control selects SPC = {}, SPCADD of sets {:?}); ignored",
            add.sid, add.sets
        )));
    }
    chosen
}

/// The scalar points of the deck (EPOINT, SPOINT).
fn scalar_points(deck: &Deck) -> BTreeMap<i64, &CardRef> {
    let b = &deck.bulk;
    b.epoints
        .iter()
        .chain(b.spoints.iter())
        .map(|(id, at)| (*id, at))
        .collect()
}

/// The selected TFs that define a scalar point from B0 and A0 terms, by point.
fn transfer_functions<'d>(cx: &mut Ctx, sel: &Selected<'d>, deck: &Deck) -> BTreeMap<i64, &'d crate::deck::cards::Tf> {
    let tfs = &sel.tfs;
    let scalar = scalar_points(deck);
    let mut tf_of: BTreeMap<i64, &crate::deck::cards::Tf> = BTreeMap::new();
    for t in tfs {
        if !scalar.contains_key(&t.gd) {
            cx.err(t.at.error(format!(
                "TF dependent point {} must be an EPOINT or SPOINT (a TF on a structural DOF is not supported)",
                t.gd
            )));
            continue;
        }
        if t.b[1] != 0.0 || t.b[2] != 0.0 || t.terms.iter().any(|x| x.a[1] != 0.0 || x.a[2] != 0.0) {
            cx.err(t.at.error(
                "TF with velocity or acceleration terms (B1, B2, A1, A2 nonzero) is not supported: only B0 and A0",
            ));
            continue;
        }
        if t.b[0] == 0.0 {
            cx.err(t.at.error("TF B0 is zero: the dependent point is not defined"));
            continue;
        }
        if t.terms.iter().any(|x| x.g == t.gd) {
            cx.err(t.at.error(format!(
                "TF references itself: point {} is both dependent and independent",
                t.gd
            )));
            continue;
        }
        if tf_of.insert(t.gd, t).is_some() {
            cx.err(t.at.error(format!("point {} is defined by more than one TF", t.gd)));
        }
    }

    tf_of
}

/// The components a static solution prescribes (see [`Structure::prescribed`]), each
/// with its selected SPC's D: those held at D ≠ 0, and every component an SPCD names,
/// which a selected SPC must hold (SPCD remark 1).
fn prescribed_values(
    cx: &mut Ctx,
    deck: &Deck,
    sel: &Selected,
    constrained: &HashMap<i64, u8>,
) -> BTreeMap<DofLabel, f64> {
    let mut out = BTreeMap::new();
    for s in &sel.spcs {
        if let Some((d, _)) = &s.enforced {
            for &g in &s.grids {
                for comp in s.c.iter() {
                    out.insert(
                        DofLabel {
                            point: g,
                            comp: comp as u8,
                        },
                        *d,
                    );
                }
            }
        }
    }
    for p in &deck.bulk.spcds {
        if p.c.0 == 0 {
            cx.err(p.at.field_error(
                &p.at_point,
                format!(
                    "SPCD {} names point {} with no component: a scalar point's value cannot be enforced",
                    p.sid, p.point
                ),
            ));
        }
        for comp in p.c.iter() {
            let l = DofLabel {
                point: p.point,
                comp: comp as u8,
            };
            let held = constrained.get(&p.point).is_some_and(|c| c & (1 << (comp - 1)) != 0);
            if !held {
                cx.err(p.at.field_error(
                    &p.at_point,
                    format!(
                        "SPCD {} enforces grid {} component {comp}, which no selected SPC (nor PS) holds: an SPCD \
                         sets the value of a constrained component",
                        p.sid, p.point
                    ),
                ));
                continue;
            }
            out.entry(l).or_insert(0.0);
        }
    }
    out
}

/// The selected SPCs' nonzero enforced values, as errors to raise where they cannot
/// be applied.
fn enforced_values(sel: &Selected) -> Vec<Diagnostic> {
    sel.spcs
        .iter()
        .filter_map(|s| {
            let (d, at) = s.enforced.as_ref()?;
            Some(s.at.field_error(
                at,
                format!("an enforced displacement (D = {d:e}) is not supported: impactlab holds constrained components at zero"),
            ))
        })
        .collect()
}

/// The grids and their constrained components (PS, GRDSET and the selected SPC1s),
/// each in the grid's displacement frame.
fn constrained_grids(cx: &mut Ctx, deck: &Deck, sel: &Selected) -> HashMap<i64, u8> {
    let b = &deck.bulk;
    let spcs = &sel.spcs;
    let scalar = scalar_points(deck);
    let mut constrained: HashMap<i64, u8> = HashMap::new();
    for g in &b.grids {
        let ps = g.ps.unwrap_or(b.grdset.ps);
        constrained.insert(g.id, ps.0);
    }
    for s in spcs {
        for gid in &s.grids {
            match constrained.get_mut(gid) {
                Some(_) if s.c.0 == 0 => cx.err(s.at.error(format!(
                    "constrains grid {gid} in no component (a blank or 0 component names a scalar point)"
                ))),
                Some(c) => *c |= s.c.0,
                None if scalar.contains_key(gid) => cx.err(s.at.error(format!(
                    "SPC1 constrains point {gid}, a scalar point: only grids are supported"
                ))),
                None => cx.err(s.at.error(format!("SPC1 references grid {gid}, which does not exist"))),
            }
        }
    }

    constrained
}

/// The numbering of the solved DOFs: the components of each grid that no SPC
/// constrains and no rigid element makes dependent, in id order, then the scalar points no TF defines.
fn number_dofs<'d>(
    deck: &'d Deck,
    constrained: &HashMap<i64, u8>,
    tf_of: &BTreeMap<i64, &crate::deck::cards::Tf>,
    rigid: &'d crate::model::rigid::Rigid,
) -> Numbering<'d> {
    let grids: BTreeMap<i64, &crate::deck::cards::Grid> = deck.bulk.grids.iter().map(|g| (g.id, g)).collect();
    let scalar = scalar_points(deck);
    let mut dofs = Vec::new();
    let mut grid_first = HashMap::with_capacity(grids.len());
    for &id in grids.keys() {
        let solved = !(constrained[&id] | rigid.dependent(id)) & 0b11_1111;
        grid_first.insert(id, (dofs.len(), solved));
        for comp in (1..=6u8).filter(|c| solved & (1 << (c - 1)) != 0) {
            dofs.push(DofLabel { point: id, comp });
        }
    }
    let mut scalar_index = HashMap::new();
    for &id in scalar.keys() {
        if !tf_of.contains_key(&id) {
            scalar_index.insert(id, dofs.len());
            dofs.push(DofLabel { point: id, comp: 0 });
        }
    }
    Numbering {
        grids,
        scalar,
        dofs,
        grid_first,
        scalar_index,
        rigid,
    }
}

/// The rigid elements resolved (their dependent components are left out of the
/// solved DOFs by [`number_dofs`]): an SPC on a dependent DOF is an error naming both
/// cards; a PS (GRID or GRDSET) on it yields to the tie, with a warning.
fn rigid_elements(cx: &mut Ctx, deck: &Deck, geo: &Geometry, sel: &Selected) -> crate::model::rigid::Rigid {
    let mut errors = Vec::new();
    let rigid = crate::model::rigid::resolve(&deck.bulk, geo, &mut errors);
    for d in errors {
        cx.err(d);
    }
    for s in &sel.spcs {
        for (gm, t) in s.grids.iter().filter_map(|g| Some((g, rigid.ties.get(g)?))) {
            if s.c.0 & t.dependent == 0 {
                continue;
            }
            cx.err(s.at.error(match t.whole() {
                Some((gn, _)) => format!(
                    "SPC1 constrains grid {gm}, which {} (at {}) makes dependent: constrain its independent grid \
                     {gn} instead",
                    t.name, t.at.pos
                ),
                None => format!(
                    "SPC1 constrains components of grid {gm} that {} (at {}) makes dependent: constrain the grids \
                     they follow instead",
                    t.name, t.at.pos
                ),
            }));
        }
    }
    let b = &deck.bulk;
    let ps: HashMap<i64, u8> = b.grids.iter().map(|g| (g.id, g.ps.unwrap_or(b.grdset.ps).0)).collect();
    for (gm, t) in &rigid.ties {
        let held = |g: &i64| ps.get(g).copied().unwrap_or(0);
        match t.whole() {
            Some((gn, _)) if held(gm) & !held(&gn) != 0 => cx.warn(t.at.warning(format!(
                "grid {gm}'s PS holds components its independent grid {gn} does not: {} ties them to grid \
                 {gn}'s motion instead",
                t.name
            ))),
            None if held(gm) & t.dependent != 0 => cx.warn(t.at.warning(format!(
                "grid {gm}'s PS holds components {} makes dependent: they follow the tie instead",
                t.name
            ))),
            _ => {}
        }
    }
    rigid
}

/// Each TF's dependent point as a functional of the solved DOFs.
fn dependent_points(cx: &mut Ctx, tf_of: &BTreeMap<i64, &crate::deck::cards::Tf>, num: &Numbering) -> Dependent {
    let mut dependent = Vec::new();
    let mut dep_index: HashMap<i64, usize> = HashMap::new();
    for (&gd, t) in tf_of {
        let mut f = Functional::new();
        let mut ok = true;
        for term in &t.terms {
            if tf_of.contains_key(&term.g) {
                cx.err(t.at.error(format!(
                    "TF independent point {} is itself defined by a TF: chained transfer functions are not supported",
                    term.g
                )));
                ok = false;
                continue;
            }
            match num.lookup(cx, &t.at, "TF", term.g, term.c) {
                Some(i) => f.push((i, -term.a[0] / t.b[0])),
                None => ok = false,
            }
        }
        if ok {
            dep_index.insert(gd, dependent.len());
            dependent.push(DependentPoint {
                label: DofLabel { point: gd, comp: 0 },
                functional: f,
                at: t.at.clone(),
                tied: false,
            });
        }
    }

    Dependent {
        points: dependent,
        index: dep_index,
    }
}

/// The element cards and CONM2s with their materials and sections resolved, then
/// the drilling supports their grids need.
fn build_elements<'a, 's>(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &'a Geometry,
    rigid: &'a crate::model::rigid::Rigid,
    survey: Option<&'s mut Surveyor<'s>>,
) -> Elements<'a, 's> {
    let mut out = Elements {
        list: Vec::new(),
        on_element: HashMap::new(),
        plies: HashMap::new(),
        rigid,
        survey,
        geo,
        built: 0,
    };
    connected(cx, deck, num, geo, &mut out);
    point_masses(cx, deck, num, geo, &mut out);
    scalar_elements(cx, deck, num, geo, rigid, &mut out);
    general_elements(cx, deck, num, geo, rigid, &mut out);
    if out.survey.is_none() {
        drilling_supports(num, geo, &mut out);
    }
    out
}

/// The rigid elements' dependent components as dependent points (functionals of the
/// solved DOFs: the rows of their ties), appended to `dependent` after the TF points,
/// for the output requests: grid → the index there of each dependent component.
fn tied_points(
    rigid: &crate::model::rigid::Rigid,
    num: &Numbering,
    dependent: &mut Dependent,
) -> BTreeMap<i64, [Option<usize>; 6]> {
    let mut out = BTreeMap::new();
    for (&gm, t) in &rigid.ties {
        let mut at = [None; 6];
        for (c, slot) in at.iter_mut().enumerate().filter(|(c, _)| t.ties(*c)) {
            *slot = Some(dependent.points.len());
            dependent.points.push(DependentPoint {
                label: DofLabel {
                    point: gm,
                    comp: c as u8 + 1,
                },
                functional: t.functional(c, &|g| num.grid_dofs(g)),
                at: t.at.clone(),
                tied: true,
            });
        }
        out.insert(gm, at);
    }
    out
}

/// A placement for an element whose kernel works in the basic axes (a rod, a mass, a
/// shell in the basic XY plane), needed only when one of its grids is displaced in
/// another frame.
fn frames_only(grids: &[i64], geo: &Geometry, points: &[[f64; 3]]) -> Option<Placement> {
    offset_in_basic(grids, geo, points, [0.0; 3])
}

/// [`frames_only`] with the kernel's corners at the grids moved by `offset` (basic),
/// tied to them rigidly: needed when a grid is displaced in another frame or the
/// offset is not zero.
fn offset_in_basic(grids: &[i64], geo: &Geometry, points: &[[f64; 3]], offset: [f64; 3]) -> Option<Placement> {
    (offset != [0.0; 3] || grids.iter().any(|g| geo.frames.contains_key(g))).then(|| Placement {
        turn: grids
            .iter()
            .map(|&g| Placement::turn_of(&Matrix3::identity(), &geo.frame(g), offset))
            .collect(),
        points: points.to_vec(),
    })
}

/// True when a shell's corners lie in one plane z = const of the basic system (within
/// 1e-9 relative) and run counter-clockwise about +z: its kernel then works in the
/// basic axes themselves, as it always has for the paper's plate.
fn in_basic_xy(points: &[[f64; 3]]) -> bool {
    let z = points[0][2];
    if points.iter().any(|p| (p[2] - z).abs() > 1e-9 * (1.0 + z.abs())) {
        return false;
    }
    let n = points.len();
    let twice_area: f64 = (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    twice_area > 0.0
}

/// Every grid that a shell out of the basic XY plane touches, whose rotations some
/// direction of no shell stiffens, gets a [`Drill`] spring along that direction.
fn drilling_supports(num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let mut placed: std::collections::BTreeSet<i64> = std::collections::BTreeSet::new();
    for e in out
        .list
        .iter()
        .filter(|e| e.kernel.family().shell().is_some() && e.placement.is_some())
    {
        placed.extend(e.grids.iter().copied());
    }
    if placed.is_empty() {
        return;
    }
    let mut blocks: BTreeMap<i64, Matrix3<f64>> = placed.iter().map(|&g| (g, Matrix3::zeros())).collect();
    for e in out.list.iter().filter(|e| e.kernel.family().shell().is_some()) {
        if !e.grids.iter().any(|g| placed.contains(g)) {
            continue;
        }
        for l in e.stiffness() {
            for (a, &(ga, ca)) in l.at.iter().enumerate() {
                for (b, &(gb, cb)) in l.at.iter().enumerate() {
                    if ga == gb && ca >= 3 && cb >= 3 {
                        if let Some(k) = blocks.get_mut(&e.grids[ga]) {
                            k[(ca - 3, cb - 3)] += l.values[(a, b)];
                        }
                    }
                }
            }
        }
    }
    for (g, k) in blocks {
        let x = geo.positions.get(&g).copied().unwrap_or_default();
        if let Some(d) = Drill::for_rotations(x, &k) {
            out.list.push(Element::new(0, vec![g], vec![num.grid_dofs(g)], d));
        }
    }
}

/// The element cards of [`crate::elements::KINDS`], kind by kind in the table's
/// order and each in deck order, with their properties and materials resolved and
/// their frames (see [`Placement`]).
fn connected(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let b = &deck.bulk;
    let mut props = Properties::new(cx, b);
    for kind in &crate::elements::KINDS {
        for c in b.elements.iter().filter(|c| c.kind.card == kind.card) {
            let mut ok = true;
            let mut xyz = Vec::with_capacity(c.g.len());
            for g in &c.g {
                match (num.grids.get(g), geo.positions.get(g)) {
                    (Some(_), Some(x)) => xyz.push(*x),
                    // A grid whose position did not resolve: its error is reported.
                    (Some(_), None) => ok = false,
                    (None, _) => {
                        cx.err(c.at.error(format!(
                            "{} {} references grid {g}, which does not exist",
                            kind.card, c.eid
                        )));
                        ok = false;
                    }
                }
            }
            let mut plies = None;
            let (kernel, placement) = match kind.build {
                Build::Rod(build) => {
                    let Some(section) = props.rod(cx, c) else { continue };
                    if !ok {
                        continue;
                    }
                    (build(&xyz, section), frames_only(&c.g, geo, &xyz))
                }
                Build::Panel(build) => {
                    let Some(section) = props.panel(cx, c) else { continue };
                    if !ok {
                        continue;
                    }
                    (build(&xyz, section), frames_only(&c.g, geo, &xyz))
                }
                Build::Bar(build) => {
                    let section = props.bar(cx, c);
                    let Some(placed) = ok.then(|| place_bar(cx, c, &xyz, geo)).flatten() else {
                        continue;
                    };
                    let Some(section) = section else { continue };
                    let card = c.bar.as_ref().expect("a bar's card keeps its bar fields");
                    let spec = crate::elements::bar::BarSpec {
                        card: kind.card,
                        section,
                        released: card.released.map(|r| r.0),
                    };
                    (build(&placed.0, spec), Some(placed.1))
                }
                Build::Shell(build) => {
                    let Some(placed) = ok.then(|| place_shell(cx, c, &xyz, geo)).flatten() else {
                        // The section is still resolved, so that its errors are reported.
                        props.shell(cx, c, None);
                        continue;
                    };
                    let Some((section, layers)) = props.shell(cx, c, Some(placed.material_angle)) else {
                        continue;
                    };
                    plies = layers;
                    (build(&placed.corners, section), placed.placement)
                }
            };
            let kernel = match kernel {
                Ok(k) => k,
                Err(BadShape(why)) => {
                    cx.err(c.at.error(format!("{} {} {why}", kind.card, c.eid)));
                    continue;
                }
            };
            for &g in &c.g {
                *out.on_element.entry(g).or_default() += 1;
            }
            let dofs = c.g.iter().map(|&g| num.grid_dofs(g)).collect();
            if let Some(layers) = plies {
                out.plies.insert(out.built, layers);
            }
            let e = Element::boxed(c.eid, c.g.clone(), dofs, kernel);
            out.push(
                match placement {
                    Some(p) => e.placed(p),
                    None => e,
                },
                |g| num.grid_dofs(g),
            );
        }
    }
}

/// A bar's ends in its own axes (A at the origin, B along x) and its placement: its
/// ends are its grids moved by their offsets WA, WB (in the grids' displacement frames
/// or the basic system, as OFFT says); x runs from end A to end B, y is the part of
/// the orientation vector v normal to x (v in GA's displacement frame or the basic
/// system, or from GA to G0), z = x × y.
fn place_bar(cx: &mut Ctx, c: &Connection, xyz: &[[f64; 3]], geo: &Geometry) -> Option<(Vec<[f64; 3]>, Placement)> {
    let card = c.bar.as_ref().expect("a bar's card keeps its bar fields");
    let frames = [geo.frame(c.g[0]), geo.frame(c.g[1])];
    let offset = |k: usize| {
        let w = Vector3::from(card.offsets[k]);
        if card.offsets_basic[k] {
            w
        } else {
            frames[k] * w
        }
    };
    let (wa, wb) = (offset(0), offset(1));
    let (a, b) = (Vector3::from(xyz[0]) + wa, Vector3::from(xyz[1]) + wb);
    let l = (b - a).norm();
    let size = (Vector3::from(xyz[0]).norm() + Vector3::from(xyz[1]).norm()).max(1e-300);
    if l.is_nan() || l <= 1e-12 * size {
        cx.err(c.at.error(format!(
            "{} {} has zero length: its ends (its grids moved by WA and WB) coincide",
            c.kind.card, c.eid
        )));
        return None;
    }
    let x = (b - a) / l;
    let v = match card.orientation {
        BarOrientation::Vector(v) if card.orientation_basic => Vector3::from(v),
        BarOrientation::Vector(v) => frames[0] * Vector3::from(v),
        BarOrientation::Grid(g0) => {
            let Some(p) = geo.positions.get(&g0) else {
                cx.err(c.at.field_error(
                    &card.orientation_at,
                    format!("{} {}: G0 = {g0} is not a grid of the deck", c.kind.card, c.eid),
                ));
                return None;
            };
            Vector3::from(*p) - Vector3::from(xyz[0])
        }
    };
    let y = v - x * v.dot(&x);
    if y.norm().is_nan() || y.norm() <= 1e-9 * v.norm() {
        cx.err(c.at.field_error(
            &card.orientation_at,
            format!(
                "{} {}: the orientation vector lies along the bar's axis, so it gives no plane 1",
                c.kind.card, c.eid
            ),
        ));
        return None;
    }
    let y = y.normalize();
    let axes = Matrix3::from_columns(&[x, y, x.cross(&y)]);
    let turn = vec![
        Placement::turn_of(&axes, &frames[0], wa.into()),
        Placement::turn_of(&axes, &frames[1], wb.into()),
    ];
    Some((
        vec![[0.0; 3], [l, 0.0, 0.0]],
        Placement {
            turn,
            points: xyz.to_vec(),
        },
    ))
}

/// Where a shell's kernel works and how its material axes lie.
struct PlacedShell {
    /// The corners as its kernel takes them.
    corners: Vec<[f64; 3]>,
    /// How its kernel's DOFs come from its grids' (`None`: they are the same).
    placement: Option<Placement>,
    /// The material x axis, degrees counter-clockwise from the kernel's x axis.
    material_angle: f64,
}

/// A shell's frame and material axis: in the basic XY plane (counter-clockwise about
/// +z) its kernel works in the basic axes, as for the paper's plate; anywhere else in
/// its own frame ([`crate::geometry::shell_frame`]). The material x axis is the G1→G2
/// side turned by THETA, or the x axis of system MCID projected onto the element.
fn place_shell(cx: &mut Ctx, c: &Connection, xyz: &[[f64; 3]], geo: &Geometry) -> Option<PlacedShell> {
    let (frame, corners, placement) = if in_basic_xy(xyz) {
        // The reference plane ZOFFS along +z.
        let placement = offset_in_basic(&c.g, geo, xyz, [0.0, 0.0, c.zoffs]);
        (Matrix3::identity(), xyz.to_vec(), placement)
    } else {
        let f = match crate::geometry::shell_frame(xyz) {
            Ok(f) => f,
            Err(FrameError::Degenerate) => {
                cx.err(c.at.error(format!(
                    "{} {} is degenerate: its corners lie on one line or coincide",
                    c.kind.card, c.eid
                )));
                return None;
            }
            Err(FrameError::Warped(w)) => {
                cx.err(c.at.error(format!(
                    "{} {} is warped: its corners stand {w:.3} of its half mean diagonal off its mean plane, \
                     beyond the {} a flat element projected onto that plane is taken to stand for",
                    c.kind.card,
                    c.eid,
                    crate::geometry::MAX_WARP
                )));
                return None;
            }
        };
        let turn =
            c.g.iter()
                .zip(&f.offsets)
                .map(|(&g, &d)| {
                    let d = Vector3::from(d) + f.axes.column(2) * c.zoffs;
                    Placement::turn_of(&f.axes, &geo.frame(g), d.into())
                })
                .collect();
        let placement = Placement {
            turn,
            points: xyz.to_vec(),
        };
        (f.axes, f.local, Some(placement))
    };
    let side = Vector3::from(corners[1]) - Vector3::from(corners[0]);
    let g1g2 = if frame == Matrix3::identity() {
        side.y.atan2(side.x).to_degrees()
    } else {
        0.0
    };
    let material_angle = match c.orientation {
        Orientation::Theta(theta) => g1g2 + theta,
        Orientation::Mcid(mcid) => {
            let at = c
                .orientation_at
                .as_ref()
                .expect("a shell's card keeps its THETA/MCID field");
            let Some(sys) = geo.systems.get(&mcid) else {
                cx.err(c.at.field_error(
                    at,
                    format!(
                        "{} {}: MCID = {mcid} names a coordinate system that no CORD card defines",
                        c.kind.card, c.eid
                    ),
                ));
                return None;
            };
            let centroid = xyz.iter().map(|&p| Vector3::from(p)).sum::<Vector3<f64>>() / xyz.len() as f64;
            let x_axis = sys.frame_at(&centroid).map(|f| f.column(0).into_owned());
            match x_axis.and_then(|x| crate::geometry::angle_in_plane(&frame, &x)) {
                Some(a) => a,
                None => {
                    cx.err(c.at.field_error(
                        at,
                        format!(
                            "{} {}: the x axis of system {mcid} at the element is along its normal (or undefined \
                             there), so its projection gives no material axis",
                            c.kind.card, c.eid
                        ),
                    ));
                    return None;
                }
            }
        }
    };
    Some(PlacedShell {
        corners,
        placement,
        material_angle,
    })
}

/// The property and material cards, resolved once per property (a laminate once per
/// property and material axis).
struct Properties<'d> {
    bulk: &'d crate::deck::cards::Bulk,
    mat1: HashMap<i64, &'d crate::deck::cards::Mat1>,
    prod: HashMap<i64, &'d crate::deck::cards::Prod>,
    pshear: HashMap<i64, &'d crate::deck::cards::Pshear>,
    bars: HashMap<i64, &'d crate::deck::cards::BarProperty>,
    pshell: HashMap<i64, &'d crate::deck::cards::Pshell>,
    pcomp: HashMap<i64, &'d crate::deck::cards::Pcomp>,
    /// COSMIC's plate properties by (card, id).
    cosmic: HashMap<(&'static str, i64), &'d crate::deck::cards::Pshell>,
    shells: HashMap<i64, Option<ShellSection>>,
    cosmic_shells: HashMap<(&'static str, i64), Option<ShellSection>>,
    laminates: HashMap<(i64, u64), Option<(ShellSection, PlyStack)>>,
}

impl<'d> Properties<'d> {
    fn new(cx: &mut Ctx, b: &'d crate::deck::cards::Bulk) -> Self {
        let pshell: HashMap<i64, &crate::deck::cards::Pshell> = b.pshells.iter().map(|p| (p.pid, p)).collect();
        for p in b.pcomps.iter().filter(|p| pshell.contains_key(&p.pid)) {
            cx.err(p.at.error(format!("property {} is both a PSHELL and a PCOMP", p.pid)));
        }
        Properties {
            bulk: b,
            mat1: b.mat1s.iter().map(|m| (m.mid, m)).collect(),
            prod: b.prods.iter().map(|p| (p.pid, p)).collect(),
            pshear: b.pshears.iter().map(|p| (p.pid, p)).collect(),
            bars: b.bar_properties.iter().map(|p| (p.pid, p)).collect(),
            pshell,
            pcomp: b.pcomps.iter().map(|p| (p.pid, p)).collect(),
            cosmic: b.cosmic_plates.iter().map(|(card, p)| ((*card, p.pid), p)).collect(),
            shells: HashMap::new(),
            cosmic_shells: HashMap::new(),
            laminates: HashMap::new(),
        }
    }

    /// The MAT1 `mid` property `pid` (its card `at`) references; an error if none.
    fn mat1_of(&self, cx: &mut Ctx, at: &CardRef, pid: i64, mid: i64) -> Option<&'d crate::deck::cards::Mat1> {
        let m = self.mat1.get(&mid).copied();
        if m.is_none() {
            cx.err(at.error(format!("{} {pid} references MAT1 {mid}, which does not exist", at.name)));
        }
        m
    }

    /// A rod's PROD and MAT1.
    fn rod(&self, cx: &mut Ctx, c: &'d Connection) -> Option<RodSection> {
        let property = if c.kind.card == "CTUBE" { "PTUBE" } else { "PROD" };
        let Some(p) = c.rod.as_deref().or_else(|| self.prod.get(&c.pid).copied()) else {
            cx.err(c.at.error(format!(
                "{} {} references {property} {}, which does not exist",
                c.kind.card, c.eid, c.pid
            )));
            return None;
        };
        let m = self.mat1_of(cx, &p.at, p.pid, p.mid)?;
        Some(RodSection {
            e: m.e,
            g: m.g,
            area: p.a,
            torsion: p.j,
            rho: m.rho,
            nsm: p.nsm,
        })
    }

    /// A shear panel's PSHEAR and MAT1.
    fn panel(&self, cx: &mut Ctx, c: &Connection) -> Option<crate::elements::shear::PanelSection> {
        let Some(p) = self.pshear.get(&c.pid) else {
            cx.err(c.at.error(format!(
                "{} {} references PSHEAR {}, which does not exist",
                c.kind.card, c.eid, c.pid
            )));
            return None;
        };
        let m = self.mat1_of(cx, &p.at, p.pid, p.mid)?;
        if m.g <= 0.0 {
            cx.err(p.at.error(format!(
                "PSHEAR {}: its MAT1 {} gives no shear modulus (G = {:e}): a shear panel has no other stiffness",
                p.pid, p.mid, m.g
            )));
            return None;
        }
        Some(crate::elements::shear::PanelSection {
            g: m.g,
            nu: m.nu,
            t: p.t,
            rho: m.rho,
            nsm: p.nsm,
        })
    }

    /// A bar's property (a CBAR's PBAR or PBARL, a CBEAM's PBEAM or PBEAML) and MAT1:
    /// its section's constants, given or computed from its dimensions.
    fn bar(&self, cx: &mut Ctx, c: &Connection) -> Option<crate::elements::bar::BarSection> {
        let (names, beam) = match c.kind.card {
            "CBEAM" => ("PBEAM or PBEAML", true),
            _ => ("PBAR or PBARL", false),
        };
        let p = match self.bars.get(&c.pid) {
            Some(p) if p.at.name.starts_with("PBEAM") == beam => p,
            other => {
                let but = match other {
                    Some(p) => format!(
                        ": property {} is a {}, which a {} takes",
                        c.pid,
                        p.at.name,
                        if beam { "CBAR" } else { "CBEAM" }
                    ),
                    None => String::new(),
                };
                cx.err(c.at.error(format!(
                    "{} {} references {names} {}, which does not exist{but}",
                    c.kind.card, c.eid, c.pid
                )));
                return None;
            }
        };
        let Some(m) = self.mat1.get(&p.mid) else {
            cx.err(p.at.error(format!(
                "{} {} references MAT1 {}, which does not exist",
                p.at.name, p.pid, p.mid
            )));
            return None;
        };
        let k = match &p.dims {
            crate::deck::cards::BarDims::Constants(k) => *k,
            crate::deck::cards::BarDims::Shape(shape, dims) => {
                crate::elements::section::constants(*shape, dims).expect("the reader checked the section's dimensions")
            }
        };
        Some(crate::elements::bar::BarSection {
            e: m.e,
            g: m.g,
            area: k.area,
            i1: k.i1,
            i2: k.i2,
            i12: k.i12,
            j: k.j,
            rho: m.rho,
            nsm: p.nsm,
            points: k.points,
            torsional_inertia: if beam { m.rho * (k.i1 + k.i2) } else { 0.0 },
        })
    }

    /// A shell's PSHELL or PCOMP with its materials, and a laminate's plies; `axes`
    /// the material x axis (degrees from the element kernel's x axis), `None` when the
    /// element's grids are not all known (a laminate is then not resolved).
    fn shell(&mut self, cx: &mut Ctx, c: &Connection, axes: Option<f64>) -> Option<(ShellSection, Option<PlyStack>)> {
        let b = self.bulk;
        if let Some(card) = c.property_card {
            let key = (card, c.pid);
            if !self.cosmic_shells.contains_key(&key) {
                let s = match self.cosmic.get(&key) {
                    Some(p) => shell_section(cx, p, &self.mat1, &b.mat2s),
                    None => {
                        cx.err(c.at.error(format!(
                            "{} {} references {card} {}, which does not exist",
                            c.at.name, c.eid, c.pid
                        )));
                        None
                    }
                };
                self.cosmic_shells.insert(key, s);
            }
            let s = self.cosmic_shells[&key].clone();
            return self.oriented(s, self.cosmic.get(&key).copied(), axes);
        }
        match (self.shells.get(&c.pid), self.pcomp.get(&c.pid)) {
            (_, Some(p)) if !self.pshell.contains_key(&c.pid) => {
                let axes = axes?;
                let lam = self
                    .laminates
                    .entry((c.pid, axes.to_bits()))
                    .or_insert_with(|| laminate_section(cx, p, &b.mat1s, &b.mat8s, axes))
                    .clone();
                lam.map(|(section, layers)| (section, Some(layers)))
            }
            (cached, _) => {
                let s = match cached {
                    Some(s) => s.clone(),
                    None => {
                        let s = match self.pshell.get(&c.pid) {
                            Some(p) => shell_section(cx, p, &self.mat1, &b.mat2s),
                            None => {
                                cx.err(c.at.error(format!(
                                    "{} {} references property {} (PSHELL or PCOMP), which does not exist",
                                    c.kind.card, c.eid, c.pid
                                )));
                                None
                            }
                        };
                        self.shells.insert(c.pid, s.clone());
                        s
                    }
                };
                self.oriented(s, self.pshell.get(&c.pid).copied(), axes)
            }
        }
    }

    /// A PSHELL's section in the element's axes: turned to the material axis when
    /// one of its materials is a MAT2 (anisotropic).
    fn oriented(
        &self,
        s: Option<ShellSection>,
        p: Option<&crate::deck::cards::Pshell>,
        axes: Option<f64>,
    ) -> Option<(ShellSection, Option<PlyStack>)> {
        let anisotropic = p.is_some_and(|p| {
            [p.mid1, p.mid2, p.mid3, p.mid4]
                .iter()
                .flatten()
                .any(|mid| self.bulk.mat2s.iter().any(|m| m.mid == *mid))
        });
        match (s, axes) {
            (Some(s), Some(angle)) if anisotropic => Some((turned_section(&s, angle), None)),
            (s, _) => s.map(|s| (s, None)),
        }
    }
}

/// A PSHELL's section, its MAT2 materials given in the material axes, in the
/// element's axes when the material x axis is `angle` degrees from the element's x:
/// G = Tᵀ G_material T with T [`crate::laminate::strain_rotation`], and the transverse
/// shear's 2×2 turned as a tensor. A half turn leaves a plane material as it is, so
/// an angle of a whole number of half turns returns the section unchanged (exactly,
/// as the paper's plate has it on every element).
fn turned_section(s: &ShellSection, angle: f64) -> ShellSection {
    if angle.rem_euclid(180.0) == 0.0 {
        return s.clone();
    }
    let turn = |g: Option<Matrix3<f64>>| g.map(|g| crate::laminate::rotated(&g, angle));
    let (sn, cs) = angle.to_radians().sin_cos();
    // (γxz, γyz) in material axes = R (γxz, γyz) in element axes.
    let r = Matrix2::new(cs, sn, -sn, cs);
    ShellSection {
        g_membrane: turn(s.g_membrane),
        g_bending: turn(s.g_bending),
        g_coupling: turn(s.g_coupling),
        shear: s.shear.map(|h| r.transpose() * h * r),
        ..s.clone()
    }
}

/// CONM2s: the mass at its grid moved by its offset (X1, X2, X3 in system CID's axes
/// at the grid; CID = −1: X1-X3 are the mass's basic location), its inertia in CID's
/// axes (basic for CID 0 and −1), tied rigidly to its grid and turned to the grid's
/// displacement frame.
fn point_masses(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let b = &deck.bulk;
    for m in &b.conm2s {
        if !num.grids.contains_key(&m.g) {
            cx.err(m.at.error(format!("CONM2 {} references grid {}, which does not exist", m.eid, m.g)));
            continue;
        }
        let Some(&x) = geo.positions.get(&m.g) else { continue };
        let axes = match m.cid {
            -1 | 0 => Matrix3::identity(),
            cid => match geo.systems.get(&cid).and_then(|s| s.frame_at(&Vector3::from(x))) {
                Some(f) => f,
                None => {
                    cx.err(m.at.error(format!(
                        "CONM2 {}: CID = {cid} names a coordinate system that no CORD card defines (or one \
                         undefined at its grid)",
                        m.eid
                    )));
                    continue;
                }
            },
        };
        let offset = match m.cid {
            -1 => Vector3::from(m.offset) - Vector3::from(x),
            _ => axes * Vector3::from(m.offset),
        };
        let at = Vector3::from(x) + offset;
        let point = PointMass {
            x: at.into(),
            mass: m.mass,
            inertia: m.inertia,
        };
        let e = Element::new(m.eid, vec![m.g], vec![num.grid_dofs(m.g)], point);
        let placed = if m.cid <= 0 {
            offset_in_basic(&[m.g], geo, &[x], offset.into())
        } else {
            Some(Placement {
                turn: vec![Placement::turn_of(&axes, &geo.frame(m.g), offset.into())],
                points: vec![x],
            })
        };
        out.push(
            match placed {
                Some(p) => e.placed(p),
                None => e,
            },
            |g| num.grid_dofs(g),
        );
    }
}

/// The scalar springs and masses (CELAS1-4, CMASS1-4) between their terminals: a
/// grid's component in its displacement frame, or a scalar point; ground left out.
fn scalar_elements(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &Geometry,
    rigid: &crate::model::rigid::Rigid,
    out: &mut Elements,
) {
    use crate::deck::cards::ScalarValue;
    use crate::elements::scalar::{Scalar, ScalarKind};
    let b = &deck.bulk;
    let pelas: HashMap<i64, f64> = b.pelas.iter().map(|p| (p.pid, p.value)).collect();
    let pmass: HashMap<i64, f64> = b.pmass.iter().map(|p| (p.pid, p.value)).collect();
    for c in &b.scalars {
        let card = c.at.name.as_str();
        let value = match c.value {
            ScalarValue::Value(v) => Some(v),
            ScalarValue::Property(pid) => {
                let (props, name) = if c.spring { (&pelas, "PELAS") } else { (&pmass, "PMASS") };
                let v = props.get(&pid).copied();
                if v.is_none() {
                    cx.err(c.at.error(format!(
                        "{card} {} references {name} {pid}, which does not exist",
                        c.eid
                    )));
                }
                v
            }
        };
        let mut grids = Vec::new();
        let mut dofs = Vec::new();
        let mut slots = Vec::new();
        let mut points = Vec::new();
        let mut ok = true;
        for &(g, comp) in c.terminals.iter().filter(|(g, _)| *g != 0) {
            let (d, slot, x) = if num.grids.contains_key(&g) {
                if comp == 0 {
                    cx.err(c.at.field_error(
                        &c.first_at,
                        format!(
                            "{card} {}: grid {g} needs a component 1-6 (0 or blank is a scalar point's)",
                            c.eid
                        ),
                    ));
                    ok = false;
                    continue;
                }
                if rigid.ties.contains_key(&g) {
                    cx.err(c.at.error(format!(
                        "{card} {} is on grid {g}, which a rigid element makes dependent: connect it to an independent grid",
                        c.eid
                    )));
                    ok = false;
                    continue;
                }
                (num.grid_dofs(g), comp - 1, geo.positions.get(&g).copied())
            } else if num.scalar.contains_key(&g) {
                if comp != 0 {
                    cx.err(c.at.field_error(
                        &c.first_at,
                        format!(
                            "{card} {}: point {g} is a scalar point: its component is 0 or blank",
                            c.eid
                        ),
                    ));
                    ok = false;
                    continue;
                }
                let i = num.index(&DofLabel { point: g, comp: 0 });
                let mut d = [None; 6];
                d[0] = i;
                (d, 0, None)
            } else {
                cx.err(c.at.error(format!("{card} {} references point {g}, which does not exist", c.eid)));
                ok = false;
                continue;
            };
            slots.push((grids.len(), slot));
            grids.push(g);
            dofs.push(d);
            points.push(x);
        }
        let Some(v) = value.filter(|_| ok) else { continue };
        let kind = if c.spring {
            ScalarKind::Spring(v)
        } else {
            ScalarKind::Mass(v)
        };
        let kernel = Scalar {
            card: crate::elements::scalar::card_name(card),
            kind,
            slots,
            points,
        };
        out.push(Element::new(c.eid, grids, dofs, kernel), |g| num.grid_dofs(g));
    }
}

/// The GENELs: each a [`crate::elements::general::General`] over its {uᵢ} and {u_d}
/// (grid components in their displacement frames, scalar points), K given or Z
/// inverted, [S] given or computed from the grids' positions.
fn general_elements(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &Geometry,
    rigid: &crate::model::rigid::Rigid,
    out: &mut Elements,
) {
    use crate::elements::general::{from_lower, rigid_row, rigid_s, General};
    for c in &deck.bulk.genels {
        let mut points: Vec<i64> = Vec::new();
        let mut dofs = Vec::new();
        let mut xs = Vec::new();
        let mut slots = Vec::new();
        let mut ok = true;
        for &(p, comp) in c.ui.iter().chain(&c.ud) {
            let at = match points.iter().position(|&q| q == p) {
                Some(i) => i,
                None => {
                    let (d, x) = if num.grids.contains_key(&p) {
                        if rigid.ties.contains_key(&p) {
                            cx.err(c.at.error(format!(
                                "GENEL {} is on grid {p}, which a rigid element makes dependent: connect it to an \
                                 independent grid",
                                c.eid
                            )));
                            ok = false;
                            continue;
                        }
                        (num.grid_dofs(p), geo.positions.get(&p).copied())
                    } else if num.scalar.contains_key(&p) {
                        let mut d = [None; 6];
                        d[0] = num.index(&DofLabel { point: p, comp: 0 });
                        (d, None)
                    } else {
                        cx.err(c.at.error(format!("GENEL {} references point {p}, which does not exist", c.eid)));
                        ok = false;
                        continue;
                    };
                    points.push(p);
                    dofs.push(d);
                    xs.push(x);
                    points.len() - 1
                }
            };
            let scalar = xs[at].is_none() && num.scalar.contains_key(&p);
            if scalar != (comp == 0) {
                cx.err(c.at.error(format!(
                    "GENEL {}: point {p} component {comp}: a grid takes a component 1-6, a scalar point 0",
                    c.eid
                )));
                ok = false;
                continue;
            }
            slots.push((at, comp.saturating_sub(1)));
        }
        if !ok {
            continue;
        }
        if points.len() > crate::elements::MAX_GRIDS {
            cx.err(c.at.error(format!(
                "GENEL {} connects {} points: a GENEL of more than {} is not supported",
                c.eid,
                points.len(),
                crate::elements::MAX_GRIDS
            )));
            continue;
        }
        let m = c.ui.len();
        let given = from_lower(m, &c.lower);
        let k = if c.flexibility {
            match General::stiffness_of_flexibility(given) {
                Ok(k) => k,
                Err(e) => {
                    cx.err(c.at.error(format!("GENEL {} {e}", c.eid)));
                    continue;
                }
            }
        } else {
            given
        };
        let n = c.ud.len();
        let s = match (&c.s, n) {
            (_, 0) => None,
            (Some(v), _) => Some(nalgebra::DMatrix::from_row_slice(m, n, v)),
            (None, _) => {
                let at_dof = |&(p, comp): &(i64, usize)| {
                    let i = points.iter().position(|&q| q == p).expect("resolved above");
                    xs[i].map(|x| (x, geo.frame(p), comp))
                };
                // The rigid motions about the first dependent grid, read at each DOF;
                // none where a DOF is a scalar point's (it has no position).
                let rows = |list: &[(i64, usize)], x0: [f64; 3]| -> Option<nalgebra::DMatrix<f64>> {
                    let r: Option<Vec<[f64; 6]>> = list
                        .iter()
                        .map(|d| at_dof(d).map(|(x, t, comp)| rigid_row(x, &t, comp, x0)))
                        .collect();
                    r.map(|r| nalgebra::DMatrix::from_row_iterator(r.len(), 6, r.into_iter().flatten()))
                };
                let computed = at_dof(&c.ud[0]).and_then(|(x0, _, _)| Some((rows(&c.ui, x0)?, rows(&c.ud, x0)?)));
                let Some((ri, rd)) = computed else {
                    cx.err(c.at.error(format!(
                        "GENEL {}: [S] is not given and a scalar point has no position to compute it from: give [S]",
                        c.eid
                    )));
                    continue;
                };
                match rigid_s(&ri, &rd) {
                    Ok(s) => Some(s),
                    Err(e) => {
                        cx.err(c.at.error(format!("GENEL {} {e}", c.eid)));
                        continue;
                    }
                }
            }
        };
        let kernel = General::new(slots, k, s, xs);
        out.push(Element::new(c.eid, points, dofs, kernel), |g| num.grid_dofs(g));
    }
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

/// What case control asks to be written: DISP, VELO, NLLOAD, STRESS, STRAIN, FORCE
/// (or ELFORCE).
fn output_plan(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    (dependent, tied): (&Dependent, &BTreeMap<i64, [Option<usize>; 6]>),
    built: &Elements,
    contact: Option<&Contact>,
) -> OutputPlan {
    let elements = &built.list;
    let case = &deck.case;
    let (grids, scalar) = (&num.grids, &num.scalar);
    let (dep_index, dependent) = (&dependent.index, &dependent.points);
    let mut outputs = OutputPlan::default();
    let set_members = |req: Option<&crate::deck::case::OutputRequest>| -> Option<Vec<i64>> {
        match req.map(|r| &r.set) {
            None | Some(OutputSet::None) => None,
            Some(OutputSet::All) => Some(Vec::new()),
            Some(OutputSet::Set(id)) => case.sets.get(id).map(|s| s.members.clone()),
        }
    };
    let all_points = || -> Vec<i64> { grids.keys().copied().chain(scalar.keys().copied()).collect() };
    for (key, target) in [("DISP", 0), ("VELO", 1)] {
        let req = case.outputs.get(key);
        let Some(mut members) = set_members(req) else { continue };
        if matches!(req.map(|r| &r.set), Some(OutputSet::All)) {
            members = all_points();
        }
        let mut list = Vec::new();
        for p in members {
            if let Some(&j) = dep_index.get(&p) {
                list.push((dependent[j].label, Source::Dependent(j)));
            } else if grids.contains_key(&p) || scalar.contains_key(&p) {
                let comps: Vec<u8> = if scalar.contains_key(&p) {
                    vec![0]
                } else {
                    (1..=6).collect()
                };
                for comp in comps {
                    let l = DofLabel { point: p, comp };
                    if let Some(j) = tied.get(&p).and_then(|t| t[comp as usize - 1]) {
                        list.push((l, Source::Dependent(j)));
                    } else if let Some(i) = num.index(&l) {
                        list.push((l, Source::Dof(i)));
                    }
                }
            }
        }
        if target == 0 {
            outputs.disp = list;
        } else {
            outputs.velo = list;
        }
    }
    if let (Some(members), Some(c)) = (set_members(case.outputs.get("NLLOAD")), contact) {
        let all = members.is_empty();
        outputs.nlload = (0..c.loads.len())
            .filter(|&k| all || members.contains(&c.loads[k].label.point))
            .collect();
    }
    let elem_pos: HashMap<i64, usize> = elements
        .iter()
        .enumerate()
        .filter(|(_, e)| !matches!(e.kernel.family(), Family::Point { .. }))
        .map(|(i, e)| (e.eid, i))
        .collect();
    for key in ["STRESS", "STRAIN", "FORCE"] {
        let req = match key {
            "FORCE" => case.outputs.get("FORCE").or(case.outputs.get("ELFORCE")),
            _ => case.outputs.get(key),
        };
        let Some(members) = set_members(req) else { continue };
        let list: Vec<usize> = if members.is_empty() {
            let mut v: Vec<usize> = elem_pos.values().copied().collect();
            v.sort();
            v
        } else {
            members.iter().filter_map(|m| elem_pos.get(m).copied()).collect()
        };
        match key {
            "STRESS" => outputs.stress = list,
            "STRAIN" => outputs.strain = list,
            _ => outputs.force = list,
        }
    }
    // Ply results of every written laminate element, in the order its element's
    // results are written.
    outputs.plies = outputs
        .written()
        .filter(|(_, what)| *what != crate::elements::Output::Force)
        .filter_map(|(e, _)| Some((e, built.plies.get(&e)?.clone())))
        .collect();
    outputs.failure_fields = built
        .plies
        .iter()
        .filter(|(_, p)| p.iter().any(|l| !l.criteria.is_empty()))
        .map(|(e, p)| (*e, p.clone()))
        .collect();
    outputs.failure_fields.sort_by_key(|(e, _)| *e);
    if case.outputs.contains_key("ACCEL") {
        cx.warn(Diagnostic::warning(
            case.outputs.get("ACCEL").map(|r| r.pos.clone()),
            "ACCEL output is not written (accelerations are not part of every scheme's state); ignored",
        ));
    }

    outputs
}

/// What the contact definition refers to.
struct ContactRefs<'a> {
    dependent: &'a [DependentPoint],
    dep_index: &'a HashMap<i64, usize>,
    elements: &'a [Element],
    on_element: &'a HashMap<i64, usize>,
    labels: &'a [DofLabel],
}

fn build_contact(
    cx: &mut Ctx,
    nolins: &[&crate::deck::cards::Nolin3],
    refs: &ContactRefs,
    lookup: impl Fn(&mut Ctx, &CardRef, &str, i64, usize) -> Option<usize>,
) -> Option<Contact> {
    // Errors already found (a missing material, a bad TF) make the checks of the
    // impactor fail as a consequence; they are reported only on an otherwise clean model.
    let prior_errors = cx.diags.iter().any(|d| d.is_error());
    let first = nolins.first()?;
    let (driver, driver_label, loads) = contact_loads(cx, nolins, refs, lookup)?;
    let imp = find_impactor(cx, first, &loads, refs.on_element, prior_errors)?;
    let mass = refs
        .elements
        .iter()
        .filter(|e| e.grids == [imp.label.point])
        .filter_map(|e| match e.kernel.family() {
            Family::Point { mass } => Some(mass),
            _ => None,
        })
        .sum::<f64>();
    if mass <= 0.0 {
        // After other errors the mass may be missing only because its grid is (an
        // unresolved location): that error says why.
        if !prior_errors {
            cx.err(
                imp.at
                    .error(format!("the impactor grid {} has no CONM2 mass", imp.label.point)),
            );
        }
        return None;
    }
    let stiffness = impactor_stiffness(cx, imp, &driver, driver_label, prior_errors)?;
    let nonconservative = nonconservative_remainder(cx, &loads, &driver, stiffness, refs.labels);
    let imp_grid = imp.label.point;
    let imp_dofs = impactor_dofs(refs.elements, imp);
    let imp_dof = imp.dof;
    Some(Contact {
        driver,
        driver_label,
        exponent: first.a,
        stiffness,
        impactor: Impactor {
            grid: imp_grid,
            dof: imp_dof,
            mass,
            dofs: imp_dofs,
        },
        loads,
        nonconservative,
    })
}

/// The NOLIN3 loads of one contact (one driver, one exponent), the driver as a
/// functional of the solved DOFs and its label.
fn contact_loads(
    cx: &mut Ctx,
    nolins: &[&crate::deck::cards::Nolin3],
    refs: &ContactRefs,
    lookup: impl Fn(&mut Ctx, &CardRef, &str, i64, usize) -> Option<usize>,
) -> Option<(Functional, DofLabel, Vec<NonlinearLoad>)> {
    let (dependent, dep_index) = (refs.dependent, refs.dep_index);
    let first = nolins.first()?;
    // One driver and one exponent for all NOLIN3 loads: one contact.
    let mut ok = true;
    for n in nolins {
        if n.gj != first.gj || n.cj != first.cj {
            cx.err(n.at.error(format!(
                "NOLIN3 driven by point {} while another is driven by point {}: one contact (one driving DOF) is supported",
                n.gj, first.gj
            )));
            ok = false;
        }
        if n.a != first.a {
            cx.err(n.at.error(format!(
                "NOLIN3 exponent {} differs from {} on another card of the same contact",
                n.a, first.a
            )));
            ok = false;
        }
    }
    let (driver, driver_label) = match dep_index.get(&first.gj) {
        Some(&j) => (dependent[j].functional.clone(), dependent[j].label),
        None => {
            let i = lookup(cx, &first.at, "NOLIN3 driver", first.gj, first.cj)?;
            (
                vec![(i, 1.0)],
                DofLabel {
                    point: first.gj,
                    comp: first.cj as u8,
                },
            )
        }
    };
    let mut loads = Vec::new();
    for n in nolins {
        if dep_index.contains_key(&n.gi) {
            cx.err(n.at.error(format!(
                "NOLIN3 loads point {}, which a TF defines: it cannot carry a load",
                n.gi
            )));
            ok = false;
            continue;
        }
        if let Some(dof) = lookup(cx, &n.at, "NOLIN3", n.gi, n.ci) {
            loads.push(NonlinearLoad {
                dof,
                label: DofLabel {
                    point: n.gi,
                    comp: n.ci as u8,
                },
                scale: n.s,
                at: n.at.clone(),
            });
        } else {
            ok = false;
        }
    }
    ok.then_some((driver, driver_label, loads))
}

/// The impactor: the loaded grid that no structural element touches.
fn find_impactor<'l>(
    cx: &mut Ctx,
    first: &crate::deck::cards::Nolin3,
    loads: &'l [NonlinearLoad],
    on_element: &HashMap<i64, usize>,
    prior_errors: bool,
) -> Option<&'l NonlinearLoad> {
    let free: Vec<&NonlinearLoad> = loads
        .iter()
        .filter(|l| l.label.comp != 0 && !on_element.contains_key(&l.label.point))
        .collect();
    match free.as_slice() {
        [one] => Some(*one),
        [] => {
            if prior_errors {
                return None;
            }
            cx.err(first.at.error(
                "cannot identify the impactor: every grid loaded by NOLIN3 is attached to an element \
                 (the impactor is a point mass loaded by the contact and attached to nothing else)",
            ));
            None
        }
        many => {
            if prior_errors {
                return None;
            }
            cx.err(first.at.error(format!(
                "cannot identify the impactor: {} grids loaded by NOLIN3 carry no element ({})",
                many.len(),
                many.iter().map(|l| l.label.point.to_string()).collect::<Vec<_>>().join(", ")
            )));
            None
        }
    }
}

/// The Hertz K the impactor's load implies, K = −S/(∂α/∂u), which must be positive.
fn impactor_stiffness(
    cx: &mut Ctx,
    imp: &NonlinearLoad,
    driver: &Functional,
    driver_label: DofLabel,
    prior_errors: bool,
) -> Option<f64> {
    let c_imp: f64 = driver.iter().filter(|(j, _)| *j == imp.dof).map(|(_, c)| c).sum();
    if c_imp == 0.0 {
        if prior_errors {
            return None;
        }
        cx.err(imp.at.error(format!(
            "the contact's driving point {driver_label} does not depend on the impactor DOF {}",
            imp.label
        )));
        return None;
    }
    let stiffness = -imp.scale / c_imp;
    if stiffness <= 0.0 {
        cx.err(imp.at.error(format!(
            "the impactor load S = {} pushes the impactor into the target as the indentation grows \
             (S·∂α/∂u = {} must be negative for a repulsive contact)",
            imp.scale,
            imp.scale * c_imp
        )));
        return None;
    }
    Some(stiffness)
}

/// The non-conservative remainder S_i + K ∂α/∂u_i of the loads over all DOFs touched,
/// each nonzero entry warned about.
fn nonconservative_remainder(
    cx: &mut Ctx,
    loads: &[NonlinearLoad],
    driver: &Functional,
    stiffness: f64,
    labels: &[DofLabel],
) -> Functional {
    let mut rem: BTreeMap<usize, f64> = BTreeMap::new();
    for l in loads {
        *rem.entry(l.dof).or_default() += l.scale;
    }
    for &(j, c) in driver {
        *rem.entry(j).or_default() += stiffness * c;
    }
    let nonconservative: Functional = rem.into_iter().filter(|(_, v)| *v != 0.0).collect();
    for &(j, v) in &nonconservative {
        let load = loads.iter().find(|l| l.dof == j);
        let msg = format!(
            "contact load on {} is not derivable from the Hertz potential of the impactor's K = {stiffness:.6e}: \
             remainder {v:+.4e} ({:.2e} of K); its work is booked as external work. A balanced deck uses S = {:.6e}",
            labels[j],
            (v / stiffness).abs(),
            load.map(|l| l.scale - v).unwrap_or(-v),
        );
        match load {
            Some(l) => cx.warn(l.at.error(msg)),
            None => cx.warn(Diagnostic::warning(None, msg)),
        }
    }
    nonconservative
}

/// Every solved DOF of the impactor's grid (its CONM2's and the loaded one).
fn impactor_dofs(elements: &[Element], imp: &NonlinearLoad) -> Vec<usize> {
    let imp_grid = imp.label.point;
    let mut v = Vec::new();
    for e in elements.iter().filter(|e| e.grids == [imp_grid]) {
        if matches!(e.kernel.family(), Family::Point { .. }) {
            v.extend(e.dofs.iter().flatten().flatten().copied());
        }
    }
    if !v.contains(&imp.dof) {
        v.push(imp.dof);
    }
    v.sort();
    v.dedup();
    v
}

/// The material matrix of a MAT1 (plane stress) or MAT2 id, checked positive definite.
fn material_matrix(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<(Matrix3<f64>, f64)> {
    material(cx, mid, used_by, mat1, mat2s, true)
}

/// PSHELL MID3's transverse shear material, the 2×2 G relating (Qx, Qy)/(TS·T) to
/// (γxz, γyz): a MAT1's G on the diagonal, or a MAT2's [G11 G12; G12 G22], whose
/// G13, G23 and G33 must then be blank (Altair OptiStruct Reference Guide, MAT2,
/// comment 3: a MAT2 referenced by PSHELL MID3 uses G11, G12, G22), positive definite.
fn transverse_shear_material(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<nalgebra::Matrix2<f64>> {
    if let Some(m) = mat2s.iter().find(|m| m.mid == mid) {
        if m.g[0][2] != 0.0 || m.g[1][2] != 0.0 || m.g[2][2] != 0.0 {
            cx.err(m.at.error(format!(
                "MAT2 {mid} is a transverse shear material (PSHELL MID3): G11, G12 and G22 form its 2×2 matrix, \
                 and G13, G23, G33 must be blank"
            )));
            return None;
        }
        let g = nalgebra::Matrix2::new(m.g[0][0], m.g[0][1], m.g[0][1], m.g[1][1]);
        if g.cholesky().is_none() {
            cx.err(m.at.error(format!(
                "MAT2 {mid} (PSHELL MID3) is not positive definite: [G11 G12; G12 G22] gives no shear energy for \
                 some shear strain"
            )));
            return None;
        }
        return Some(g);
    }
    if let Some(m) = mat1.get(&mid) {
        if m.g <= 0.0 {
            cx.err(m.at.error(format!("MAT1 {mid} (PSHELL MID3) has no shear modulus G")));
            return None;
        }
        return Some(nalgebra::Matrix2::identity() * m.g);
    }
    cx.err(used_by.error(format!("material {mid} (MAT1 or MAT2), PSHELL MID3, does not exist")));
    None
}

/// A MAT2's or MAT1's plane-stress matrix and density; a MAT2 must be positive
/// definite when `definite` (a coupling material, MID4, need not be).
fn material(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
    definite: bool,
) -> Option<(Matrix3<f64>, f64)> {
    if let Some(m) = mat2s.iter().find(|m| m.mid == mid) {
        let g = Matrix3::from_fn(|i, j| m.g[i][j]);
        if definite && g.cholesky().is_none() {
            cx.err(m.at.error(format!(
                "MAT2 {mid} is not positive definite: no strain energy for some strain state (check G11..G33)"
            )));
            return None;
        }
        return Some((g, m.rho));
    }
    if let Some(m) = mat1.get(&mid) {
        let q = m.e / (1.0 - m.nu * m.nu);
        let g = Matrix3::new(q, q * m.nu, 0.0, q * m.nu, q, 0.0, 0.0, 0.0, m.g);
        return Some((g, m.rho));
    }
    cx.err(used_by.error(format!("material {mid} (MAT1 or MAT2) does not exist")));
    None
}

fn shell_section(
    cx: &mut Ctx,
    p: &crate::deck::cards::Pshell,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<ShellSection> {
    let mem = match p.mid1 {
        Some(mid) => Some(material_matrix(cx, mid, &p.at, mat1, mat2s)?),
        None => None,
    };
    let bend = match p.mid2 {
        Some(mid) => Some(material_matrix(cx, mid, &p.at, mat1, mat2s)?),
        None => None,
    };
    if mem.is_none() && bend.is_none() {
        cx.err(p.at.error("PSHELL has neither MID1 nor MID2: the shell has no stiffness"));
        return None;
    }
    let coupling = match p.mid4 {
        Some(_) if mem.is_none() || bend.is_none() => {
            cx.err(p.at.error("PSHELL MID4 (membrane-bending coupling) needs both MID1 and MID2"));
            return None;
        }
        Some(mid) => Some(material(cx, mid, &p.at, mat1, mat2s, false)?.0),
        None => None,
    };
    let shear = match p.mid3 {
        Some(mid) => Some(transverse_shear_material(cx, mid, &p.at, mat1, mat2s)? * (p.ts_t * p.t)),
        None => None,
    };
    // NASTRAN takes the shell's density from MID1 (else MID2).
    let rho = mem.or(bend).map(|(_, r)| r).unwrap_or(0.0);
    let section = ShellSection {
        thickness: p.t,
        g_membrane: mem.map(|(g, _)| g),
        g_bending: bend.map(|(g, _)| g * p.bend_ratio),
        g_coupling: coupling,
        shear,
        mass_per_area: rho * p.t + p.nsm,
    };
    if !section_is_definite(&section) {
        cx.err(p.at.error(if section.g_coupling.is_some() {
            "the membrane, bending and coupling stiffnesses [A B; B D] are not positive definite (MID4 too \
             large against MID1 and MID2)"
                .to_string()
        } else {
            format!(
                "the membrane and bending stiffnesses A = G1·T and D = G2·T³/12 are not positive definite in \
                 double precision: T = {:e} is too small or too large for them",
                p.t
            )
        }));
        return None;
    }
    Some(section)
}

/// True when a section's stiffness, [A B; B D] (B zero when uncoupled; A or D alone
/// when the other is absent), is finite and positive definite in double precision.
/// Its materials are checked where they are read; what this adds is the coupling
/// (MID4 against MID1 and MID2) and the scaling by the thickness, which can overflow
/// or underflow (a bending stiffness G·T³/12 of 0 for T = 1e-110).
fn section_is_definite(s: &ShellSection) -> bool {
    fn definite<const N: usize>(k: nalgebra::SMatrix<f64, N, N>) -> bool {
        k.iter().all(|v| v.is_finite()) && k.cholesky().is_some()
    }
    match (s.a(), s.d()) {
        (Some(a), Some(d)) => {
            let b = s.b().unwrap_or_else(Matrix3::zeros);
            let mut k = nalgebra::Matrix6::zeros();
            k.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
            k.fixed_view_mut::<3, 3>(0, 3).copy_from(&b);
            k.fixed_view_mut::<3, 3>(3, 0).copy_from(&b.transpose());
            k.fixed_view_mut::<3, 3>(3, 3).copy_from(&d);
            definite(k)
        }
        (Some(m), None) | (None, Some(m)) => definite(m),
        (None, None) => true,
    }
}

/// The section of a PCOMP for an element whose material x axis is `axes` degrees
/// counter-clockwise from basic x (its plies' fibres at θ + `axes` in basic axes): its
/// plies (MAT8 or MAT1) through the lamination stage, the laminate's A/t, 12D/t³ and,
/// for an unsymmetric laminate, B/t² as the plate's membrane, bending and coupling
/// materials (NASTRAN's MID1, MID2 and MID4 equivalents). A, B and D are taken about
/// the reference plane (the grids' plane), Z0 from it to the bottom surface: a Z0
/// other than −T/2 (an offset laminate) couples membrane and bending through B, as
/// NASTRAN's equivalent PSHELL does with its MID4.
fn laminate_section(
    cx: &mut Ctx,
    p: &crate::deck::cards::Pcomp,
    mat1s: &[crate::deck::cards::Mat1],
    mat8s: &[crate::deck::cards::Mat8],
    axes: f64,
) -> Option<(ShellSection, PlyStack)> {
    use crate::laminate::{plies_of, ply_layers, Laminate};
    let plies = match plies_of(p, mat1s, mat8s) {
        Ok(plies) => plies,
        Err(e) => {
            cx.err(p.at.error(format!("PCOMP {}: {e}", p.pid)));
            return None;
        }
    };
    let lam = match Laminate::new(&plies, p.z0, axes) {
        Ok(l) => l,
        Err(e) => {
            cx.err(p.at.error(format!("PCOMP {}: {e}", p.pid)));
            return None;
        }
    };
    // Transverse shear: the plies' integral with the shear correction factor 5/6
    // (first-order shear deformation theory's), reordered from (yz, xz) to (xz, yz).
    let shear = lam
        .shear
        .map(|h| Matrix2::new(h[(1, 1)], h[(0, 1)], h[(1, 0)], h[(0, 0)]) * (5.0 / 6.0));
    if shear.is_none() {
        cx.warn(p.at.error(format!(
            "PCOMP {}: not every ply's MAT8 gives G1Z and G2Z: the laminate is taken as rigid in transverse shear \
             (a thin plate)",
            p.pid
        )));
    }
    let blank_f12 = p
        .stack()
        .iter()
        .any(|ply| mat8s.iter().any(|m| m.mid == ply.mid && m.f12.is_none()));
    if p.ft.as_deref() == Some("TSAI") && blank_f12 {
        cx.warn(p.at.error(format!(
            "PCOMP {}: FT = TSAI with a ply whose MAT8 leaves F12 blank: F12 = 0 there, as NASTRAN takes it",
            p.pid
        )));
    }
    let section = ShellSection {
        thickness: lam.thickness,
        g_membrane: Some(lam.membrane_material()),
        g_bending: Some(lam.bending_material()),
        g_coupling: (!lam.is_uncoupled()).then(|| lam.coupling_material()),
        shear,
        mass_per_area: lam.mass_per_area + p.nsm,
    };
    // Plies of positive thickness and positive definite Q make a positive definite
    // [A B; B D] in exact arithmetic; in double precision, plies thin or soft enough
    // (or stiff enough) underflow or overflow it.
    if !section_is_definite(&section) {
        cx.err(p.at.error(format!(
            "PCOMP {}: the laminate's stiffness [A B; B D] is not positive definite in double precision \
             (A11 = {:e}, D11 = {:e}): its plies are too thin, too soft or too stiff for it to be represented",
            p.pid,
            lam.a[(0, 0)],
            lam.d[(0, 0)],
        )));
        return None;
    }
    Some((
        section,
        std::sync::Arc::new(ply_layers(&plies, p.z0, axes, p.sb.filter(|_| p.ft.is_some()))),
    ))
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
