//! Scene reading never panics, whatever the bytes: every input ends in a scene or a
//! `SceneError`. A scene that reads is turned into its deck and model when its mesh
//! is small (at most 64 rod elements or a 9×9 plate); larger ones are only read and
//! validated, so that one input costs at most a small model's build.
#![no_main]

use impactlab::scene::{self, Target};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(s) = scene::parse(Path::new("fuzz.toml"), text) else { return };
    let small = match &s.target {
        Target::Rod { elements, .. } => *elements <= 64,
        Target::Plate { mesh, .. } => *mesh <= 9,
    };
    let _ = scene::contact_stiffness(&s);
    if small {
        if let Ok(deck) = scene::to_deck(&s) {
            let _ = impactlab::model_from_text("fuzz", &deck);
        }
    }
});
