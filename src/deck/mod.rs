//! The deck reader: NASTRAN bulk data files to typed data with source positions.
//!
//! Stages: lines (with INCLUDE expanded) → sections → raw cards (fields, continuation,
//! replication) → typed cards. Every error carries file, line, column, card and field;
//! all errors of a deck are collected (up to [`diag::MAX_ERRORS`]).

pub mod bulk;
pub mod cards;
pub mod case;
pub mod diag;
pub mod image;
pub mod number;
pub mod source;

pub use cards::{Bulk, CardRef, Components};
pub use case::{CaseControl, Executive, OutputSet, MODES, STATICS};
pub use diag::{Diagnostic, Diagnostics, Pos, Severity};

use std::collections::HashMap;
use std::fmt;
use std::path::Path;

/// The deck's declared unit system (from a `$ Units: length, force, time` comment).
/// impactlab never converts units: these names only label outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Units {
    /// Length unit name.
    pub length: String,
    /// Force unit name.
    pub force: String,
    /// Time unit name.
    pub time: String,
}

impl Units {
    /// The name of a unit the deck does not declare.
    pub const UNSPECIFIED: &'static str = "unspecified";

    /// True when the deck declared its units.
    pub fn declared(&self) -> bool {
        self.time != Self::UNSPECIFIED
    }

    /// True when the deck's time unit is the second (the paper's).
    pub fn in_seconds(&self) -> bool {
        self.time == "s"
    }

    /// Joules in one of the deck's energy units (force·length), when both are units
    /// this knows (length m, cm, mm, in, ft; force N, kN, lbf, kip; the exact SI
    /// definitions: 1 in = 0.0254 m, 1 lbf = 4.4482216152605 N).
    pub fn joules_per_energy_unit(&self) -> Option<f64> {
        let length = match self.length.as_str() {
            "m" => 1.0,
            "cm" => 1e-2,
            "mm" => 1e-3,
            "in" => 0.0254,
            "ft" => 0.3048,
            _ => return None,
        };
        let force = match self.force.as_str() {
            "N" => 1.0,
            "kN" => 1e3,
            "lbf" => 4.448_221_615_260_5,
            "kip" => 4_448.221_615_260_5,
            _ => return None,
        };
        Some(length * force)
    }

    /// A scale and a label for printing times of the order of a contact: microseconds
    /// when the deck's time unit is the second, the deck's own unit otherwise.
    pub fn short_time(&self) -> (f64, String) {
        if self.in_seconds() {
            (1e6, "µs".into())
        } else {
            (1.0, self.time.clone())
        }
    }
}

impl Default for Units {
    fn default() -> Self {
        Units {
            length: Self::UNSPECIFIED.into(),
            force: Self::UNSPECIFIED.into(),
            time: Self::UNSPECIFIED.into(),
        }
    }
}

/// A deck read without errors.
#[derive(Debug, Clone)]
pub struct Deck {
    /// The deck's file stem, naming its outputs.
    pub name: String,
    /// Executive control.
    pub executive: Executive,
    /// Case control.
    pub case: CaseControl,
    /// Bulk data, typed.
    pub bulk: Bulk,
    /// The declared units (or `unspecified`).
    pub units: Units,
    /// SHA-256 (hex) of the deck's bytes followed by those of each INCLUDEd file in
    /// the order read.
    pub sha256: String,
    /// Warnings found while reading.
    pub warnings: Vec<Diagnostic>,
    /// The cards of kinds the reader does not know, in deck order (kept when the
    /// deck is read with [`ReadOptions::structure`] or `allow_unknown`).
    pub unknown: Vec<UnknownCard>,
    /// Every bulk data card as read (replication and INCLUDE expanded), for a deck
    /// read with [`ReadOptions::keep_cards`]: a scene that strikes the deck writes its
    /// structural cards back ([`bulk::RawCard::free_field`]). Empty otherwise.
    pub cards: Vec<bulk::RawCard>,
}

/// A card of a kind the reader does not know.
#[derive(Debug, Clone, PartialEq)]
pub struct UnknownCard {
    /// Its name.
    pub name: String,
    /// Where it starts.
    pub pos: Pos,
    /// Its first line as written.
    pub line: String,
}

