//! Bad input: every deck in `tests/bad-decks/` gets its expected exit code and error
//! lines (file:line:col, card, field, token, what was expected), never a panic, and
//! writes nothing. Property test: random edits of the paper's decks never panic the
//! reader or the model builder.

use crate::common;

use common::root;
use proptest::prelude::*;
use std::process::Command;

#[test]
fn every_bad_deck_gets_its_expected_error() {
    let dir = root().join("tests/bad-decks");
    let mut decks: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "bdf"))
        .filter(|p| !p.ends_with("include-cycle-b.bdf"))
        .collect();
    decks.sort();
    assert!(decks.len() >= 25, "{} decks", decks.len());
    let out = tempfile::tempdir().unwrap();
    for deck in decks {
        let name = deck.file_stem().unwrap().to_str().unwrap().to_string();
        let expected = std::fs::read_to_string(deck.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{name}: no .expected file"));
        let mut lines = expected.lines();
        let code: i32 = lines.next().unwrap().strip_prefix("exit ").unwrap().parse().unwrap();
        let target = out.path().join(&name);
        let o = Command::new(env!("CARGO_BIN_EXE_impactlab"))
            .args(["run", deck.file_name().unwrap().to_str().unwrap(), "--out"])
            .arg(&target)
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "{name}: {err}");
        let mut rest = err.as_ref();
        for want in lines {
            let at = rest
                .find(want)
                .unwrap_or_else(|| panic!("{name}: missing line\n  {want}\nin\n{err}"));
            rest = &rest[at + want.len()..];
        }
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert!(!target.exists(), "{name}: outputs written on failure");
    }
}

/// One random edit of a deck line: replace a field, delete or duplicate a line, or
/// insert random printable text.
#[derive(Debug, Clone)]
enum Edit {
    Field { line: usize, field: usize, text: String },
    Delete { line: usize },
    Duplicate { line: usize },
    Insert { line: usize, text: String },
}

fn edit() -> impl Strategy<Value = Edit> {
    let token = prop_oneof![
        "[ -~]{0,12}",
        Just(String::new()),
        Just("=".to_string()),
        Just("==".to_string()),
        Just("*(1)".to_string()),
        Just("=(3)".to_string()),
        Just("THRU".to_string()),
        Just("-0.0".to_string()),
        Just("1.0+999".to_string()),
        Just("+C1".to_string()),
        Just("NaN".to_string()),
    ];
    prop_oneof![
        (0..400usize, 0..10usize, token.clone()).prop_map(|(line, field, text)| Edit::Field { line, field, text }),
        (0..400usize).prop_map(|line| Edit::Delete { line }),
        (0..400usize).prop_map(|line| Edit::Duplicate { line }),
        (0..400usize, "[ -~]{0,40}").prop_map(|(line, text)| Edit::Insert { line, text }),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for e in edits {
        let n = lines.len().max(1);
        match e {
            Edit::Field { line, field, text } => {
                let l = &mut lines[line % n];
                let mut f: Vec<String> = l.split(',').map(String::from).collect();
                let k = field % f.len();
                f[k] = text.clone();
                *l = f.join(",");
            }
            Edit::Delete { line } => {
                lines.remove(line % n);
            }
            Edit::Duplicate { line } => {
                let l = lines[line % n].clone();
                lines.insert(line % n, l);
            }
            Edit::Insert { line, text } => lines.insert(line % n, text.clone()),
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Random edits of the rod deck: the reader and builder return a model or
    /// diagnostics, never panic; every diagnostic names the deck's file.
    #[test]
    fn random_rod_deck_edits_never_panic(edits in proptest::collection::vec(edit(), 1..6)) {
        let text = std::fs::read_to_string(root().join("reference-data/decks/rod.bdf")).unwrap();
        let deck = apply(&text, &edits);
        match impactlab::deck::parse_deck_str("edited.bdf", &deck, Default::default()) {
            Ok(d) => {
                if let Err(e) = impactlab::model::build_model(&d) {
                    prop_assert!(e.to_string().contains("edited.bdf"), "{}", e);
                }
            }
            Err(e) => prop_assert!(e.to_string().contains("edited.bdf:"), "{}", e),
        }
    }
}

/// Goal: every input a fuzz target crashed on (`fuzz/regressions/TARGET/`) now ends
/// in a result or an error, read as that target reads it.
#[test]
fn fuzz_crash_inputs_no_longer_crash() {
    use impactlab::deck::{parse_deck_str, Limits, ReadOptions};
    let dir = root().join("fuzz/regressions");
    let mut n = 0;
    for e in std::fs::read_dir(dir.join("deck")).unwrap() {
        let bytes = std::fs::read(e.unwrap().path()).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        for (allow_unknown, structure) in [(false, false), (true, false), (false, true)] {
            let opts = ReadOptions {
                allow_unknown,
                structure,
                keep_cards: false,
                limits: Limits::untrusted(),
            };
            if let Ok(deck) = parse_deck_str("fuzz.bdf", text, opts) {
                if structure {
                    let _ = impactlab::model::check::check(&deck);
                } else {
                    let _ = impactlab::model::build_model(&deck);
                }
            }
        }
        n += 1;
    }
    for e in std::fs::read_dir(dir.join("scene")).into_iter().flatten() {
        let text = std::fs::read_to_string(e.unwrap().path()).unwrap_or_default();
        if let Ok(s) = impactlab::scene::parse(std::path::Path::new("fuzz.toml"), &text) {
            if let Ok(deck) = impactlab::scene::to_deck(&s) {
                let _ = impactlab::model_from_text("fuzz", &deck);
            }
        }
        n += 1;
    }
    assert!(n >= 1, "no crash inputs found under {}", dir.display());
}
