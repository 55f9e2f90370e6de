//! Executive control and case control.

use super::diag::{Diagnostic, Diagnostics, Pos};
use super::number::parse_int;
use super::source::SrcLine;
use std::collections::BTreeMap;

/// Executive control: only what decides the analysis.
#[derive(Debug, Clone, Default)]
pub struct Executive {
    /// ID statement's text.
    pub id: Option<String>,
    /// Solution sequence (SOL): a direct transient one, 101 for a linear static one
    /// (SOL 1, 101, SESTATIC, STATICS) or 103 for normal modes (SOL 3, 103, SEMODES,
    /// MODES).
    pub sol: Option<u32>,
    /// The SOL statement's solution as written (`101`, `SESTATIC`).
    pub solution: Option<String>,
    /// TIME statement's text.
    pub time_limit: Option<String>,
    /// The statement that makes the deck a restart (`NASTRAN FILES = OPTP`: the old
    /// problem tape of an earlier run holds its structure), with where it is.
    pub restart: Option<(String, Pos)>,
    /// A DMAP alter's call of NASTRAN's INPUT module, which generates the structure
    /// (grids, elements, constraints) from parameters, with where it is.
    pub generated: Option<(String, Pos)>,
}

/// Solution sequences that mean direct transient response.
pub const DIRECT_TRANSIENT_SOLS: [u32; 4] = [9, 27, 109, 129];

/// The solution number of linear statics, as [`Executive::sol`] holds it for SOL 1,
/// 101, SESTATIC and STATICS.
pub const STATICS: u32 = 101;

/// The solution number impactlab keeps for normal modes: NASTRAN-95's SOL 3, MSC's
/// 103, SEMODES and MODES.
pub const MODES: u32 = 103;

/// A case-control selection with where it was written.
#[derive(Debug, Clone)]
pub struct Selection {
    /// The selected set id.
    pub id: i64,
    /// Where the selection is written.
    pub pos: Pos,
}

/// What an output request selects.
#[derive(Debug, Clone, PartialEq)]
pub enum OutputSet {
    /// `= ALL`.
    All,
    /// `= NONE`.
    None,
    /// `= n`: case-control SET n.
    Set(i64),
}

/// An output request (`DISP = 15`).
#[derive(Debug, Clone)]
pub struct OutputRequest {
    /// What it selects.
    pub set: OutputSet,
    /// Where it is written.
    pub pos: Pos,
}

/// A case-control SET: its members (THRU ranges expanded).
#[derive(Debug, Clone)]
pub struct SetDef {
    /// Member ids (empty for `SET n = ALL`).
    pub members: Vec<i64>,
    /// `SET n = ALL`: every point or element.
    pub all: bool,
    /// Where the SET is written.
    pub pos: Pos,
}

/// Case control: titles, sets, selections and output requests.
#[derive(Debug, Clone, Default)]
pub struct CaseControl {
    /// Where case control ends (its last line), for errors about what it lacks.
    pub at: Option<Pos>,
    /// TITLE.
    pub title: String,
    /// SUBTITLE.
    pub subtitle: String,
    /// LABEL.
    pub label: String,
    /// SET definitions by id.
    pub sets: BTreeMap<i64, SetDef>,
    /// SPC selection.
    pub spc: Option<Selection>,
    /// IC selection (TIC cards).
    pub ic: Option<Selection>,
    /// NONLINEAR selection (NOLIN3 cards).
    pub nonlinear: Option<Selection>,
    /// TSTEP selection.
    pub tstep: Option<Selection>,
    /// TFL selection (TF cards).
    pub tfl: Option<Selection>,
    /// LOAD selection (the static loads of a SOL 101 deck).
    pub load: Option<Selection>,
    /// METHOD selection (the EIGR or EIGRL of a normal modes deck).
    pub method: Option<Selection>,
    /// DLOAD selection (the TLOAD1, TLOAD2 or DLOAD of a transient deck's dynamic load).
    pub dload: Option<Selection>,
    /// LOADSET selection (the LSEQ cards that give static load sets as the dynamic
    /// loads' distributions).
    pub loadset: Option<Selection>,
    /// Output requests by keyword: NLLOAD, DISP, VELO, ACCEL, STRESS, STRAIN, FORCE,
    /// ELFORCE (NASTRAN's longer names and synonyms read as these).
    pub outputs: BTreeMap<String, OutputRequest>,
    /// Output requests of quantities impactlab does not write (SPCFORCES, OLOAD,
    /// ESE ...), with where each is asked for.
    pub not_written: Vec<(String, Pos)>,
    /// A static deck's SUBCASEs, in deck order, each with the LOAD, SPC, TEMPERATURE
    /// and LABEL it selects (its own, or those above the first SUBCASE); empty when it
    /// has none. The deck's `load`, `spc`, `temperature` and `label` are then the
    /// first one's.
    pub subcases: Vec<Subcase>,
    /// The temperature set of a thermal load: TEMPERATURE(LOAD) (or TEMP(LOAD),
    /// TEMPERATURE(BOTH)) = n.
    pub temperature: Option<Selection>,
    /// The `SUBSTRUCTURE PHASEn` line that opens an automated substructuring run's
    /// Substructure Control Deck (to ENDSUBS), with where it is.
    pub substructuring: Option<(String, Pos)>,
}

