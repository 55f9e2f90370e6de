//! Physics with no solver code: the Hertz contact law's constants (the paper's Eq. 5
//! and Eq. 18) and the analytic references ([`analytic`]: the rigid-wall closed form,
//! the ball on a semi-infinite rod, d'Alembert's strain, the infinite plate, the
//! Navier plate's frequencies and strains).

pub mod analytic;
pub mod references;

/// Hertz contact stiffness of a sphere of radius `r` on a flat (the paper's Eq. 5,
/// and Eq. 18 with k_t the target's transverse modulus E33):
/// K = 4/3 √r · k_i k_t / (k_i + k_t), with k = E/(1 − ν²) for an isotropic body.
pub fn hertz_stiffness(r: f64, k_impactor: f64, k_target: f64) -> f64 {
    4.0 / 3.0 * r.sqrt() * k_impactor * k_target / (k_impactor + k_target)
}

/// The plane-strain modulus E/(1 − ν²) of an isotropic body (Eq. 5's k).
pub fn plane_strain_modulus(e: f64, nu: f64) -> f64 {
    e / (1.0 - nu * nu)
}
