//! The `impactlab` command line: the clap structs, and the dispatch of each
//! subcommand to its function in [`cli`], which maps errors to exit codes.

mod cli;

use clap::{Parser, Subcommand};
use impactlab::integrate::Scheme;
use impactlab::run::Engine;
use std::path::PathBuf;
use std::process::ExitCode;

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
pub enum Command {
    /// Run a NASTRAN-style transient deck (or a scene, .toml) and write history.csv,
    /// energy.csv, summary.json.
    Run(RunArgs),
    /// A scene: write its NASTRAN deck, or measure what each optional effect costs.
    Scene(SceneArgs),
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
    /// Will impactlab take this deck? Build its structure alone (no impactor needed)
    /// and report grids, elements, DOFs, mass, centre of gravity and inertia, the
    /// coordinate systems and every card it does not take (exit 0 when it takes the
    /// deck, 2 when not).
    Check(CheckArgs),
    /// Run verification cases and gate on their checks (exit 1 if any fails).
    Verify(VerifyArgs),
    /// Run cases and write their reports (figures, ledger, verdicts) and an index.
    Report(ReportArgs),
    /// Compare two runs' (or two `verify` runs') output directories: what moved and
    /// by how much; exit 1 when anything moved beyond tolerance.
    Audit(AuditArgs),
    /// Compare a static run's displacements with NASTRAN's printed output (.f06, .out):
    /// the largest differences by grid and component, per SUBCASE; exit 1 when one
    /// exceeds --tolerance.
    Compare(CompareArgs),
    /// Time the paper's 49×49 plate (3000 steps) and report where the time goes.
    Bench(BenchArgs),
    /// Sweep a deck or a scene over impact velocity, impactor mass, Hertz K and exponent on the
    /// convolution engine: sweep.csv (one row per point) and summary.json.
    Sweep(SweepArgs),
    /// Merge the output directories of a sharded sweep into the sweep.csv an unsharded
    /// run writes.
    Collect(CollectArgs),
    /// Print a page of the user guide's reference that is generated from the program
    /// (`docs/src/reference/`), which a test holds to it.
    #[command(hide = true)]
    Reference {
        /// `cli` (cli.md), `summary` (summary-schema.md), `summary-schema`
        /// (summary.schema.json) or `cards` (card-fields.md).
        #[arg(value_enum)]
        page: ReferencePage,
    },
}

