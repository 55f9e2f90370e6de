//! Deck to run, end to end, never panics and never allocates more than it says: a
//! rod of 1 to 8 CRODs struck by a CONM2 through NOLIN3 Hertz contact, every number
//! of it fuzzed (modulus, density, area, impactor mass, velocity, K, exponent, Δt;
//! NaN, ±inf, 0, negatives, subnormals and 1e±300 among them, as any f64 bit pattern
//! can be), run for at most 64 steps by any scheme. Each input ends in a run
//! (possibly stopped by the energy guard) or in an error.
#![no_main]

use impactlab::integrate::Scheme;
use impactlab::run::{run_model, RunOptions};
use libfuzzer_sys::arbitrary::{self, Arbitrary};
use libfuzzer_sys::fuzz_target;

#[derive(Debug, Arbitrary)]
struct Input {
    modulus: f64,
    density: f64,
    area: f64,
    mass: f64,
    velocity: f64,
    stiffness: f64,
    exponent: f64,
    dt: f64,
    elements: u8,
    steps: u8,
    scheme: u8,
}

/// The deck: grids 1..=n+1 along x, the impactor on grid 999, indentation on EPOINT 1001.
fn deck(i: &Input) -> String {
    let n = 1 + i.elements as usize % 8;
    let h = 1.0 / n as f64;
    let mut d = String::from(
        "SOL 9\nCEND\nNONLINEAR = 5\nIC = 1\nTFL = 111\nSPC = 4\nTSTEP = 7\n\
         SET 30 = 1,999,1001\nNLLOAD = 30\nDISP = 30\nSTRESS = 30\nBEGIN BULK\nEPOINT,1001\n\
         GRID,999,,-0.5,0.0,0.0\n",
    );
    for g in 1..=n + 1 {
        d += &format!("GRID,{g},,{:e},0.0,0.0\n", (g - 1) as f64 * h);
    }
    for e in 1..=n {
        d += &format!("CROD,{e},1,{e},{}\n", e + 1);
    }
    d += &format!(
        "CONM2,200,999,0,{m:e}\nPROD,1,11,{a:e}\nMAT1,11,{e:e},,0.3,{r:e}\n\
         SPC1,4,23456,1,THRU,{last}\nSPC1,4,23456,999\n\
         TF,111,1001,0,+1.0,0.0,0.0,,,+TF-1\n+TF-1,999,1,-1.0,0.0,0.0,,,,+TF-2\n+TF-2,1,1,1.0,0.0,0.0\n\
         TSTEP,7,{steps},{dt:e},1\n\
         NOLIN3,5,1,1,{k:e},1001,1,{x:e}\nNOLIN3,5,999,1,{mk:e},1001,1,{x:e}\n\
         TIC,1,999,1,0.0,{v:e}\nENDDATA\n",
        m = i.mass,
        a = i.area,
        e = i.modulus,
        r = i.density,
        last = n + 1,
        steps = 1 + i.steps as usize % 64,
        dt = i.dt,
        k = i.stiffness,
        mk = -i.stiffness,
        x = i.exponent,
        v = i.velocity,
    );
    d
}

fuzz_target!(|i: Input| {
    let Ok(model) = impactlab::model_from_text("fuzz", &deck(&i)) else { return };
    let opts = RunOptions {
        scheme: Scheme::ALL[i.scheme as usize % Scheme::ALL.len()],
        max_memory: Some(256 << 20),
        ..Default::default()
    };
    let _ = run_model(&model, &opts);
});
