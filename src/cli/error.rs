//! The program's error: every stage's error, and the exit code each maps to. It exists
//! only here, at the command line; the library's stages each return their own.

use impactlab::deck::DeckError;
use impactlab::integrate::SolveError;
use impactlab::model::{LoadError, ModelError};
use impactlab::run::RunError;
use impactlab::study::StudyError;

/// Everything that can fail, by stage; [`Error::exit_code`] maps it to the program's exit code.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A deck could not be loaded.
    #[error("{0}")]
    Load(#[from] LoadError),
    /// The solver failed.
    #[error("numerical failure: {0}")]
    Solve(#[from] SolveError),
    /// A run failed.
    #[error("{0}")]
    Run(#[from] RunError),
    /// A model modification could not be made.
    #[error("{0}")]
    Modify(#[from] impactlab::model::ModifyError),
    /// A verification case could not be read.
    #[error("{0}")]
    Case(#[from] impactlab::verify::CaseError),
    /// A check could not be evaluated.
    #[error("{0}")]
    Check(#[from] impactlab::verify::CheckError),
    /// Gold files could not be written.
    #[error("{0}")]
    Bless(#[from] impactlab::verify::BlessError),
    /// A mesh could not be generated.
    #[error("{0}")]
    Mesh(#[from] impactlab::mesh::MeshError),
    /// A scene could not be read or built.
    #[error("{0}")]
    Scene(#[from] impactlab::scene::SceneError),
    /// A figure could not be drawn.
    #[error("{0}")]
    Plot(#[from] impactlab::plot::PlotError),
    /// An audit could not read its inputs.
    #[error("{0}")]
    Audit(#[from] impactlab::verify::audit::AuditError),
    /// A comparison could not read its inputs.
    #[error("{0}")]
    Compare(#[from] impactlab::verify::printed::PrintedError),
    /// A study could not be run or written.
    #[error("{0}")]
    Study(#[from] StudyError),
    /// A report could not be made.
    #[error("{0}")]
    Report(#[from] impactlab::report::ReportError),
    /// Field files could not be written.
    #[error("{0}")]
    Fields(#[from] impactlab::report::fields::FieldsError),
    /// The mutation campaign's page could not be made.
    #[error("{0}")]
    Mutants(#[from] impactlab::study::mutants::MutantsError),
    /// A command-line option is invalid.
    #[error("invalid option: {0}")]
    Usage(String),
    /// A run stopped by a guard after its partial outputs were written.
    #[error("numerical failure: {0}")]
    Stopped(String),
    /// An output could not be written.
    #[error("cannot write outputs to {path}: {source}")]
    Io {
        /// The path being written.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
}

impl From<DeckError> for Error {
    fn from(e: DeckError) -> Self {
        Error::Load(e.into())
    }
}

impl From<impactlab::run::statics::StaticError> for Error {
    fn from(e: impactlab::run::statics::StaticError) -> Self {
        use impactlab::run::statics::StaticError;
        match e {
            StaticError::Model(m) => m.into(),
            StaticError::Solve(s) => Error::Solve(s),
        }
    }
}

impl From<ModelError> for Error {
    fn from(e: ModelError) -> Self {
        Error::Load(e.into())
    }
}

/// 3 for a run that failed numerically, 2 for one that could not start.
fn run_code(e: &RunError) -> i32 {
    match e {
        RunError::Input(_) => 2,
        _ => 3,
    }
}

impl Error {
    /// 2 for bad input, 3 for numerical failure (1 is reserved for failed verification).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Solve(_) | Error::Stopped(_) => 3,
            Error::Run(e) => run_code(e),
            Error::Study(e) => match e {
                StudyError::Run(r) => run_code(r),
                StudyError::Solve(_)
                | StudyError::Unconfirmed(_)
                | StudyError::Static(impactlab::run::statics::StaticError::Solve(_)) => 3,
                _ => 2,
            },
            _ => 2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the exit codes by stage: a stage's input error is 2 wherever it is
    /// raised (directly, or inside a study), a numerical failure 3 (a solve, a run
    /// stopped by a guard, a threshold the direct engine does not confirm).
    #[test]
    fn input_errors_exit_2_and_numerical_failures_3() {
        let check = || impactlab::verify::CheckError::Failed {
            case: "c".into(),
            check: "k",
            message: "m".into(),
        };
        assert_eq!(Error::Check(check()).exit_code(), 2);
        assert_eq!(Error::Study(StudyError::Check(check())).exit_code(), 2);
        assert_eq!(Error::Study(StudyError::Input("x".into())).exit_code(), 2);
        assert_eq!(Error::Usage("x".into()).exit_code(), 2);
        assert_eq!(Error::Run(RunError::Input("x".into())).exit_code(), 2);
        assert_eq!(
            Error::Study(StudyError::Run(RunError::Input("x".into()))).exit_code(),
            2
        );
        assert_eq!(Error::Stopped("x".into()).exit_code(), 3);
        assert_eq!(Error::Study(StudyError::Unconfirmed("x".into())).exit_code(), 3);
    }
}
