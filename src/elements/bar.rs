//! CBAR and CBEAM: two-node Euler-Bernoulli beam, axial, torsion and bending in two
//! planes, in the element's own axes between its (offset) ends.
//!
//! Formulation: element x from end A to end B, y the orientation vector's part
//! normal to x (plane 1 is x-y), z = x × y; DOFs u, v, w, θx, θy, θz at each end.
//! Axial u and twist θx linear; v (with θz = v′) and w (with θy = −w′) cubic Hermite.
//! Strain at a section point (y, z): ε = u′ − y v″ − z w″; strain energy
//! ½∫ EA u′² + GJ θx′² + E (I1 v″² + 2 I12 v″ w″ + I2 w″²) dx, integrated by two-point
//! Gauss (exact: the curvatures are linear), so the stiffness is the exact
//! Euler-Bernoulli stiffness; no shear flexibility (PBAR's K1, K2 blank). The shape
//! functions are exact for end loads, so static solutions under nodal loads are exact
//! at the nodes. Free vibration with the lumped mass below (verification case
//! beam-frequencies, a simply supported beam on 8, 16, 32 elements): bending
//! frequencies converge at order 4 in the element length (the rotations, massless,
//! condensed exactly), torsional frequencies at order 2 (linear twist, lumped
//! inertia).
//!
//! Pin flags (PA, PB) release end DOFs in element axes: the released DOFs are
//! condensed out statically, u_r = −K_rr⁻¹ K_rc u_c, so no force acts on them; a set of
//! releases that leaves a mechanism within the element (the same DOF at both ends of
//! an unsupported motion) is refused.
//!
//! Mass (NASTRAN's default, lumped, PARAM COUPMASS off): (ρA + NSM)·L/2 on the three
//! translations of each end; a CBEAM adds its torsional inertia ρ(I1 + I2)·L/2 about
//! the axis at each end, a CBAR none. The mass sits at the bar's ends (its offset
//! ends), whatever the pin flags.
//!
//! Coupled mass (a CBAR under PARAM COUPMASS, or CPBAR under COUPMASS 0), as
//! NASTRAN-95 builds it (its BAR routine's consistent mass, m = (ρA + NSM)·L): across
//! the axis, the consistent mass of the cubic deflections of the stiffness, ∫(ρA + NSM)
//! (v² + w²) dx, in both planes; along it, the mean of the lumped and the consistent
//! linear masses, m/12 [5 1; 1 5], under which a chain of bars has its axial roots
//! exact to fourth order in the element length (the lumped mass's error and the
//! consistent one's cancel at second order); no torsional or rotary inertia. It sits
//! at the offset ends, as the lumped mass does. With pin flags it is condensed as the
//! stiffness is, Pᵀ M P. NASTRAN-95 condenses it one release at a time against the
//! unreleased stiffness: the same for a single release and for releases the
//! stiffness does not couple, not for two it does (both ends' θz; tests below).
//!
//! Recovery at ends A and B: the strains and stresses (σ = Eε) at the section's
//! points C, D, E, F; and the resultants: axial force N = EA u′, torque T = GJ θx′,
//! bending moments M1 = E(I1 v″ + I12 w″) (plane 1) and M2 = E(I12 v″ + I2 w″)
//! (plane 2), shears V1 = −M1′, V2 = −M2′: NASTRAN's signs, V1 = (M1A − M1B)/L (its
//! printed bar forces: NASTRAN-95's demonstration problem D01-14-1A, a bar of unit
//! length with M1 = 1 at A and 0 at B, prints SHEAR PLANE 1 = +1).

use super::{BadShape, Cell, Kernel, LocalMatrix, Measure, Recovered};
use nalgebra::{DMatrix, SMatrix, SVector};

type M12 = SMatrix<f64, 12, 12>;
type V12 = SVector<f64, 12>;

