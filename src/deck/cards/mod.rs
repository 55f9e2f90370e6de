//! Typed bulk data cards, read from raw cards field by field.
//!
//! Field index `k` is the card's data field counted from 0 (NASTRAN field 2 of the
//! first line), running on through continuation lines 8 fields a line.

mod bush;
mod constraints;
mod damping;
mod dynamic;
mod elements;
mod excitation;
mod geometry;
mod loads;
mod materials;
mod properties;
mod reader;

pub use bush::*;
pub use constraints::*;
pub use damping::*;
pub use dynamic::*;
pub use elements::*;
pub use excitation::*;
pub use geometry::*;
pub use loads::*;
pub use materials::*;
pub use properties::*;
use reader::Reader;

use super::bulk::RawCard;
use super::diag::{Diagnostic, Diagnostics, Pos};
use super::number::{parse_int, parse_real, RealToken};

/// Where a card came from, for messages raised after reading (model building).
#[derive(Debug, Clone)]
pub struct CardRef {
    /// Card name.
    pub name: compact_str::CompactString,
    /// Where the card starts.
    pub pos: Pos,
    /// The card's source lines, for quoting.
    pub source: String,
}

impl CardRef {
    /// An error about this card, quoting it.
    pub fn error(&self, message: impl Into<String>) -> Diagnostic {
        Diagnostic::error(Some(self.pos.clone()), message)
            .card(&self.name)
            .quote(&self.source)
    }

    /// A warning about this card, quoting it.
    pub fn warning(&self, message: impl Into<String>) -> Diagnostic {
        Diagnostic::warning(Some(self.pos.clone()), message)
            .card(&self.name)
            .quote(&self.source)
    }

    /// An error about one field of this card, pointing at it.
    pub fn field_error(&self, f: &FieldRef, message: impl Into<String>) -> Diagnostic {
        let d = Diagnostic::error(Some(f.pos.clone()), message)
            .card(&self.name)
            .field(f.number, f.name)
            .quote(&self.source);
        if f.token.is_empty() {
            d
        } else {
            d.token(&f.token)
        }
    }
}

/// Where one field of a card was written, for messages raised after reading (a
/// coordinate system that does not exist, three points on a line).
#[derive(Debug, Clone)]
pub struct FieldRef {
    /// Where the field starts (the card's start when the field is absent).
    pub pos: Pos,
    /// NASTRAN field number on its line.
    pub number: usize,
    /// The field's name.
    pub name: &'static str,
    /// The field as written, trimmed; empty when blank.
    pub token: compact_str::CompactString,
}

/// A set of DOF components 1-6 (bit i-1 for component i); empty for scalar points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Components(pub u8);

impl Components {
    /// True when component `c` (1-6) is in the set.
    pub fn contains(self, c: usize) -> bool {
        (1..=6).contains(&c) && self.0 & (1 << (c - 1)) != 0
    }
    /// The components in the set, ascending.
    pub fn iter(self) -> impl Iterator<Item = usize> {
        (1..=6).filter(move |&c| self.contains(c))
    }
}

