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