/// One SUBCASE of a static deck: a load case.
#[derive(Debug, Clone)]
pub struct Subcase {
    /// Its number (SUBCASE n).
    pub id: i64,
    /// LABEL.
    pub label: String,
    /// LOAD selection.
    pub load: Option<Selection>,
    /// SPC selection.
    pub spc: Option<Selection>,
    /// TEMPERATURE(LOAD) selection (its own, or the one above the first SUBCASE).
    pub temperature: Option<Selection>,
    /// Where its SUBCASE line is.
    pub pos: Pos,
}

/// Reads executive control (ID, SOL, TIME) from its lines; for a deck read for its
/// structure alone (`structure`), any SOL, or none, is accepted.
pub fn parse_executive(lines: &[SrcLine], structure: bool, diags: &mut Diagnostics) -> Executive {
    let mut e = Executive::default();
    for l in lines {
        let t = l.text.trim();
        // `ID A,B`, and `ID,A,B` as some writers put it.
        let mut words = t.splitn(2, |c: char| c.is_whitespace() || c == ',');
        let key = words.next().unwrap_or("").to_ascii_uppercase();
        let rest = words.next().unwrap_or("").trim();
        match key.as_str() {
            "ID" => e.id = Some(rest.to_string()),
            "TIME" => e.time_limit = Some(rest.to_string()),
            "SOL" => {
                let word = rest.split([' ', ',']).next().unwrap_or("");
                e.solution = Some(word.to_string());
                if structure {
                    continue;
                }
                match parse_int(word) {
                    Some(n) if DIRECT_TRANSIENT_SOLS.contains(&(n as u32)) => e.sol = Some(n as u32),
                    Some(1 | 101) => e.sol = Some(STATICS),
                    Some(3 | 103) => e.sol = Some(MODES),
                    Some(n) => diags.push(
                        Diagnostic::error(
                            Some(l.pos(1)),
                            format!(
                                "SOL {n} is not supported: only direct transient response (SOL 9, 27, 109, 129), \
                                 linear statics (SOL 101) and normal modes (SOL 103)"
                            ),
                        )
                        .card("SOL")
                        .quote(&l.text),
                    ),
                    None => {
                        let up = word.to_ascii_uppercase();
                        if up == "SEDTRAN" || up == "NLTRAN" {
                            e.sol = Some(109);
                        } else if up == "SESTATIC" || up == "STATICS" {
                            e.sol = Some(STATICS);
                        } else if up == "SEMODES" || up == "MODES" {
                            e.sol = Some(MODES);
                        } else {
                            diags.push(
                                Diagnostic::error(
                                    Some(l.pos(1)),
                                    "is not a supported solution sequence (SOL 9, 27, 109, 129; SOL 101; SOL 103)",
                                )
                                .card("SOL")
                                .token(word)
                                .quote(&l.text),
                            )
                        }
                    }
                }
            }
            "APP" | "DIAG" | "CHKPNT" | "ECHOON" | "ECHOOFF" => {}
            "INPUT" => e.generated = Some((t.to_string(), l.pos(1))),
            "NASTRAN" if rest.to_ascii_uppercase().contains("OPTP") => {
                e.restart = Some((t.to_string(), l.pos(1)));
            }
            _ => diags.push(
                Diagnostic::warning(Some(l.pos(1)), "unknown executive control statement, ignored")
                    .token(&key)
                    .quote(&l.text),
            ),
        }
    }
    if e.sol.is_none() && !structure && !diags.has_errors() {
        diags.push(Diagnostic::error(
            lines.first().map(|l| l.pos(1)),
            "executive control has no SOL statement (direct transient: SOL 9, 27, 109 or 129; linear statics: SOL 101)",
        ));
    }
    e
}