/// Reading a deck failed: every error found, and the warnings.
#[derive(Debug, Clone)]
pub struct DeckError {
    /// Errors and warnings, in the order found.
    pub diagnostics: Vec<Diagnostic>,
}

impl DeckError {
    /// The errors.
    pub fn errors(&self) -> impl Iterator<Item = &Diagnostic> {
        self.diagnostics.iter().filter(|d| d.is_error())
    }
}

impl fmt::Display for DeckError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let errors: Vec<_> = self.errors().collect();
        for d in errors.iter().take(diag::MAX_ERRORS) {
            writeln!(f, "{d}")?;
        }
        if errors.len() > diag::MAX_ERRORS {
            writeln!(f, "... and {} more errors", errors.len() - diag::MAX_ERRORS)?;
        }
        write!(f, "{} error(s) in deck", errors.len())
    }
}

impl std::error::Error for DeckError {}

/// Options of the reader.
#[derive(Debug, Clone, Copy, Default)]
pub struct ReadOptions {
    /// Unknown cards become warnings instead of errors.
    pub allow_unknown: bool,
    /// The deck is read for its structure alone (`impactlab check`): any solution
    /// sequence, SUBCASEs and unknown cards are accepted, the unknown cards kept in
    /// [`Deck::unknown`] without a diagnostic each.
    pub structure: bool,
    /// Every bulk data card is kept as read, in [`Deck::cards`] (a scene writes a
    /// struck deck's structural cards back).
    pub keep_cards: bool,
    /// What one deck may ask of the reader.
    pub limits: Limits,
}

/// What one deck may ask of the reader: past these a deck is an error naming the
/// limit, never exhausted memory or an endless read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Bulk data cards in all, replicated ones included: bounds the grids, elements
    /// and DOFs a deck can describe (and what the reader holds for them).
    pub max_cards: usize,
    /// Cards one replication line may generate.
    pub max_replication: usize,
    /// How deep INCLUDEs may nest (a file the deck includes is depth 1); 0 refuses INCLUDE.
    pub max_include_depth: usize,
    /// Ids listed in all, `THRU` ranges expanded (SPC1, EPOINT, SPOINT, case-control
    /// SETs): `SET 1 = 1 THRU 100000000000` is an error, not exhausted memory.
    pub max_listed_ids: usize,
}

impl Default for Limits {
    /// For decks from the analyst's own disk: 5 million cards (the 199×199 plate has
    /// about 80 thousand; a million-line deck fits, at about 0.4 kB held per card),
    /// a million cards per replication line (far above any real mesh line, low enough
    /// that a typo such as `=(100000000)` is an error), INCLUDEs 16 deep, 50 million
    /// listed ids (0.4 GB).
    fn default() -> Self {
        Limits {
            max_cards: 5_000_000,
            max_replication: 1_000_000,
            max_include_depth: 16,
            max_listed_ids: 50_000_000,
        }
    }
}

impl Limits {
    /// For input from anywhere, such as a fuzzer's: 1 000 cards (the paper's rod deck
    /// has 300, its plate 5 100), 1 000 per replication line, no INCLUDE (it would
    /// read files named by the input), 100 000 listed ids. What one such deck costs to
    /// read is then bounded by what a small deck costs.
    pub fn untrusted() -> Self {
        Limits {
            max_cards: 1_000,
            max_replication: 1_000,
            max_include_depth: 0,
            max_listed_ids: 100_000,
        }
    }
}

/// Takes `n` ids from `ids_left`, what remains of [`Limits::max_listed_ids`]; the
/// error's text when there are not that many left.
pub(crate) fn take_ids(ids_left: &mut usize, n: u128) -> Result<(), String> {
    match usize::try_from(n).ok().filter(|&n| n <= *ids_left) {
        Some(n) => {
            *ids_left -= n;
            Ok(())
        }
        None => Err(format!(
            "lists more ids than the reader's limit allows ({ids_left} left of the deck's listed-id limit)"
        )),
    }
}