/// All bulk data of a deck, typed.
#[derive(Debug, Clone, Default)]
pub struct Bulk {
    /// GRID cards.
    pub grids: Vec<Grid>,
    /// The GRDSET card, or its defaults.
    pub grdset: GrdSet,
    /// Coordinate systems (CORD1R/C/S, CORD2R/C/S), in deck order.
    pub cords: Vec<Cord>,
    /// EPOINT ids (extra points), each with its card.
    pub epoints: Vec<(i64, CardRef)>,
    /// SPOINT ids (scalar points), each with its card.
    pub spoints: Vec<(i64, CardRef)>,
    /// Element cards (CROD, CQUAD4, CTRIA3), in deck order.
    pub elements: Vec<Connection>,
    /// PROD cards.
    pub prods: Vec<Prod>,
    /// PLOAD cards.
    pub ploads: Vec<Pload>,
    /// SPCD cards (one entry per enforced value).
    pub spcds: Vec<Spcd>,
    /// PSHEAR cards.
    pub pshears: Vec<Pshear>,
    /// PBAR, PBARL, PBEAM and PBEAML cards.
    pub bar_properties: Vec<BarProperty>,
    /// PSHELL cards.
    pub pshells: Vec<Pshell>,
    /// COSMIC's plate properties (PQUAD1 ... PTRMEM) as the PSHELL they describe, by
    /// their card (COSMIC numbers each card's ids apart).
    pub cosmic_plates: Vec<(&'static str, Pshell)>,
    /// MAT1 cards.
    pub mat1s: Vec<Mat1>,
    /// MAT2 cards.
    pub mat2s: Vec<Mat2>,
    /// MAT8 cards.
    pub mat8s: Vec<Mat8>,
    /// PCOMP cards.
    pub pcomps: Vec<Pcomp>,
    /// CONM1 cards.
    pub conm1s: Vec<Conm1>,
    /// CBUSH cards.
    pub cbushes: Vec<Cbush>,
    /// PBUSH cards.
    pub pbushes: Vec<Pbush>,
    /// CONM2 cards.
    pub conm2s: Vec<Conm2>,
    /// CELAS1-4, CMASS1-4 and CDAMP1-4 cards.
    pub scalars: Vec<ScalarCard>,
    /// GENEL cards.
    pub genels: Vec<GenelCard>,
    /// PELAS cards.
    pub pelas: Vec<ScalarProperty>,
    /// PMASS cards.
    pub pmass: Vec<ScalarProperty>,
    /// PDAMP cards, one entry a property.
    pub pdamps: Vec<ScalarProperty>,
    /// PVISC cards, one entry a property.
    pub pviscs: Vec<Pvisc>,
    /// CVISC cards, one entry an element.
    pub cviscs: Vec<Cvisc>,
    /// The damping PARAMs (G, W3, W4, ALPHA1, ALPHA2) the deck sets.
    pub damping: Vec<DampingSetting>,
    /// SPC1 cards, and each grid of an SPC card as one.
    pub spc1s: Vec<Spc1>,
    /// SPCADD cards.
    pub spcadds: Vec<SpcAdd>,
    /// RBE2 cards.
    pub rbe2s: Vec<Rbe2>,
    /// RBE3 cards.
    pub rbe3s: Vec<Rbe3>,
    /// TF cards.
    pub tfs: Vec<Tf>,
    /// TSTEP cards.
    pub tsteps: Vec<Tstep>,
    /// NOLIN3 cards.
    pub nolin3s: Vec<Nolin3>,
    /// TIC cards.
    pub tics: Vec<Tic>,
    /// EIGR and EIGRL cards.
    pub eigrs: Vec<Eigr>,
    /// DAREA cards (one entry per P, C, A).
    pub dareas: Vec<Darea>,
    /// DELAY cards (one entry per P, C, T).
    pub delays: Vec<Delay>,
    /// TLOAD1 and TLOAD2 cards.
    pub tloads: Vec<Tload>,
    /// TABLED1-4 cards.
    pub tableds: Vec<Tabled>,
    /// DLOAD cards.
    pub dloads: Vec<LoadCombination>,
    /// LSEQ cards.
    pub lseqs: Vec<Lseq>,
    /// FORCE and MOMENT cards.
    pub point_loads: Vec<PointLoad>,
    /// PLOAD4 cards.
    pub pload4s: Vec<Pload4>,
    /// GRAV cards.
    pub gravs: Vec<Grav>,
    /// TEMPRB cards.
    pub temprbs: Vec<Temprb>,
    /// TEMPP1 cards, one entry an element.
    pub tempp1s: Vec<Tempp1>,
    /// TEMP and TEMPD cards, one entry a temperature.
    pub temperatures: Vec<GridTemperature>,
    /// LOAD cards.
    pub load_combinations: Vec<LoadCombination>,
    /// PARAM WTMASS when the deck sets it, with its card: every mass of the deck
    /// (densities, non-structural and concentrated masses) has been multiplied by it.
    pub wtmass: Option<(f64, CardRef)>,
    /// PARAM COUPMASS and the per-element CPxxx parameters as the deck sets them
    /// (name upper-case, value, card): see [`Bulk::coupled_mass`].
    pub mass_params: Vec<(String, i64, CardRef)>,
    /// How fields that COSMIC and MSC read differently were read: the reading, and
    /// on how many cards.
    pub readings: std::collections::BTreeMap<&'static str, usize>,
}

/// Cards the reader knows. `PARAM` is read for WTMASS and the damping parameters,
/// any other accepted and ignored with a warning.
/// Element cards are those of [`crate::elements::KINDS`] besides these.
pub const KNOWN_CARDS: [&str; 100] = [
    "GRID", "GRDSET", "CORD1R", "CORD1C", "CORD1S", "CORD2R", "CORD2C", "CORD2S", "EPOINT", "SPOINT", "PROD", "PBAR",
    "PBARL", "PBEAM", "PBEAML", "PSHELL", "PCOMP", "MAT1", "MAT2", "MAT8", "CONM2", "RBE2", "RBE3", "SPC1", "SPC",
    "SPCADD", "TF", "TSTEP", "NOLIN3", "TIC", "FORCE", "MOMENT", "PLOAD4", "GRAV", "LOAD", "PARAM", "INCLUDE",
    "ENDDATA", "BAROR", "PTUBE", "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CMASS1", "CMASS2", "CMASS3", "CMASS4",
    "PELAS", "PMASS", "CQUAD1", "CQUAD2", "CQDMEM", "CQDMEM1", "CQDMEM2", "CTRIA1", "CTRIA2", "CTRMEM", "PQUAD1",
    "PTRIA1", "PQUAD2", "PTRIA2", "PQDMEM", "PQDMEM1", "PQDMEM2", "PTRMEM", "PCOMP1", "PCOMP2", "CRIGD1", "PSHEAR",
    "GENEL", "SPCD", "PLOAD2", "PLOAD", "TEMPRB", "EIGR", "EIGRL", "DAREA", "DELAY", "TLOAD1", "TLOAD2", "TABLED1",
    "TABLED2", "TABLED3", "TABLED4", "DLOAD", "LSEQ", "CONM1", "CBUSH", "PBUSH", "TEMPP1", "TEMP", "TEMPD", "CDAMP1",
    "CDAMP2", "CDAMP3", "CDAMP4", "PDAMP", "CVISC", "PVISC",
];

/// Every card the reader types: the element cards of [`crate::elements::KINDS`] and
/// [`KNOWN_CARDS`], in alphabetical order.
pub fn supported() -> Vec<&'static str> {
    let mut all: Vec<&'static str> = crate::elements::KINDS
        .iter()
        .map(|k| k.card)
        .chain(KNOWN_CARDS)
        .collect();
    all.sort_unstable();
    all
}

