//! The verification layer: cases (`verification/*.toml`, [`case`]), the check kinds
//! that judge one run ([`checks`]), gold files ([`gold`]), the audit of two runs
//! ([`audit`]), NASTRAN's printed output ([`printed`], [`element_tables`]), and the
//! verdicts as a table, JSON and JUnit.
//!
//! A case names a model (a deck, or the generated plate on an n×n mesh), how to run
//! it, and a list of checks. Each check yields one [`CheckResult`]: the value it
//! measured, the reference it compared with, the tolerance, and the verdict. The
//! analytic references live in [`crate::physics`]; the checks that need families of
//! runs (Δt and mesh convergence) and the running of cases live in
//! [`crate::study::cases`], which hands back a [`CaseOutcome`].

pub mod audit;
pub mod case;
pub mod checks;
pub mod external;
pub mod gold;
pub mod element_tables;
pub mod printed;

pub use case::{
    case_files, case_model, case_options, load_cases, read_case, Case, CaseError, CheckSpec, Quantity, RodQuantity, Tol,
};
pub use checks::{check, CheckError};

use crate::model::Model;
use crate::run::RunResult;
use serde::Serialize;
use std::path::PathBuf;

/// What a check accepts, as numbers a program can read and as words for a table.
///
/// A value passes when |value − reference| ≤ max(rtol·|reference|, atol) (a check
/// without a reference is a bound on |value|); `text` says the same for a reader,
/// with what a number is relative to (of peak, per column) where it is not the value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bound {
    /// Relative tolerance, if any.
    pub rtol: Option<f64>,
    /// Absolute tolerance, if any.
    pub atol: Option<f64>,
    /// The tolerance in words.
    #[serde(rename = "tolerance")]
    pub text: String,
}

impl Bound {
    /// |value| ≤ max.
    pub fn at_most(max: f64) -> Self {
        Bound {
            rtol: None,
            atol: Some(max),
            text: format!("≤ {max:.1e}"),
        }
    }
    /// |value| ≤ max, the value being a difference relative to a peak.
    pub fn of_peak(max: f64) -> Self {
        Bound {
            text: format!("≤ {max:.1e} of peak"),
            ..Bound::at_most(max)
        }
    }
    /// |value − reference| ≤ atol, in words.
    pub fn within(atol: f64, text: String) -> Self {
        Bound {
            rtol: None,
            atol: Some(atol),
            text,
        }
    }
}

/// The verdict of one check.
#[derive(Debug, Clone, Serialize)]
pub struct CheckResult {
    /// The case.
    pub case: String,
    /// The check (its kind, or its name).
    pub check: String,
    /// The value measured.
    pub value: f64,
    /// What the value is compared with; `null` for a bound on the value itself.
    pub reference: Option<f64>,
    /// What it is compared with.
    #[serde(flatten)]
    pub bound: Bound,
    /// The verdict.
    pub passed: bool,
    /// What was measured, in words.
    pub detail: String,
    /// Wall-clock seconds of this check alone (a convergence check's includes its runs).
    pub time_s: f64,
}

impl CheckResult {
    /// The verdict of a check of `case`; its time is set by whoever timed it.
    pub fn new(
        case: &Case,
        check: String,
        value: f64,
        reference: Option<f64>,
        bound: Bound,
        passed: bool,
        detail: String,
    ) -> Self {
        CheckResult {
            case: case.name.clone(),
            check,
            value,
            reference,
            bound,
            passed,
            detail,
            time_s: 0.0,
        }
    }
}

/// A case, what it solved and the verdicts of its checks: what `verify` judged and
/// what `report` draws, so that nothing is run twice.
#[derive(Debug, Clone)]
pub struct CaseOutcome {
    /// The case.
    pub case: Case,
    /// What it solved.
    pub solved: Solved,
    /// The verdicts of its checks.
    pub checks: Vec<CheckResult>,
    /// Wall-clock seconds of the case's run.
    pub wall_s: f64,
}

/// What a case solved: a transient run of its model, or its static decks.
#[derive(Debug, Clone)]
pub enum Solved {
    /// A transient case: its model and run.
    Transient {
        /// The model.
        model: Box<Model>,
        /// Its run.
        run: Box<RunResult>,
    },
    /// A static case: each deck's solution, in the case's order.
    Static(Vec<crate::run::statics::StaticSolution>),
}

impl CaseOutcome {
    /// The model and run of a transient case.
    pub fn transient(&self) -> Option<(&Model, &RunResult)> {
        match &self.solved {
            Solved::Transient { model, run } => Some((model, run)),
            Solved::Static(_) => None,
        }
    }
}

/// The verdicts of all cases.
#[derive(Debug, Clone)]
pub struct Verdicts {
    /// Every check's verdict.
    pub results: Vec<CheckResult>,
    /// Cases that could not run at all, with why.
    pub errors: Vec<(String, String)>,
}

impl Verdicts {
    /// Checks, passed, failed and cases in error.
    pub fn counts(&self) -> Counts {
        let failed = self.results.iter().filter(|r| !r.passed).count();
        Counts {
            checks: self.results.len(),
            passed: self.results.len() - failed,
            failed,
            cases_in_error: self.errors.len(),
        }
    }

    /// True when every case ran and every check passed.
    pub fn passed(&self) -> bool {
        self.errors.is_empty() && self.results.iter().all(|r| r.passed)
    }