#[derive(clap::Args)]
pub struct SweepArgs {
    /// The deck (.bdf), or a scene (.toml).
    pub deck: PathBuf,
    /// NAME=START:STOP:COUNT or NAME=v1,v2,... with NAME one of velocity, mass, k,
    /// exponent (values in the deck's units; velocity is the speed, the deck's
    /// direction kept). Repeat for a grid (the first varies slowest).
    #[arg(long, required_unless_present = "find", conflicts_with = "find")]
    pub vary: Vec<String>,
    /// Find the threshold of this parameter instead of sweeping: `velocity`, the lowest
    /// impact speed at which `--until` holds (bisection to 1e-6 on the convolution
    /// engine, checked on the direct engine); prints the impact energy ½mv².
    #[arg(long, value_parser = ["velocity"], requires = "until")]
    pub find: Option<String>,
    /// What the threshold is: `peak_force=F` (the peak contact force reaches F, in the
    /// deck's force unit), `delamination` (it reaches the plate's Davies-Zhang
    /// threshold F_crit; needs --giic), `failure_index=L` (the largest ply failure
    /// index of the PCOMP's FT theory, over the STRESS/STRAIN set's laminate elements,
    /// reaches L; 1 is first-ply failure) or `bond_index=L` (the largest interlaminar
    /// shear over SB there, on a plate flexible in transverse shear).
    #[arg(long, requires = "find")]
    pub until: Option<String>,
    /// The interface's mode II fracture toughness G_IIc in the deck's units
    /// (force/length), for --until delamination.
    #[arg(long, value_name = "G_IIc")]
    pub giic: Option<f64>,
    /// Space these parameters' START:STOP:COUNT values geometrically.
    #[arg(long)]
    pub log: Vec<String>,
    /// The scheme: the trapezoidal ones, which the convolution engine runs.
    #[arg(long, default_value = "newmark", value_parser = trapezoidal_scheme_parser())]
    pub scheme: Scheme,
    /// Time step in the deck's time unit [default: the deck's TSTEP].
    #[arg(long)]
    pub dt: Option<f64>,
    /// Number of steps [default: the deck's TSTEP].
    #[arg(long)]
    pub steps: Option<usize>,
    /// Output directory [default: out/<deck name>-sweep].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Points run at once [default: every core].
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Run only shard I of N (I from 1): the points numbered I−1 modulo N.
    #[arg(long)]
    pub shard: Option<String>,
    /// Keep the convolution engine's kernels in DIR [default: $XDG_CACHE_HOME/impactlab,
    /// or ~/.cache/impactlab].
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,
    /// Compute the convolution engine's kernels afresh and store nothing.
    #[arg(long, conflicts_with = "cache")]
    pub no_cache: bool,
    /// The self-check: this many points, spread evenly from the first to the last,
    /// are also run on the direct engine (2: the first and the last), and the point
    /// nearest the deck's own values when the sweep spans them. 0 turns the
    /// self-check off (a warning, and `self_check.off` in summary.json).
    #[arg(long, value_name = "N", default_value_t = 2)]
    pub checks: usize,
    /// Also check every N-th point (0, N, 2N, ...) on the direct engine.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub check_every: Option<u64>,
    /// Where the kernels come from: `convolution` (the deck's own system, checked on
    /// the direct engine) or `modal` (its reduction to the modes up to --modes-up-to
    /// and residual vectors, computed once and not cached; the checked points are
    /// stepped on the modal engine on the same reduction). With --find, `modal` needs
    /// --modes-up-to, and the bracket's ends are checked on the modal engine.
    #[arg(long, default_value = "convolution", value_parser = sweep_engine_parser())]
    pub engine: Engine,
    /// The modal engine's cutoff, in cycles per the deck's time unit [default: 4 cycles
    /// over the shortest Hertz contact time on a rigid target of the sweep's points].
    #[arg(long, value_name = "FREQUENCY")]
    pub modes_up_to: Option<f64>,
}