/// Reads a deck file.
pub fn read_deck(path: &Path, opts: ReadOptions) -> Result<Deck, DeckError> {
    let mut diags = Diagnostics::default();
    let sections = source::read_sections(path, opts.limits, &mut diags);
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "deck".into());
    finish(name, sections, opts, diags)
}

/// Reads deck text held in memory.
pub fn parse_deck_str(name: &str, text: &str, opts: ReadOptions) -> Result<Deck, DeckError> {
    let mut diags = Diagnostics::default();
    let sections = source::sections_from_str(name, text, opts.limits, &mut diags);
    finish(name.to_string(), sections, opts, diags)
}

fn finish(
    name: String,
    sections: source::Sections,
    opts: ReadOptions,
    mut diags: Diagnostics,
) -> Result<Deck, DeckError> {
    let executive = case::parse_executive(&sections.executive, opts.structure, &mut diags);
    let mut ids_left = opts.limits.max_listed_ids;
    let subcases = if opts.structure {
        case::Subcases::Any
    } else if executive.sol == Some(STATICS) {
        case::Subcases::Static
    } else {
        case::Subcases::None
    };
    let mut case = case::parse_case(&sections.case, subcases, &mut ids_left, &mut diags);
    case.at = sections
        .case
        .last()
        .or(sections.executive.last())
        .or(sections.bulk.first())
        .map(|l| diag::Pos {
            file: l.file.clone(),
            line: l.line,
            column: 1,
        });
    if let (Some(sel), Some(STATICS | MODES), false) = (&case.dload, executive.sol, opts.structure) {
        diags.push(
            Diagnostic::warning(
                Some(sel.pos.clone()),
                "DLOAD selects a dynamic load, which a static or normal modes solution does not apply; ignored",
            )
            .card("DLOAD"),
        );
    }
    if let (Some((statement, at)), false) = (&case.substructuring, opts.structure) {
        // "Phase 3: completion of the analysis of individual substructures using the
        // {ua} vector produced in Phase 2" (User's Manual 1.10): the answer is not in
        // this deck.
        diags.push(
            Diagnostic::error(
                Some(at.clone()),
                "automated substructuring is not run by impactlab: the solution of this phase is made from \
                 the substructure operating file (SOF) of earlier runs, which impactlab does not read; \
                 `impactlab check` reads the substructure the deck defines",
            )
            .quote(statement),
        );
    }
    let mut typer = cards::Typer::new(opts.keep_cards);
    bulk::assemble(sections.bulk, opts.limits, &mut diags, |card, diags| {
        typer.card(card, &mut ids_left, diags)
    });
    let (bulk, unknown, cards) = typer.finish(&mut ids_left, &mut diags);
    if !opts.structure {
        report_unknown(&unknown, opts, &mut diags);
    }
    check_duplicates(&bulk, &mut diags);
    let units = sections
        .units
        .map(|(length, force, time)| Units { length, force, time })
        .unwrap_or_default();
    if diags.has_errors() {
        return Err(DeckError {
            diagnostics: diags.items,
        });
    }
    Ok(Deck {
        name,
        executive,
        case,
        bulk,
        units,
        sha256: sections.sha256,
        warnings: diags.items,
        unknown,
        cards,
    })
}

/// Cards impactlab does not read that change nothing it computes: plot elements and
/// NASTRAN's sequencing and congruence hints. A run warns of them and goes on.
const HARMLESS: [(&str, &str); 4] = [
    ("PLOTEL", "a plot element"),
    ("SEQGP", "a hint to NASTRAN's grid sequencing"),
    ("SEQEP", "a hint to NASTRAN's extra point sequencing"),
    (
        "CNGRNT",
        "a hint that elements are congruent (NASTRAN computes their matrices once)",
    ),
];

