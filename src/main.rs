//! The `impactlab` command line: argument parsing and exit codes only.

use clap::{Parser, Subcommand};
use impactlab::integrate::Scheme;
use impactlab::run::RunOptions;
use impactlab::{deck, output, run, Error};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

// Printing never panics: a closed pipe (`impactlab ... | head`) just ends the output.
macro_rules! say {
    ($($t:tt)*) => {{ use std::io::Write; let _ = write!(std::io::stdout(), $($t)*); }};
}
macro_rules! sayln {
    ($($t:tt)*) => {{ use std::io::Write; let _ = writeln!(std::io::stdout(), $($t)*); }};
}
macro_rules! say_err {
    ($($t:tt)*) => {{ use std::io::Write; let _ = writeln!(std::io::stderr(), $($t)*); }};
}

#[derive(Parser)]
#[command(
    name = "impactlab",
    version,
    about = "Low-velocity impact analysis with an audited energy ledger"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a NASTRAN-style transient deck (or a scene, .toml) and write history.csv,
    /// energy.csv, summary.json.
    Run {
        /// The deck (.bdf), or a scene (.toml).
        deck: PathBuf,
        /// Output directory [default: out/<deck name>].
        #[arg(long)]
        out: Option<PathBuf>,
        /// Time integration scheme [default: newmark, or the scene's].
        #[arg(long, value_parser = scheme_parser())]
        scheme: Option<Scheme>,
        /// Time step in the deck's time unit [default: the deck's TSTEP].
        #[arg(long)]
        dt: Option<f64>,
        /// Number of steps [default: the deck's TSTEP].
        #[arg(long)]
        steps: Option<usize>,
        /// Stop with exit code 3 when the relative energy error exceeds this.
        #[arg(long)]
        max_energy_error: Option<f64>,
        /// Unknown bulk data cards become warnings instead of errors.
        #[arg(long)]
        allow_unknown: bool,
        /// Write displacement (and shell fibre strain) fields as VTU + a .pvd collection here.
        #[arg(long)]
        fields: Option<PathBuf>,
        /// Number of field snapshots, evenly spread over the run.
        #[arg(long, default_value_t = 50)]
        field_count: usize,
        /// Also solve DOFs that no load, initial condition or contact reaches (they stay
        /// zero; dropping them is exact). For measuring what dropping them saves.
        #[arg(long)]
        all_dofs: bool,
    },
    /// A scene: write its NASTRAN deck, or measure what each optional effect costs.
    Scene {
        scene: PathBuf,
        /// Write the equivalent NASTRAN deck here.
        #[arg(long)]
        to_deck: Option<PathBuf>,
        /// Time the scene with and without each optional effect (median of 3 runs).
        #[arg(long)]
        costs: bool,
    },
    /// Generate a deck.
    Mesh {
        #[command(subcommand)]
        what: MeshKind,
    },
    /// Families of runs.
    Study {
        #[command(subcommand)]
        what: StudyKind,
    },
    /// Run verification cases and gate on their checks (exit 1 if any fails).
    Verify {
        /// Case files or directories of them [default: verification/].
        cases: Vec<PathBuf>,
        /// Where verify.json and junit.xml go.
        #[arg(long, default_value = "out/verify")]
        out: PathBuf,
        /// Cases run in parallel.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
        /// Write the gold files of the cases' gold checks from this run (never in CI).
        #[arg(long)]
        bless: bool,
    },
    /// Run cases and write their reports (figures, ledger, verdicts) and an index.
    Report {
        /// Case files or directories [default: verification/].
        cases: Vec<PathBuf>,
        #[arg(long, default_value = "reports")]
        out: PathBuf,
    },
    /// Compare two runs' output directories: what moved and by how much.
    Audit { baseline: PathBuf, candidate: PathBuf },
    /// Time the paper's 49×49 plate (3000 steps) and report where the time goes.
    Bench {
        /// Timed repeats after one warm-up run; the median is reported.
        #[arg(long, default_value_t = 5)]
        repeats: usize,
        /// Number of steps.
        #[arg(long, default_value_t = 3000)]
        steps: usize,
    },
}

#[derive(Subcommand)]
enum StudyKind {
    /// The plate on several meshes (generated): contact duration, peak force, gage strains.
    Mesh {
        /// Mesh sizes (elements per side, odd).
        #[arg(long, value_delimiter = ',', default_values_t = [25, 49, 61])]
        n: Vec<usize>,
        /// Output directory for mesh-study.csv and mesh-study.json.
        #[arg(long, default_value = "out/mesh-study")]
        out: PathBuf,
    },
    /// Stability map: the rod over Δt × impact velocity, per scheme.
    Stability {
        #[arg(long, default_value = "reports/stability")]
        out: PathBuf,
    },
    /// Work-precision study: every scheme over Δt and mesh, errors against references.
    Accuracy {
        #[arg(long, default_value = "reports/accuracy")]
        out: PathBuf,
        /// Timed repeats after a warm-up run (wall time is their median).
        #[arg(long, default_value_t = 5)]
        repeats: usize,
        /// Plate meshes of the mesh sweep (the finest is the reference).
        #[arg(long, value_delimiter = ',', default_values_t = [13, 25, 49, 61, 97])]
        plate_meshes: Vec<usize>,
    },
}