#[derive(clap::Args)]
pub struct CollectArgs {
    /// The shards' output directories.
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Where the merged sweep.csv and summary.json go.
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Subcommand)]
pub enum StudyKind {
    /// The plate on several meshes (generated): contact duration, peak force, gage strains.
    Mesh {
        /// Mesh sizes (elements per side, odd).
        #[arg(long, value_delimiter = ',', default_values_t = impactlab::study::mesh::MESHES)]
        n: Vec<usize>,
        /// Output directory: mesh-study.csv, mesh-histories.csv, README.md and figures.
        #[arg(long, default_value = "reports/mesh")]
        out: PathBuf,
        /// Remake README.md and the figures from the CSVs in the output directory; run nothing.
        #[arg(long)]
        redraw: bool,
    },
    /// The curved panel (R = 10 in) against the flat plate on several meshes: contact,
    /// energy ledger, gage strains side by side.
    Panel {
        /// Mesh sizes (elements per side, odd).
        #[arg(long, value_delimiter = ',', default_values_t = impactlab::study::mesh::MESHES)]
        n: Vec<usize>,
        /// Output directory: panel-study.csv, panel-histories.csv, README.md and figures.
        #[arg(long, default_value = "reports/panel")]
        out: PathBuf,
        /// Remake README.md and the figures from the CSVs in the output directory; run nothing.
        #[arg(long)]
        redraw: bool,
    },
    /// The stiffened plate (three blade stiffeners) struck on a stiffener and between
    /// stiffeners, beside the unstiffened plate: contact, where the energy goes, the
    /// threshold speed of each.
    Stiffened {
        /// Mesh sizes (elements per side, odd).
        #[arg(long, value_delimiter = ',', default_values_t = impactlab::study::stiffened::MESHES)]
        n: Vec<usize>,
        /// Output directory: stiffened-study.csv, stiffened-histories.csv,
        /// stiffened-thresholds.csv, README.md and the figure.
        #[arg(long, default_value = "reports/stiffened")]
        out: PathBuf,
        /// Remake README.md and the figure from the CSVs in the output directory; run nothing.
        #[arg(long)]
        redraw: bool,
    },
    /// The mutation campaign's page (reports/mutants): made from campaign.toml and each
    /// run's CSV; with --from, a cargo-mutants output directory is first recorded as a run.
    Mutants {
        /// A cargo-mutants output directory (mutants.out) to record.
        #[arg(long, requires = "run")]
        from: Option<PathBuf>,
        /// The run's name in campaign.toml (its CSV's stem).
        #[arg(long)]
        run: Option<String>,
        #[arg(long, default_value = "reports/mutants")]
        out: PathBuf,
    },
    /// Stability map: the rod over Δt × impact velocity, per scheme.
    Stability {
        #[arg(long, default_value = "reports/stability")]
        out: PathBuf,
    },
    /// The stability suite's hard cases on the N×N plate (edge impact, velocity ×100,
    /// Δt ×64, K ×1000) for the implicit schemes; exit 1 if any fails.
    HardCases {
        /// Elements per side (odd).
        #[arg(long, default_value_t = 99)]
        n: usize,
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
        /// Remake README.md and the figures from work-precision.csv in the output directory; run nothing.
        #[arg(long)]
        redraw: bool,
    },
}