/// A bar's section and material (PBAR, PBARL, PBEAM or PBEAML with its MAT1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarSection {
    /// Young's modulus E.
    pub e: f64,
    /// Shear modulus G.
    pub g: f64,
    /// Area A.
    pub area: f64,
    /// I1 = ∫y² dA (plane 1).
    pub i1: f64,
    /// I2 = ∫z² dA (plane 2).
    pub i2: f64,
    /// I12 = ∫yz dA.
    pub i12: f64,
    /// Torsion constant J.
    pub j: f64,
    /// Mass density ρ.
    pub rho: f64,
    /// Non-structural mass per unit length.
    pub nsm: f64,
    /// Stress recovery points C, D, E, F as (y, z).
    pub points: [[f64; 2]; 4],
    /// Mass moment of inertia about the axis per unit length (ρ(I1 + I2) for a
    /// CBEAM, 0 for a CBAR).
    pub torsional_inertia: f64,
    /// Thermal expansion coefficient α.
    pub alpha: f64,
    /// Reference temperature: the material is unstrained at it.
    pub tref: f64,
}

/// A temperature field on a bar, as TEMPRB gives it: the average temperature over
/// the section at end A and end B, and the effective linear gradients at each end,
/// T′1 = (1/I1)∫T y dA (plane 1) and T′2 = (1/I2)∫T z dA (plane 2). Each varies
/// linearly from end A to end B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarTemperature {
    /// TA, TB.
    pub average: [f64; 2],
    /// [T′1a, T′1b], [T′2a, T′2b].
    pub gradient: [[f64; 2]; 2],
}

/// What a bar's kernel is built from: its section and its pin flags (components
/// 1..6 released at end A, at end B, as bit sets: bit c for component c + 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarSpec {
    /// The card (CBAR or CBEAM).
    pub card: &'static str,
    /// Section and material.
    pub section: BarSection,
    /// Released components at end A and end B.
    pub released: [u8; 2],
    /// NASTRAN-95's coupled mass (a CBAR's) in place of the lumped.
    pub coupled_mass: bool,
}

/// A CBAR or CBEAM in its own axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    /// CBAR or CBEAM.
    pub card: &'static str,
    /// End A and end B in the element's axes (B − A along x).
    pub x: [[f64; 3]; 2],
    /// Section and material.
    pub section: BarSection,
    /// Its length.
    pub length: f64,
    /// u_full = P u: the released DOFs from the others (identity without pin flags).
    pub release: M12,
    /// The stiffness, condensed: Pᵀ K P.
    pub k: M12,
    /// The coupled mass, condensed (Pᵀ M P), when the deck asks for it.
    pub coupled_mass: Option<M12>,
}

/// The generalised strains (u′, θx′, v″, w″) at ξ = x/L as rows over the 12 DOFs.
fn strain_rows(l: f64, xi: f64) -> SMatrix<f64, 4, 12> {
    let mut b = SMatrix::<f64, 4, 12>::zeros();
    b[(0, 0)] = -1.0 / l;
    b[(0, 6)] = 1.0 / l;
    b[(1, 3)] = -1.0 / l;
    b[(1, 9)] = 1.0 / l;
    let n = [
        -6.0 + 12.0 * xi,
        l * (-4.0 + 6.0 * xi),
        6.0 - 12.0 * xi,
        l * (-2.0 + 6.0 * xi),
    ];
    let l2 = l * l;
    for (k, (v, w)) in [(1, 2), (5, 4), (7, 8), (11, 10)].into_iter().enumerate() {
        b[(2, v)] = n[k] / l2;
        // θy = −w′: the rotations enter w with the opposite sign.
        b[(3, w)] = if k % 2 == 1 { -n[k] / l2 } else { n[k] / l2 };
    }
    b
}

/// The displacements (u, v, w) at ξ = x/L as rows over the 12 DOFs: u linear, v and
/// w the cubic Hermite interpolation whose curvatures [`strain_rows`] gives.
fn displacement_rows(l: f64, xi: f64) -> SMatrix<f64, 3, 12> {
    let mut n = SMatrix::<f64, 3, 12>::zeros();
    n[(0, 0)] = 1.0 - xi;
    n[(0, 6)] = xi;
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let h = [
        1.0 - 3.0 * x2 + 2.0 * x3,
        l * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        l * (x3 - x2),
    ];
    for (k, (v, w)) in [(1, 2), (5, 4), (7, 8), (11, 10)].into_iter().enumerate() {
        n[(1, v)] = h[k];
        // θy = −w′.
        n[(2, w)] = if k % 2 == 1 { -h[k] } else { h[k] };
    }
    n
}

