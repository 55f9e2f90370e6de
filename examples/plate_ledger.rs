//! Builds the paper's plate on a 25×25 mesh in code (the generated deck goes through
//! the deck reader), runs it with the energy-conserving scheme and reads its ledger.
//!
//!     cargo run --release --example plate_ledger

use impactlab::integrate::Scheme;
use impactlab::run::{run_model, RunOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = impactlab::mesh::plate_model(25)?;
    let opts = RunOptions {
        scheme: Scheme::Energy,
        steps: Some(2500),
        ..Default::default()
    };
    let run = run_model(&model, &opts)?;
    let e = &run.energy;
    let energy = &run.summary.units.energy;
    println!(
        "time [{}]  KE_i  SE_i  KE_t  SE_t  total  W_ext [{energy}]",
        model.units.time
    );
    for r in e.iter().step_by(250) {
        println!(
            "{:.3e}  {:.4e}  {:.4e}  {:.4e}  {:.4e}  {:.6e}  {:.3e}",
            r.time, r.ke_impactor, r.se_impactor, r.ke_target, r.se_target, r.total, r.external_work
        );
    }
    let worst = e.iter().map(|r| r.error.abs()).fold(0.0, f64::max);
    println!("largest |(U_t − U_0 − W_ext)/U_0| over the run: {worst:.2e}");
    Ok(())
}
