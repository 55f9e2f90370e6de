//! Runs a deck and prints its typed summary.
//!
//!     cargo run --release --example run_deck -- reference-data/decks/rod.bdf

use impactlab::run::{run_model, RunOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "reference-data/decks/rod.bdf".into());
    let (model, warnings) = impactlab::load_deck(std::path::Path::new(&path), Default::default())?;
    for w in &warnings {
        eprintln!("{w}");
    }
    let run = run_model(&model, &RunOptions::default())?;
    let s = &run.summary;
    let u = &s.units;
    println!(
        "{} ({} solved DOF), scheme {}",
        s.deck, s.model.solved_dofs, s.run.scheme
    );
    for [start, end] in &s.contact.intervals {
        println!("contact from {start:.4e} to {end:.4e} {}", u.time);
    }
    println!("peak force {:.4e} {}", s.contact.peak_force, u.force);
    if let Some(f) = s.energy.transferred_fraction {
        println!("energy left in the target {:.2} %", 100.0 * f);
    }
    if let Some(r) = &s.rod {
        println!("contact ends at tC/L = {:.4}", r.contact_end_tcl.unwrap_or(f64::NAN));
    }
    Ok(())
}
