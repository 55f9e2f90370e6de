//! The program's error, by stage, and its exit codes.

use crate::deck::DeckError;
use crate::integrate::SolveError;
use crate::model::ModelError;

/// Everything that can fail, by stage; [`Error::exit_code`] maps it to the program's exit code.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The deck could not be read.
    #[error("{0}")]
    Deck(#[from] DeckError),
    /// The model could not be built.
    #[error("{0}")]
    Model(#[from] ModelError),
    /// The solver failed.
    #[error("numerical failure: {0}")]
    Solve(#[from] SolveError),
    /// A run failed.
    #[error("{0}")]
    Run(#[from] crate::run::RunError),
    /// A model modification could not be made.
    #[error("{0}")]
    Modify(#[from] crate::model::ModifyError),
    /// A verification case could not be read.
    #[error("{0}")]
    Case(#[from] crate::verify::CaseError),
    /// A check could not be evaluated.
    #[error("{0}")]
    Check(#[from] crate::verify::CheckError),
    /// A reference could not be computed.
    #[error("{0}")]
    Reference(#[from] crate::physics::references::ReferenceError),
    /// A mesh could not be generated.
    #[error("{0}")]
    Mesh(#[from] crate::mesh::MeshError),
    /// A scene could not be read or built.
    #[error("{0}")]
    Scene(#[from] crate::scene::SceneError),
    /// A figure could not be drawn.
    #[error("{0}")]
    Plot(#[from] crate::plot::PlotError),
    /// An audit could not read its inputs.
    #[error("{0}")]
    Audit(#[from] crate::verify::audit::AuditError),
    /// Field files could not be written.
    #[error("{0}")]
    Fields(#[from] crate::report::fields::FieldsError),
    /// The mutation campaign's page could not be made.
    #[error("{0}")]
    Mutants(#[from] crate::study::mutants::MutantsError),
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

impl Error {
    /// 2 for bad input, 3 for numerical failure (1 is reserved for failed verification).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Deck(_)
            | Error::Model(_)
            | Error::Modify(_)
            | Error::Case(_)
            | Error::Check(_)
            | Error::Reference(_)
            | Error::Mesh(_)
            | Error::Scene(_)
            | Error::Plot(_)
            | Error::Audit(_)
            | Error::Fields(_)
            | Error::Mutants(_)
            | Error::Usage(_)
            | Error::Io { .. }
            | Error::Run(crate::run::RunError::Input(_)) => 2,
            Error::Solve(_) | Error::Run(_) | Error::Stopped(_) => 3,
        }
    }
}
