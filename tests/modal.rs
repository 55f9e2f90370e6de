//! The modal engine: the target reduced to its lowest modes and residual vectors,
//! stepped by the same schemes and contact. Checked against the direct engine as modes
//! are added (contact duration and peak force), with and without residual vectors,
//! and for its own ledger (exact in the reduced coordinates) and truncation report.

use crate::common;

use common::{deck, rod_model};
use impactlab::integrate::Scheme;
use impactlab::model::Model;
use impactlab::run::convolution::{engine_difference, Kernels, Scale};
use impactlab::run::modal::{self, ModalParams};
use impactlab::run::{run_model, Engine, RunOptions, RunResult};
use impactlab::study::sweep::DIRECT_CHECK_MAX;

fn plate() -> Model {
    impactlab::load_deck(&deck("plate.bdf"), Default::default()).unwrap().0
}

fn on(model: &Model, scheme: Scheme, steps: usize, modal: Option<ModalParams>) -> RunResult {
    let opts = RunOptions {
        scheme,
        steps: Some(steps),
        engine: if modal.is_some() { Engine::Modal } else { Engine::Direct },
        modal: modal.unwrap_or_default(),
        ..Default::default()
    };
    run_model(model, &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// Relative differences of the contact duration and the peak force from `reference`.
fn errors(run: &RunResult, reference: &RunResult) -> (f64, f64) {
    let (d, f) = run.summary.contact.relative_difference(&reference.summary.contact);
    (d.expect("both contacts end"), f)
}

/// The default cutoff over the impactor's Hertz time on a rigid target.
fn default_cutoff(model: &Model) -> f64 {
    let c = model.contact.as_ref().unwrap();
    let v0 = model.v0[c.impactor.dof].abs();
    let (_, _, t) = impactlab::physics::analytic::rigid_target(c.impactor.mass, v0, c.stiffness);
    impactlab::run::modal::CYCLES_PER_CONTACT / t
}

/// The relative L2 difference of the contact force histories (every step).
fn force_error(run: &RunResult, reference: &RunResult) -> f64 {
    let (a, b) = (&run.series.force, &reference.series.force);
    assert_eq!(a.len(), b.len());
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    (d / b.iter().map(|y| y * y).sum::<f64>()).sqrt()
}

/// Goal: on the paper's plate, the modal run's contact force converges to the direct
/// run's as modes are added (cutoffs of a quarter, a half and all of the default: the
/// L2 difference of the force history falls each time), and at the default cutoff
/// with residual vectors the contact duration and peak force are within 1e-3 of the
/// direct run's (the contact's extremes move erratically with the modes; the L2
/// difference does not; measured 2.5e-4 and 5.6e-4). Without residual vectors the
/// same modes are further off, by at least 5× in the L2 difference (measured 7.4×:
/// 3.8e-2 against 5.2e-3). The truncation report: the reduced model holds the whole
/// static flexibility at the contact (to 1e-8, room for the dense solve of K_r;
/// measured within 1e-12: a fault in the residual vectors or the basis change moves
/// it by their share, 0.7-2.7 % here), the modes alone less. Model: plate.bdf,
/// Newmark, Δt 1e-7 s, 2400 steps (past the contact's end at 204 µs).
#[test]
fn the_plates_modal_run_converges_to_the_direct_run() {
    let model = plate();
    let steps = 2400;
    let direct = on(&model, Scheme::Newmark, steps, None);
    let full = default_cutoff(&model);
    let mut last = f64::INFINITY;
    let mut report = Vec::new();
    let mut at_default = None;
    for share in [0.25, 0.5, 1.0] {
        let params = ModalParams {
            cutoff: Some(share * full),
            residual_vectors: true,
        };
        let modal = on(&model, Scheme::Newmark, steps, Some(params));
        let t = modal.summary.run.modal.clone().unwrap();
        let (ed, ef) = errors(&modal, &direct);
        let e = force_error(&modal, &direct);
        report.push(format!(
            "cutoff {:.4e}: {} modes, force L2 {e:.2e}, duration {ed:.2e}, peak force {ef:.2e}, flexibility by \
             modes {:.6}, reduced {:.10}",
            t.cutoff_frequency, t.modes, t.flexibility_by_modes, t.flexibility_reduced
        ));
        assert!((t.flexibility_reduced - 1.0).abs() <= 1e-8, "{}", report.join("\n"));
        assert!(t.flexibility_by_modes < 1.0, "{}", report.join("\n"));
        assert!(e < last, "not converging:\n{}", report.join("\n"));
        last = e;
        at_default = Some((ed, ef));
    }
    let (ed, ef) = at_default.unwrap();
    assert!(ed <= 1e-3 && ef <= 1e-3, "{}", report.join("\n"));
    let bare = on(
        &model,
        Scheme::Newmark,
        steps,
        Some(ModalParams {
            cutoff: Some(full),
            residual_vectors: false,
        }),
    );
    let (ed, ef) = errors(&bare, &direct);
    let e = force_error(&bare, &direct);
    report.push(format!(
        "without residual vectors: force L2 {e:.2e}, duration {ed:.2e}, peak force {ef:.2e}"
    ));
    eprintln!("{}", report.join("\n"));
    assert!(e > 5.0 * last, "{}", report.join("\n"));
}

/// Goal: the ledger closes in the reduced coordinates as on the direct engine: the
/// energy-conserving scheme to round-off (1e-10, the bound the direct engine's tests
/// hold it to; measured 6.0e-13 on the rod) on the free-free rod (its rigid-body mode
/// among the modes) and the plate; the rod's momentum is conserved (measured 3e-13).
/// The rod's contact duration and peak force at the default cutoff (22 modes) are the
/// direct run's within 1e-3, the plate's bound (measured 2.0e-4 and 2.8e-4).
#[test]
fn the_modal_ledger_closes_and_the_rod_is_the_direct_rod() {
    let rod = rod_model();
    let steps = rod.time.steps;
    let direct = on(&rod, Scheme::Energy, steps, None);
    let modal = on(&rod, Scheme::Energy, steps, Some(ModalParams::default()));
    let t = modal.summary.run.modal.clone().unwrap();
    assert_eq!(t.rigid_modes, 1, "{t:?}");
    let (ed, ef) = errors(&modal, &direct);
    assert!(ed <= 1e-3 && ef <= 1e-3, "duration {ed:e}, peak force {ef:e}, {t:?}");
    let e = modal.summary.energy.max_relative_error.unwrap();
    assert!(e <= 1e-10, "rod: {e:e}");
    let m = modal.summary.momentum.max_abs_change.unwrap() / modal.summary.momentum.initial.unwrap();
    assert!(m.abs() <= 1e-10, "rod momentum {m:e}");
    let plate = plate();
    let modal = on(&plate, Scheme::Energy, 600, Some(ModalParams::default()));
    let e = modal.summary.energy.max_relative_error.unwrap();
    assert!(e <= 1e-10, "plate: {e:e}");
    assert!(modal.energy.iter().all(|r| r.ke_target_eq16.is_nan()));
}

/// Goal: the reduced system is an arrowhead, so that a step costs O(p·nb), not
/// O(p²): between two interior coordinates (those that are no DOF of the deck) M_r
/// holds exactly I and K_r a diagonal, ascending (the reduced model's own modes with
/// the boundary held); every other entry lies in the impactor's or a boundary DOF's
/// row or column. On the rod (a rigid-body mode, one boundary DOF) and the plate (four).
#[test]
fn the_reduced_system_is_an_arrowhead() {
    for (name, model) in [("rod", rod_model()), ("plate", plate())] {
        let opts = RunOptions {
            engine: Engine::Modal,
            ..Default::default()
        };
        let p = impactlab::run::prepare(&model, &opts).unwrap();
        let r = modal::reduce(p.model.as_ref(), &p.system, &ModalParams::default(), None, &|_| {}).unwrap();
        let interior: Vec<bool> = r.model.dofs.iter().map(|d| d.point < 0).collect();
        let first = interior.iter().position(|&i| i).unwrap();
        assert!(
            interior[first..].iter().all(|&i| i),
            "{name}: the interior coordinates come last"
        );
        let n = interior.len();
        let mut k_diagonal = vec![0.0; n];
        for (matrix, entries) in [("K", &r.system.k), ("M", &r.system.m)] {
            for t in entries.iter().filter(|t| interior[t.row] && interior[t.col]) {
                assert_eq!(t.row, t.col, "{name}: {matrix}_r couples two interior coordinates");
                if matrix == "M" {
                    assert_eq!(t.val, 1.0, "{name}: M_r's interior diagonal");
                } else {
                    k_diagonal[t.row] = t.val;
                }
            }
            let m = entries.iter().filter(|t| interior[t.row] && interior[t.col]).count();
            assert!(m <= n - first, "{name}: {m} interior entries of {matrix}_r");
        }
        let m_interior = r.system.m.iter().filter(|t| interior[t.row] && interior[t.col]).count();
        assert_eq!(m_interior, n - first, "{name}: every interior coordinate has unit mass");
        let k = &k_diagonal[first..];
        assert!(k.windows(2).all(|w| w[0] <= w[1]), "{name}: {k:?}");
    }
}

/// Goal: `impactlab run --engine modal` runs the paper's rod, prints its truncation
/// and writes it to summary.json (`run.engine`, `run.modal`); `--modes-up-to` sets
/// the cutoff and is refused without `--engine modal` (exit 2, saying what to add).
#[test]
fn run_engine_modal_reports_its_truncation() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let deck = common::deck("rod.bdf");
    let run = |flags: &[&str]| {
        let args = [
            &["run", deck.to_str().unwrap(), "--out", out.to_str().unwrap()][..],
            flags,
        ]
        .concat();
        common::impactlab(&args)
    };
    let o = run(&["--engine", "modal", "--modes-up-to", "50000"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        text.contains("  modal:    19 modes to 5.0000e4 cycles/s (1 rigid), 8 residual vectors"),
        "{text}"
    );
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["run"]["engine"], "modal");
    assert_eq!(s["run"]["modal"]["modes"], 19);
    assert_eq!(s["run"]["modal"]["cutoff_from"], "as asked");
    let o = run(&["--modes-up-to", "5e4"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("add --engine modal"));
}

/// Goal: `--max-memory` holds the modal reduction too: every mode of the paper's plate
/// (--modes-up-to 1e6 cycles/s: every root of its 2 304 DOFs with mass, of 6 912)
/// under a limit of 0.07 GiB (the run's system and records take 0.025 GiB of it) stops
/// the extraction before it forms more Lanczos vectors than half the rest holds
/// vectors of its 6 912 DOFs (433: 432, the next block of four would pass it; the
/// modes and the basis are that long), exit 2, with what to lower; the default cutoff
/// (372 vectors, 163 modes) runs under it.
#[test]
fn max_memory_holds_the_modal_reduction() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plate");
    let deck = common::deck("plate.bdf");
    let run = |limit: &str, flags: &[&str]| {
        let args = [
            &[
                "run",
                deck.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--engine",
                "modal",
                "--max-memory",
                limit,
            ][..],
            flags,
        ]
        .concat();
        common::impactlab(&args)
    };
    let o = run("0.07", &["--modes-up-to", "1e6"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("over the memory limit: 432 Lanczos vectors of 2304 DOFs with mass")
            && err.contains("--modes-up-to"),
        "{err}"
    );
    assert!(!out.exists(), "a refused run writes nothing");
    let o = run("0.07", &["--steps", "100"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Goal: the run's progress bar says when the modal engine is reducing (most of a
/// large model's run, all before its first step: 45 s of the 199 × 199 panel's 49 s)
/// and what it is at: the Lanczos vectors formed and the modes converged at each
/// convergence test, rising, then the modes' vectors and the residual vector it is at;
/// and has its own message back for the stepping. Model: the paper's plate, its bar's
/// message read every millisecond while it runs (its reduction takes about 0.4 s, its
/// extraction's convergence tests come some 10 to 60 Lanczos vectors apart).
#[test]
fn the_progress_bar_says_when_the_modal_engine_reduces() {
    let model = plate();
    let bar = indicatif::ProgressBar::hidden();
    bar.set_message("plate newmark");
    let opts = RunOptions {
        engine: Engine::Modal,
        steps: Some(100),
        progress: Some(bar.clone()),
        ..Default::default()
    };
    let done = std::sync::atomic::AtomicBool::new(false);
    let said = std::thread::scope(|s| {
        let watcher = s.spawn(|| {
            let mut said = Vec::new();
            while !done.load(std::sync::atomic::Ordering::Relaxed) {
                let m = bar.message();
                if said.last() != Some(&m) {
                    said.push(m);
                }
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            said
        });
        run_model(&model, &opts).unwrap_or_else(|e| panic!("{e}"));
        done.store(true, std::sync::atomic::Ordering::Relaxed);
        watcher.join().unwrap()
    });
    let details: Vec<&str> = said
        .iter()
        .filter_map(|m| m.strip_prefix("plate newmark, reducing to modes and residual vectors: "))
        .collect();
    // "N Lanczos vectors, M modes converged", as the tests come.
    let counts: Vec<(usize, usize)> = details
        .iter()
        .filter_map(|d| {
            let (v, m) = d.strip_suffix(" modes converged")?.split_once(" Lanczos vectors, ")?;
            Some((v.parse().ok()?, m.parse().ok()?))
        })
        .collect();
    assert!(counts.len() >= 2, "{said:?}");
    assert!(
        counts.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 >= w[0].1),
        "{counts:?}"
    );
    assert!(counts.last().unwrap().1 > 0, "{counts:?}");
    assert!(
        details
            .iter()
            .any(|d| d.starts_with("163 modes from ") && d.ends_with(" Lanczos vectors, forming their vectors")),
        "{said:?}"
    );
    assert!(
        details.iter().any(|d| d.starts_with("163 modes; residual vector ")),
        "{said:?}"
    );
    assert_eq!(bar.message(), "plate newmark");
}

/// Goal: with every mode kept the reduced model spans what the direct run moves, so
/// the modal engine is the direct engine to round-off: the dynamic-load path on
/// NASTRAN-95's bar struck by a TLOAD1 (reference-data/decks/t09071a-subcase1.bdf,
/// NASTRAN's three-point scheme): every displacement column within 1e-9 of its peak
/// (round-off through the dense reduced system; measured 2.1e-13). A fault in the
/// basis change, the reduced K and M, or the remapping of the loads breaks it.
#[test]
fn with_every_mode_the_modal_engine_is_the_direct_engine() {
    let all = ModalParams {
        cutoff: Some(1e12),
        residual_vectors: true,
    };
    let bar = impactlab::load_deck(&deck("t09071a-subcase1.bdf"), Default::default())
        .unwrap()
        .0;
    let direct = on(&bar, Scheme::Nastran, bar.time.steps, None);
    let modal = on(&bar, Scheme::Nastran, bar.time.steps, Some(all));
    let t = modal.summary.run.modal.clone().unwrap();
    assert_eq!(direct.history_columns, modal.history_columns);
    for j in 0..direct.history_columns.len() {
        let peak = direct.history.iter().fold(0.0f64, |m, r| m.max(r[j].abs()));
        let worst = direct
            .history
            .iter()
            .zip(&modal.history)
            .fold(0.0f64, |m, (x, y)| m.max((x[j] - y[j]).abs()));
        assert!(
            worst <= 1e-9 * peak.max(f64::MIN_POSITIVE),
            "{}: {worst:e} of {peak:e}, {t:?}",
            direct.history_columns[j].name()
        );
    }
}

/// The kernels of a model's modal reduction and a run on them of `point` (the model
/// with another impactor or Hertz law); the modal engine's run of `point` on the
/// model's reduction ([`Reduction::for_point`]); and its own modal run at the same
/// cutoff.
fn modal_kernel_run(
    model: &Model,
    point: &Model,
    scheme: Scheme,
    steps: usize,
    cutoff: f64,
) -> (RunResult, RunResult, RunResult) {
    let params = ModalParams {
        cutoff: Some(cutoff),
        ..Default::default()
    };
    let opts = RunOptions {
        scheme,
        steps: Some(steps),
        engine: Engine::Convolution,
        ..Default::default()
    };
    let prepared = impactlab::run::prepare(model, &opts).unwrap();
    let (m, sys) = (prepared.model.as_ref(), &prepared.system);
    let bar = indicatif::ProgressBar::hidden();
    let r = modal::reduce(m, sys, &params, None, &|_| {}).unwrap();
    let kernels = Kernels::compute_modal(&r, m.time.dt, steps, &bar).unwrap();
    let on_kernels = kernels.run(point, &opts, &bar).unwrap_or_else(|e| panic!("{e}"));
    let modal_opts = RunOptions {
        engine: Engine::Modal,
        modal: params,
        ..opts
    };
    let p = impactlab::run::prepare(point, &modal_opts).unwrap();
    let shared = r.for_point(&p.model, &p.system).unwrap();
    let on_shared = modal::run_reduced(&p.model, &shared, &modal_opts).unwrap();
    (on_kernels, on_shared, on(point, scheme, steps, Some(params)))
}

/// Goal: a model's modal reduction serves another impactor speed and mass
/// (`Reduction::for_point`, as a modal sweep's checks use it): the modal run on it is
/// the point's own modal run at the same cutoff, bit for bit. The convolution engine's
/// kernels taken from the modal reduction reproduce the modal engine's run to round-off (the same reduced model, its contact solved from a
/// history sum instead of a dense solve), for another impactor speed and mass than
/// the reduction's model (the kernels depend on neither): the force and every history
/// column to the sweep's bound, 1e-9 of their family's peak (measured 8.1e-13 on the
/// plate, 1.1e-12 on the rod; against each column's own peak the plate's centre shear,
/// which the truncated basis leaves at 1.7e-4 of the normal strains, is 7.9e-10), the
/// ledger's total and momentum to 1e-9 of the impact's. Rod at 100 in/s and the plate
/// at 1 in/s (its deck's 1470: the cutoff is the deck's), Newmark and energy.
#[test]
fn kernels_from_the_modal_reduction_are_the_modal_run() {
    let vary = |m: &Model, v: f64, mass: f64| {
        let ct = m.contact.as_ref().unwrap();
        let v0 = m.v0[ct.impactor.dof].abs();
        impactlab::model::Modify {
            velocity_scale: Some(v / v0),
            impactor_mass_scale: Some(mass),
            ..Default::default()
        }
        .apply(m)
        .unwrap()
    };
    for (model, steps, speed) in [(rod_model(), 2000, 100.0), (plate(), 2400, 1.0)] {
        let cutoff = default_cutoff(&model);
        for scheme in [Scheme::Newmark, Scheme::Energy] {
            let point = vary(&model, speed, 1.3);
            let (conv, shared, modal) = modal_kernel_run(&model, &point, scheme, steps, cutoff);
            // The model's reduction serves the point: the very run of its own.
            assert_eq!(shared.series.force, modal.series.force, "{} {scheme}", model.name);
            assert_eq!(shared.history, modal.history, "{} {scheme}", model.name);
            let (d, what, t) = engine_difference(&modal, &conv, Scale::Family).expect("same steps");
            println!("{} {scheme}: {d:.2e} ({what} at {t:e})", model.name);
            assert!(
                d <= DIRECT_CHECK_MAX,
                "{} {scheme}: {d:e} ({what} at {t:e})",
                model.name
            );
            // The ledger: the total and the momentum, against the impact's energy and
            // the impactor's momentum.
            let (u0, p0) = (modal.energy[0].total, modal.energy[0].momentum.abs());
            for (a, b) in modal.energy.iter().zip(&conv.energy) {
                assert!(
                    (a.total - b.total).abs() <= 1e-9 * u0,
                    "{} {scheme}: total at {}",
                    model.name,
                    a.time
                );
                assert!(
                    (a.momentum - b.momentum).abs() <= 1e-9 * p0,
                    "{} {scheme}: momentum at {}",
                    model.name,
                    a.time
                );
            }
        }
    }
}

/// Goal: `impactlab sweep --engine modal` takes its kernels from one modal reduction at
/// the cutoff of its hardest point (by default; `summary.json` says so, with the
/// truncation), checks the first, the deck's and the last point stepped on the modal
/// engine (within the sweep's 1e-9; the deck's 62.1 in/s is nearest point 1, at
/// 48 in/s), and its peak forces are the convolution sweep's within the modal
/// engine's 1e-3 at the default cutoff; its figures' footer names the engines. Refused:
/// `--modes-up-to` without `--engine modal`, a kernel cache, a threshold search (exit
/// 2). Model: the paper's rod, 6 velocities.
#[test]
fn sweep_engine_modal_takes_its_kernels_from_the_reduction() {
    let dir = tempfile::tempdir().unwrap();
    let rod = deck("rod.bdf");
    let sweep = |out: &str, flags: &[&str]| {
        let out = dir.path().join(out);
        let args = [
            &[
                "sweep",
                rod.to_str().unwrap(),
                "--vary",
                "velocity=10:200:6",
                "--out",
                out.to_str().unwrap(),
            ][..],
            flags,
        ]
        .concat();
        (common::impactlab(&args), out)
    };
    let (o, modal) = sweep("modal", &["--engine", "modal"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        text.contains("3 modal checks") && text.contains("kernels:  the modal reduction"),
        "{text}"
    );
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(modal.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        (s["kernels"].as_str(), s["check_engine"].as_str()),
        (Some("modal"), Some("modal"))
    );
    let from = s["modal"]["cutoff_from"].as_str().unwrap();
    assert!(
        from.contains("at point 5: the shortest of the sweep's 6 points"),
        "{from}"
    );
    assert!(s["modal"]["modes"].as_u64().unwrap() > 10);
    let svg = std::fs::read_to_string(modal.join("peak-force.svg")).unwrap();
    assert!(
        svg.contains("modal kernels; ringed: also run on the modal engine"),
        "the figures' footer"
    );
    let (header, rows) = impactlab::study::sweep::read_csv(&modal.join("sweep.csv")).unwrap();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let checked: Vec<usize> = rows
        .iter()
        .filter(|r| !r[col("direct_check")].is_nan())
        .map(|r| r[0] as usize)
        .collect();
    assert_eq!(checked, [0, 1, 5]);
    assert!(rows
        .iter()
        .all(|r| r[col("direct_check")].is_nan() || r[col("direct_check")] <= DIRECT_CHECK_MAX));
    let (o, conv) = sweep("conv", &["--checks", "0", "--no-cache"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (_, reference) = impactlab::study::sweep::read_csv(&conv.join("sweep.csv")).unwrap();
    for (a, b) in rows.iter().zip(&reference) {
        let (fa, fb) = (a[col("peak_force")], b[col("peak_force")]);
        assert!((fa / fb - 1.0).abs() <= 1e-3, "point {}: {fa:e} against {fb:e}", a[0]);
    }
    for (flags, says) in [
        (&["--modes-up-to", "5e4"][..], "add --engine modal"),
        (&["--engine", "modal", "--cache", "x"][..], "not cached"),
    ] {
        let (o, _) = sweep("refused", flags);
        assert_eq!(o.status.code(), Some(2), "{flags:?}");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(says),
            "{flags:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let o = common::impactlab(&[
        "sweep",
        rod.to_str().unwrap(),
        "--find",
        "velocity",
        "--until",
        "peak_force=100",
        "--engine",
        "modal",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

/// Goal: the modal engine runs a scene on a user's deck, a curved panel whose shells
/// solve their massless rotations (`impactlab mesh panel --n 15 --radius 10`, 1 176
/// DOFs, struck off-centre at grid 706 along its normal), and agrees with the direct
/// run (contact duration and peak force within 1e-3, the plate's bound; measured
/// 2.4e-7 and 1.4e-8 with 326 modes), its reduced model holding the whole static
/// flexibility at the contact. On this panel the Lanczos vectors' component along M's
/// null space (the rotations) grows to 1e240 of the vectors: without the Ritz vectors'
/// purification the reduced stiffness is garbage and the run stops on a non-positive
/// pivot.
#[test]
fn a_scene_on_a_curved_panel_deck_runs_on_the_modal_engine() {
    let dir = tempfile::tempdir().unwrap();
    curved_panel(dir.path(), "15");
    let scene = dir.path().join("strike.toml");
    std::fs::write(
        &scene,
        "title = \"panel struck off-centre\"\nunits = { length = \"in\", force = \"lbf\", time = \"s\" }\n\
         [target]\nkind = \"deck\"\ndeck = \"panel.bdf\"\n\
         [impactor]\ngrid = 706\ndirection = \"normal\"\nmass = 8.096e-5\nradius = 0.1875\n\
         material = { e = 30.0e6, nu = 0.3 }\nvelocity = 1470.0\n\
         [contact]\nk = 7.779e5\n\
         [run]\ndt = 1e-7\nend = 800e-6\nafter_separation = 10e-6\n",
    )
    .unwrap();
    let (s, model, _) = impactlab::scene::load(&scene).unwrap();
    let run = |engine| {
        let opts = RunOptions {
            engine,
            ..RunOptions::for_scene(&s)
        };
        run_model(&model, &opts).unwrap_or_else(|e| panic!("{engine:?}: {e}"))
    };
    let (direct, modal) = (run(Engine::Direct), run(Engine::Modal));
    let (d, p) = errors(&modal, &direct);
    println!("duration {d:.1e}, peak force {p:.1e}");
    assert!(d <= 1e-3 && p <= 1e-3, "duration {d:e}, peak force {p:e}");
    let t = modal.summary.run.modal.as_ref().unwrap();
    assert!((t.flexibility_reduced - 1.0).abs() <= 1e-8, "{t:?}");
}

/// Goal: with every mode the reduction is exact: on a 9×9 plate (`impactlab mesh plate
/// --n 9`, 64 DOFs with mass, its rotations massless), a cutoff above every root keeps
/// all 64 modes, no residual vector is needed (the modes hold the whole flexibility),
/// and the modal run is the direct run: the contact force and every history column
/// within 1e-9 of their family's peak (`engine_difference`, Scale::Family; measured
/// 8.5e-13). Without the Ritz vectors' purification the rotations at the impact are
/// off by 6.3e-8: the modes' components along M's null space.
#[test]
fn with_every_mode_the_modal_run_is_the_direct_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("plate9.bdf");
    let o = common::impactlab(&["mesh", "plate", "--n", "9", "--out", deck.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let model = impactlab::load_deck(&deck, Default::default()).unwrap().0;
    let direct = on(&model, Scheme::Newmark, 2000, None);
    let params = ModalParams {
        cutoff: Some(1e9),
        ..Default::default()
    };
    let modal = on(&model, Scheme::Newmark, 2000, Some(params));
    let t = modal.summary.run.modal.as_ref().unwrap();
    assert_eq!((t.modes, t.residual_vectors), (64, 0), "{t:?}");
    let (d, what, at) = engine_difference(&direct, &modal, Scale::Family).unwrap();
    println!("{d:.2e} ({what} at {at:e})");
    assert!(d <= 1e-9, "{d:e} ({what} at {at:e})");
}

/// `dir/panel.bdf`: the curved panel `impactlab mesh panel --n n --radius 10`.
fn curved_panel(dir: &std::path::Path, n: &str) -> std::path::PathBuf {
    let panel = dir.join("panel.bdf");
    let o = common::impactlab(&[
        "mesh",
        "panel",
        "--n",
        n,
        "--radius",
        "10",
        "--out",
        panel.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    panel
}

/// Runs [`curved_panel`] `n` on the modal engine cut at `cutoff` cycles/s for 10
/// steps: its exit code and standard error.
fn curved_panel_cut_at(n: &str, cutoff: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let panel = curved_panel(dir.path(), n);
    let out = dir.path().join("out");
    let o = common::impactlab(&[
        "run",
        panel.to_str().unwrap(),
        "--steps",
        "10",
        "--engine",
        "modal",
        "--modes-up-to",
        cutoff,
        "--out",
        out.to_str().unwrap(),
    ]);
    (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// Goal: a cutoff whose extraction needs many hundreds of Lanczos steps on shells
/// whose rotations carry no mass is honoured. The recurrence's round-off along those
/// DOFs grows by about α/β a step; past some hundreds of steps it overflowed, the
/// products turned NaN, and the extraction lost the roots it had converged (here 568
/// of them, by step 954: the run stopped with exit 3, and before that check ran on 0
/// modes and said nothing). Model: the curved panel `impactlab mesh panel --n 19
/// --radius 10` cut at 8e4 cycles/s, 300 steps (past the peak force, at 19.9 µs).
/// Reference: the direct run: the contact force history within 1e-5 (L2; measured
/// 5.2e-8), with more modes than the breakdown had held (measured 635).
#[test]
fn a_long_extraction_on_massless_rotations_is_honoured() {
    let dir = tempfile::tempdir().unwrap();
    let panel = curved_panel(dir.path(), "19");
    let model = impactlab::load_deck(&panel, Default::default()).unwrap().0;
    let direct = on(&model, Scheme::Newmark, 300, None);
    let params = ModalParams {
        cutoff: Some(8e4),
        ..Default::default()
    };
    let modal = on(&model, Scheme::Newmark, 300, Some(params));
    let t = modal.summary.run.modal.as_ref().unwrap();
    let e = force_error(&modal, &direct);
    println!("{} modes, force history {e:.1e}", t.modes);
    assert!(t.modes > 568, "{t:?}");
    assert!(e <= 1e-5, "{e:e}");
}

/// Goal: a cutoff the reduction cannot honour stops the run with the reason, never
/// naming a DOF the deck does not have: where the modes and residual vectors span
/// every DOF with mass, the reduced system is singular along a basis vector, which the
/// run reported as a "mechanism" at "point -588" to be constrained with SPC1. Model:
/// the curved panel `impactlab mesh panel --n 15 --radius 10` cut at 1e5 cycles/s.
/// Reference: exit 3 (a numerical failure), the dependent basis named as such, with
/// its modes and residual vectors (558 and 30), and the cutoff to lower.
#[test]
fn a_cutoff_whose_basis_is_dependent_stops_the_run_with_the_reason() {
    let (code, stderr) = curved_panel_cut_at("15", "1e5");
    assert_eq!(code, Some(3), "{stderr}");
    assert!(
        stderr.contains("basis vectors") && stderr.contains("nearly dependent") && !stderr.contains("SPC1"),
        "{stderr}"
    );
}

/// Runs `impactlab` with `args` (its output directory last, `--out DIR` appended):
/// its `name` JSON file, or its standard error when it fails.
fn json_of(args: &[&str], name: &str) -> Result<serde_json::Value, String> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut all = args.to_vec();
    all.extend(["--out", out.to_str().unwrap()]);
    let o = common::impactlab(&all);
    if !o.status.success() {
        return Err(String::from_utf8_lossy(&o.stderr).into_owned());
    }
    Ok(serde_json::from_slice(&std::fs::read(out.join(name)).unwrap()).unwrap())
}

/// Goal: a cutoff above the structure's highest mode keeps every mode it has and is
/// the direct run: the paper's rod (145 structural DOFs, every one with mass) cut at
/// 1e6 cycles/s, above its highest root (2.5e5). The Lanczos run spans the whole
/// space with mass and must then accept every root it holds (its residual is zero,
/// not the round-off left in the last vector, against which some were refused), and
/// the reduction must keep no residual vector past the DOFs with mass (round-off
/// normalised to unit mass, which leaves the reduced mass singular: the run stopped
/// on it). Reference: the direct run: contact duration and peak
/// force within 1e-10 (measured 1.5e-13, 5.7e-14), the basis exactly as many vectors
/// as DOFs with mass. The highest mode it reports is the free-free chain's highest
/// root, f₁/sin(π/288) (144 equal elements, f₁ its lowest elastic root from a normal
/// modes solution), to 1e-9 (measured 1.1e-12; f₁ comes from another extraction, with
/// another shift): from the first, tiny shift it came out 1.4e-3 high, and
/// the extraction is now made again from a second shift. (With those accurate modes,
/// nalgebra's eigendecomposition of the held modes paired two vectors with each
/// other's eigenvalues, and the run left the direct run by 3e-3: the duration above
/// catches it.)
#[test]
fn a_cutoff_above_the_highest_mode_is_the_direct_run() {
    let rod = common::root().join("reference-data/decks/rod.bdf");
    let rod = rod.to_str().unwrap();
    let direct = json_of(&["run", rod], "summary.json").unwrap();
    let modal = json_of(
        &["run", rod, "--engine", "modal", "--modes-up-to", "1e6"],
        "summary.json",
    )
    .unwrap();
    for key in ["duration", "peak_force"] {
        let (d, m) = (
            direct["contact"][key].as_f64().unwrap(),
            modal["contact"][key].as_f64().unwrap(),
        );
        assert!((m / d - 1.0).abs() < 1e-10, "{key}: direct {d:e}, modal {m:e}");
    }
    let t = &modal["run"]["modal"];
    let basis = t["modes"].as_u64().unwrap() + t["residual_vectors"].as_u64().unwrap();
    assert_eq!(basis, t["structure_dofs"].as_u64().unwrap(), "{t}");
    // The rod and its impactor are each free: the lowest elastic root is the third.
    let deck = impactlab::deck::read_deck(std::path::Path::new(rod), Default::default()).unwrap();
    let (s, _) = impactlab::run::modes::lowest(&deck, 3).unwrap();
    let top = s.modes[2].cycles / (std::f64::consts::PI / 288.0).sin();
    let highest = t["highest_mode_frequency"].as_f64().unwrap();
    assert!(
        (highest / top - 1.0).abs() < 1e-9,
        "highest {highest:e} against {top:e}"
    );
}

/// Goal: a threshold search runs on the modal engine: its kernels from one reduction
/// at the cutoff it is given, the bracket's ends checked on the modal engine on that
/// reduction; without a cutoff it is refused (the default cutoff comes from the
/// contact time at a speed, the speed being what the search looks for). Model: the
/// paper's rod, the speed at which the peak force reaches 300 lbf. Reference: the
/// search on the convolution engine (checked on the direct engine): the two speeds
/// within the bracket's width, 1e-6 (measured: the same bits), and `threshold.json`
/// naming the engine each was checked on.
#[test]
fn a_threshold_search_runs_on_the_modal_engine() {
    let rod = common::root().join("reference-data/decks/rod.bdf");
    let find = [
        "sweep",
        rod.to_str().unwrap(),
        "--find",
        "velocity",
        "--until",
        "peak_force=300",
    ];
    let conv = json_of(&[&find[..], &["--no-cache"]].concat(), "threshold.json").unwrap();
    let modal = json_of(
        &[&find[..], &["--engine", "modal", "--modes-up-to", "2e5"]].concat(),
        "threshold.json",
    )
    .unwrap();
    let (c, m) = (conv["velocity"].as_f64().unwrap(), modal["velocity"].as_f64().unwrap());
    assert!((m / c - 1.0).abs() <= 1e-6, "convolution {c:e}, modal {m:e}");
    assert_eq!(
        (conv["checked_on"].as_str(), modal["checked_on"].as_str()),
        (Some("direct"), Some("modal"))
    );
    assert!(modal["direct_check"].as_f64().unwrap() <= 1e-9, "{modal}");
    let refused = json_of(&[&find[..], &["--engine", "modal"]].concat(), "threshold.json").unwrap_err();
    assert!(refused.contains("needs its cutoff (--modes-up-to)"), "{refused}");
}
