//! The stage map holds: no module of the library uses a module after it in the stage
//! order `src/lib.rs` declares (its `pub mod` lines, in order), with no exception:
//! each stage returns its own error (the program-wide one is the command line's), so
//! an error type that gathered later stages' errors would be a use of them.
//! `load_deck`/`model_from_text` (the root's deck-to-model functions) count as the
//! model stage. Doc comments are not uses.

use std::collections::BTreeSet;
use std::path::Path;

fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The `crate::X` each module's code (not its comments) uses.
fn uses(module: &str) -> BTreeSet<String> {
    let src = root().join("src");
    let mut files = Vec::new();
    let single = src.join(format!("{module}.rs"));
    if single.exists() {
        files.push(single);
    }
    let dir = src.join(module);
    if dir.is_dir() {
        collect(&dir, &mut files);
    }
    let mut out = BTreeSet::new();
    for f in files {
        for line in std::fs::read_to_string(&f).unwrap().lines() {
            let code = line.split("//").next().unwrap_or("");
            for (i, _) in code.match_indices("crate::") {
                let name: String = code[i + 7..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                out.insert(match name.as_str() {
                    "load_deck" | "model_from_text" => "model".to_string(),
                    _ => name,
                });
            }
        }
    }
    out.remove(module);
    out
}

fn collect(dir: &Path, files: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, files);
        } else if p.extension().is_some_and(|x| x == "rs") {
            files.push(p);
        }
    }
}

/// Goal: data flows one way. Reference: the order of `pub mod` in src/lib.rs.
#[test]
fn no_module_uses_a_stage_after_it() {
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let order: Vec<String> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .map(|l| l.trim_end_matches(';').to_string())
        .collect();
    assert!(order.len() >= 15, "{order:?}");
    let mut wrong = Vec::new();
    for (k, m) in order.iter().enumerate() {
        for u in uses(m) {
            match order.iter().position(|x| *x == u) {
                Some(j) if j < k => {}
                Some(_) => wrong.push(format!("{m} uses {u}, a later stage")),
                None => wrong.push(format!("{m} uses crate::{u}, not a module of the stage list")),
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}
