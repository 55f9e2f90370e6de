//! The convolution engine: the target's linear response to a unit contact load
//! computed once, the contact solved by an exact history sum. Checked against the
//! direct engine (the same discrete scheme, so the same numbers to round-off), and
//! its kernel for the two properties a linear elastic target must have: passivity and
//! reciprocity.

use crate::common;

use common::{deck, rod_model};
use impactlab::integrate::convolution::{linear_response, unit_response, Convolver};
use impactlab::integrate::Scheme;
use impactlab::model::DofLabel;
use impactlab::run::{prepare, run_model, Engine, RunError, RunOptions};

fn options(scheme: Scheme, engine: Engine) -> RunOptions {
    RunOptions {
        scheme,
        engine,
        ..Default::default()
    }
}

fn peak(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0, |a, x| a.max(x.abs()))
}

/// Goal: on the paper's rod, both trapezoidal schemes give on the convolution engine
/// what they give on the direct engine: the force at every step and every history
/// column within 1e-12 of its peak, the ledger's total within 1e-12 of U_0, and the
/// `energy` scheme's energy error at round-off; the summary says which engine ran.
#[test]
fn the_convolution_engine_is_the_direct_run_to_round_off() {
    let model = rod_model();
    for scheme in [Scheme::Newmark, Scheme::Energy] {
        let direct = run_model(&model, &options(scheme, Engine::Direct)).unwrap();
        let conv = run_model(&model, &options(scheme, Engine::Convolution)).unwrap();
        assert_eq!(conv.series.force.len(), direct.series.force.len());
        let f = peak(direct.series.force.iter().copied());
        for (a, b) in direct.series.force.iter().zip(&conv.series.force) {
            assert!((a - b).abs() <= 1e-12 * f, "{scheme}: force {a} vs {b}");
        }
        assert_eq!(conv.history_columns, direct.history_columns);
        assert_eq!(conv.history.len(), direct.history.len());
        for j in 0..direct.history_columns.len() {
            let p = peak(direct.history.iter().map(|r| r[j]));
            let worst = peak(direct.history.iter().zip(&conv.history).map(|(a, b)| a[j] - b[j]));
            assert!(
                worst <= 1e-12 * p,
                "{scheme} {}: {worst:e} of {p:e}",
                direct.history_columns[j].name()
            );
        }
        let u0 = direct.energy[0].total;
        for (a, b) in direct.energy.iter().zip(&conv.energy) {
            assert!((a.total - b.total).abs() <= 1e-12 * u0, "{scheme} total at {}", a.time);
            assert!(b.se_target.is_nan() && b.ke_target.is_nan(), "not reconstructed: NaN");
        }
        assert_eq!(conv.summary.run.engine, Engine::Convolution);
        let json = serde_json::to_string(&conv.summary).unwrap();
        assert!(json.contains(r#""engine":"convolution""#));
        assert!(!serde_json::to_string(&direct.summary).unwrap().contains("engine"));
    }
    let energy = run_model(&model, &options(Scheme::Energy, Engine::Convolution)).unwrap();
    let worst = energy.summary.energy.max_relative_error.unwrap();
    assert!(worst < 1e-13, "energy scheme on the convolution engine: {worst:e}");
}

/// Goal: the energy guard stops a convolution run where it stops the direct run. The
/// convolution engine forms its ledger after the contact history; a trip at step n
/// must still end the force, the ledger and the history rows at step n, with the
/// outputs up to there. Model: the paper's rod (newmark), the guard at half the
/// run's largest energy error.
#[test]
fn the_energy_guard_stops_both_engines_at_the_same_step() {
    let model = rod_model();
    let free = run_model(&model, &options(Scheme::Newmark, Engine::Direct)).unwrap();
    let limit = 0.5 * free.summary.energy.max_relative_error.unwrap();
    let guarded = |engine| {
        let opts = RunOptions {
            max_energy_error: Some(limit),
            ..options(Scheme::Newmark, engine)
        };
        match run_model(&model, &opts) {
            Err(RunError::EnergyGuard { trip, partial }) => (trip, partial),
            other => panic!(
                "{engine:?}: the guard did not trip: {:?}",
                other.map(|r| r.summary.energy)
            ),
        }
    };
    let (t_direct, direct) = guarded(Engine::Direct);
    let (t_conv, conv) = guarded(Engine::Convolution);
    assert_eq!(t_conv.step, t_direct.step);
    assert!(t_direct.step < free.series.force.len() - 1, "it stopped early");
    assert_eq!(conv.series.force.len(), t_direct.step + 1);
    assert_eq!(conv.series.force.len(), direct.series.force.len());
    assert_eq!(conv.energy.len(), direct.energy.len());
    assert_eq!(conv.history.len(), direct.history.len());
    assert_eq!(conv.stats.steps, direct.stats.steps);
    let f = peak(direct.series.force.iter().copied());
    for (a, b) in direct.series.force.iter().zip(&conv.series.force) {
        assert!((a - b).abs() <= 1e-12 * f);
    }
}

/// Goal: what the engine cannot compute is refused with a reason, not approximated:
/// the explicit and the lagged schemes, and field snapshots (they need every DOF).
#[test]
fn the_convolution_engine_refuses_what_it_cannot_compute() {
    let model = rod_model();
    for scheme in [Scheme::Central, Scheme::Nastran] {
        match run_model(&model, &options(scheme, Engine::Convolution)) {
            Err(RunError::Engine(why)) => assert!(why.contains("newmark, energy"), "{why}"),
            other => panic!("{scheme}: {:?}", other.map(|r| r.summary.run.scheme)),
        }
    }
    let snapshots = RunOptions {
        snapshot_times: vec![1e-5],
        ..options(Scheme::Newmark, Engine::Convolution)
    };
    match run_model(&model, &snapshots) {
        Err(RunError::Engine(why)) => assert!(why.contains("direct engine"), "{why}"),
        other => panic!("{:?}", other.is_ok()),
    }
}

/// Goal: the kernel is passive. From rest, the work done on the target by any load
/// history, E(n) = Σ_k (w(k) − w(k−1))·p_k/2 (the trapezoidal rule's exact work
/// identity), equals ½vᵀMv + ½uᵀKu and is never negative, whatever the signs of the
/// loads. Model: the paper's rod, its unit response over 2500 steps, three load
/// histories (a contact-like pulse, an alternating one, a pseudo-random one).
#[test]
fn the_kernel_is_passive() {
    let rod = rod_model();
    let p = prepare(&rod, &RunOptions::default()).unwrap();
    let (model, sys) = (p.model.as_ref(), &p.system);
    let k = unit_response(model, sys, 2e-7, 2500, &mut |_, _| {}).unwrap();
    let pulse: Vec<f64> = (0..400)
        .map(|n| (std::f64::consts::PI * n as f64 / 400.0).sin())
        .collect();
    let alternating: Vec<f64> = (0..600).map(|n| if n % 37 < 18 { 1.0 } else { -1.0 }).collect();
    let mut x = 12345u64;
    let random: Vec<f64> = (0..2500)
        .map(|_| {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    for (name, p) in [("pulse", pulse), ("alternating", alternating), ("random", random)] {
        let (mut e, mut w_prev, mut scale) = (0.0f64, 0.0, 0.0f64);
        // w as the engine forms it: the work kernel convolved with the loads by FFT.
        let fft = Convolver::new(k.work.len());
        let ws = fft.convolve(&fft.spectrum(&k.work), &fft.spectrum(&p), 1.0);
        for n in 1..=p.len() {
            let w = ws[n - 1];
            e += (w - w_prev) * p[n - 1] / 2.0;
            w_prev = w;
            scale = scale.max(e.abs());
            // Exactly E(n) ≥ 0; the sum accumulates round-off of about 1e-16 per step.
            assert!(e >= -1e-12 * scale, "{name}: E({n}) = {e:e} < 0");
        }
        assert!(scale > 0.0, "{name}: some work was done");
    }
}

/// Goal: the kernel is reciprocal (Maxwell–Betti, discrete: A, M and K symmetric):
/// the response at one translational DOF to a unit load at another equals the
/// response at the second to the load at the first, at every step, to 1e-12 of its
/// peak. Models: the rod (struck end grid 1 T1, mid grid 73 T1, 1000 steps) and the
/// paper's plate (struck grid 2525 T3, gage grid 3325 T3, 300 steps).
#[test]
fn the_kernel_is_reciprocal() {
    let plate = impactlab::load_deck(&deck("plate.bdf"), Default::default()).unwrap().0;
    for (model, a, b, dt, steps) in [
        (rod_model(), (1, 1), (73, 1), 2e-7, 1000),
        (plate, (2525, 3), (3325, 3), 1e-7, 300),
    ] {
        let p = prepare(&model, &RunOptions::default()).unwrap();
        let (model, sys) = (p.model.as_ref(), &p.system);
        let at = |(point, comp): (i64, u8)| model.dofs.iter().position(|d| *d == DofLabel { point, comp }).unwrap();
        let (ia, ib) = (at(a), at(b));
        let response = |from: usize, to: usize| {
            let mut load = vec![0.0; model.n()];
            load[from] = 1.0;
            let mut out = Vec::new();
            linear_response(model, sys, dt, steps, &load, &mut |u, _| out.push(u[to])).unwrap();
            out
        };
        let (ab, ba) = (response(ia, ib), response(ib, ia));
        let p = peak(ab.iter().copied());
        assert!(p > 0.0, "{}: the load reaches the other DOF", model.name);
        // Symmetric A, M, K: equal in exact arithmetic; the two solves differ by
        // round-off (about 1e-15 of the peak).
        for k in 0..steps {
            assert!(
                (ab[k] - ba[k]).abs() <= 1e-12 * p,
                "{} step {}: {} vs {}",
                model.name,
                k + 1,
                ab[k],
                ba[k]
            );
        }
    }
}

/// Goal: the kernel cache reuses kernels only for the very input they were made for.
/// A second run reads them (no solve) and gives the same numbers bit for bit; another
/// Δt, another Hertz K or another output set makes a new file; a corrupt or truncated
/// file is recomputed with the reason, never read as data. Model: the paper's rod.
#[test]
fn the_kernel_cache_is_reused_only_when_valid() {
    use impactlab::run::convolution::CacheUse;
    let dir = tempfile::tempdir().unwrap();
    let model = rod_model();
    let opts = RunOptions {
        kernel_cache: Some(dir.path().to_path_buf()),
        ..options(Scheme::Newmark, Engine::Convolution)
    };
    let first = run_model(&model, &opts).unwrap();
    assert_eq!(first.summary.run.kernel_cache, Some(CacheUse::Miss));
    let second = run_model(&model, &opts).unwrap();
    assert_eq!(second.summary.run.kernel_cache, Some(CacheUse::Hit));
    assert_eq!(second.stats.solves, 0, "read, not computed");
    assert_eq!(second.history, first.history);
    assert_eq!(second.series.force, first.series.force);
    let files = || std::fs::read_dir(dir.path()).unwrap().count();
    assert_eq!(files(), 1);
    // Another Δt, another K (every NOLIN3 scale with it), another output set: new files.
    let other_dt = RunOptions {
        dt: Some(1e-7),
        steps: Some(5000),
        ..opts.clone()
    };
    assert_eq!(
        run_model(&model, &other_dt).unwrap().summary.run.kernel_cache,
        Some(CacheUse::Miss)
    );
    let stiffer = impactlab::model::Modify {
        contact_stiffness_scale: Some(2.0),
        ..Default::default()
    }
    .apply(&model)
    .unwrap();
    assert_eq!(
        run_model(&stiffer, &opts).unwrap().summary.run.kernel_cache,
        Some(CacheUse::Miss)
    );
    let mut fewer = model.clone();
    fewer.outputs.disp.pop();
    assert_eq!(
        run_model(&fewer, &opts).unwrap().summary.run.kernel_cache,
        Some(CacheUse::Miss)
    );
    assert_eq!(files(), 4);
    // Corrupt every file, then truncate them: recomputed, the same numbers.
    for damage in ["flip", "truncate"] {
        for p in std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().path()) {
            let mut b = std::fs::read(&p).unwrap();
            match damage {
                "flip" => {
                    let k = b.len() / 2;
                    b[k] ^= 1;
                }
                _ => b.truncate(b.len() / 3),
            }
            std::fs::write(&p, b).unwrap();
        }
        let again = run_model(&model, &opts).unwrap();
        match &again.summary.run.kernel_cache {
            Some(CacheUse::Recomputed(why)) => assert!(why.contains("corrupt or truncated"), "{damage}: {why}"),
            other => panic!("{damage}: {other:?}"),
        }
        assert_eq!(again.history, first.history, "{damage}");
    }
}