#[derive(Subcommand)]
pub enum MeshKind {
    /// The paper's clamped composite plate on an N×N mesh (N odd).
    Plate {
        /// Elements along each side.
        #[arg(long)]
        n: usize,
        /// The shell elements: `quad4` (CQUAD4, the paper's) or `tria3` (each square
        /// cut into two CTRIA3).
        #[arg(long, default_value = "quad4", value_parser = cells_parser())]
        cells: impactlab::mesh::Cells,
        /// Blade stiffeners under the plate (0.15 × 0.5 in CBARs of the skin's G11,
        /// offset to its back face), equally spaced along x under grid rows.
        #[arg(long, default_value_t = 0)]
        stiffeners: usize,
        /// Where to write the deck [default: stdout].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The paper's plate wrapped onto a cylinder of radius R (its 6 in × 6 in as arc
    /// and width, clamped, struck at the centre): a curved panel, N×N (N odd).
    Panel {
        /// Elements along each side.
        #[arg(long)]
        n: usize,
        /// The cylinder's radius, in the deck's length unit (in).
        #[arg(long)]
        radius: f64,
        /// The shell elements: `quad4` or `tria3`.
        #[arg(long, default_value = "quad4", value_parser = cells_parser())]
        cells: impactlab::mesh::Cells,
        /// Where to write the deck [default: stdout].
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(clap::Args)]
pub struct RunArgs {
    /// The deck (.bdf), or a scene (.toml).
    pub deck: PathBuf,
    /// Output directory [default: out/<deck name>].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Time integration scheme [default: newmark, or the scene's].
    #[arg(long, value_parser = scheme_parser())]
    pub scheme: Option<Scheme>,
    /// How to compute the run: `direct` (step by step, the reference),
    /// `convolution` (the target's response to a unit contact load once, then the
    /// contact by an exact history sum; newmark and energy only, no --fields) or
    /// `modal` (the target reduced to its modes up to --modes-up-to and residual
    /// vectors at the contact and the loads; not central).
    #[arg(long, default_value = "direct", value_parser = engine_parser())]
    pub engine: Engine,
    /// The modal engine's cutoff: keep the modes up to this frequency, in cycles per
    /// the deck's time unit [default: 4 cycles over the impactor's Hertz contact time
    /// on a rigid target].
    #[arg(long, value_name = "FREQUENCY")]
    pub modes_up_to: Option<f64>,
    /// Keep the convolution engine's kernels in DIR [default: $XDG_CACHE_HOME/impactlab,
    /// or ~/.cache/impactlab].
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,
    /// Compute the convolution engine's kernels afresh and store nothing.
    #[arg(long, conflicts_with = "cache")]
    pub no_cache: bool,
    /// Time step in the deck's time unit [default: the deck's TSTEP].
    #[arg(long)]
    pub dt: Option<f64>,
    /// Number of steps [default: the deck's TSTEP].
    #[arg(long)]
    pub steps: Option<usize>,
    /// The energy guard: stop with exit code 3 when |relative energy error| exceeds
    /// this, writing the outputs up to there marked incomplete; `off` disables it.
    /// A structure loaded from rest (DLOAD, no initial energy) is not guarded.
    #[arg(long, value_parser = energy_guard_parser, default_value = "5e-2")]
    pub max_energy_error: EnergyGuard,
    /// Refuse, before allocating, a run estimated to need more than this many GiB
    /// (the system and the per-step records; exit 2). The modal engine's reduction
    /// keeps to what the limit leaves, and stops (exit 2) when it would pass it.
    #[arg(long, default_value_t = 4.0)]
    pub max_memory: f64,
    /// The interface's mode II fracture toughness G_IIc in the deck's units
    /// (force/length): summary.json then gives the plate's delamination threshold
    /// F_crit (Davies-Zhang) against the peak force.
    #[arg(long, value_name = "G_IIc")]
    pub giic: Option<f64>,
    /// Unknown bulk data cards become warnings instead of errors.
    #[arg(long)]
    pub allow_unknown: bool,
    /// Write fields for ParaView here: a VTU per snapshot (grid ids, displacement, velocity; element ids, strains) and a .pvd collection.
    #[arg(long)]
    pub fields: Option<PathBuf>,
    /// Number of field snapshots, evenly spread over the run.
    #[arg(long, default_value_t = 50)]
    pub field_count: usize,
    /// Also solve DOFs that no load, initial condition or contact reaches (they stay
    /// zero; dropping them is exact). For measuring what dropping them saves.
    #[arg(long)]
    pub all_dofs: bool,
    /// Report progress on standard error even when it is not a terminal (a line every
    /// 10 s, for logs: the steps done, or before the first step what the run is doing,
    /// as the modal engine's reduction); on a terminal a progress bar is always drawn.
    #[arg(long)]
    pub progress: bool,
}

#[derive(clap::Args)]
pub struct SceneArgs {
    pub scene: PathBuf,
    /// Write the equivalent NASTRAN deck here.
    #[arg(long)]
    pub to_deck: Option<PathBuf>,
    /// Time the scene with and without each optional effect (median of 3 runs).
    #[arg(long)]
    pub costs: bool,
}

#[derive(clap::Args)]
pub struct CheckArgs {
    /// The deck (.bdf): any solution sequence; loads, output requests and cards that
    /// do not change the structure are listed as ignored.
    pub deck: PathBuf,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Also find the structure's N lowest natural frequencies (Lanczos, as a normal
    /// modes run finds them; the structure is built whole, stiffness and all).
    #[arg(long, value_name = "N")]
    pub modes: Option<usize>,
}

#[derive(clap::Args)]
pub struct VerifyArgs {
    /// Case files or directories of them [default: verification/].
    pub cases: Vec<PathBuf>,
    /// Where verify.json and junit.xml go.
    #[arg(long, default_value = "out/verify")]
    pub out: PathBuf,
    /// Cases run in parallel.
    #[arg(long, default_value_t = 2)]
    pub jobs: usize,
    /// Write the gold files of the cases' gold checks from this run (never in CI).
    #[arg(long)]
    pub bless: bool,
}

#[derive(clap::Args)]
pub struct ReportArgs {
    /// Case files or directories [default: verification/].
    pub cases: Vec<PathBuf>,
    #[arg(long, default_value = "reports")]
    pub out: PathBuf,
}

#[derive(clap::Args)]
pub struct BenchArgs {
    /// Timed repeats after one warm-up run; the median is reported.
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Number of steps.
    #[arg(long, default_value_t = 3000)]
    pub steps: usize,
    /// Instead: how the reader, assembly, factorisation, stepping and peak memory
    /// scale over the 49, 99 and 199 plates (each run --steps steps), and the reader
    /// over decks up to a million lines.
    #[arg(long)]
    pub size: bool,
    /// Instead: `check` on a 250 000-element panel deck, by stage, with its peak
    /// memory against the deck's size (median of --repeats after a warm-up).
    #[arg(long, conflicts_with = "size")]
    pub check: bool,
    /// Instead: the Lanczos extraction of the 20 lowest roots of the 49, 99 and 199
    /// plates (its structure alone), by stage, with its time per root.
    #[arg(long, conflicts_with_all = ["size", "check"])]
    pub modes: bool,
}

#[derive(clap::Args)]
pub struct AuditArgs {
    /// A run's output directory, or a `verify` output directory.
    pub baseline: PathBuf,
    /// The same kind of directory, from the change under review.
    pub candidate: PathBuf,
    /// Relative tolerance: of |baseline| for a summary number, of the column's peak
    /// |value| for a CSV column.
    #[arg(long, default_value_t = 0.0)]
    pub rtol: f64,
    /// Absolute tolerance, in the quantity's own units.
    #[arg(long, default_value_t = 0.0)]
    pub atol: f64,
    /// text (a table), json, or markdown (to paste into a pull request).
    #[arg(long, value_enum, default_value_t = AuditFormat::Text)]
    pub format: AuditFormat,
}

#[derive(clap::Args)]
pub struct CompareArgs {
    /// The output directory of `impactlab run` on a static, normal modes or transient
    /// deck.
    pub run: PathBuf,
    /// NASTRAN's printed output of the same deck (its DISPLACEMENT VECTOR tables, its
    /// REAL EIGENVALUES table for a normal modes run, or its SORT2 displacement
    /// histories for a transient run).
    pub nastran: PathBuf,
    /// How many of the largest differences to list per SUBCASE.
    #[arg(long, default_value_t = 10)]
    pub top: usize,
    /// The largest difference allowed, relative to the largest printed translation
    /// (rotation for R1-R3), or to each printed eigenvalue; exit 1 beyond it. None by
    /// default.
    #[arg(long)]
    pub tolerance: Option<f64>,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum AuditFormat {
    Text,
    Json,
    Markdown,
}

/// `--max-energy-error`: a limit, or none.
#[derive(Debug, Clone, Copy)]
pub struct EnergyGuard(pub Option<f64>);

fn energy_guard_parser(s: &str) -> Result<EnergyGuard, String> {
    if s == "off" {
        return Ok(EnergyGuard(None));
    }
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x.is_finite() => Ok(EnergyGuard(Some(x))),
        _ => Err(format!("expected a positive number or `off`, not `{s}`")),
    }
}

/// `--scheme`: one of [`Scheme::ALL`] by name.
fn scheme_parser() -> impl clap::builder::TypedValueParser<Value = Scheme> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(Scheme::ALL.map(Scheme::name))
        .map(|name| Scheme::from_name(&name).expect("one of the listed names"))
}

fn cells_parser() -> impl clap::builder::TypedValueParser<Value = impactlab::mesh::Cells> {
    use clap::builder::TypedValueParser;
    use impactlab::mesh::Cells;
    clap::builder::PossibleValuesParser::new(["quad4", "tria3"]).map(|name| match name.as_str() {
        "tria3" => Cells::Tria3,
        _ => Cells::Quad4,
    })
}

/// `--scheme` of a sweep: the schemes the convolution engine runs (the trapezoidal
/// ones), and only those listed.
fn trapezoidal_scheme_parser() -> impl clap::builder::TypedValueParser<Value = Scheme> {
    use clap::builder::TypedValueParser;
    let names: Vec<&str> = Scheme::ALL
        .into_iter()
        .filter(|s| s.newmark_params().is_some())
        .map(Scheme::name)
        .collect();
    clap::builder::PossibleValuesParser::new(names)
        .map(|name| Scheme::from_name(&name).expect("one of the listed names"))
}

/// `--engine`: `direct`, `convolution` or `modal`.
fn engine_parser() -> impl clap::builder::TypedValueParser<Value = Engine> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(["direct", "convolution", "modal"]).map(|name| match name.as_str() {
        "convolution" => Engine::Convolution,
        "modal" => Engine::Modal,
        _ => Engine::Direct,
    })
}

