//! The integration tests, built as one crate: each file of `tests/` is a module of
//! it (run one with `cargo test --test integration MODULE::`). One test binary is
//! linked instead of one a file, and its tests share one pool of threads: a file's
//! slow test no longer holds the others back.

mod common;

mod bad_decks;
mod beams;
mod book;
mod bush;
mod card_rules;
mod check;
mod cli;
mod concentrated_masses;
mod convolution;
mod damping;
mod damage;
mod deck_reader;
mod dynamic_loads;
mod elements;
mod hysteresis;
mod faults;
mod laminate;
mod modal;
mod modes;
mod nastran95_demos;
mod plate_element;
mod plate_impact;
mod report;
mod reports_current;
mod rod_impact;
mod scalar_elements;
mod scenes;
mod shells_3d;
mod slurm;
mod stability;
mod stages;
mod statics;
mod thermal;
mod verify_gate;
