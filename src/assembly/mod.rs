//! Assembly: element matrices scattered into global sparse matrices over the solved
//! DOFs (constrained DOFs are simply dropped: homogeneous SPCs).

use crate::elements::{mass, quad4, rod};
use crate::model::{Element, Model};
use faer::sparse::{SparseColMat, Triplet};

/// Global stiffness and mass as triplet lists (duplicates summed when compressed).
#[derive(Debug, Clone)]
pub struct System {
    pub n: usize,
    pub k: Vec<Triplet<usize, usize, f64>>,
    pub m: Vec<Triplet<usize, usize, f64>>,
    /// Compressed K and M, for products.
    pub k_csc: SparseColMat<usize, f64>,
    pub m_csc: SparseColMat<usize, f64>,
    /// The shell elements' part of K (the ledger's strain energy of shells).
    pub k_shell_csc: SparseColMat<usize, f64>,
    /// The diagonal of M when M is diagonal (lumped masses, no rotary inertia coupling).
    pub m_lumped: Option<Vec<f64>>,
}

fn scatter(out: &mut Vec<Triplet<usize, usize, f64>>, dofs: &[Option<usize>], local: impl Fn(usize, usize) -> f64) {
    for (a, da) in dofs.iter().enumerate() {
        let Some(i) = da else { continue };
        for (b, db) in dofs.iter().enumerate() {
            let Some(j) = db else { continue };
            let v = local(a, b);
            if v != 0.0 {
                out.push(Triplet::new(*i, *j, v));
            }
        }
    }
}

/// Assembles K and M of a model.
pub fn assemble(model: &Model) -> System {
    let n = model.n();
    let mut k = Vec::new();
    let mut m = Vec::new();
    let mut k_shell = Vec::new();
    for e in &model.elements {
        match e {
            Element::Quad4 { xy, section, dofs, .. } => {
                if let Some(a) = section.a() {
                    let ke = quad4::membrane_stiffness(xy, &a);
                    let d: Vec<Option<usize>> = dofs.iter().flat_map(|g| [g[0], g[1]]).collect();
                    scatter(&mut k_shell, &d, |i, j| ke[(i, j)]);
                }
                if let Some(dm) = section.d() {
                    let ke = quad4::bending_stiffness(xy, &dm);
                    let d: Vec<Option<usize>> = dofs.iter().flat_map(|g| [g[2], g[3], g[4]]).collect();
                    scatter(&mut k_shell, &d, |i, j| ke[(i, j)]);
                }
                let mn = quad4::lumped_mass(xy, section.mass_per_area);
                for (corner, mi) in dofs.iter().zip(mn) {
                    for d in corner[..3].iter().flatten() {
                        m.push(Triplet::new(*d, *d, mi));
                    }
                }
            }
            Element::Rod { x, section, dofs, .. } => {
                let ke = rod::stiffness(x[0], x[1], section);
                let all: Vec<Option<usize>> = dofs.iter().flatten().copied().collect();
                scatter(&mut k, &all, |a, b| ke[(a, b)]);
                let mn = rod::lumped_mass(x[0], x[1], section);
                for end in dofs {
                    for d in end[..3].iter().flatten() {
                        m.push(Triplet::new(*d, *d, mn));
                    }
                }
            }
            Element::Mass {
                mass: mm,
                inertia,
                dofs,
                ..
            } => {
                for d in dofs[..3].iter().flatten() {
                    m.push(Triplet::new(*d, *d, *mm));
                }
                let j = mass::inertia_matrix(*inertia);
                scatter(&mut m, &dofs[3..], |a, b| j[a][b]);
            }
        }
    }
    let k_shell_csc = SparseColMat::try_new_from_triplets(n, n, &k_shell).expect("indices are in range");
    k.extend_from_slice(&k_shell);
    let k_csc = SparseColMat::try_new_from_triplets(n, n, &k).expect("indices are in range");
    let m_csc = SparseColMat::try_new_from_triplets(n, n, &m).expect("indices are in range");
    let lumped = m.iter().all(|t| t.row == t.col || t.val == 0.0);
    let mut sys = System {
        m_lumped: None,
        n,
        k,
        m,
        k_csc,
        m_csc,
        k_shell_csc,
    };
    if lumped {
        sys.m_lumped = Some(sys.m_diag());
    }
    sys
}

impl System {
    /// a·M + b·K, compressed.
    pub fn combine(&self, a: f64, b: f64) -> SparseColMat<usize, f64> {
        let t: Vec<_> = self
            .m
            .iter()
            .map(|t| Triplet::new(t.row, t.col, a * t.val))
            .chain(self.k.iter().map(|t| Triplet::new(t.row, t.col, b * t.val)))
            .collect();
        SparseColMat::try_new_from_triplets(self.n, self.n, &t).expect("indices are in range")
    }

    /// y = K x
    pub fn k_mul(&self, x: &[f64], y: &mut [f64]) {
        mul(&self.k_csc, x, y);
    }

    /// y = M x
    pub fn m_mul(&self, x: &[f64], y: &mut [f64]) {
        match &self.m_lumped {
            Some(d) => y.iter_mut().zip(d.iter().zip(x)).for_each(|(y, (d, x))| *y = d * x),
            None => mul(&self.m_csc, x, y),
        }
    }

    /// Diagonal of M.
    pub fn m_diag(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        for t in &self.m {
            if t.row == t.col {
                d[t.row] += t.val;
            }
        }
        d
    }

    /// Diagonal of K.
    pub fn k_diag(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        for t in &self.k {
            if t.row == t.col {
                d[t.row] += t.val;
            }
        }
        d
    }
}

/// y = A x for a compressed sparse column matrix.
pub fn mul(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    y.iter_mut().for_each(|v| *v = 0.0);
    let a = a.as_ref();
    let cp = a.symbolic().col_ptr();
    let ri = a.symbolic().row_idx();
    let vals = a.val();
    for j in 0..a.ncols() {
        let xj = x[j];
        if xj == 0.0 {
            continue;
        }
        for p in cp[j]..cp[j + 1] {
            y[ri[p]] += vals[p] * xj;
        }
    }
}