/// NASTRAN-95's coupled mass of an unreleased bar (see the module's notes): the
/// deflections' consistent mass by four-point Gauss (exact for their degree 6), the
/// axial mean of lumped and consistent.
pub fn coupled_mass(l: f64, s: &BarSection) -> M12 {
    let per_length = s.rho * s.area + s.nsm;
    let a = (3.0 - 2.0 * (6.0f64 / 5.0).sqrt()) / 7.0;
    let b = (3.0 + 2.0 * (6.0f64 / 5.0).sqrt()) / 7.0;
    let (wa, wb) = ((18.0 + 30f64.sqrt()) / 36.0, (18.0 - 30f64.sqrt()) / 36.0);
    let mut m = M12::zeros();
    for (x, w) in [(-a.sqrt(), wa), (-b.sqrt(), wb), (a.sqrt(), wa), (b.sqrt(), wb)] {
        let n = displacement_rows(l, 0.5 * (1.0 + x)).remove_row(0);
        m += n.transpose() * n * (per_length * w * 0.5 * l);
    }
    let total = per_length * l;
    for (i, j, f) in [(0, 0, 5.0), (6, 6, 5.0), (0, 6, 1.0), (6, 0, 1.0)] {
        m[(i, j)] = f * total / 12.0;
    }
    m
}

/// The section's rigidities: diag(EA, GJ) and E·[[I1, I12], [I12, I2]].
fn rigidity(s: &BarSection) -> SMatrix<f64, 4, 4> {
    let mut d = SMatrix::<f64, 4, 4>::zeros();
    d[(0, 0)] = s.e * s.area;
    d[(1, 1)] = s.g * s.j;
    d[(2, 2)] = s.e * s.i1;
    d[(2, 3)] = s.e * s.i12;
    d[(3, 2)] = s.e * s.i12;
    d[(3, 3)] = s.e * s.i2;
    d
}

/// Two-point Gauss on ξ ∈ [0, 1] (weights ½ each): exact for cubics in ξ.
fn gauss_points() -> [f64; 2] {
    let g = 0.5 / 3f64.sqrt();
    [0.5 - g, 0.5 + g]
}

/// The unreleased element stiffness (two-point Gauss, exact).
pub fn stiffness(l: f64, s: &BarSection) -> M12 {
    let d = rigidity(s);
    gauss_points()
        .iter()
        .map(|&xi| {
            let b = strain_rows(l, xi);
            b.transpose() * d * b * (0.5 * l)
        })
        .sum()
}

impl Bar {
    /// The bar between its ends (in its axes, along x): refused when they coincide or
    /// when the pin flags release a mechanism.
    pub fn build(points: &[[f64; 3]], spec: BarSpec) -> Result<Self, BadShape> {
        let x = [points[0], points[1]];
        let l = (0..3).map(|k| (x[1][k] - x[0][k]).powi(2)).sum::<f64>().sqrt();
        if l.is_nan() || l <= 0.0 {
            return Err(BadShape("has zero length (its ends coincide)"));
        }
        let s = spec.section;
        let k = stiffness(l, &s);
        let released: Vec<usize> = (0..12)
            .filter(|&i| spec.released[i / 6] & (1 << (i % 6)) != 0)
            .collect();
        let mut p = M12::identity();
        if !released.is_empty() {
            let kept: Vec<usize> = (0..12).filter(|i| !released.contains(i)).collect();
            let krr = DMatrix::from_fn(released.len(), released.len(), |a, b| k[(released[a], released[b])]);
            let krc = DMatrix::from_fn(released.len(), kept.len(), |a, b| k[(released[a], kept[b])]);
            let scale = krr.diagonal().amax();
            let Some(chol) = (scale > 0.0)
                .then(|| nalgebra::Cholesky::new(krr.clone()))
                .flatten()
                .filter(|c| c.l().diagonal().min() > 1e-7 * scale.sqrt())
            else {
                return Err(BadShape(
                    "has pin flags (PA, PB) that free a motion of the bar itself: the same component \
                     released at both ends, or a rotation and the deflection it carries",
                ));
            };
            let back = -chol.solve(&krc);
            for &r in &released {
                p[(r, r)] = 0.0;
            }
            for (a, &r) in released.iter().enumerate() {
                for (b, &c) in kept.iter().enumerate() {
                    p[(r, c)] = back[(a, b)];
                }
            }
        }
        Ok(Bar {
            card: spec.card,
            x,
            section: s,
            length: l,
            release: p,
            k: p.transpose() * k * p,
            coupled_mass: spec.coupled_mass.then(|| p.transpose() * coupled_mass(l, &s) * p),
        })
    }