/// Parses a comma/space separated id list as a case-control SET writes it: ids,
/// `a THRU b`, `a THRU b BY k`, and `EXCEPT` after a range, which leaves out the ids
/// that follow it as long as they fall in that range (CASE.TXT, SET: "EXCEPT ...
/// deletes" the listed members from the preceding THRU range).
fn parse_id_list(text: &str, pos: &Pos, src: &str, ids_left: &mut usize, diags: &mut Diagnostics) -> Vec<i64> {
    let toks: Vec<String> = text
        .split([',', ' '])
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(str::to_ascii_uppercase)
        .collect();
    let mut out = Vec::new();
    let mut i = 0;
    let error = |message: String| Diagnostic::error(Some(pos.clone()), message).card("SET").quote(src);
    // The last THRU range, for EXCEPT.
    let mut range: Option<(i64, i64)> = None;
    while i < toks.len() {
        let t = &toks[i];
        if t == "THRU" {
            let (a, b) = (out.last().copied(), toks.get(i + 1).and_then(|s| parse_int(s)));
            i += 2;
            let step = if toks.get(i).is_some_and(|t| t == "BY") {
                i += 2;
                toks.get(i - 1).and_then(|s| parse_int(s)).filter(|&k| k > 0)
            } else {
                Some(1)
            };
            match (a, b, step) {
                (Some(a), Some(b), Some(k)) if b >= a => {
                    if let Err(e) = super::take_ids(ids_left, ((b as i128 - a as i128) / k as i128) as u128) {
                        diags.push(error(e));
                        return out;
                    }
                    out.extend((a + k..=b).step_by(k as usize));
                    range = Some((a, b));
                }
                (Some(a), Some(b), Some(_)) => diags.push(error(format!("THRU range {a} THRU {b} is reversed"))),
                (_, _, None) => diags.push(error("BY needs a positive integer step after it".into())),
                _ => diags.push(error("THRU needs an integer on each side".into())),
            }
            continue;
        }
        if t == "EXCEPT" {
            let Some((a, b)) = range else {
                diags.push(error("EXCEPT follows no THRU range".into()));
                return out;
            };
            i += 1;
            let mut leave = Vec::new();
            while let Some(v) = toks.get(i).and_then(|s| parse_int(s)).filter(|v| (a..=b).contains(v)) {
                if toks.get(i + 1).is_some_and(|t| t == "THRU") {
                    let end = toks.get(i + 2).and_then(|s| parse_int(s)).unwrap_or(v).min(b);
                    leave.extend(v..=end);
                    i += 3;
                } else {
                    leave.push(v);
                    i += 1;
                }
            }
            out.retain(|m| !((a..=b).contains(m) && leave.contains(m)));
            range = None;
            continue;
        }
        match parse_int(t) {
            Some(v) => {
                if let Err(e) = super::take_ids(ids_left, 1) {
                    diags.push(error(e));
                    return out;
                }
                out.push(v)
            }
            None => diags.push(
                Diagnostic::error(Some(pos.clone()), "is not an integer set member")
                    .card("SET")
                    .token(t)
                    .quote(src),
            ),
        }
        i += 1;
    }
    out
}

const SELECTORS: [&str; 9] = [
    "SPC",
    "IC",
    "NONLINEAR",
    "TSTEP",
    "TFL",
    "LOAD",
    "METHOD",
    "DLOAD",
    "LOADSET",
];

