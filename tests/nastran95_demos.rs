//! NASTRAN-95's own demonstration and test decks (`reference-data/nastran95-demos/inp/`,
//! 132 decks in COSMIC's dialect) through `impactlab check`, against the committed
//! table `reference-data/nastran95-demos.md`: for each deck, taken, or refused naming
//! the cards impactlab does not implement or why its structure does not build.
//!
//! Goal: no deck is refused for a reading error (NASTRAN-95 read every one of them),
//! and no deck's verdict changes unnoticed. A deck that moves in the table fails the
//! test until the table is written again on purpose:
//! `IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test nastran95_demos`.

mod common;

use common::root;
use impactlab::deck::{read_deck, ReadOptions};
use std::fmt::Write as _;

/// The table's line of one deck.
fn verdict(path: &std::path::Path) -> Result<(String, bool), String> {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let read = ReadOptions {
        structure: true,
        ..Default::default()
    };
    let deck = read_deck(path, read).map_err(|e| format!("{name}: a reading error:\n{e}"))?;
    let r = impactlab::model::check::check(&deck);
    let sol = r.solution.clone().unwrap_or_else(|| "-".into());
    // Messages name the deck by its path: keep the file's own name.
    let local = |s: &str| {
        let first = s.lines().next().unwrap_or("");
        match first.find(&name) {
            Some(i) => first[i..].to_string(),
            None => first.to_string(),
        }
    };
    let (what, why) = if r.takes {
        let kinds: Vec<String> = r.elements.iter().map(|(k, n)| format!("{k} {n}")).collect();
        ("taken", kinds.join(", "))
    } else if !r.unsupported.is_empty() {
        let cards: Vec<&str> = r.unsupported.iter().map(|c| c.card.as_str()).collect();
        ("not supported", cards.join(", "))
    } else {
        ("does not build", local(&r.errors[0]))
    };
    let row = format!(
        "| {} | {sol} | {what} | {} |",
        name.trim_end_matches(".inp"),
        why.replace('|', "\\|")
    );
    Ok((row, r.takes))
}

#[test]
fn every_demonstration_deck_is_read_and_its_verdict_is_the_tables() {
    let dir = root().join("reference-data/nastran95-demos/inp");
    let mut decks: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "inp"))
        .collect();
    decks.sort();
    assert_eq!(decks.len(), 132);
    let mut rows = Vec::new();
    let mut misread = Vec::new();
    let mut taken = 0;
    for d in &decks {
        match verdict(d) {
            Ok((row, takes)) => {
                taken += usize::from(takes);
                rows.push(row);
            }
            Err(e) => misread.push(e),
        }
    }
    assert!(misread.is_empty(), "{}", misread.join("\n\n"));
    let mut table = String::new();
    let _ = writeln!(
        table,
        "# NASTRAN-95's demonstration decks through `impactlab check`\n\n\
         Written by `tests/nastran95_demos.rs` (`IMPACTLAB_WRITE_DEMO_TABLE=1 cargo test --test \
         nastran95_demos`), which fails when a deck's verdict differs from this table. The decks are \
         NASTRAN-95's own (`nastran95-demos/inp/`, see its README). Taken: {taken} of {}.\n\n\
         | deck | SOL | verdict | elements, cards not supported, or the first error |\n|---|---|---|---|",
        decks.len()
    );
    for r in &rows {
        let _ = writeln!(table, "{r}");
    }
    let path = root().join("reference-data/nastran95-demos.md");
    if std::env::var_os("IMPACTLAB_WRITE_DEMO_TABLE").is_some() {
        std::fs::write(&path, &table).unwrap();
    }
    let committed = std::fs::read_to_string(&path).expect("the committed table");
    if committed != table {
        let old: Vec<&str> = committed.lines().collect();
        let changed: Vec<String> = table
            .lines()
            .filter(|l| !old.contains(l))
            .map(|l| format!("  now: {l}"))
            .collect();
        panic!(
            "the demonstration decks' verdicts differ from reference-data/nastran95-demos.md:\n{}",
            changed.join("\n")
        );
    }
}
