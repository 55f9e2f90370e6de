//! The deck reader and model builder never panic, whatever the bytes: every input
//! ends in a model or in diagnostics. Read with the untrusted limits (1 000 cards,
//! no INCLUDE), so one input costs at most what a small deck costs. The first byte's
//! low bits choose whether unknown cards are errors or warnings, and whether the deck
//! is read for its structure alone and checked (`impactlab check`), so every path is
//! explored. A linear static deck (SOL 101) is solved, as `impactlab run` solves it,
//! and a normal modes deck (SOL 103) of at most 50 points (the Lanczos method's cost
//! grows as the cube of the roots asked for; a deck of 1 000 cards may ask for
//! thousands).
#![no_main]

use impactlab::deck::{parse_deck_str, Limits, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    // The first byte's low bits: unknown cards allowed; read for the structure alone
    // (`impactlab check`); every card kept (as a scene reads its deck).
    let opts = ReadOptions {
        allow_unknown: data.first().is_some_and(|b| b & 1 == 1),
        structure: data.first().is_some_and(|b| b & 2 == 2),
        keep_cards: data.first().is_some_and(|b| b & 4 == 4),
        limits: Limits::untrusted(),
    };
    if let Ok(deck) = parse_deck_str("fuzz.bdf", text, opts) {
        if opts.structure {
            let _ = impactlab::model::check::check(&deck);
        } else if deck.executive.sol == Some(impactlab::deck::STATICS) {
            let _ = impactlab::run::statics::solve(&deck);
        } else if deck.executive.sol == Some(impactlab::deck::MODES) {
            if deck.bulk.grids.len() + deck.bulk.spoints.len() <= 50 {
                let _ = impactlab::run::modes::solve(&deck);
            }
        } else {
            let _ = impactlab::model::build_model(&deck);
        }
    }
});
