//! impactlab: low-velocity impact analysis of linear finite-element targets struck by
//! a rigid impactor through a Hertzian contact, with an audited energy ledger.
//!
//! The pipeline (one home per stage): [`deck`] → [`model`] → [`assembly`] →
//! [`integrate`] → [`ledger`] → [`output`].

pub mod assembly;
pub mod deck;
pub mod elements;
pub mod error;
pub mod integrate;
pub mod ledger;
pub mod mesh;
pub mod model;
pub mod numerics;
pub mod output;
pub mod paper;
pub mod physics;
pub mod plot;
pub mod report;
pub mod run;
pub mod scene;
pub mod study;
pub mod verify;

pub use error::Error;

/// Reads a deck and builds its model; warnings are returned alongside.
pub fn load_deck(
    path: &std::path::Path,
    opts: deck::ReadOptions,
) -> Result<(model::Model, Vec<deck::Diagnostic>), Error> {
    let d = deck::read_deck(path, opts)?;
    let (m, mut warnings) = model::build_model(&d)?;
    let mut all = d.warnings;
    all.append(&mut warnings);
    Ok((m, all))
}

/// Builds the model of a deck held in memory (a generated mesh or a scene's deck);
/// warnings are dropped, errors name `name` as the file.
pub fn model_from_text(name: &str, text: &str) -> Result<model::Model, Error> {
    let d = deck::parse_deck_str(name, text, deck::ReadOptions::default())?;
    Ok(model::build_model(&d)?.0)
}
