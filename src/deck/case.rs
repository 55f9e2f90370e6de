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
    /// Solution sequence (SOL): a direct transient one, or 101 for a linear static
    /// one (SOL 1, 101, SESTATIC, STATICS).
    pub sol: Option<u32>,
    /// The SOL statement's solution as written (`101`, `SESTATIC`).
    pub solution: Option<String>,
    /// TIME statement's text.
    pub time_limit: Option<String>,
}

/// Solution sequences that mean direct transient response.
pub const DIRECT_TRANSIENT_SOLS: [u32; 4] = [9, 27, 109, 129];

/// The solution number of linear statics, as [`Executive::sol`] holds it for SOL 1,
/// 101, SESTATIC and STATICS.
pub const STATICS: u32 = 101;

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
    /// Member ids.
    pub members: Vec<i64>,
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
    /// Output requests by keyword: NLLOAD, DISP, VELO, ACCEL, STRESS, STRAIN, FORCE,
    /// ELFORCE.
    pub outputs: BTreeMap<String, OutputRequest>,
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
                    Some(n) => diags.push(
                        Diagnostic::error(
                            Some(l.pos(1)),
                            format!(
                                "SOL {n} is not supported: only direct transient response (SOL 9, 27, 109, 129) and \
                                 linear statics (SOL 101)"
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
                        } else {
                            diags.push(
                                Diagnostic::error(
                                    Some(l.pos(1)),
                                    "is not a supported solution sequence (SOL 9, 27, 109, 129; SOL 101)",
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

/// Parses a comma/space separated id list with THRU ranges, as in SET and SPC1.
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
    while i < toks.len() {
        let t = &toks[i];
        if t == "THRU" {
            let (a, b) = (out.last().copied(), toks.get(i + 1).and_then(|s| parse_int(s)));
            match (a, b) {
                (Some(a), Some(b)) if b >= a => {
                    if let Err(e) = super::take_ids(ids_left, (b as i128 - a as i128) as u128) {
                        diags.push(error(e));
                        return out;
                    }
                    out.extend(a + 1..=b)
                }
                (Some(a), Some(b)) => diags.push(error(format!("THRU range {a} THRU {b} is reversed"))),
                _ => diags.push(error("THRU needs an integer on each side".into())),
            }
            i += 2;
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

const SELECTORS: [&str; 6] = ["SPC", "IC", "NONLINEAR", "TSTEP", "TFL", "LOAD"];
const OUTPUTS: [&str; 8] = [
    "NLLOAD", "DISP", "VELO", "ACCEL", "STRESS", "STRAIN", "FORCE", "ELFORCE",
];
const IGNORED: [&str; 6] = ["ECHO", "LINE", "MAXLINES", "OUTPUT", "OLOAD", "SPCFORCE"];

/// How case control takes SUBCASE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Subcases {
    /// A transient deck: one case, no SUBCASE.
    None,
    /// A static deck: at most one SUBCASE, whose selections are the deck's.
    One,
    /// A deck read for its structure alone: any, their SPC selections read as the deck's.
    Any,
}

/// Reads case control from its lines; findings go to `diags`; `ids_left` is what
/// remains of [`super::Limits::max_listed_ids`]; `subcases` says how SUBCASE is taken.
pub fn parse_case(lines: &[SrcLine], subcases: Subcases, ids_left: &mut usize, diags: &mut Diagnostics) -> CaseControl {
    let mut cc = CaseControl::default();
    let mut first_subcase: Option<Pos> = None;
    let mut i = 0;
    while i < lines.len() {
        let l = &lines[i];
        i += 1;
        let t = l.text.trim();
        let pos = l.pos(1);
        if t.split_whitespace()
            .next()
            .is_some_and(|w| w.eq_ignore_ascii_case("SUBCASE"))
        {
            subcase(subcases, &mut first_subcase, pos, &l.text, diags);
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
            [k] if OUTPUTS.contains(k) => output_request(&mut cc, k, &rhs, pos, &l.text, diags),
            ["SUBCASE"] | ["SUBCASE", ..] => subcase(subcases, &mut first_subcase, pos, &l.text, diags),
            [k] if IGNORED.contains(k) => diags.push(
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
    check_output_sets(&cc, diags);
    cc
}

/// A SUBCASE line, taken as `subcases` says; `first` is where the first one was.
fn subcase(subcases: Subcases, first: &mut Option<Pos>, pos: Pos, text: &str, diags: &mut Diagnostics) {
    let refuse = |message: String| {
        Diagnostic::error(Some(pos.clone()), message)
            .card("SUBCASE")
            .quote(text)
    };
    match (subcases, &first) {
        (Subcases::Any, _) => {}
        (Subcases::One, None) => *first = Some(pos),
        (Subcases::One, Some(at)) => diags.push(refuse(format!(
            "a second SUBCASE (the first at {at}): impactlab solves one static load case a deck; give each its own \
             deck"
        ))),
        (Subcases::None, _) => diags.push(refuse("SUBCASE is not supported: one transient case per deck".into())),
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
    let members = parse_id_list(rhs, &pos, src, ids_left, diags);
    let def = SetDef {
        members,
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

/// `SPC = n`, `IC = n`, `NONLINEAR = n`, `TSTEP = n`, `TFL = n`.
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

/// Every set named by an output request must exist.
fn check_output_sets(cc: &CaseControl, diags: &mut Diagnostics) {
    for (k, req) in &cc.outputs {
        if let OutputSet::Set(id) = req.set {
            if !cc.sets.contains_key(&id) {
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