/// Output requests impactlab writes: NASTRAN's name, and the key it is kept under.
/// A request may be written by any abbreviation of its name of four letters or more
/// (CASE.TXT: "the first four characters ... are sufficient").
const OUTPUTS: [(&str, &str); 10] = [
    ("NLLOAD", "NLLOAD"),
    ("DISPLACEMENT", "DISP"),
    ("VELOCITY", "VELO"),
    ("ACCELERATION", "ACCEL"),
    ("STRESS", "STRESS"),
    ("ELSTRESS", "STRESS"),
    ("STRAIN", "STRAIN"),
    ("ELSTRAIN", "STRAIN"),
    ("FORCE", "FORCE"),
    ("ELFORCE", "ELFORCE"),
];

/// Output requests of quantities impactlab does not write: listed as not written,
/// never dropped in silence.
const NOT_WRITTEN: [&str; 22] = [
    "SPCFORCES",
    "MPCFORCES",
    "OLOAD",
    "ESE",
    "EKE",
    "EDE",
    "GPKE",
    "GPFORCE",
    "GPSTRESS",
    "STRFIELD",
    "SDISPLACEMENT",
    "SVELOCITY",
    "SACCELERATION",
    "NOUTPUT",
    "BOUTPUT",
    "THERMAL",
    "FLUX",
    "PRESSURE",
    "ELSDCON",
    "GPSDCON",
    "AEROF",
    "APRESSURE",
];

/// Commands that change nothing impactlab computes: printing and paging controls.
const IGNORED: [&str; 8] = ["ECHO", "LINE", "MAXLINES", "OUTPUT", "PLOTID", "PAGE", "SKIP", "SORT"];

/// The NASTRAN name `word` abbreviates (four letters at least) among `names`.
fn abbreviates<'a>(word: &str, names: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let word = word.trim();
    names
        .into_iter()
        .find(|n| *n == word || (word.len() >= 4 && n.starts_with(word)))
}

/// The key an output request's keyword is kept under, if impactlab writes it.
fn output_key(word: &str) -> Option<&'static str> {
    // Exact names first: ELSTRESS is not an abbreviation of ELSTRAIN.
    let exact = OUTPUTS.iter().find(|(n, _)| *n == word);
    let short = || OUTPUTS.iter().find(|(n, _)| word.len() >= 4 && n.starts_with(word));
    // Keys as they were always written here (ACCEL, DISP, VELO).
    let key = OUTPUTS.iter().find(|(_, k)| *k == word);
    exact.or(key).or_else(short).map(|(_, k)| *k)
}

/// The line without a `$` comment (a title keeps its text whole).
fn without_comment(t: &str) -> &str {
    let up = t.trim_start().to_ascii_uppercase();
    if ["TITLE", "SUBTITLE", "SUBTI", "LABEL"]
        .iter()
        .any(|k| up.starts_with(k) && up[k.len()..].trim_start().starts_with('='))
    {
        return t;
    }
    t.split('$').next().unwrap_or("")
}

/// `OUTPUT(PLOT)`, `OUTPUT(XYPLOT)`, `OUTPUT(XYOUT)`: the plotting packages, which run
/// to the end of case control.
fn is_plot_section(t: &str) -> bool {
    let up: String = t
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    ["OUTPUT(PLOT)", "OUTPUT(XYPLOT)", "OUTPUT(XYOUT)", "OUTPUT(XYPLOTS)"].contains(&up.as_str())
}

/// How case control takes SUBCASE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Subcases {
    /// A transient deck: one case, no SUBCASE.
    None,
    /// A static deck: each SUBCASE a load case ([`CaseControl::subcases`]).
    Static,
    /// A deck read for its structure alone: any, their SPC selections read as the deck's.
    Any,
}