/// What a field holds, as the reader reads it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldKind {
    /// An integer.
    Integer,
    /// An identification number: a positive integer.
    Id,
    /// A real number.
    Real,
    /// A list of DOF components (`123456`).
    Components,
    /// One DOF component (0-6).
    Component,
    /// Ids from this field on, with `THRU` ranges.
    Ids,
    /// A word: a name or a flag.
    Word,
}

/// What a blank field means.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Blank {
    /// The field is required: a blank is an error.
    Refused,
    /// The field takes this value.
    Default(String),
    /// The field takes the value of the field so named.
    As(String),
    /// The field is absent: its card's reader decides (a default that depends on other
    /// fields, or the field's meaning left out).
    Absent,
}

/// One field as a card's reader reads it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldRead {
    /// Data field index (0 = NASTRAN field 2 of the first line; 8 fields a line).
    pub k: usize,
    /// The field's name in the reader's messages.
    pub name: String,
    /// What it holds.
    pub kind: FieldKind,
    /// What a blank means.
    pub blank: Blank,
}

/// The fields the reader reads of card `name`, in field order: each field's name,
/// kind and what its blank means, as the reader's own calls say. The card is read
/// twice, its first two lines (16 data fields) blank, then each field holding its own
/// number (data field k: k + 1). A field read only on the second has no known blank
/// meaning; a default that differs between the two is the value of the field whose
/// number it is (a PID's EID), or has no known meaning either. A field read only when
/// another holds some other value is not found. `None` for a card the reader does not
/// type.
pub fn fields_read(name: &str) -> Option<Vec<FieldRead>> {
    if !supported().contains(&name) {
        return None;
    }
    let pos = Pos {
        file: "probe".into(),
        line: 1,
        column: 1,
    };
    let mut read: Vec<FieldRead> = Vec::new();
    for numbered in [false, true] {
        let card = RawCard {
            name: name.into(),
            pos: pos.clone(),
            fields: (0..16)
                .map(|k| super::image::Field {
                    text: if numbered {
                        (k + 1).to_string().into()
                    } else {
                        Default::default()
                    },
                    pos: pos.clone(),
                    number: k % 8 + 2,
                })
                .collect(),
            source: String::new(),
            replicated_at: None,
        };
        let (mut diags, mut ids_left, mut b, mut unknown) =
            (Diagnostics::default(), usize::MAX, Bulk::default(), Vec::new());
        let mut r = Reader::new(&card, &mut diags, &mut ids_left);
        r.trace = Some(Vec::new());
        type_one(&mut r, &mut b, &mut unknown, &card);
        let trace = r.trace.take().unwrap_or_default();
        for f in &trace {
            match read.iter().position(|g| g.k == f.k) {
                // A default that moves with the other fields is another field's value
                // (a PID's EID): field j holds j + 1 on the numbered card.
                Some(i) if matches!(read[i].blank, Blank::Default(_)) && f.blank != read[i].blank => {
                    let from = match &f.blank {
                        Blank::Default(v) => v.parse::<f64>().ok(),
                        _ => None,
                    };
                    read[i].blank = from
                        .and_then(|v| trace.iter().find(|g| g.k != f.k && (g.k + 1) as f64 == v))
                        .map_or(Blank::Absent, |g| Blank::As(g.name.clone()));
                }
                Some(_) => {}
                None if !numbered => read.push(f.clone()),
                None => read.push(FieldRead {
                    blank: Blank::Absent,
                    ..f.clone()
                }),
            }
        }
    }
    read.sort_by_key(|f| f.k);
    Some(read)
}