    /// The verdicts of cases run (or not) in order.
    pub fn of<E: std::fmt::Display>(outcomes: &[(String, Result<CaseOutcome, E>)]) -> Self {
        let mut v = Verdicts {
            results: Vec::new(),
            errors: Vec::new(),
        };
        for (name, o) in outcomes {
            match o {
                Ok(o) => v.results.extend(o.checks.iter().cloned()),
                Err(e) => v.errors.push((name.clone(), e.to_string())),
            }
        }
        v
    }
}

/// The verdicts as a plain-text table.
pub fn table(v: &Verdicts) -> String {
    let mut s = format!(
        "{:<12} {:<50} {:>13} {:>13} {:<28} {}\n",
        "case", "check", "value", "reference", "tolerance", "verdict"
    );
    for r in &v.results {
        s += &format!(
            "{:<12} {:<50} {:>13.6e} {:>13} {:<28} {}\n",
            r.case,
            r.check,
            r.value,
            r.reference.map_or("-".into(), |x| format!("{x:.6e}")),
            r.bound.text,
            if r.passed { "pass" } else { "FAIL" }
        );
        if !r.passed {
            s += &format!("{:<12} {:<50} {}\n", "", "", r.detail);
        }
    }
    for (c, e) in &v.errors {
        s += &format!("{c:<12} {:<50} ERROR: {e}\n", "(case did not run)");
    }
    let c = v.counts();
    s += &format!(
        "{} checks, {} passed, {} failed, {} cases in error\n",
        c.checks, c.passed, c.failed, c.cases_in_error
    );
    s
}

/// The counts of a verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Checks.
    pub checks: usize,
    /// Checks passed.
    pub passed: usize,
    /// Checks failed.
    pub failed: usize,
    /// Cases that could not run.
    pub cases_in_error: usize,
}

/// `verify.json`: the verdict first (`passed`, `counts`), then every check.
pub fn json(v: &Verdicts) -> Vec<u8> {
    #[derive(Serialize)]
    struct File<'a> {
        passed: bool,
        counts: Counts,
        impactlab_version: &'static str,
        results: &'a [CheckResult],
        errors: Vec<CaseInError<'a>>,
    }
    #[derive(Serialize)]
    struct CaseInError<'a> {
        case: &'a str,
        error: &'a str,
    }
    let file = File {
        passed: v.passed(),
        counts: v.counts(),
        impactlab_version: env!("CARGO_PKG_VERSION"),
        results: &v.results,
        errors: v
            .errors
            .iter()
            .map(|(case, error)| CaseInError { case, error })
            .collect(),
    };
    let mut b = serde_json::to_vec_pretty(&file).expect("plain data");
    b.push(b'\n');
    b
}

/// `junit.xml`: one test suite per case, one test case per check.
pub fn junit(v: &Verdicts) -> Vec<u8> {
    use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
    let mut report = Report::new("impactlab verify");
    let mut names: Vec<&str> = v.results.iter().map(|r| r.case.as_str()).collect();
    names.extend(v.errors.iter().map(|e| e.0.as_str()));
    names.dedup();
    for name in names {
        let mut suite = TestSuite::new(name);
        for r in v.results.iter().filter(|r| r.case == name) {
            let status = if r.passed {
                TestCaseStatus::success()
            } else {
                let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                s.set_message(format!(
                    "value {:e}, reference {}, tolerance {}",
                    r.value,
                    r.reference.map_or("none".into(), |x| format!("{x:e}")),
                    r.bound.text
                ));
                s.set_description(r.detail.clone());
                s
            };
            let mut tc = TestCase::new(r.check.clone(), status);
            tc.set_classname(format!("verify.{name}"));
            tc.set_time(std::time::Duration::from_secs_f64(r.time_s));
            suite.add_test_case(tc);
        }
        for (_, e) in v.errors.iter().filter(|e| e.0 == name) {
            let mut s = TestCaseStatus::non_success(NonSuccessKind::Error);
            s.set_message(e.clone());
            let mut tc = TestCase::new("run", s);
            tc.set_classname(format!("verify.{name}"));
            suite.add_test_case(tc);
        }
        report.add_test_suite(suite);
    }
    report.to_string().expect("serialisable report").into_bytes()
}

/// A gold file that could not be written, or its check judged again.
#[derive(Debug, thiserror::Error)]
pub enum BlessError {
    /// The gold file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The gold file.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
    /// The check could not be judged again.
    #[error("{0}")]
    Check(#[from] CheckError),
}

/// Writes the gold files of a case's `gold` checks from its run (by hand, never in
/// CI), then judges those checks again against what was written.
pub fn bless(o: &mut CaseOutcome) -> Result<Vec<PathBuf>, BlessError> {
    let mut written = Vec::new();
    let Solved::Transient { model, run } = &o.solved else {
        return Ok(written);
    };
    for spec in &o.case.checks {
        if let CheckSpec::Gold { file, .. } = spec {
            let path = case::rel(&o.case, file);
            let bytes = crate::output::csv_bytes(&run.history_header(), run.history.iter().cloned());
            crate::output::write_file_atomically(&path, &bytes).map_err(|source| BlessError::Write {
                path: path.display().to_string(),
                source,
            })?;
            written.push(path);
            let verdict = check(&o.case, model, run, spec)?.expect("a gold check judges one run");
            if let Some(r) = o.checks.iter_mut().find(|r| r.check == verdict.check) {
                *r = verdict;
            }
        }
    }
    Ok(written)
}