/// Reads case control from its lines; findings go to `diags`; `ids_left` is what
/// remains of [`super::Limits::max_listed_ids`]; `subcases` says how SUBCASE is taken.
pub fn parse_case(lines: &[SrcLine], subcases: Subcases, ids_left: &mut usize, diags: &mut Diagnostics) -> CaseControl {
    let mut cc = CaseControl::default();
    // A static deck's selections above its first SUBCASE, which every SUBCASE starts
    // from, and the SUBCASE being read.
    let mut above: Option<Above> = None;
    let mut open: Option<(i64, Pos)> = None;
    let mut i = 0;
    while i < lines.len() {
        let l = &lines[i];
        i += 1;
        let t = without_comment(&l.text).trim();
        let pos = l.pos(1);
        if t.is_empty() {
            continue;
        }
        if is_plot_section(t) {
            diags.push(
                Diagnostic::warning(
                    Some(pos),
                    format!(
                        "the plotting section ({} lines to BEGIN BULK) is skipped: impactlab draws its own figures",
                        lines.len() - i + 1
                    ),
                )
                .quote(&l.text),
            );
            break;
        }
        if t.split_whitespace()
            .next()
            .is_some_and(|w| w.eq_ignore_ascii_case("SUBSTRUCTURE"))
        {
            // The Substructure Control Deck runs to ENDSUBS.
            let end = lines[i..]
                .iter()
                .position(|l| {
                    let w = without_comment(&l.text).split_whitespace().next().unwrap_or("");
                    w.eq_ignore_ascii_case("ENDSUBS")
                })
                .map_or(lines.len(), |k| i + k + 1);
            diags.push(
                Diagnostic::warning(
                    Some(pos.clone()),
                    format!(
                        "the Substructure Control Deck ({} lines to ENDSUBS) is skipped",
                        end - i + 1
                    ),
                )
                .quote(&l.text),
            );
            cc.substructuring = Some((t.to_string(), pos));
            i = end;
            continue;
        }
        if t.split_whitespace()
            .next()
            .is_some_and(|w| w.eq_ignore_ascii_case("SUBCASE"))
        {
            subcase(subcases, &mut cc, &mut above, &mut open, pos, &l.text, diags);
            continue;
        }
        let Some(eq) = t.find('=') else {
            diags.push(Diagnostic::warning(Some(l.pos(1)), "case control line without '=' is ignored").quote(&l.text));
            continue;
        };
        let lhs = t[..eq].trim();
        let mut rhs = t[eq + 1..].trim().to_string();
        let key_full = lhs.to_ascii_uppercase();
        let key = key_full.split('(').next().unwrap_or("").trim().to_string();
        let words: Vec<&str> = key.split_whitespace().collect();
        match words.as_slice() {
            ["TITLE"] => cc.title = rhs,
            ["SUBTITLE"] | ["SUBTI"] => cc.subtitle = rhs,
            ["LABEL"] => cc.label = rhs,
            ["SET", n] => {
                // A SET continues on the lines after one that ends with a comma.
                let mut src = l.text.clone();
                while rhs.trim_end().ends_with(',') && i < lines.len() {
                    rhs.push_str(lines[i].text.trim());
                    src.push('\n');
                    src.push_str(&lines[i].text);
                    i += 1;
                }
                set_definition(&mut cc, n, &rhs, &src, pos, ids_left, diags);
            }
            [k] if SELECTORS.contains(k) => selector(&mut cc, k, &rhs, pos, &l.text, diags),
            ["TEMPERATURE"] | ["TEMP"] => temperature(&mut cc, &key_full, &rhs, pos, &l.text, diags),
            [k] if output_key(k).is_some() => {
                let key = output_key(k).expect("matched");
                output_request(&mut cc, key, &rhs, pos, &l.text, diags)
            }
            ["SUBCASE"] | ["SUBCASE", ..] => subcase(subcases, &mut cc, &mut above, &mut open, pos, &l.text, diags),
            [k] if abbreviates(k, NOT_WRITTEN).is_some() => {
                let name = abbreviates(k, NOT_WRITTEN).expect("matched");
                diags.push(
                    Diagnostic::warning(Some(pos.clone()), format!("{name} is not written by impactlab"))
                        .card(k)
                        .quote(&l.text),
                );
                cc.not_written.push((name.to_string(), pos));
            }
            [k] if abbreviates(k, IGNORED).is_some() => diags.push(
                Diagnostic::warning(Some(pos), "case control request is not supported and is ignored")
                    .card(k)
                    .quote(&l.text),
            ),
            _ => diags.push(
                Diagnostic::warning(Some(pos), "unknown case control command, ignored")
                    .token(lhs)
                    .quote(&l.text),
            ),
        }
    }
    close_subcase(&mut cc, &mut open);
    if let Some(first) = cc.subcases.first() {
        (cc.label, cc.load, cc.spc, cc.temperature) = (
            first.label.clone(),
            first.load.clone(),
            first.spc.clone(),
            first.temperature.clone(),
        );
    }
    check_output_sets(&mut cc, diags);
    cc
}