/// Types raw cards as they come, in the order they come. Unknown card names are
/// collected. The raw cards are dropped as they are typed, unless `keep` is set: they
/// are then returned.
///
/// BAROR's fields stand for any CBAR's blank ones, wherever the BAROR is: a CBAR
/// with such blanks that comes before any BAROR holds back every card after it until
/// a BAROR or the end, so that the cards are still typed in their order.
pub struct Typer {
    bulk: Bulk,
    unknown: Vec<super::UnknownCard>,
    kept: Option<Vec<RawCard>>,
    baror: Option<RawCard>,
    held: Vec<RawCard>,
}

impl Typer {
    /// A typer that keeps the raw cards when `keep` is set.
    pub fn new(keep: bool) -> Self {
        Typer {
            bulk: Bulk::default(),
            unknown: Vec::new(),
            kept: keep.then(Vec::new),
            baror: None,
            held: Vec::new(),
        }
    }

    /// Types one card. `ids_left` is what remains of [`super::Limits::max_listed_ids`].
    pub fn card(&mut self, card: RawCard, ids_left: &mut usize, diags: &mut Diagnostics) {
        if card.name == "BAROR" {
            match &self.baror {
                Some(first) => diags.push(
                    Diagnostic::error(
                        Some(card.pos.clone()),
                        format!(
                            "only one BAROR card may appear in the bulk data (the first is at {})",
                            first.pos
                        ),
                    )
                    .card("BAROR")
                    .quote(&card.source),
                ),
                None => {
                    self.baror = Some(card.clone());
                    for c in std::mem::take(&mut self.held) {
                        self.type_card(c, ids_left, diags);
                    }
                }
            }
        }
        let needs_baror = card.name == "CBAR" && [1, 4, 5, 6, 7].iter().any(|&k| card.text(k).is_empty());
        if !self.held.is_empty() || self.baror.is_none() && needs_baror {
            self.held.push(card);
        } else {
            self.type_card(card, ids_left, diags);
        }
    }

    /// The bulk data typed, the unknown cards and the raw cards kept.
    pub fn finish(
        mut self,
        ids_left: &mut usize,
        diags: &mut Diagnostics,
    ) -> (Bulk, Vec<super::UnknownCard>, Vec<RawCard>) {
        for c in std::mem::take(&mut self.held) {
            self.type_card(c, ids_left, diags);
        }
        let mut b = self.bulk;
        if let Some((w, _)) = &b.wtmass {
            let w = *w;
            b.scale_masses(w);
        }
        implicit_scalar_points(&mut b);
        (b, self.unknown, self.kept.unwrap_or_default())
    }