#[derive(Subcommand)]
enum MeshKind {
    /// The paper's clamped composite plate on an N×N mesh (N odd).
    Plate {
        /// Elements along each side.
        #[arg(long)]
        n: usize,
        /// Where to write the deck [default: stdout].
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli) {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            say_err!("{e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

/// `--scheme`: one of [`Scheme::ALL`] by name.
fn scheme_parser() -> impl clap::builder::TypedValueParser<Value = Scheme> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(Scheme::ALL.map(Scheme::name))
        .map(|name| Scheme::from_name(&name).expect("one of the listed names"))
}

fn execute(cli: Cli) -> Result<u8, Error> {
    match cli.command {
        Command::Run {
            deck: path,
            out,
            scheme,
            dt,
            steps,
            max_energy_error,
            allow_unknown,
            all_dofs,
            fields,
            field_count,
        } => {
            if let Some(dt) = dt {
                if !(dt > 0.0 && dt.is_finite()) {
                    return Err(Error::Usage(format!("--dt must be a positive number, not {dt}")));
                }
            }
            if steps == Some(0) {
                return Err(Error::Usage("--steps must be positive".into()));
            }
            let is_scene = path.extension().is_some_and(|e| e == "toml");
            let (model, opts, scene) = if is_scene {
                if all_dofs || allow_unknown {
                    return Err(Error::Usage(format!(
                        "{}: --all-dofs and --allow-unknown apply to decks; a scene generates a deck with \
                         no unknown cards and says itself which DOFs to solve (effects.membrane = true)",
                        path.display()
                    )));
                }
                let (s, model, _) = impactlab::scene::load(&path)?;
                let mut o = RunOptions::for_scene(&s);
                o.scheme = scheme.unwrap_or(s.run.scheme);
                (model, o, Some(s))
            } else {
                let (model, warnings) = impactlab::load_deck(&path, deck::ReadOptions { allow_unknown })?;
                for w in &warnings {
                    say_err!("{w}");
                }
                (
                    model,
                    RunOptions {
                        scheme: scheme.unwrap_or_default(),
                        skip_inert: !all_dofs,
                        ..Default::default()
                    },
                    None,
                )
            };
            let mut opts = RunOptions {
                dt: dt.or(opts.dt),
                steps: steps.or(opts.steps),
                max_energy_error,
                progress: std::io::stderr().is_terminal(),
                ..opts
            };
            if fields.is_some() {
                opts.snapshot_times = impactlab::report::fields::field_times(
                    opts.dt.unwrap_or(model.time.dt),
                    opts.steps.unwrap_or(model.time.steps),
                    field_count,
                );
            }
            let mut r = run::run_model(&model, &opts)?;
            if let Some(s) = &scene {
                let m = &r.summary;
                r.summary.effects = Some(impactlab::scene::effects(
                    s,
                    m.model.inert_dofs_skipped,
                    m.run.steps_done,
                ));
                r.summary.contact_stiffness_source = impactlab::scene::contact_stiffness(s).map(|k| k.1).ok();
            }
            let dir = out.unwrap_or_else(|| PathBuf::from("out").join(&model.name));
            output::write_dir_atomically(&dir, &output::run_files(&model, &r)).map_err(|source| Error::Io {
                path: dir.display().to_string(),
                source,
            })?;
            say!("{}", output::human_summary(&model, &r));
            sayln!("  outputs:  {}", dir.display());
            if let Some(fdir) = fields {
                let files = impactlab::report::fields::write_fields(&model, &r, &fdir).map_err(Error::Usage)?;
                sayln!(
                    "  fields:   {} VTU files and fields.pvd in {}",
                    files.len() - 1,
                    fdir.display()
                );
            }
            Ok(0)
        }
        Command::Scene { scene, to_deck, costs } => {
            let (s, model, deck) = impactlab::scene::load(&scene)?;
            let opts = RunOptions::for_scene(&s);
            let (k, how) = impactlab::scene::contact_stiffness(&s).map_err(Error::Usage)?;
            sayln!("Hertz K = {k:.6e} ({how})");
            if let Some(p) = to_deck {
                output::write_file_atomically(&p, deck.as_bytes()).map_err(|source| Error::Io {
                    path: p.display().to_string(),
                    source,
                })?;
                sayln!("deck: {}", p.display());
            }
            if costs {
                say!("{}", impactlab::study::scene_costs(&model, &opts)?);
            }
            Ok(0)
        }
        Command::Mesh {
            what: MeshKind::Plate { n, out },
        } => {
            let text = impactlab::mesh::plate_deck(n).map_err(Error::Usage)?;
            match out {
                Some(p) => output::write_file_atomically(&p, text.as_bytes()).map_err(|source| Error::Io {
                    path: p.display().to_string(),
                    source,
                })?,
                None => say!("{text}"),
            }
            Ok(0)
        }
        Command::Study {
            what: StudyKind::Mesh { n, out },
        } => {
            let opts = impactlab::study::mesh_study_options(std::io::stderr().is_terminal());
            let rows = impactlab::study::plate_mesh_study(&n, &opts)?;
            let files = impactlab::study::mesh_study_files(&rows);
            output::write_dir_atomically(&out, &files).map_err(|source| Error::Io {
                path: out.display().to_string(),
                source,
            })?;
            say!("{}", String::from_utf8_lossy(&files[0].1));
            sayln!("outputs: {}", out.display());
            Ok(0)
        }
        Command::Verify {
            cases,
            out,
            jobs,
            bless,
        } => {
            use impactlab::verify;
            let cases = verify::load_cases(&cases)?;
            if bless {
                for c in &cases {
                    if c.checks.iter().any(|k| matches!(k, verify::CheckSpec::Gold { .. })) {
                        let (run, _) = verify::run_case(c)?;
                        for p in verify::bless(c, &run)? {
                            sayln!("wrote {}", p.display());
                        }
                    }
                }
            }
            let v = verify::verify(&cases, jobs);
            say!("{}", verify::table(&v));
            let files = [("verify.json", verify::json(&v)), ("junit.xml", verify::junit(&v))];
            output::write_dir_atomically(&out, &files).map_err(|source| Error::Io {
                path: out.display().to_string(),
                source,
            })?;
            sayln!("outputs: {}", out.display());
            Ok(if v.passed() { 0 } else { 1 })
        }
        Command::Report { cases, out } => {
            use impactlab::{report, verify};
            let cases = verify::load_cases(&cases)?;
            let mut done = Vec::new();
            for c in cases.iter().filter(|c| c.deck.is_some()) {
                let r = report::report_case(c, &out.join(&c.name))?;
                say!("{}", r.human);
                sayln!(
                    "{}: {} checks passed, {} failed, {} figures",
                    r.name,
                    r.passed,
                    r.failed,
                    r.figures.len()
                );
                done.push(r);
            }
            let index = out.join("README.md");
            output::write_file_atomically(&index, report::index(&out).as_bytes()).map_err(|source| Error::Io {
                path: index.display().to_string(),
                source,
            })?;
            sayln!("index: {}", index.display());
            Ok(0)
        }
        Command::Audit { baseline, candidate } => {
            let moved = impactlab::verify::audit::audit(&baseline, &candidate).map_err(Error::Usage)?;
            say!("{}", impactlab::verify::audit::audit_text(&moved));
            Ok(0)
        }
        Command::Study {
            what:
                StudyKind::Accuracy {
                    out,
                    repeats,
                    plate_meshes,
                },
        } => {
            let rows =
                impactlab::study::accuracy::run_study(&out, repeats.max(1), &plate_meshes, &|s| say_err!("  {s}"))?;
            sayln!("{} runs; outputs: {}", rows.len(), out.display());
            Ok(0)
        }
        Command::Study {
            what: StudyKind::Stability { out },
        } => {
            use impactlab::study::stability;
            let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reference-data/decks/rod.bdf");
            let (model, _) = impactlab::load_deck(&path, Default::default())?;
            let cells = stability::run_map(&model, 2e-7, 500e-6, &|s| say_err!("  {s}"))?;
            let io = |source| Error::Io {
                path: out.display().to_string(),
                source,
            };
            std::fs::create_dir_all(&out).map_err(io)?;
            output::write_file_atomically(&out.join("stability-map.csv"), stability::csv(&cells).as_bytes())
                .map_err(io)?;
            stability::figure(&cells, 2e-7, &out.join("stability-map")).map_err(Error::Usage)?;
            output::write_file_atomically(&out.join("README.md"), stability::readme(&cells).as_bytes()).map_err(io)?;
            let failed = cells.iter().filter(|c| c.outcome.is_err()).count();
            sayln!(
                "{} runs, {} refused or failed; outputs: {}",
                cells.len(),
                failed,
                out.display()
            );
            Ok(0)
        }
        Command::Bench { repeats, steps } => {
            let report = impactlab::study::bench_plate(repeats.max(1), steps)?;
            say!("{report}");
            Ok(0)
        }
    }
}
