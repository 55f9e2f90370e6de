//! CONM2: concentrated mass at a grid, in the basic system, without offset.
//! Mass on the three translations; the inertia matrix [I11 −I21 −I31; …] on the
//! rotations (NASTRAN's sign convention for products of inertia).

/// Rotational inertia matrix from (I11, I21, I22, I31, I32, I33).
pub fn inertia_matrix(i: [f64; 6]) -> [[f64; 3]; 3] {
    let [i11, i21, i22, i31, i32, i33] = i;
    [[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]]
}
