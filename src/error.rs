//! The program's error, by stage, and its exit codes.

use crate::deck::DeckError;
use crate::integrate::SolveError;
use crate::model::ModelError;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{0}")]
    Deck(#[from] DeckError),
    #[error("{0}")]
    Model(#[from] ModelError),
    #[error("numerical failure: {0}")]
    Solve(#[from] SolveError),
    #[error("numerical failure: {0}")]
    Run(#[from] crate::run::RunError),
    #[error("{0}")]
    Modify(#[from] crate::model::ModifyError),
    #[error("{0}")]
    Case(#[from] crate::verify::CaseError),
    #[error("{0}")]
    Check(#[from] crate::verify::CheckError),
    #[error("{0}")]
    Reference(#[from] crate::physics::references::ReferenceError),
    #[error("{0}")]
    Mesh(#[from] crate::mesh::MeshError),
    #[error("{0}")]
    Scene(#[from] crate::scene::SceneError),
    #[error("{0}")]
    Plot(#[from] crate::plot::PlotError),
    #[error("{0}")]
    Audit(#[from] crate::verify::audit::AuditError),
    #[error("{0}")]
    Fields(#[from] crate::report::fields::FieldsError),
    #[error("invalid option: {0}")]
    Usage(String),
    /// A run stopped by a guard after its partial outputs were written.
    #[error("numerical failure: {0}")]
    Stopped(String),
    #[error("cannot write outputs to {path}: {source}")]
    Io {
        path: String,
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
            | Error::Usage(_)
            | Error::Io { .. } => 2,
            Error::Solve(_) | Error::Run(_) | Error::Stopped(_) => 3,
        }
    }
}