    /// The end loads (element axes, on the DOFs the stiffness acts on) that a
    /// temperature field puts on the bar: `f = Pᵀ ∫ Bᵀ s dx`, the work of the thermal
    /// stress resultants s = (EαA(T − Tref), 0, −EαI1 T′1, −EαI2 T′2) on the
    /// generalised strains (u′, θx′, v″, w″), ε = u′ − y v″ − z w″ at a section point
    /// (hence the signs: a hotter +y side curves the bar away from +y). s is linear
    /// along the bar and B is, so two-point Gauss is exact; with pin flags P carries a
    /// released DOF's share to the others, as it does the stiffness. The solution of
    /// the bar under these loads is exact at its ends (its curvatures are linear, as
    /// the thermal ones are).
    pub fn thermal_load(&self, t: &BarTemperature) -> [f64; 12] {
        let (sec, l) = (&self.section, self.length);
        let resultants = |xi: f64| {
            let at = |v: [f64; 2]| v[0] + (v[1] - v[0]) * xi;
            let ea = sec.e * sec.alpha;
            SVector::<f64, 4>::new(
                ea * sec.area * (at(t.average) - sec.tref),
                0.0,
                -ea * sec.i1 * at(t.gradient[0]),
                -ea * sec.i2 * at(t.gradient[1]),
            )
        };
        let f: V12 = gauss_points()
            .iter()
            .map(|&xi| strain_rows(l, xi).transpose() * resultants(xi) * (0.5 * l))
            .sum();
        let f = self.release.transpose() * f;
        std::array::from_fn(|i| f[i])
    }

    fn full(&self, ue: &[f64]) -> V12 {
        self.release * V12::from_column_slice(&ue[..12])
    }

    /// Strains at the points C, D, E, F of end A, then of end B.
    fn point_strains(&self, u: &V12) -> [f64; 8] {
        let mut out = [0.0; 8];
        for (end, xi) in [0.0, 1.0].into_iter().enumerate() {
            let g = strain_rows(self.length, xi) * u;
            for (k, [y, z]) in self.section.points.iter().enumerate() {
                out[4 * end + k] = g[0] - y * g[2] - z * g[3];
            }
        }
        out
    }

    /// N, T, V1, V2, M1, M2 at end A, then at end B.
    fn resultants(&self, u: &V12) -> [f64; 12] {
        let d = rigidity(&self.section);
        let (a, b) = (
            d * strain_rows(self.length, 0.0) * u,
            d * strain_rows(self.length, 1.0) * u,
        );
        // NASTRAN's shear: V = (M_A − M_B)/L, the moment's fall from end A to B.
        let (v1, v2) = ((a[2] - b[2]) / self.length, (a[3] - b[3]) / self.length);
        let mut out = [0.0; 12];
        for (end, r) in [a, b].iter().enumerate() {
            out[6 * end..6 * end + 6].copy_from_slice(&[r[0], r[1], v1, v2, r[2], r[3]]);
        }
        out
    }
}

const POINTS: [super::BarPoint; 4] = [
    super::BarPoint::C,
    super::BarPoint::D,
    super::BarPoint::E,
    super::BarPoint::F,
];
const ENDS: [super::End; 2] = [super::End::A, super::End::B];
const RESULTANTS: [super::Resultant; 6] = [
    super::Resultant::Axial,
    super::Resultant::Torque,
    super::Resultant::Shear1,
    super::Resultant::Shear2,
    super::Resultant::Moment1,
    super::Resultant::Moment2,
];