    fn type_card(&mut self, whole: RawCard, ids_left: &mut usize, diags: &mut Diagnostics) {
        let (b, unknown) = (&mut self.bulk, &mut self.unknown);
        for piece in pieces(&whole, self.baror.as_ref()) {
            let card: &RawCard = &piece;
            let mut r = Reader::new(card, diags, ids_left);
            type_one(&mut r, b, unknown, card);
            for what in r.readings {
                *b.readings.entry(what).or_default() += 1;
            }
        }
        if let Some(kept) = &mut self.kept {
            kept.push(whole);
        }
    }
}

/// Types one card (one of a card of several, [`pieces`]) into `b`, or records it as
/// unknown.
fn type_one(r: &mut Reader, b: &mut Bulk, unknown: &mut Vec<super::UnknownCard>, card: &RawCard) {
    match card.name.as_str() {
        "BAROR" => r.extra_fields(8),
        "GRID" => card_grid(r, b),
        "GRDSET" => card_grdset(r, b),
        "CORD1R" | "CORD1C" | "CORD1S" => card_cord1(r, b),
        "CORD2R" | "CORD2C" | "CORD2S" => card_cord2(r, b),
        "EPOINT" | "SPOINT" => card_points(r, b, card),
        "PROD" => card_prod(r, b),
        "PTUBE" => card_ptube(r, b),
        "CELAS1" | "CELAS2" | "CELAS3" | "CELAS4" | "CMASS1" | "CMASS2" | "CMASS3" | "CMASS4" | "CDAMP1" | "CDAMP2"
        | "CDAMP3" | "CDAMP4" => card_scalar(r, b),
        "PVISC" => card_pvisc(r, b),
        "CVISC" => card_cvisc(r, b),
        "PELAS" | "PMASS" | "PDAMP" => card_scalar_property(r, b),
        "PCOMP1" | "PCOMP2" => card_pcomp_uniform(r, b),
        "CQUAD1" | "CQUAD2" | "CQDMEM" | "CQDMEM1" | "CQDMEM2" | "CTRIA1" | "CTRIA2" | "CTRMEM" => {
            card_cosmic_plate(r, b)
        }
        "PQUAD1" | "PTRIA1" | "PQUAD2" | "PTRIA2" | "PQDMEM" | "PQDMEM1" | "PQDMEM2" | "PTRMEM" => {
            card_cosmic_plate_property(r, b)
        }
        "CONROD" => card_conrod(r, b),
        "PBAR" | "PBEAM" => card_pbar(r, b),
        "PBARL" | "PBEAML" => card_pbarl(r, b),
        "PSHELL" => card_pshell(r, b),
        "MAT1" => card_mat1(r, b),
        "MAT2" => card_mat2(r, b),
        "MAT8" => card_mat8(r, b),
        "PCOMP" => card_pcomp(r, b),
        "CONM1" => card_conm1(r, b),
        "CBUSH" => card_cbush(r, b),
        "TEMPP1" => card_tempp1(r, b),
        "TEMP" | "TEMPD" => card_temp(r, b),
        "PBUSH" => card_pbush(r, b),
        "CONM2" => card_conm2(r, b),
        "SPC1" => card_spc1(r, b),
        "SPC" => card_spc(r, b),
        "SPCADD" => card_spcadd(r, b),
        "RBE2" => card_rbe2(r, b),
        "CRIGD1" => card_crigd1(r, b),
        "PSHEAR" => card_pshear(r, b),
        "GENEL" => card_genel(r, b),
        "SPCD" => card_spcd(r, b),
        "PLOAD2" => card_pload2(r, b),
        "PLOAD" => card_pload(r, b),
        "RBE3" => card_rbe3(r, b),
        "TF" => card_tf(r, b, card),
        "TSTEP" => card_tstep(r, b, card),
        "NOLIN3" => card_nolin3(r, b),
        "TIC" => card_tic(r, b),
        "FORCE" | "MOMENT" => card_point_load(r, b),
        "PLOAD4" => card_pload4(r, b),
        "GRAV" => card_grav(r, b),
        "TEMPRB" => card_temprb(r, b),
        "EIGR" => card_eigr(r, b),
        "EIGRL" => card_eigrl(r, b),
        "DAREA" => card_darea_delay(r, b, false),
        "DELAY" => card_darea_delay(r, b, true),
        "TLOAD1" => card_tload(r, b, false),
        "TLOAD2" => card_tload(r, b, true),
        "TABLED1" => card_tabled(r, b, 1),
        "TABLED2" => card_tabled(r, b, 2),
        "TABLED3" => card_tabled(r, b, 3),
        "TABLED4" => card_tabled(r, b, 4),
        "LSEQ" => card_lseq(r, b),
        "LOAD" | "DLOAD" => card_load(r, b),
        "PARAM" => card_param(r, b, card),
        name => match crate::elements::kind(name) {
            Some(kind) => card_element(r, b, kind),
            None => unknown.push(super::UnknownCard {
                name: card.name.to_string(),
                pos: card.pos.clone(),
                line: card.source.lines().next().unwrap_or("").to_string(),
            }),
        },
    }
}

