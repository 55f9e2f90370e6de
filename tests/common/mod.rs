#![allow(dead_code)]
//! Shared helpers for the integration tests.

use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::{run_model, Run, RunOptions};
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

pub fn run(model: &Model, scheme: Scheme, dt: Option<f64>, steps: Option<usize>) -> Run {
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

/// Linear interpolation of a sampled signal (clamped to zero outside its range).
pub fn interp(t: &[f64], y: &[f64], x: f64) -> f64 {
    if x <= t[0] || x > *t.last().unwrap() {
        return 0.0;
    }
    let k = t.partition_point(|&s| s < x);
    let w = (x - t[k - 1]) / (t[k] - t[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}
