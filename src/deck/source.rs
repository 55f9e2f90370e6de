//! Reading deck files: INCLUDE expansion and the split into executive control,
//! case control and bulk data.

use super::diag::{Diagnostic, Diagnostics, Pos};
use super::Limits;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One physical line of a deck with where it came from.
#[derive(Debug, Clone)]
pub struct SrcLine {
    /// The file as named when read.
    pub file: Arc<str>,
    /// Line, from 1.
    pub line: usize,
    /// The line's text, without its end-of-line.
    pub text: String,
}

impl SrcLine {
    /// The position of `column` (from 1) on this line.
    pub fn pos(&self, column: usize) -> Pos {
        Pos {
            file: self.file.clone(),
            line: self.line,
            column,
        }
    }
}

/// The three sections of a deck, as lines.
#[derive(Debug, Default)]
pub struct Sections {
    /// Executive control lines (up to CEND).
    pub executive: Vec<SrcLine>,
    /// Case control lines (up to BEGIN BULK).
    pub case: Vec<SrcLine>,
    /// Bulk data lines (up to ENDDATA).
    pub bulk: Vec<SrcLine>,
    /// Unit system declared in a `$ Units: length, force, time` comment, if any.
    pub units: Option<(String, String, String)>,
    /// SHA-256 (hex) of every byte read, the deck first, INCLUDEd files in order.
    pub sha256: String,
}

/// Reads `path`, expands INCLUDEs (relative to the including file) and splits sections.
pub fn read_sections(path: &Path, limits: Limits, diags: &mut Diagnostics) -> Sections {
    let mut read = Read {
        max_depth: limits.max_include_depth,
        ..Default::default()
    };
    let errors = diags.items.iter().filter(|d| d.is_error()).count();
    expand(path, None, &mut read, diags);
    if read.lines.is_empty() && diags.items.iter().filter(|d| d.is_error()).count() > errors {
        // The deck itself could not be read: that error says it all.
        return Sections::default();
    }
    let file: Arc<str> = Arc::from(path.display().to_string().as_str());
    let mut s = split(file, read.lines, diags);
    s.sha256 = hex(read.hasher);
    s
}

/// Reads deck text held in memory (used by tests and fuzzing); INCLUDEs are resolved
/// relative to the working directory.
pub fn sections_from_str(name: &str, text: &str, limits: Limits, diags: &mut Diagnostics) -> Sections {
    let file: Arc<str> = Arc::from(name);
    let mut read = Read {
        stack: vec![PathBuf::from(name)],
        max_depth: limits.max_include_depth,
        ..Default::default()
    };
    read.hasher.update(text.as_bytes());
    push_lines(file.clone(), text, Path::new("."), &mut read, diags);
    let mut s = split(file, read.lines, diags);
    s.sha256 = hex(read.hasher);
    s
}

/// What reading a deck and its INCLUDEs gathers.
#[derive(Default)]
struct Read {
    /// The files being read, innermost last (to find INCLUDE cycles).
    stack: Vec<PathBuf>,
    /// [`Limits::max_include_depth`].
    max_depth: usize,
    lines: Vec<SrcLine>,
    hasher: Sha256,
}

fn hex(h: Sha256) -> String {
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

fn expand(path: &Path, from: Option<Pos>, read: &mut Read, diags: &mut Diagnostics) {
    let canon = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
    if read.stack.contains(&canon) {
        diags.push(
            Diagnostic::error(from, format!("INCLUDE cycle: '{}' includes itself", path.display())).card("INCLUDE"),
        );
        return;
    }
    // Only regular files: a device or FIFO (`/dev/zero`, `/dev/stdin`) never ends.
    let regular = std::fs::metadata(path).and_then(|m| {
        if m.is_file() {
            std::fs::read(path)
        } else {
            Err(std::io::Error::other("not a regular file"))
        }
    });
    let bytes = match regular {
        Ok(b) => b,
        Err(e) => {
            let what = if from.is_some() { "INCLUDE file" } else { "deck" };
            let mut d = Diagnostic::error(from.clone(), format!("cannot read {what} '{}': {e}", path.display()));
            if from.is_some() {
                d = d.card("INCLUDE");
            }
            diags.push(d);
            return;
        }
    };
    read.hasher.update(&bytes);
    let text = String::from_utf8_lossy(&bytes);
    let file: Arc<str> = Arc::from(path.display().to_string().as_str());
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    read.stack.push(canon);
    push_lines(file, &text, &dir, read, diags);
    read.stack.pop();
}

fn push_lines(file: Arc<str>, text: &str, dir: &Path, read: &mut Read, diags: &mut Diagnostics) {
    for (i, raw) in text.lines().enumerate() {
        let line = SrcLine {
            file: file.clone(),
            line: i + 1,
            text: expand_tabs(raw.trim_end_matches('\r')),
        };
        if let Some(target) = include_target(&line.text) {
            match target {
                Ok(_) if read.stack.len() > read.max_depth => diags.push(
                    Diagnostic::error(
                        Some(line.pos(1)),
                        match read.max_depth {
                            0 => "INCLUDE is not allowed for this input (the reader's limit: no INCLUDE)".to_string(),
                            n => format!("INCLUDE nested more than {n} deep (the reader's limit)"),
                        },
                    )
                    .card("INCLUDE")
                    .quote(&line.text),
                ),
                Ok(name) => {
                    let p = dir.join(&name);
                    expand(&p, Some(line.pos(1)), read, diags);
                }
                Err(msg) => diags.push(
                    Diagnostic::error(Some(line.pos(1)), msg)
                        .card("INCLUDE")
                        .quote(&line.text),
                ),
            }
            continue;
        }
        read.lines.push(line);
    }
}

/// Tabs advance to the next multiple of 8 columns (the small-field grid).
fn expand_tabs(s: &str) -> String {
    if !s.contains('\t') {
        return s.to_string();
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if c == '\t' {
            let n = 8 - out.chars().count() % 8;
            out.extend(std::iter::repeat_n(' ', n));
        } else {
            out.push(c);
        }
    }
    out
}

/// `INCLUDE 'file'` (MSC style). Returns the quoted file name, or an error message.
fn include_target(text: &str) -> Option<Result<String, &'static str>> {
    let t = text.trim_start();
    // `get` rather than indexing: the line may hold multi-byte characters.
    if !t.get(..7).is_some_and(|w| w.eq_ignore_ascii_case("INCLUDE")) {
        return None;
    }
    let rest = t[7..].trim();
    if !(rest.starts_with('\'') || rest.starts_with('"') || rest.is_empty()) {
        return None; // some other word starting with INCLUDE
    }
    let q = rest.chars().next();
    match q {
        Some(q) if rest.len() >= 2 && rest[1..].contains(q) => {
            let end = rest[1..].find(q).unwrap() + 1;
            Some(Ok(rest[1..end].to_string()))
        }
        _ => Some(Err("INCLUDE needs a quoted file name: INCLUDE 'file.bdf'")),
    }
}