fn report_unknown(unknown: &[UnknownCard], opts: ReadOptions, diags: &mut Diagnostics) {
    let harmless = |n: &str| HARMLESS.iter().find(|h| h.0 == n).map(|h| h.1);
    // One warning a kind, at its first card.
    for (name, what) in HARMLESS {
        let mut these = unknown.iter().filter(|u| u.name == name);
        if let Some(first) = these.next() {
            let n = 1 + these.count();
            diags.push(
                Diagnostic::warning(
                    Some(first.pos.clone()),
                    format!("{n} card(s), {what}: they change nothing impactlab computes; ignored"),
                )
                .card(name),
            );
        }
    }
    let unknown: Vec<&UnknownCard> = unknown.iter().filter(|u| harmless(&u.name).is_none()).collect();
    if unknown.is_empty() {
        return;
    }
    let mut names: Vec<&str> = unknown.iter().map(|u| u.name.as_str()).collect();
    names.sort();
    names.dedup();
    let list = names.join(", ");
    for &UnknownCard { name: n, pos, .. } in &unknown {
        let msg = format!(
            "unknown card (this deck has {} unknown card type(s): {list}); supported: {}",
            names.len(),
            cards::supported().join(" ")
        );
        let d = if opts.allow_unknown {
            Diagnostic::warning(Some(pos.clone()), format!("{msg}; ignored because of --allow-unknown"))
        } else {
            Diagnostic::error(Some(pos.clone()), format!("{msg}; use --allow-unknown to ignore them"))
        };
        diags.push(d.card(n));
    }
}

fn check_duplicates(b: &Bulk, diags: &mut Diagnostics) {
    fn dup<'a>(kind: &str, items: impl Iterator<Item = (i64, &'a CardRef)>, diags: &mut Diagnostics) {
        let mut seen: HashMap<i64, &CardRef> = HashMap::new();
        for (id, at) in items {
            if let Some(first) = seen.get(&id) {
                diags.push(at.error(format!("duplicate {kind} id {id} (first defined at {})", first.pos)));
            } else {
                seen.insert(id, at);
            }
        }
    }
    dup(
        "point",
        b.grids
            .iter()
            .map(|g| (g.id, &g.at))
            .chain(b.epoints.iter().map(|(i, a)| (*i, a)))
            .chain(b.spoints.iter().map(|(i, a)| (*i, a))),
        diags,
    );
    dup(
        "element",
        b.elements
            .iter()
            .map(|c| (c.eid, &c.at))
            .chain(b.scalars.iter().map(|c| (c.eid, &c.at)))
            .chain(b.cbushes.iter().map(|c| (c.eid, &c.at))),
        diags,
    );
    dup(
        "mass element",
        b.conm1s
            .iter()
            .map(|c| (c.eid, &c.at))
            .chain(b.conm2s.iter().map(|c| (c.eid, &c.at))),
        diags,
    );
    // NASTRAN-95 keeps its mass elements apart from the structural ones and runs a
    // deck whose CONM2 shares an element's id (its demonstration problem D12-01-1A
    // does); MSC refuses it. Taken, with a warning.
    let structural: HashMap<i64, &CardRef> = b
        .elements
        .iter()
        .map(|c| (c.eid, &c.at))
        .chain(b.cbushes.iter().map(|c| (c.eid, &c.at)))
        .collect();
    let masses = b
        .conm1s
        .iter()
        .map(|c| (c.eid, &c.at))
        .chain(b.conm2s.iter().map(|c| (c.eid, &c.at)));
    for (eid, at) in masses {
        if let Some(first) = structural.get(&eid) {
            diags.push(at.warning(format!(
                "{} {eid} has the id of the {} at {}: NASTRAN-95 takes this, MSC does not; the two are kept apart",
                at.name, first.name, first.pos
            )));
        }
    }
    dup(
        "property",
        b.prods
            .iter()
            .map(|p| (p.pid, &p.at))
            .chain(b.pshells.iter().map(|p| (p.pid, &p.at)))
            .chain(b.pelas.iter().map(|p| (p.pid, &p.at)))
            .chain(b.pmass.iter().map(|p| (p.pid, &p.at)))
            .chain(b.pbushes.iter().map(|p| (p.pid, &p.at))),
        diags,
    );
    dup(
        "material",
        b.mat1s
            .iter()
            .map(|m| (m.mid, &m.at))
            .chain(b.mat2s.iter().map(|m| (m.mid, &m.at))),
        diags,
    );
}
