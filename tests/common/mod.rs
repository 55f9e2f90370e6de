#![allow(dead_code)]
//! Shared helpers for the integration tests.

use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::{run_model, RunOptions, RunResult};
use std::path::PathBuf;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs the `impactlab` binary from the project's root.
pub fn impactlab(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("impactlab runs")
}

pub fn deck(name: &str) -> PathBuf {
    root().join("reference-data/decks").join(name)
}

/// The paper's rod model, from its restored deck.
pub fn rod_model() -> Model {
    impactlab::load_deck(&deck("rod.bdf"), Default::default())
        .expect("rod deck loads")
        .0
}

pub fn run(model: &Model, scheme: Scheme, dt: Option<f64>, steps: Option<usize>) -> RunResult {
    run_model(
        model,
        &RunOptions {
            scheme,
            dt,
            steps,
            ..Default::default()
        },
    )
    .expect("run succeeds")
}

/// Case control and a TSTEP for decks that are mostly bulk data.
pub const BULK_HEAD: &str = "SOL 9\nCEND\nTSTEP = 1\nBEGIN BULK\nTSTEP,1,10,1.0-6,1\n";

/// A deck of `bulk` cards after [`BULK_HEAD`], read as `t.bdf`.
pub fn bulk_deck(bulk: &str) -> impactlab::deck::Deck {
    impactlab::deck::parse_deck_str(
        "t.bdf",
        &format!("{BULK_HEAD}{bulk}\nENDDATA\n"),
        impactlab::deck::ReadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// The error messages of a deck that must fail to read.
pub fn deck_errors(text: &str) -> Vec<String> {
    match impactlab::deck::parse_deck_str("t.bdf", text, impactlab::deck::ReadOptions::default()) {
        Ok(_) => panic!("deck should fail"),
        Err(impactlab::deck::DeckError { diagnostics }) => diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| d.to_string())
            .collect(),
    }
}

/// The error messages of a deck of `bulk` cards after [`BULK_HEAD`].
pub fn bulk_errors(bulk: &str) -> Vec<String> {
    deck_errors(&format!("{BULK_HEAD}{bulk}\nENDDATA\n"))
}

/// The paper's plate as its cross-ply PCOMP (reference-data/decks/plate-pcomp.bdf) with
/// FT = `ft` and its MAT8's allowables and interaction term as given (continuation
/// lines of the MAT8 card), written into `dir` beside its mesh.
pub fn pcomp_with_ft(dir: &std::path::Path, ft: &str, mat8_continuation: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(deck("plate-pcomp.bdf")).unwrap();
    let mat8 = "MAT8,8,5.735+6,1.2855+6,0.2231,5.7+5,,,1.8-4";
    assert!(text.contains(mat8) && text.contains("PCOMP,1,,,,,,,,+P0"));
    let text = text
        .replace("PCOMP,1,,,,,,,,+P0", &format!("PCOMP,1,,,,{ft},,,,+P0"))
        .replace(mat8, &format!("{mat8},+M1\n+M1,{mat8_continuation}"));
    let out = dir.join(format!("plate-{}.bdf", ft.to_lowercase()));
    std::fs::write(&out, text).unwrap();
    std::fs::copy(deck("plate-mesh-49x49.bdf"), dir.join("plate-mesh-49x49.bdf")).unwrap();
    out
}

/// Glass/epoxy allowables (psi): A1, A2, TREF blank, then Xt, Xc, Yt, Yc, S.
pub const ALLOWABLES: &str = ",,,1.54+5,8.85+4,4.5+3,1.71+4,1.04+4";

/// Tsai-Hill's index of a ply stress under [`ALLOWABLES`] (X by the sign of σ1, Y by
/// that of σ2), written out here apart from the library's.
pub fn hill(s1: f64, s2: f64, t: f64) -> f64 {
    let (xt, xc, yt, yc, sh) = (1.54e5, 8.85e4, 4.5e3, 1.71e4, 1.04e4);
    let x = if s1 >= 0.0 { xt } else { xc };
    let y = if s2 >= 0.0 { yt } else { yc };
    (s1 * s1 - s1 * s2) / (x * x) + (s2 / y).powi(2) + (t / sh).powi(2)
}

/// What a Python `script` run by pyNastran's interpreter (`IMPACTLAB_PYNASTRAN_PYTHON`,
/// else `python3`) with `args` prints as JSON; `None` (and a note) where pyNastran
/// cannot run it, except under CI, where that fails.
pub fn pynastran_json<T: serde::de::DeserializeOwned>(script: &str, args: &[&std::ffi::OsStr]) -> Option<T> {
    let python = std::env::var("IMPACTLAB_PYNASTRAN_PYTHON").unwrap_or_else(|_| "python3".into());
    match std::process::Command::new(&python)
        .arg("-c")
        .arg(script)
        .args(args)
        .output()
    {
        Ok(o) if o.status.success() => Some(serde_json::from_slice(&o.stdout).unwrap()),
        other => {
            assert!(
                std::env::var_os("CI").is_none(),
                "pyNastran is required under CI: {other:?}"
            );
            eprintln!("skipped: no pyNastran in {python}; see .ci/run to install it");
            None
        }
    }
}

/// The paper's plate deck on an n×n mesh with its impactor, contact and transient
/// cards taken out: the structure alone, as an analyst's SOL 103 deck would hold it.
pub fn plate_structure(n: usize) -> String {
    impactlab::mesh::plate_structure_deck(n).unwrap()
}