/// A static deck's selections above its first SUBCASE: LABEL, LOAD, SPC and
/// TEMPERATURE(LOAD).
type Above = (String, Option<Selection>, Option<Selection>, Option<Selection>);

/// A SUBCASE line, taken as `subcases` says: in a static deck it ends the SUBCASE
/// being read (`open`) and starts the next from the selections `above` the first.
fn subcase(
    subcases: Subcases,
    cc: &mut CaseControl,
    above: &mut Option<Above>,
    open: &mut Option<(i64, Pos)>,
    pos: Pos,
    text: &str,
    diags: &mut Diagnostics,
) {
    let refuse = |message: String| {
        Diagnostic::error(Some(pos.clone()), message)
            .card("SUBCASE")
            .quote(text)
    };
    match subcases {
        Subcases::Any => {}
        Subcases::None => diags.push(refuse("SUBCASE is not supported: one transient case per deck".into())),
        Subcases::Static => {
            let id = without_comment(text).split_whitespace().nth(1).and_then(parse_int);
            let Some(id) = id.filter(|&n| n > 0) else {
                diags.push(refuse(
                    "SUBCASE needs its number, a positive integer (SUBCASE 1)".into(),
                ));
                return;
            };
            close_subcase(cc, open);
            if let Some(s) = cc.subcases.iter().find(|s| s.id == id) {
                diags.push(refuse(format!("SUBCASE {id} is given twice (first at {})", s.pos)));
                return;
            }
            let (label, load, spc, temperature) = above
                .get_or_insert_with(|| {
                    (
                        cc.label.clone(),
                        cc.load.clone(),
                        cc.spc.clone(),
                        cc.temperature.clone(),
                    )
                })
                .clone();
            (cc.label, cc.load, cc.spc, cc.temperature) = (label, load, spc, temperature);
            *open = Some((id, pos));
        }
    }
}

/// Ends the SUBCASE being read: its selections join [`CaseControl::subcases`].
fn close_subcase(cc: &mut CaseControl, open: &mut Option<(i64, Pos)>) {
    if let Some((id, pos)) = open.take() {
        cc.subcases.push(Subcase {
            id,
            label: cc.label.clone(),
            load: cc.load.clone(),
            spc: cc.spc.clone(),
            temperature: cc.temperature.clone(),
            pos,
        });
    }
}

/// `SET n = …`: the set's members (its lines joined in `src`).
fn set_definition(
    cc: &mut CaseControl,
    n: &str,
    rhs: &str,
    src: &str,
    pos: Pos,
    ids_left: &mut usize,
    diags: &mut Diagnostics,
) {
    let Some(id) = parse_int(n) else {
        diags.push(
            Diagnostic::error(Some(pos), "is not a set number")
                .card("SET")
                .token(n)
                .quote(src),
        );
        return;
    };
    let all = rhs.trim().eq_ignore_ascii_case("ALL");
    let members = if all {
        Vec::new()
    } else {
        parse_id_list(rhs, &pos, src, ids_left, diags)
    };
    let def = SetDef {
        members,
        all,
        pos: pos.clone(),
    };
    if cc.sets.insert(id, def).is_some() {
        diags.push(
            Diagnostic::error(Some(pos), format!("SET {id} is defined twice"))
                .card("SET")
                .quote(src),
        );
    }
}

