//! A laminated plate, deck to run, never panics and never allocates more than it says:
//! the paper's plate on a 3×3 mesh (CQUAD4, or CTRIA3 when asked), its property a
//! PCOMP of 1 to 6 plies (SYM or not) of one MAT8. Every number is fuzzed (E1, E2,
//! NU12, G12, G1Z, G2Z, RHO, the allowables and F12, each ply's T and THETA, SB, the
//! impact speed, Δt and G_IIc), either as any f64 bit pattern (NaN, ±inf, 0,
//! negatives, subnormals, 1e±300) or as the paper's value scaled by a power of two;
//! G1Z, G2Z and the allowables blank or not, FT any theory or none. Run for at most 32
//! steps by any scheme (the explicit one refuses plates), on the direct or the
//! convolution engine. It exercises the lamination stage, the thin and the
//! shear-deformable kernels, ply recovery and the failure indices. Each input ends in
//! a run (possibly stopped by the energy guard) or in an error, and a run that
//! completes wrote only finite numbers.
#![no_main]

use impactlab::integrate::Scheme;
use impactlab::mesh::{plate_deck_with, Cells, Edges};
use impactlab::run::{run_model, Engine, RunOptions};
use libfuzzer_sys::arbitrary::{self, Arbitrary};
use libfuzzer_sys::fuzz_target;

/// A number: any f64 bit pattern, or a plausible one, the field's nominal value
/// scaled by 2^(k/8) (2^-16 to 2^15), so that most inputs reach the element and the
/// run and the extremes of stiffness ratio and ply thickness are explored there.
#[derive(Debug, Clone, Copy, Arbitrary)]
enum Num {
    Raw(f64),
    Scaled(i8),
}

impl Num {
    fn value(self, nominal: f64) -> f64 {
        match self {
            Num::Raw(v) => v,
            Num::Scaled(k) => nominal * 2f64.powi(i32::from(k) / 8),
        }
    }
}

#[derive(Debug, Arbitrary)]
struct Input {
    e1: Num,
    e2: Num,
    nu12: Num,
    g12: Num,
    g1z: Option<Num>,
    g2z: Option<Num>,
    rho: Num,
    allowables: [Option<Num>; 5],
    f12: Option<Num>,
    sb: Option<Num>,
    /// Each ply's T and THETA (THETA's scaled form: k × 7.5°).
    plies: Vec<(Num, Num)>,
    sym: bool,
    ft: u8,
    triangles: bool,
    velocity: Num,
    dt: Num,
    steps: u8,
    scheme: u8,
    convolution: bool,
    g_iic: Num,
}

/// A number in exponent form.
fn num(v: Num, nominal: f64) -> String {
    format!("{:e}", v.value(nominal))
}

/// A field: a number, or blank.
fn field(v: Option<Num>, nominal: f64) -> String {
    v.map(|v| num(v, nominal)).unwrap_or_default()
}

/// A card of `fields`, eight to a line, the continuations marked +C1, +C2, ….
fn card(name: &str, fields: &[String], tag: char) -> String {
    let mut d = name.to_string();
    for (k, line) in fields.chunks(8).enumerate() {
        if k > 0 {
            d += &format!("\n+{tag}{k}");
        }
        for f in line {
            d += ",";
            d += f;
        }
        if (k + 1) * 8 < fields.len() {
            d += &",".repeat(8 - line.len() + 1);
            d += &format!("+{tag}{}", k + 1);
        }
    }
    d + "\n"
}

/// The PCOMP and MAT8 cards of the input, replacing the plate's PSHELL and MAT2s.
fn property(i: &Input) -> String {
    let ft = ["", "HILL", "HOFF", "TSAI", "STRN"][i.ft as usize % 5];
    let lam = if i.sym { "SYM" } else { "" };
    let mut p: Vec<String> = ["1", "", "", &field(i.sb, 1e4), ft, "", "", lam]
        .map(String::from)
        .to_vec();
    for &(t, theta) in i.plies.iter().take(6) {
        let theta = match theta {
            Num::Raw(v) => v,
            Num::Scaled(k) => 7.5 * f64::from(k),
        };
        p.extend(["8".into(), num(t, 0.025), format!("{theta:e}"), "YES".into()]);
    }
    let a = &i.allowables;
    let m = [
        "8".into(),
        num(i.e1, 5.735e6),
        num(i.e2, 1.2855e6),
        num(i.nu12, 0.2231),
        num(i.g12, 5.7e5),
        field(i.g1z, 5.7e5),
        field(i.g2z, 4.59e5),
        num(i.rho, 1.8e-4),
        String::new(),
        String::new(),
        String::new(),
        field(a[0], 1.5e5),
        field(a[1], 1.0e5),
        field(a[2], 4.0e3),
        field(a[3], 2.0e4),
        field(a[4], 1.0e4),
        String::new(),
        field(i.f12, -1.0e-11),
    ];
    card("PCOMP", &p, 'P') + &card("MAT8", &m, 'M')
}

/// The paper's 3×3 plate with the input's laminate, speed and time step.
fn deck(i: &Input) -> Option<String> {
    let cells = if i.triangles { Cells::Tria3 } else { Cells::Quad4 };
    let plate = plate_deck_with(3, Edges::Clamped, cells).ok()?;
    let mut d = String::new();
    for line in plate.lines() {
        if line.starts_with("PSHELL") {
            d += &property(i);
        } else if line.starts_with("MAT2") || line.starts_with("+A101") {
        } else if line.starts_with("TSTEP") {
            d += &format!("TSTEP,1,{},{},1\n", 1 + i.steps as usize % 32, num(i.dt, 1e-7));
        } else if line.starts_with("TIC") {
            d += &format!("TIC,3,999,3,0.0,{}\n", num(i.velocity, 1470.0));
        } else {
            d += line;
            d.push('\n');
        }
    }
    Some(d)
}

fuzz_target!(|i: Input| {
    let Some(text) = deck(&i) else { return };
    let Ok(model) = impactlab::model_from_text("fuzz", &text) else {
        return;
    };
    let opts = RunOptions {
        scheme: Scheme::ALL[i.scheme as usize % Scheme::ALL.len()],
        engine: if i.convolution {
            Engine::Convolution
        } else {
            Engine::Direct
        },
        interlaminar_toughness: Some(i.g_iic.value(5.71)),
        max_memory: Some(256 << 20),
        ..Default::default()
    };
    if let Ok(run) = run_model(&model, &opts) {
        let values = run
            .history
            .iter()
            .flatten()
            .chain(&run.series.force)
            .chain(&run.series.alpha);
        assert!(
            values.into_iter().all(|v| v.is_finite()),
            "a completed run wrote a value that is not a finite number"
        );
    }
});