/// Scalar points defined by their use: "a scalar point ... referenced on a scalar
/// connection card need not be defined on an SPOINT card" (BULK.TXT, SPOINT): a
/// scalar element's terminal of component 0 that no GRID, SPOINT or EPOINT defines.
fn implicit_scalar_points(b: &mut Bulk) {
    let known: std::collections::HashSet<i64> = b
        .grids
        .iter()
        .map(|g| g.id)
        .chain(b.spoints.iter().chain(&b.epoints).map(|(i, _)| *i))
        .collect();
    let mut added = std::collections::HashSet::new();
    for c in &b.scalars {
        for &(g, comp) in &c.terminals {
            if g > 0 && comp == 0 && !known.contains(&g) && added.insert(g) {
                b.spoints.push((g, c.at.clone()));
            }
        }
    }
}

/// Cards that define up to two elements or properties (fields 2-5 and 6-9; "one or
/// two ROD elements may be defined on a single card", COSMIC's CROD), or four (PMASS,
/// PDAMP: fields 2-3, 4-5, 6-7, 8-9): the fields of one.
fn per_card(name: &str) -> Option<usize> {
    match name {
        "CROD" | "CELAS3" | "CELAS4" | "CMASS3" | "CMASS4" | "CDAMP3" | "CDAMP4" | "PELAS" | "PQUAD2" | "PTRIA2"
        | "PQDMEM" | "PQDMEM1" | "PQDMEM2" | "PTRMEM" | "PSHEAR" | "CVISC" | "PVISC" => Some(4),
        "PMASS" | "PDAMP" => Some(2),
        _ => None,
    }
}

/// The cards one raw card stands for: one for each element or property written on a
/// card of several ([`per_card`]); a CBAR with its blank fields 3 and 6-9 taken from
/// BAROR ("the contents of fields on this card will be assumed for any CBAR card
/// whose corresponding fields are blank"); the card itself otherwise.
fn pieces<'a>(card: &'a RawCard, baror: Option<&RawCard>) -> Vec<std::borrow::Cow<'a, RawCard>> {
    use std::borrow::Cow;
    // COSMIC's PSHEAR holds two properties; MSC's, one with its F1 F2 (reals) after it.
    let msc_pshear =
        card.name == "PSHEAR" && parse_real(card.text(4)).is_some_and(|t| !matches!(t, RealToken::Integer(_)));
    if let Some(w) = per_card(&card.name).filter(|&w| card.fields.len() > w && !msc_pshear) {
        let first_line = card.fields.len().min(8);
        let mut out: Vec<RawCard> = (0..first_line)
            .step_by(w)
            .filter(|&k| {
                card.fields[k..(k + w).min(first_line)]
                    .iter()
                    .any(|f| !f.text.is_empty())
            })
            .map(|k| RawCard {
                fields: card.fields[k..(k + w).min(first_line)].to_vec(),
                ..card.clone()
            })
            .collect();
        // Continuation fields, if any, go to the last for its reader to refuse.
        if let Some(last) = out.last_mut() {
            last.fields.extend(card.fields.iter().skip(8).cloned());
        }
        return out.into_iter().map(Cow::Owned).collect();
    }
    match baror {
        Some(d) if card.name == "CBAR" => {
            let mut c = card.clone();
            let g0_given =
                parse_int(card.text(7)) == Some(2) || parse_int(d.text(7)) == Some(2) && card.text(7).is_empty();
            for k in [1, 4, 5, 6, 7] {
                if g0_given && (k == 5 || k == 6) {
                    continue;
                }
                if c.text(k).is_empty() && !d.text(k).is_empty() {
                    while c.fields.len() <= k {
                        c.fields.push(super::bulk::Field {
                            text: Default::default(),
                            pos: c.pos.clone(),
                            number: c.fields.len() % 8 + 2,
                        });
                    }
                    c.fields[k] = d.fields[k].clone();
                }
            }
            vec![Cow::Owned(c)]
        }
        _ => vec![Cow::Borrowed(card)],
    }
}