/// `SPC = n`, `IC = n`, `NONLINEAR = n`, `TSTEP = n`, `TFL = n`, `LOAD = n`, `METHOD = n`,
/// `DLOAD = n`, `LOADSET = n`.
fn selector(cc: &mut CaseControl, k: &str, rhs: &str, pos: Pos, text: &str, diags: &mut Diagnostics) {
    match parse_int(rhs) {
        Some(id) => {
            let sel = Some(Selection { id, pos });
            match k {
                "SPC" => cc.spc = sel,
                "IC" => cc.ic = sel,
                "NONLINEAR" => cc.nonlinear = sel,
                "TSTEP" => cc.tstep = sel,
                "LOAD" => cc.load = sel,
                "METHOD" => cc.method = sel,
                "DLOAD" => cc.dload = sel,
                "LOADSET" => cc.loadset = sel,
                _ => cc.tfl = sel,
            }
        }
        None => diags.push(
            Diagnostic::error(Some(pos), "is not a set identification number")
                .card(k)
                .token(rhs)
                .quote(text),
        ),
    }
}

/// `TEMPERATURE(LOAD) = n` (TEMP, BOTH alike): the thermal load's temperature set.
/// TEMPERATURE(MATERIAL) selects temperatures for temperature-dependent materials,
/// which impactlab does not take (MATTi tables are refused where a deck has
/// temperatures): it is ignored, with a warning.
fn temperature(cc: &mut CaseControl, key: &str, rhs: &str, pos: Pos, text: &str, diags: &mut Diagnostics) {
    let describer: String = key
        .split_once('(')
        .map(|(_, d)| d.trim_end_matches(')').trim().to_string())
        .unwrap_or_else(|| "BOTH".into());
    let card = key.split('(').next().unwrap_or("TEMPERATURE").trim();
    // As NASTRAN-95 reads a describer, by its first four characters (its own
    // demonstration deck d01161a writes MATERIALS).
    match describer.get(..4).unwrap_or(&describer) {
        "LOAD" | "BOTH" => match parse_int(rhs) {
            Some(id) => cc.temperature = Some(Selection { id, pos }),
            None => diags.push(
                Diagnostic::error(Some(pos), "is not a temperature set identification number")
                    .card(card)
                    .token(rhs)
                    .quote(text),
            ),
        },
        "MATE" => diags.push(
            Diagnostic::warning(
                Some(pos),
                "temperatures for temperature-dependent materials are not used by impactlab; ignored",
            )
            .card(card)
            .quote(text),
        ),
        other => diags.push(
            Diagnostic::error(Some(pos), "is not LOAD, MATERIAL or BOTH")
                .card(card)
                .token(other)
                .quote(text),
        ),
    }
}

/// `DISP = ALL | NONE | n` and the other output requests.
fn output_request(cc: &mut CaseControl, k: &str, rhs: &str, pos: Pos, text: &str, diags: &mut Diagnostics) {
    let up = rhs.to_ascii_uppercase();
    let set = match up.as_str() {
        "ALL" => Some(OutputSet::All),
        "NONE" => Some(OutputSet::None),
        _ => parse_int(&up).map(OutputSet::Set),
    };
    match set {
        Some(set) => {
            cc.outputs.insert(k.to_string(), OutputRequest { set, pos });
        }
        None => diags.push(
            Diagnostic::error(Some(pos), "is not ALL, NONE or a set number")
                .card(k)
                .token(rhs)
                .quote(text),
        ),
    }
}

/// Every set named by an output request must exist; a request of a `SET n = ALL`
/// is a request of ALL.
fn check_output_sets(cc: &mut CaseControl, diags: &mut Diagnostics) {
    for (k, req) in &mut cc.outputs {
        if let OutputSet::Set(id) = req.set {
            if cc.sets.get(&id).is_some_and(|s| s.all) {
                req.set = OutputSet::All;
            } else if !cc.sets.contains_key(&id) {
                diags.push(
                    Diagnostic::error(
                        Some(req.pos.clone()),
                        format!("names SET {id}, which case control does not define"),
                    )
                    .card(k),
                );
            }
        }
    }
}

/// The `&'static str` among `names` equal to `name` (the first of them otherwise).
pub(crate) fn static_name(name: &str, names: &[&'static str]) -> &'static str {
    names.iter().find(|n| **n == name).copied().unwrap_or(names[0])
}
