//! The deck reader and model builder never panic, whatever the bytes: every input
//! ends in a model or in diagnostics.
#![no_main]

use impactlab::deck::{parse_deck_str, ReadOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    for allow_unknown in [false, true] {
        if let Ok(deck) = parse_deck_str("fuzz.bdf", text, ReadOptions { allow_unknown }) {
            let _ = impactlab::model::build_model(&deck);
        }
    }
});