/// The parameters that choose coupled mass (NASTRAN-95 User's Manual, PARAM):
/// COUPMASS for every element that has it, the others each for one kind (active only
/// when COUPMASS is 0).
pub const COUPLED_MASS_PARAMS: [&str; 11] = [
    "COUPMASS", "CPBAR", "CPROD", "CPQUAD1", "CPQUAD2", "CPTRIA1", "CPTRIA2", "CPTUBE", "CPQDPLT", "CPTRPLT", "CPTRBSC",
];

/// PARAM: WTMASS, which scales every mass of the deck, COUPMASS and its per-element
/// parameters ([`COUPLED_MASS_PARAMS`]), and the damping parameters
/// ([`DampingParam`]) are read; any other is not used by impactlab and ignored with
/// a warning.
fn card_param(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
    if let Some(p) = DampingParam::of_name(r.word(0, "N")) {
        card_damping_param(r, b, p);
        return;
    }
    let name = r.text(0).to_ascii_uppercase();
    if COUPLED_MASS_PARAMS.contains(&name.as_str()) {
        let v = r.int(1, "V1");
        if r.ok {
            b.mass_params.push((name, v, r.at()));
        }
        return;
    }
    if r.text(0).eq_ignore_ascii_case("WTMASS") {
        let w = r.real_or(1, "V1", 1.0);
        r.positive(1, "V1", w);
        if r.ok {
            b.wtmass = Some((w, r.at()));
        }
        return;
    }
    r.diags.push(
        Diagnostic::warning(Some(card.pos.clone()), "PARAM cards are not used by impactlab; ignored")
            .card("PARAM")
            .quote(&card.source),
    );
}

impl Bulk {
    /// The PARAM card that asks for the coupled mass of the elements `param` governs
    /// ("CPROD": CROD and CONROD, "CPTUBE": CTUBE, "CPBAR": CBAR, ...), as NASTRAN-95
    /// reads them: a positive COUPMASS asks for it for every such element, a negative
    /// one or none for lumped masses (the default), and COUPMASS = 0 leaves it to
    /// `param`, positive for coupled (the last card of a name counts). `None`: lumped.
    pub fn coupled_mass(&self, param: &str) -> Option<&CardRef> {
        match self.mass_param("COUPMASS")? {
            (v, at) if v > 0 => Some(at),
            (0, _) => self.mass_param(param).filter(|(v, _)| *v > 0).map(|(_, at)| at),
            _ => None,
        }
    }

    /// The value and card of the deck's last PARAM `name` of [`COUPLED_MASS_PARAMS`].
    pub fn mass_param(&self, name: &str) -> Option<(i64, &CardRef)> {
        self.mass_params
            .iter()
            .rev()
            .find(|(n, _, _)| n == name)
            .map(|(_, v, at)| (*v, at))
    }