/// `--engine` of a sweep: where its kernels come from, `convolution` or `modal`.
fn sweep_engine_parser() -> impl clap::builder::TypedValueParser<Value = Engine> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(["convolution", "modal"]).map(|name| match name.as_str() {
        "modal" => Engine::Modal,
        _ => Engine::Convolution,
    })
}

/// The generated pages of the user guide's reference.
#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ReferencePage {
    /// The command-line reference.
    Cli,
    /// `summary.json`'s keys.
    Summary,
    /// `summary.json`'s JSON Schema.
    SummarySchema,
    /// Every card's fields as the reader reads them.
    Cards,
}

/// The command-line reference: every command's and subcommand's long help, each
/// under its own heading, as clap renders it (at its fixed width, so the page does
/// not depend on the terminal).
fn reference() -> String {
    use clap::CommandFactory;
    use std::fmt::Write;
    fn section(cmd: &mut clap::Command, path: &str, level: usize, out: &mut String) {
        let _ = write!(
            out,
            "{} `{path}`\n\n```text\n{}\n```\n\n",
            "#".repeat(level),
            cmd.render_long_help()
                .to_string()
                .trim_end()
                .lines()
                .map(str::trim_end)
                .collect::<Vec<_>>()
                .join("\n")
        );
        for sub in cmd
            .get_subcommands_mut()
            .filter(|s| !s.is_hide_set() && s.get_name() != "help")
        {
            let path = format!("{path} {}", sub.get_name());
            section(sub, &path, level + 1, out);
        }
    }
    let mut cmd = Cli::command();
    cmd.build();
    let mut out = String::from(
        "# Command-line reference\n\nEvery command and flag, as `impactlab COMMAND --help` prints it. This page is \
         generated from the program (`impactlab reference cli > docs/src/reference/cli.md`) and `tests/book.rs` fails \
         when it differs.\n\n",
    );
    section(&mut cmd, "impactlab", 2, &mut out);
    out
}

fn main() -> ExitCode {
    cli::handle_signals();
    let result = match Cli::parse().command {
        Command::Run(a) => cli::run(a),
        Command::Scene(a) => cli::scene(a),
        Command::Mesh { what } => cli::mesh(what),
        Command::Study { what } => cli::study(what),
        Command::Check(a) => cli::check(a),
        Command::Verify(a) => cli::verify(a),
        Command::Report(a) => cli::report(a),
        Command::Audit(a) => cli::audit(a),
        Command::Compare(a) => cli::compare(a),
        Command::Bench(a) => cli::bench(a),
        Command::Sweep(a) => cli::sweep(a),
        Command::Collect(a) => cli::collect(a),
        Command::Reference { page } => {
            match page {
                ReferencePage::Cli => print!("{}", reference()),
                ReferencePage::Summary => print!("{}", impactlab::run::summary::schema_markdown()),
                ReferencePage::SummarySchema => println!(
                    "{}",
                    serde_json::to_string_pretty(&impactlab::run::summary::json_schema())
                        .expect("a JSON value serialises")
                ),
                ReferencePage::Cards => print!("{}", impactlab::deck::cards::fields_markdown()),
            }
            Ok(0)
        }
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            cli::say_err(&e.to_string());
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