impl Kernel for Bar {
    fn card(&self) -> &'static str {
        self.card
    }
    fn family(&self) -> super::Family<'_> {
        super::Family::Beam {
            section: &self.section,
            length: self.length,
        }
    }
    fn stiffness(&self) -> Vec<LocalMatrix> {
        vec![LocalMatrix {
            at: (0..12).map(|i| (i / 6, i % 6)).collect(),
            values: DMatrix::from_fn(12, 12, |i, j| self.k[(i, j)]),
        }]
    }
    fn mass(&self) -> Vec<LocalMatrix> {
        if let Some(m) = &self.coupled_mass {
            return vec![LocalMatrix {
                at: (0..12).map(|i| (i / 6, i % 6)).collect(),
                values: DMatrix::from_fn(12, 12, |i, j| m[(i, j)]),
            }];
        }
        let s = &self.section;
        let m = 0.5 * (s.rho * s.area + s.nsm) * self.length;
        let it = 0.5 * s.torsional_inertia * self.length;
        vec![LocalMatrix::diagonal(
            (0..2)
                .flat_map(|g| (0..3).map(move |c| ((g, c), m)).chain([((g, 3), it)]))
                .filter(|&(_, v)| v != 0.0),
        )]
    }
    fn strain_energy(&self, ue: &[f64]) -> f64 {
        let u = V12::from_column_slice(&ue[..12]);
        0.5 * (u.transpose() * self.k * u)[(0, 0)]
    }
    fn recovered(&self, what: super::Output) -> Vec<Recovered> {
        let at_points = |measure| {
            ENDS.iter().flat_map(move |&end| {
                POINTS.iter().map(move |&p| Recovered {
                    measure,
                    at: Some(super::At::Point(end, p)),
                })
            })
        };
        match what {
            super::Output::Strain => at_points(Measure::Strain).collect(),
            super::Output::Stress => at_points(Measure::Stress).chain(at_points(Measure::Strain)).collect(),
            super::Output::Force => ENDS
                .iter()
                .flat_map(|&end| {
                    RESULTANTS.iter().map(move |&r| Recovered {
                        measure: Measure::Force(r),
                        at: Some(super::At::End(end)),
                    })
                })
                .collect(),
        }
    }
    fn recover(&self, ue: &[f64], what: super::Output) -> Vec<f64> {
        let u = self.full(ue);
        match what {
            super::Output::Strain => self.point_strains(&u).to_vec(),
            super::Output::Stress => {
                let strains = self.point_strains(&u);
                let e = self.section.e;
                strains.iter().map(|s| e * s).chain(strains).collect()
            }
            super::Output::Force => self.resultants(&u).to_vec(),
        }
    }
    fn material_law(&self, strains: &[f64]) -> Option<Vec<f64>> {
        Some(strains.iter().map(|s| self.section.e * s).collect())
    }
    fn eq16_mass(&self) -> Option<f64> {
        let s = &self.section;
        Some((s.rho * s.area + s.nsm) * self.length)
    }
    fn points(&self) -> Vec<[f64; 3]> {
        self.x.to_vec()
    }
    fn cell(&self) -> Option<Cell> {
        Some(Cell::Line)
    }
}

