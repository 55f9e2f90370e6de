//! The deck reader and model builder never panic, whatever the bytes: every input
//! ends in a model or in diagnostics. Read with the untrusted limits (1 000 cards,
//! no INCLUDE), so one input costs at most what a small deck costs. The first byte's
//! low bit chooses whether unknown cards are errors or warnings, so each input is
//! read once and both paths are explored.
#![no_main]

use impactlab::deck::{parse_deck_str, Limits, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let opts = ReadOptions {
        allow_unknown: data.first().is_some_and(|b| b & 1 == 1),
        limits: Limits::untrusted(),
    };
    if let Ok(deck) = parse_deck_str("fuzz.bdf", text, opts) {
        let _ = impactlab::model::build_model(&deck);
    }
});