fn first_word(text: &str) -> String {
    text.trim_start()
        .split(|c: char| c.is_whitespace() || c == ',' || c == '=' || c == '(')
        .next()
        .unwrap_or("")
        .to_ascii_uppercase()
}

/// The deck's lines split into sections; `file` names the deck where it has no line.
fn split(file: Arc<str>, lines: Vec<SrcLine>, diags: &mut Diagnostics) -> Sections {
    #[derive(PartialEq)]
    enum S {
        Exec,
        Case,
        Bulk,
        Done,
    }
    let mut s = Sections::default();
    if lines.is_empty() {
        let whole = Pos {
            file,
            line: 0,
            column: 0,
        };
        diags.push(Diagnostic::error(
            Some(whole),
            "the deck is empty: it needs executive control (SOL ...) ending in CEND, case control and BEGIN BULK ... ENDDATA",
        ));
        return s;
    }
    let mut state = S::Exec;
    let mut last_pos = None;
    let has_cend = lines.iter().any(|l| first_word(&l.text) == "CEND");
    if !has_cend {
        // A bulk-only deck is not a runnable transient deck.
        state = S::Case;
        diags.push(Diagnostic::error(
            lines.first().map(|l| l.pos(1)),
            "no CEND card: a deck needs executive control (SOL ...) ending in CEND",
        ));
    }
    for l in lines {
        last_pos = Some(l.pos(1));
        let trimmed = l.text.trim_start();
        if trimmed.starts_with('$') {
            if let Some(u) = units_comment(trimmed) {
                s.units = Some(u);
            }
            continue;
        }
        if trimmed.is_empty() {
            continue;
        }
        match state {
            S::Exec => {
                if first_word(&l.text) == "CEND" {
                    state = S::Case;
                } else {
                    s.executive.push(l);
                }
            }
            S::Case => {
                // `BEGIN BULK`; COSMIC also reads `BEGIN` alone, after executive control's
                // DMAP (whose own `BEGIN $` stands before CEND).
                let up = l.text.split('$').next().unwrap_or("").trim().to_ascii_uppercase();
                let words: Vec<&str> = up.split_whitespace().collect();
                if words == ["BEGIN", "BULK"] || words == ["BEGIN"] {
                    state = S::Bulk;
                } else {
                    s.case.push(l);
                }
            }
            S::Bulk => {
                if first_word(&l.text) == "ENDDATA" {
                    state = S::Done;
                } else {
                    s.bulk.push(l);
                }
            }
            S::Done => diags.push(Diagnostic::warning(Some(l.pos(1)), "text after ENDDATA is ignored").quote(&l.text)),
        }
    }
    match state {
        S::Case => diags.push(Diagnostic::error(last_pos, "missing BEGIN BULK")),
        S::Bulk => diags.push(Diagnostic::error(
            last_pos,
            "missing ENDDATA at the end of the bulk data",
        )),
        _ => {}
    }
    s
}

/// `$ Units: in, lbf, s` declares the deck's unit system (length, force, time).
fn units_comment(comment: &str) -> Option<(String, String, String)> {
    let body = comment.trim_start_matches('$').trim();
    let lower = body.to_ascii_lowercase();
    let rest = lower.strip_prefix("units:")?;
    let start = body.len() - rest.len();
    let parts: Vec<String> = body[start..]
        .trim_end_matches('.')
        .split(',')
        .map(|p| p.trim().to_string())
        .collect();
    match parts.as_slice() {
        [l, f, t] if !l.is_empty() && !f.is_empty() && !t.is_empty() => Some((l.clone(), f.clone(), t.clone())),
        _ => None,
    }
}