/// A section with every constant distinct (I12 too) and a mass, for tests.
#[cfg(test)]
pub(crate) fn sample_section() -> BarSection {
    BarSection {
        e: 1.0e7,
        g: 3.8e6,
        area: 0.6,
        i1: 0.08,
        i2: 0.03,
        i12: 0.01,
        j: 0.02,
        rho: 2.5e-4,
        nsm: 1e-5,
        points: [[0.5, 0.3], [-0.5, 0.3], [-0.5, -0.3], [0.5, -0.3]],
        torsional_inertia: 0.0,
        alpha: 1.3e-5,
        tref: 20.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bar of the sample section with I12 = 0, lumped or coupled mass.
    fn bar_of(released: [u8; 2], coupled_mass: bool) -> Result<Bar, BadShape> {
        Bar::build(
            &[[0.0; 3], [2.5, 0.0, 0.0]],
            BarSpec {
                card: "CBAR",
                section: BarSection {
                    i12: 0.0,
                    ..sample_section()
                },
                released,
                coupled_mass,
            },
        )
    }

    fn bar(released: [u8; 2]) -> Result<Bar, BadShape> {
        bar_of(released, false)
    }

    /// Goal: the stiffness is the textbook Euler-Bernoulli one. Model: one bar,
    /// I12 = 0. Reference: a cantilever (end A clamped) under a tip force P in plane 1
    /// deflects PL³/3EI1 and turns PL²/2EI1; in plane 2 with I2; under an axial force
    /// PL/EA; under a torque TL/GJ. Tolerance: round-off (the element is exact for end
    /// loads).
    #[test]
    fn cantilever_tip_under_end_loads_is_exact() {
        let b = bar([0, 0]).unwrap();
        let (s, l) = (b.section, b.length);
        let kff = b.k.fixed_view::<6, 6>(6, 6).into_owned();
        let solve = |f: SVector<f64, 6>| kff.lu().solve(&f).unwrap();
        let p = 3.0;
        let u = solve(SVector::<f64, 6>::from_column_slice(&[0.0, p, 0.0, 0.0, 0.0, 0.0]));
        assert!((u[1] / (p * l.powi(3) / (3.0 * s.e * s.i1)) - 1.0).abs() < 1e-12);
        assert!((u[5] / (p * l * l / (2.0 * s.e * s.i1)) - 1.0).abs() < 1e-12);
        let u = solve(SVector::<f64, 6>::from_column_slice(&[0.0, 0.0, p, 0.0, 0.0, 0.0]));
        assert!((u[2] / (p * l.powi(3) / (3.0 * s.e * s.i2)) - 1.0).abs() < 1e-12);
        assert!((u[4] / (-p * l * l / (2.0 * s.e * s.i2)) - 1.0).abs() < 1e-12);
        let u = solve(SVector::<f64, 6>::from_column_slice(&[p, 0.0, 0.0, p, 0.0, 0.0]));
        assert!((u[0] / (p * l / (s.e * s.area)) - 1.0).abs() < 1e-12);
        assert!((u[3] / (p * l / (s.g * s.j)) - 1.0).abs() < 1e-12);
    }

    /// Goal: a temperature field's end loads give a bar the free thermal shape
    /// exactly. Model: one cantilever bar (end A clamped, I12 = 0) under temperatures
    /// and gradients varying linearly from end A to end B. Reference: the cantilever
    /// is statically determinate, so no stress builds up and it takes its free thermal
    /// strains, u′ = α(T − Tref), v″ = −αT′1, w″ = −αT′2: at the tip
    /// u = αL(T̄ − Tref), v = −αL²(T′1a/3 + T′1b/6), θz = v′ = −αL(T′1a + T′1b)/2,
    /// w = −αL²(T′2a/3 + T′2b/6), θy = −w′ = αL(T′2a + T′2b)/2 (T̄ the mean of TA
    /// and TB). Tolerance: round-off (the element's curvatures are linear, as these).
    #[test]
    fn cantilever_takes_its_free_thermal_shape_exactly() {
        let b = bar([0, 0]).unwrap();
        let (s, l) = (b.section, b.length);
        let t = BarTemperature {
            average: [35.0, 80.0],
            gradient: [[2.0, -7.0], [4.0, 1.5]],
        };
        let f = b.thermal_load(&t);
        let kff = b.k.fixed_view::<6, 6>(6, 6).into_owned();
        let u = kff.lu().solve(&SVector::<f64, 6>::from_column_slice(&f[6..])).unwrap();
        let a = s.alpha;
        let [[g1a, g1b], [g2a, g2b]] = t.gradient;
        let want = [
            a * l * (0.5 * (t.average[0] + t.average[1]) - s.tref),
            -a * l * l * (g1a / 3.0 + g1b / 6.0),
            -a * l * l * (g2a / 3.0 + g2b / 6.0),
            0.0,
            a * l * (g2a + g2b) / 2.0,
            -a * l * (g1a + g1b) / 2.0,
        ];
        for (k, w) in want.iter().enumerate() {
            assert!(
                (u[k] - w).abs() < 1e-12 * want[1].abs(),
                "DOF {k}: {} against {w}",
                u[k]
            );
        }
        // A free bar's thermal loads are in equilibrium: no net force or moment, to
        // round-off of the loads' own size (1e-13 of the largest force times L).
        let scale = f.iter().fold(0.0f64, |m, v| m.max(v.abs())) * l.max(1.0);
        let net: [f64; 3] = std::array::from_fn(|c| f[c] + f[6 + c]);
        let moment = f[5] + f[11] + l * f[7];
        assert!(
            net.iter().all(|v| v.abs() < 1e-13 * scale) && moment.abs() < 1e-13 * scale,
            "{net:?} {moment}"
        );
    }

    /// Goal: a rigid motion stores nothing and stresses nothing, with and without pin
    /// flags and with I12. Model: one bar, every rigid translation and rotation.
    /// Tolerance: round-off.
    #[test]
    fn rigid_motion_is_strain_free() {
        for released in [[0, 0], [0b110000, 0], [0, 0b001000]] {
            let b = Bar::build(
                &[[0.0; 3], [2.5, 0.0, 0.0]],
                BarSpec {
                    card: "CBAR",
                    section: sample_section(),
                    released,
                    coupled_mass: false,
                },
            )
            .unwrap();
            for k in 0..6 {
                let mut u = V12::zeros();
                let (mut t, mut r) = ([0.0; 3], [0.0; 3]);
                if k < 3 {
                    t[k] = 1e-3;
                } else {
                    r[k - 3] = 1e-3;
                }
                for (end, x) in b.x.iter().enumerate() {
                    let rx = nalgebra::Vector3::from(r).cross(&nalgebra::Vector3::from(*x));
                    for c in 0..3 {
                        u[6 * end + c] = t[c] + rx[c];
                        u[6 * end + 3 + c] = r[c];
                    }
                }
                assert!((b.k * u).norm() < 1e-9 * b.k.norm() * 1e-3, "{released:?} {k}");
                let mut rec = b.recover(u.as_slice(), super::super::Output::Stress);
                rec.extend(b.recover(u.as_slice(), super::super::Output::Force));
                assert!(rec.iter().all(|v| v.abs() < 1e-6), "{released:?} {k}: {rec:?}");
            }
        }
    }

    /// Goal: a pin flag frees what it names. Model: a bar clamped at A whose end B's
    /// rotation about z (plane 1) is released: a moment there meets no stiffness, and
    /// a tip force deflects it as before while M1 at B is zero. And releasing the
    /// axial DOF at both ends is a mechanism, refused.
    #[test]
    fn pin_flag_releases_its_component() {
        let b = bar([0, 1 << 5]).unwrap();
        assert_eq!(b.k.row(11).norm(), 0.0);
        let mut u = V12::zeros();
        u[7] = 1e-3;
        let forces = b.recover(u.as_slice(), super::super::Output::Force);
        let m1_b = forces[6 + 4];
        assert!(m1_b.abs() < 1e-9 * forces[4].abs(), "{m1_b} vs {}", forces[4]);
        assert!(bar([1, 1]).is_err());
        assert!(bar([0b100, 0b100]).is_err(), "w free at both ends: the bar translates");
        assert!(bar([0b10000, 0b10000]).is_ok(), "pinned-pinned in plane 2");
    }

    /// [`bar`] with NASTRAN-95's coupled mass.
    fn coupled(released: [u8; 2]) -> Bar {
        bar_of(released, true).expect("a bar")
    }

    /// Goal: the coupled mass is NASTRAN-95's. Reference: the table of its BAR
    /// routine's consistent mass (single-precision version, BARS), (ρA + NSM)L/420
    /// times 175 and 35 along the axis, 156, ±22L, 54, ±13L, 4L² and −3L² across it in
    /// each plane, nothing on the twist; it is derived here by quadrature of the
    /// stiffness's shape functions, so the signs of the rotations are checked too.
    /// Tolerance: round-off (1e-13 of the largest term).
    #[test]
    fn coupled_mass_is_nastran_95s_table() {
        let b = coupled([0, 0]);
        let l = b.length;
        let s = &b.section;
        let mut table = M12::zeros();
        let upper = [
            (0, 0, 175.0),
            (0, 6, 35.0),
            (1, 1, 156.0),
            (1, 5, 22.0 * l),
            (1, 7, 54.0),
            (1, 11, -13.0 * l),
            (2, 2, 156.0),
            (2, 4, -22.0 * l),
            (2, 8, 54.0),
            (2, 10, 13.0 * l),
            (4, 4, 4.0 * l * l),
            (4, 8, -13.0 * l),
            (4, 10, -3.0 * l * l),
            (5, 5, 4.0 * l * l),
            (5, 7, 13.0 * l),
            (5, 11, -3.0 * l * l),
            (6, 6, 175.0),
            (7, 7, 156.0),
            (7, 11, -22.0 * l),
            (8, 8, 156.0),
            (8, 10, 22.0 * l),
            (10, 10, 4.0 * l * l),
            (11, 11, 4.0 * l * l),
        ];
        for (i, j, v) in upper {
            table[(i, j)] = v * (s.rho * s.area + s.nsm) * l / 420.0;
            table[(j, i)] = table[(i, j)];
        }
        let m = b.coupled_mass.expect("asked for");
        assert!((m - table).amax() <= 1e-13 * table.amax(), "{m} against {table}");
    }

    /// Goal: with pin flags the coupled mass is condensed as NASTRAN-95 condenses it
    /// where the two ways agree. Reference: NASTRAN-95's BAR routine, which takes the
    /// releases one at a time, M ← M − (K_lj M_ji + K_ji M_lj)/K_jj + K_lj K_ji M_jj/K_jj²
    /// with the unreleased K, then zeroes row and column j. Model: θz released at B;
    /// θz at A with θy at B (uncoupled in K, I12 = 0). Tolerance: round-off (1e-12 of
    /// the largest term). Where the stiffness couples two releases (θz at both ends,
    /// K_jk = 2EI1/L), one at a time is not the condensation of the stiffness, and the
    /// two differ (by a fifth of the largest term): the bar is then a link in plane 1,
    /// its deflection linear, and Pᵀ M P is that deflection's consistent mass,
    /// m/6 [2 1; 1 2] on v (to round-off).
    #[test]
    fn released_coupled_mass_is_condensed_as_the_stiffness_is() {
        let k = stiffness(2.5, &coupled([0, 0]).section);
        let one_at_a_time = |released: &[usize]| {
            let mut m = coupled([0, 0]).coupled_mass.expect("asked for");
            for &j in released {
                let mut next = m;
                if k[(j, j)] != 0.0 {
                    for i in 0..12 {
                        for l in 0..12 {
                            next[(i, l)] =
                                m[(i, l)] - k[(l, j)] * m[(j, i)] / k[(j, j)] - k[(j, i)] * m[(l, j)] / k[(j, j)]
                                    + k[(l, j)] * k[(j, i)] * m[(j, j)] / k[(j, j)].powi(2);
                        }
                    }
                }
                next.row_mut(j).fill(0.0);
                next.column_mut(j).fill(0.0);
                m = next;
            }
            m
        };
        for (released, dofs) in [([0, 0b100000], vec![11]), ([0b100000, 0b10000], vec![5, 10])] {
            let ours = coupled(released).coupled_mass.expect("asked for");
            let theirs = one_at_a_time(&dofs);
            assert!(
                (ours - theirs).amax() <= 1e-12 * theirs.amax(),
                "{released:?}: {ours} against {theirs}"
            );
        }
        let ours = coupled([0b100000, 0b100000]).coupled_mass.expect("asked for");
        let theirs = one_at_a_time(&[5, 11]);
        let apart = (ours - theirs).amax() / theirs.amax();
        assert!(apart > 0.1, "{apart:e}");
        let s = coupled([0, 0]).section;
        let m = (s.rho * s.area + s.nsm) * 2.5;
        for (i, j, v) in [(1, 1, m / 3.0), (7, 7, m / 3.0), (1, 7, m / 6.0)] {
            assert!(
                (ours[(i, j)] - v).abs() <= 1e-13 * m,
                "{i} {j}: {} against {v}",
                ours[(i, j)]
            );
        }
    }
}
