#![allow(dead_code)]
//! Shared helpers for the integration tests.

use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::{run_model, RunOptions, RunResult};
use std::path::PathBuf;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
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
