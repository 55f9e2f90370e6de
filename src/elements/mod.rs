//! Element kernels: pure functions from geometry and material to local matrices and
//! recovered strains. They know nothing of global numbering.

pub mod mass;
pub mod quad4;
pub mod rod;
