//! impactlab: low-velocity impact analysis of linear finite-element targets struck by
//! a rigid impactor through a Hertzian contact, with an audited energy ledger.
//!
//! Modules in stage order (their declaration order below): each uses only modules
//! listed before it (`tests/stages.rs` checks it); the two deck-to-model functions
//! below count as the model stage. Each stage returns its own error type; the
//! program-wide error, which maps them to exit codes, is the command line's.
//!
//! - [`numerics`]: shared numerics: interpolation, crossings, slopes, medians.
//! - [`plot`]: the figure writer (PNG and SVG with a bundled font).
//! - [`elements`]: element kernels, the one element interface and the table of element
//!   cards (pure functions of geometry and section: they use no other module).
//! - [`deck`]: input: NASTRAN decks to typed cards with source positions (element cards
//!   by the elements' table).
//! - [`geometry`]: coordinate systems (CORD1R … CORD2S through RID), each grid's basic
//!   position and displacement frame, a shell's own frame: where frames are turned.
//! - [`damage`]: damage onset: the delamination threshold load and the plies' failure
//!   indices.
//! - [`laminate`]: classical lamination theory: a PCOMP's plies to A, B, D.
//! - [`model`]: DOFs, constraints, elements, contact, initial conditions, output plan.
//! - [`assembly`]: global K and M over the solved DOFs; inert DOFs dropped.
//! - [`physics`]: the Hertz law and the analytic references, with no solver code.
//! - [`integrate`]: the time schemes and their one driver loop.
//! - [`mesh`]: input: generated decks (the paper's plate on any mesh, its rod with any element count).
//! - [`paper`]: input: the paper's two decks, embedded.
//! - [`scene`]: input: impacts described in TOML, turned into the decks they stand for.
//! - [`ledger`]: the energy ledger and momentum, per step.
//! - [`run`]: one run: the pipeline, the recorder, the typed summary and history columns;
//!   the convolution engine's kernels and their cache.
//! - [`output`]: a run's files, written atomically, and its printed summary.
//! - [`verify`]: verification cases, check kinds, gold files, audit, verdicts.
//! - [`study`]: families of runs: verification cases, convergence, accuracy, stability,
//!   sweeps, bench.
//! - [`report`]: reports from case outcomes; VTU fields.

#![warn(missing_docs)]

pub mod numerics;
pub mod plot;
pub mod elements;
pub mod deck;
pub mod geometry;
pub mod damage;
pub mod laminate;
pub mod model;
pub mod assembly;
pub mod physics;
pub mod integrate;
pub mod eigen;
pub mod mesh;
pub mod paper;
pub mod scene;
pub mod ledger;
pub mod run;
pub mod output;
pub mod verify;
pub mod study;
pub mod report;

/// Reads a deck and builds its model; warnings are returned alongside.
///
/// ```
/// let deck = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("reference-data/decks/plate.bdf");
/// let (model, warnings) = impactlab::load_deck(&deck, Default::default())?;
/// assert_eq!(model.units.length, "in");
/// assert_eq!(model.elements.len(), 49 * 49 + 1); // the CQUAD4s and the impactor's CONM2
/// for w in &warnings {
///     eprintln!("{w}"); // file:line:column, card, field, message and the card quoted
/// }
/// # Ok::<(), impactlab::model::LoadError>(())
/// ```
pub fn load_deck(
    path: &std::path::Path,
    opts: deck::ReadOptions,
) -> Result<(model::Model, Vec<deck::Diagnostic>), model::LoadError> {
    let d = deck::read_deck(path, opts)?;
    let (m, mut warnings) = model::build_model(&d)?;
    let mut all = d.warnings;
    all.append(&mut warnings);
    Ok((m, all))
}

/// Builds the model of a deck held in memory (a generated mesh or a scene's deck);
/// warnings are dropped, errors name `name` as the file.
///
/// ```
/// let model = impactlab::model_from_text("rod", impactlab::paper::ROD_DECK)?;
/// assert_eq!(model.units.length, "in");
/// assert_eq!(model.elements.len(), 145); // 144 CRODs and the ball's CONM2
/// # Ok::<(), impactlab::model::LoadError>(())
/// ```
pub fn model_from_text(name: &str, text: &str) -> Result<model::Model, model::LoadError> {
    let d = deck::parse_deck_str(name, text, deck::ReadOptions::default())?;
    Ok(model::build_model(&d)?.0)
}