    /// Multiplies every term of the mass by PARAM WTMASS, as NASTRAN does ("the terms
    /// of the structural mass matrix are multiplied by the value of this parameter"):
    /// the materials' densities, the properties' non-structural masses and the
    /// concentrated masses and inertias.
    fn scale_masses(&mut self, w: f64) {
        for m in &mut self.mat1s {
            m.rho *= w;
        }
        for m in &mut self.mat2s {
            m.rho *= w;
        }
        for m in &mut self.mat8s {
            m.rho *= w;
        }
        for p in self
            .prods
            .iter_mut()
            .chain(self.elements.iter_mut().filter_map(|c| c.rod.as_deref_mut()))
        {
            p.nsm *= w;
        }
        for p in &mut self.bar_properties {
            p.nsm *= w;
        }
        for p in self
            .pshells
            .iter_mut()
            .chain(self.cosmic_plates.iter_mut().map(|(_, p)| p))
        {
            p.nsm *= w;
        }
        for p in &mut self.pcomps {
            p.nsm *= w;
        }
        for p in &mut self.pmass {
            p.value *= w;
        }
        for c in self.scalars.iter_mut().filter(|c| c.role == ScalarRole::Mass) {
            if let ScalarValue::Value(m) = &mut c.value {
                *m *= w;
            }
        }
        for c in &mut self.conm1s {
            for m in &mut c.lower {
                *m *= w;
            }
        }
        for c in &mut self.conm2s {
            c.mass *= w;
            for i in &mut c.inertia {
                *i *= w;
            }
        }
    }
}

/// The card fields reference page (`docs/src/reference/card-fields.md`): every card
/// the reader types, with the fields [`fields_read`] finds it reading; a field whose
/// name was met before on the card ends the table with the fields repeated from there.
pub fn fields_markdown() -> String {
    use std::fmt::Write;
    let at = |k: usize| format!("{}.{}", k / 8 + 1, k % 8 + 2);
    let mut out = String::from(FIELDS_PAGE_HEAD);
    for name in supported() {
        let read = fields_read(name).unwrap_or_default();
        let _ = writeln!(out, "## {name}\n");
        if read.is_empty() {
            let _ = writeln!(out, "No field is read on a blank card (see [Decks](decks.md)).\n");
            continue;
        }
        let _ = writeln!(out, "| field | name | holds | blank |\n|---|---|---|---|");
        for (i, f) in read.iter().enumerate() {
            if let Some(first) = read[..i].iter().position(|g| g.name == f.name) {
                let names: Vec<&str> = read[first..i].iter().map(|g| g.name.as_str()).collect();
                let _ = writeln!(out, "| {} … | {} | repeated | |", at(f.k), names.join(", "));
                break;
            }
            let kind = match f.kind {
                FieldKind::Integer => "integer",
                FieldKind::Id => "id (> 0)",
                FieldKind::Real => "real",
                FieldKind::Components => "components (1-6)",
                FieldKind::Component => "component (0-6)",
                FieldKind::Ids => "ids to the card's end (THRU)",
                FieldKind::Word => "word",
            };
            let blank = match &f.blank {
                Blank::Refused => "required".to_string(),
                Blank::Default(v) => format!("`{v}`"),
                Blank::As(name) => format!("{name}'s"),
                Blank::Absent => "—".to_string(),
            };
            let _ = writeln!(out, "| {} | {} | {kind} | {blank} |", at(f.k), f.name);
        }
        out.push('\n');
    }
    out
}

/// The head of [`fields_markdown`]'s page.
const FIELDS_PAGE_HEAD: &str = "# Card fields\n\n\
Every bulk data card the reader types, with the fields its reader reads: the field as \
*line.field* (1.2 is field 2 of the card's first line, 2.2 the first data field of its first \
continuation), the name the reader's messages give it, what it holds, and what a blank \
field means: `required` (a blank is an error), the value taken, or — (the reader \
decides from the card's other fields, or leaves the field's meaning out). This page is \
generated from the reader itself (`impactlab reference cards > docs/src/reference/card-fields.md`), \
which is run on each card with its first two lines blank and again with each field \
holding its own number, and `tests/book.rs` fails when it differs. What the program does with each card, \
and what it refuses, is in [Decks](decks.md). Not listed: fields read only when \
another holds some other value, and groups a card's reader parses itself: a PBARL's \
dimensions (its TYPE names them), a TABLED's entries to its ENDT, an RBE3's weighted \
groups, a PBUSH's lines after their flag (K, B, GE), a PARAM's values (its name decides \
them).\n\n";
