//! Elements: kernels (pure functions from geometry and material to local matrices and
//! recovered strains, one file per kind) and [`Element`], the one type through which
//! assembly, the ledger, the recorder and field output see every element kind.
//!
//! Each kind implements [`Kernel`] over its element-local DOFs (T1..R3 of each of its
//! grids, grid-major); [`Element`] holds the kernel with the element's id, grids and
//! solved-DOF numbers and maps local to global. Nothing outside this module names an
//! element kind to assemble, book energy, recover results or draw a cell: a new kind
//! is a new [`Kernel`] implementation, and the ledger's strain energy, the history
//! columns and the VTK cells follow from it.
//!
//! An element card's kind is one line of [`KINDS`]: its card name, its grid count and
//! how it is built from its grids and resolved property. The deck reader types every
//! card of the table alike and the model builder builds it through the table: a new
//! kind is a kernel file here and a line there.

pub mod bar;
pub mod bush;
pub mod damper;
pub mod dkmt;
pub mod drill;
pub mod general;
pub mod mass;
pub mod mitc4;
pub mod quad4;
pub mod rod;
pub mod scalar;
pub mod section;
pub mod shear;
pub mod shell;
pub mod tria3;

use nalgebra::{DMatrix, Matrix3, Matrix6};
use std::any::Any;
use std::fmt;
use std::sync::Arc;

/// The most grids an element has (CQUAD4).
pub const MAX_GRIDS: usize = 4;

/// A matrix over some of an element's local DOFs: row and column `k` belong to
/// component `at[k].1` (0..6 for T1..R3) of the element's grid `at[k].0`.
#[derive(Debug, Clone)]
pub struct LocalMatrix {
    /// (grid index within the element, component 0..6) of each row and column.
    pub at: Vec<(usize, usize)>,
    /// The matrix.
    pub values: DMatrix<f64>,
}

impl LocalMatrix {
    /// A diagonal matrix: `value` on each listed DOF.
    pub fn diagonal(entries: impl IntoIterator<Item = ((usize, usize), f64)>) -> Self {
        let (at, d): (Vec<(usize, usize)>, Vec<f64>) = entries.into_iter().unzip();
        LocalMatrix {
            at,
            values: DMatrix::from_diagonal(&nalgebra::DVector::from_vec(d)),
        }
    }

    /// A lumped mass: `masses[g]` on each of grid g's three translations, none on its
    /// rotations.
    pub fn translational(masses: &[f64]) -> Self {
        LocalMatrix::diagonal(
            masses
                .iter()
                .enumerate()
                .flat_map(|(g, &m)| (0..3).map(move |c| ((g, c), m))),
        )
    }
}

/// What an output request asks an element to recover (case control's STRAIN, STRESS
/// and FORCE).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Output {
    /// Strains.
    Strain,
    /// Stresses, then strains (and a shear-deformable shell's transverse shear forces,
    /// which its interlaminar recovery needs).
    Stress,
    /// The force and moment resultants: a rod's axial force and torque, a beam's at
    /// each end, a shell's per unit length.
    Force,
}

/// Stress or strain, or a shear-deformable shell's transverse shear force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Measure {
    /// Stress (force per area).
    Stress,
    /// Strain (dimensionless).
    Strain,
    /// A transverse shear force resultant, Qx or Qy (force per length).
    ShearForce(Transverse),
    /// A force or moment resultant: a rod's, a beam's at one of its ends, a shell's.
    Force(Resultant),
}

/// An element's force and moment resultants: a rod's and a beam's at a section (see
/// [`bar`] for their signs), a shell's per unit length at its centre, in its
/// kernel's axes (Nx = ∫σx dz, Mx = ∫σx z dz, Qx = ∫τxz dz).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Resultant {
    /// Axial force N.
    Axial,
    /// Torque T.
    Torque,
    /// Shear V1 (plane 1).
    Shear1,
    /// Shear V2 (plane 2).
    Shear2,
    /// Bending moment M1 (plane 1).
    Moment1,
    /// Bending moment M2 (plane 2).
    Moment2,
    /// A shell's membrane force Nx.
    Nx,
    /// A shell's membrane force Ny.
    Ny,
    /// A shell's membrane shear force Nxy.
    Nxy,
    /// A shell's bending moment Mx.
    Mx,
    /// A shell's bending moment My.
    My,
    /// A shell's twisting moment Mxy.
    Mxy,
    /// A shell's transverse shear force Qx.
    Qx,
    /// A shell's transverse shear force Qy.
    Qy,
    /// A bushing's force along its x axis.
    Fx,
    /// A bushing's force along its y axis.
    Fy,
    /// A bushing's force along its z axis.
    Fz,
    /// A bushing's moment about its x axis.
    MomentX,
    /// A bushing's moment about its y axis.
    MomentY,
    /// A bushing's moment about its z axis.
    MomentZ,
}

impl Resultant {
    /// Its unit from the deck's force and length units: a force, a moment (force ×
    /// length), or a shell's, per unit length.
    pub fn unit(self, f: &str, l: &str) -> String {
        match self {
            Resultant::Axial | Resultant::Shear1 | Resultant::Shear2 => f.to_string(),
            Resultant::Fx | Resultant::Fy | Resultant::Fz => f.to_string(),
            Resultant::Torque | Resultant::Moment1 | Resultant::Moment2 => format!("{f}*{l}"),
            Resultant::MomentX | Resultant::MomentY | Resultant::MomentZ => format!("{f}*{l}"),
            Resultant::Nx | Resultant::Ny | Resultant::Nxy | Resultant::Qx | Resultant::Qy => format!("{f}/{l}"),
            Resultant::Mx | Resultant::My | Resultant::Mxy => format!("{f}*{l}/{l}"),
        }
    }

    /// Its name in a column: `axial`, `m1`, `nx`, `mxy`.
    fn name(self) -> &'static str {
        match self {
            Resultant::Axial => "axial",
            Resultant::Torque => "torque",
            Resultant::Shear1 => "v1",
            Resultant::Shear2 => "v2",
            Resultant::Moment1 => "m1",
            Resultant::Moment2 => "m2",
            Resultant::Nx => "nx",
            Resultant::Ny => "ny",
            Resultant::Nxy => "nxy",
            Resultant::Mx => "mx",
            Resultant::My => "my",
            Resultant::Mxy => "mxy",
            Resultant::Qx => "qx",
            Resultant::Qy => "qy",
            Resultant::Fx => "fx",
            Resultant::Fy => "fy",
            Resultant::Fz => "fz",
            Resultant::MomentX => "momx",
            Resultant::MomentY => "momy",
            Resultant::MomentZ => "momz",
        }
    }
}

/// A beam's end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum End {
    /// End A (at GA).
    A,
    /// End B (at GB).
    B,
}

/// A beam section's stress recovery point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BarPoint {
    /// Point C.
    C,
    /// Point D.
    D,
    /// Point E.
    E,
    /// Point F.
    F,
}

/// Where in an element a recovered value is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum At {
    /// A shell's fibre and in-plane component.
    Fibre(Fibre, Plane),
    /// A beam's recovery point at one end.
    Point(End, BarPoint),
    /// A beam's end (its resultants).
    End(End),
}

/// The transverse shear force resultants of a shear-deformable shell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Transverse {
    /// Qx, on a face of normal x (with γxz).
    Qx,
    /// Qy, on a face of normal y (with γyz).
    Qy,
}

/// A shell fibre: Z1 = −T/2 (the struck face of the paper's plate), Z2 = +T/2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Fibre {
    /// The fibre at z = −T/2.
    Z1,
    /// The fibre at z = +T/2.
    Z2,
}

/// An in-plane tensor component (xy is the engineering shear).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Plane {
    /// Normal, x.
    Xx,
    /// Normal, y.
    Yy,
    /// Engineering shear, xy.
    Xy,
}

/// One recovered value of an element: axial (rods), a fibre's in-plane component
/// (shells), a section point's value or an end's resultant (beams).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Recovered {
    /// Stress, strain or a resultant.
    pub measure: Measure,
    /// Where in the element; `None` for a rod's axial value.
    pub at: Option<At>,
}

impl Recovered {
    /// The name of the value of element `eid`: `strain_72`, `stress_2525_z1_xx`,
    /// `shear_force_2525_qx`, `stress_9001_a_c`, `force_9001_b_m1`, `force_72_axial`,
    /// `force_2525_mx`.
    pub fn name(&self, eid: i64) -> String {
        let end = |e: End| match e {
            End::A => "a",
            End::B => "b",
        };
        let m = match self.measure {
            Measure::Stress => "stress",
            Measure::Strain => "strain",
            Measure::ShearForce(Transverse::Qx) => return format!("shear_force_{eid}_qx"),
            Measure::ShearForce(Transverse::Qy) => return format!("shear_force_{eid}_qy"),
            Measure::Force(r) => {
                return match self.at {
                    Some(At::End(e)) => format!("force_{eid}_{}_{}", end(e), r.name()),
                    _ => format!("force_{eid}_{}", r.name()),
                }
            }
        };
        match self.at {
            None | Some(At::End(_)) => format!("{m}_{eid}"),
            Some(At::Point(e, p)) => {
                let p = match p {
                    BarPoint::C => "c",
                    BarPoint::D => "d",
                    BarPoint::E => "e",
                    BarPoint::F => "f",
                };
                format!("{m}_{eid}_{}_{p}", end(e))
            }
            Some(At::Fibre(f, c)) => {
                let f = match f {
                    Fibre::Z1 => "z1",
                    Fibre::Z2 => "z2",
                };
                let c = match c {
                    Plane::Xx => "xx",
                    Plane::Yy => "yy",
                    Plane::Xy => "xy",
                };
                format!("{m}_{eid}_{f}_{c}")
            }
        }
    }
}

/// The VTK cell an element draws as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cell {
    /// A one-node vertex (VTK_VERTEX): a concentrated mass.
    Vertex,
    /// A two-node line (VTK_LINE).
    Line,
    /// A three-node triangle (VTK_TRIANGLE).
    Triangle,
    /// A four-node quadrilateral (VTK_QUAD).
    Quad,
}

impl Cell {
    /// The VTK cell type number.
    pub fn vtk_type(self) -> u8 {
        match self {
            Cell::Vertex => 1,
            Cell::Line => 3,
            Cell::Triangle => 5,
            Cell::Quad => 9,
        }
    }
}

/// Why an element's geometry cannot be built: the rest of the sentence after the
/// card and element id ("has zero length (its grids coincide)").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BadShape(pub &'static str);

/// A kind's builder: its grids' coordinates (in connection order) and its resolved
/// section to its kernel.
pub type Builder<S> = fn(&[[f64; 3]], S) -> Result<Box<dyn BoxedKernel>, BadShape>;

/// How an element kind is built, by the property it takes.
#[derive(Clone, Copy)]
pub enum Build {
    /// From a PROD and its MAT1.
    Rod(Builder<rod::RodSection>),
    /// From a PSHELL or a PCOMP and their materials (the material x axis of a
    /// laminate: the G1→G2 side).
    Shell(Builder<shell::ShellSection>),
    /// From a PBAR, PBARL, PBEAM or PBEAML and its MAT1, with the pin flags; its ends
    /// given in its own axes, after its offsets.
    Bar(Builder<bar::BarSpec>),
    /// From a PSHEAR and its MAT1, its corners in the basic system.
    Panel(Builder<shear::PanelSection>),
}

/// An element card: its name, how many grids it connects (fields 4 on) and how it
/// is built.
#[derive(Clone, Copy)]
pub struct Kind {
    /// The bulk data card.
    pub card: &'static str,
    /// Its grids G1..Gn.
    pub grids: usize,
    /// Its property and builder.
    pub build: Build,
}

/// Every element card, one line per kind (CONM2, a mass rather than an element
/// connecting grids, is read on its own).
pub static KINDS: [Kind; 8] = [
    Kind {
        card: "CROD",
        grids: 2,
        build: Build::Rod(|x, s| Ok(Box::new(rod::Rod::build(x, s)?))),
    },
    Kind {
        card: "CONROD",
        grids: 2,
        build: Build::Rod(|x, s| Ok(Box::new(rod::Rod::build(x, s)?.of_card("CONROD")))),
    },
    Kind {
        card: "CTUBE",
        grids: 2,
        build: Build::Rod(|x, s| Ok(Box::new(rod::Rod::build(x, s)?.of_card("CTUBE")))),
    },
    Kind {
        card: "CQUAD4",
        grids: 4,
        build: Build::Shell(mitc4::cquad4),
    },
    Kind {
        card: "CTRIA3",
        grids: 3,
        build: Build::Shell(dkmt::ctria3),
    },
    Kind {
        card: "CSHEAR",
        grids: 4,
        build: Build::Panel(|x, s| Ok(Box::new(shear::ShearPanel::build(x, s)?))),
    },
    Kind {
        card: "CBAR",
        grids: 2,
        build: Build::Bar(|x, s| Ok(Box::new(bar::Bar::build(x, s)?))),
    },
    Kind {
        card: "CBEAM",
        grids: 2,
        build: Build::Bar(|x, s| Ok(Box::new(bar::Bar::build(x, s)?))),
    },
];

impl fmt::Debug for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({} grids)", self.card, self.grids)
    }
}

/// The element kind of a card name.
pub fn kind(card: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.card == card)
}

/// The in-plane coordinates of a flat shell's corners, refused when they are not in
/// one plane z = const (within 1e-9 relative): the model builder hands a kernel its
/// corners in the basic XY plane or in the element's own frame, both such planes.
pub fn flat_xy<const N: usize>(points: &[[f64; 3]]) -> Result<[[f64; 2]; N], BadShape> {
    let z = points[0][2];
    if points.iter().any(|p| (p[2] - z).abs() > 1e-9 * (1.0 + z.abs())) {
        return Err(BadShape(
            "is not in a plane z = const: a kernel takes its corners in its own plane",
        ));
    }
    Ok(std::array::from_fn(|k| [points[k][0], points[k][1]]))
}

/// What an element kind computes, over its local DOFs (6 per grid, grid-major).
pub trait Kernel: fmt::Debug + Send + Sync + Any {
    /// The bulk data card the kind comes from (`CROD`, `CQUAD4`, `CONM2`).
    fn card(&self) -> &'static str;
    /// Local stiffness matrices (none for a point mass).
    fn stiffness(&self) -> Vec<LocalMatrix>;
    /// Local mass matrices.
    fn mass(&self) -> Vec<LocalMatrix>;
    /// Local viscous damping matrices: a damper's (none for any other kind).
    fn damping(&self) -> Vec<LocalMatrix> {
        Vec::new()
    }
    /// Strain energy ½ u_eᵀ K_e u_e of the local displacements `ue`.
    fn strain_energy(&self, ue: &[f64]) -> f64;
    /// The values [`Kernel::recover`] gives for a request, in order (see [`Output`]).
    fn recovered(&self, what: Output) -> Vec<Recovered>;
    /// Recovered values from the local displacements, in the order of
    /// [`Kernel::recovered`].
    fn recover(&self, ue: &[f64], what: Output) -> Vec<f64>;
    /// The stresses the kind's material law gives for the strains it recovers
    /// (`strains` in the order of `recovered(false)`), in the order of the stresses in
    /// `recovered(true)`; `None` for a kind that recovers no stress. Computed from the
    /// strains alone, apart from [`Kernel::recover`]: `verify`'s material_law holds
    /// every written stress to it, and fails on a kind that recovers stresses and
    /// answers `None`.
    fn material_law(&self, strains: &[f64]) -> Option<Vec<f64>>;
    /// The mass whose mean nodal velocity the paper's Eq. 16 books; `None` for a
    /// point mass (not part of Eq. 16).
    fn eq16_mass(&self) -> Option<f64>;
    /// Coordinates of the element's grids, in its grid order.
    fn points(&self) -> Vec<[f64; 3]>;
    /// The cell it draws as in field output (`None`: not drawn).
    fn cell(&self) -> Option<Cell>;
    /// What it is to the computations over a whole target (the analytic references,
    /// the report's figures and checks): its family and section.
    fn family(&self) -> Family<'_>;
}

/// What an element kind is to the computations over a whole target: a line of a rod
/// section, a shell of a shell section, or a concentrated mass. Its geometry is
/// [`Kernel::points`].
#[derive(Debug, Clone, Copy)]
pub enum Family<'a> {
    /// A rod (CROD) of a section and a length.
    Rod {
        /// Its section.
        section: &'a rod::RodSection,
        /// Its length.
        length: f64,
    },
    /// A shell (CQUAD4, CTRIA3) of this section.
    Shell(&'a shell::ShellSection),
    /// A beam (CBAR, CBEAM) of a section and a length.
    Beam {
        /// Its section.
        section: &'a bar::BarSection,
        /// Its length.
        length: f64,
    },
    /// A concentrated mass (CONM2) of this mass.
    Point {
        /// Its mass.
        mass: f64,
    },
    /// A support the model adds (a grid's drilling spring, [`drill::Drill`]): no
    /// mass, no recovered values, not drawn.
    Support,
    /// A scalar spring or mass between two DOFs ([`scalar::Scalar`]).
    Scalar,
    /// A shear panel (CSHEAR) of this section.
    Panel(&'a shear::PanelSection),
    /// A general element (GENEL, [`general::General`]): a stiffness over listed DOFs.
    General,
    /// A concentrated mass matrix at a grid (CONM1, [`mass::MassMatrix`]).
    MassMatrix,
    /// A spring of six stiffnesses between grids (CBUSH, [`bush::Bush`]).
    Spring,
    /// A viscous damper between grids (CVISC, [`damper::Viscous`]).
    Damper,
}

impl<'a> Family<'a> {
    /// The shell section, for a shell.
    pub fn shell(self) -> Option<&'a shell::ShellSection> {
        match self {
            Family::Shell(s) => Some(s),
            _ => None,
        }
    }
}

/// A kernel behind a box: cloned, and seen as its concrete kind; every `Kernel` that
/// is `Clone` is one.
pub trait BoxedKernel: Kernel {
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn BoxedKernel>;
    /// The concrete kind, for [`Element::kind`].
    fn as_any(&self) -> &dyn Any;
    /// The concrete kind, mutable.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<K: Kernel + Clone> BoxedKernel for K {
    fn clone_box(&self) -> Box<dyn BoxedKernel> {
        Box::new(self.clone())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Where an element stands when its kernel's own axes are not its grids'
/// displacement frames: a shell out of the basic XY plane (its kernel works in the
/// element's plane), or any element on a grid whose CD is not the basic system.
///
/// For each grid, `turn` takes the grid's T1..R3 (in its displacement frame) to the
/// kernel's six local DOFs at that corner:
/// `[u; θ]_local = [Rᵀ  −Rᵀ[d]×; 0  Rᵀ] · blockdiag(T, T) · [u; θ]_grid`, R the
/// element's axes and T the grid's frame (both as columns of basic components), d the
/// rigid offset from the grid to the kernel's corner (a warped quadrilateral's corner
/// projected onto its mean plane; zero otherwise). Stiffness and mass turn as
/// `Λᵀ K Λ`, displacements as `Λ u`: strain energy and recovered values are the
/// kernel's own of the turned displacements.
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// Grid DOFs → local DOFs, one 6×6 matrix per grid.
    pub turn: Vec<Matrix6<f64>>,
    /// The grids' basic positions.
    pub points: Vec<[f64; 3]>,
}

impl Placement {
    /// The turn of one grid: element axes `r` (columns, basic), the grid's frame `t`
    /// (columns, basic) and the offset `d` (basic) from the grid to the corner.
    pub fn turn_of(r: &Matrix3<f64>, t: &Matrix3<f64>, d: [f64; 3]) -> Matrix6<f64> {
        let rt = r.transpose() * t;
        let d = nalgebra::Vector3::from(d);
        let mut m = Matrix6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&rt);
        m.fixed_view_mut::<3, 3>(3, 3).copy_from(&rt);
        if d != nalgebra::Vector3::zeros() {
            m.fixed_view_mut::<3, 3>(0, 3)
                .copy_from(&(-(r.transpose() * d.cross_matrix() * t)));
        }
        m
    }

    /// True when grid `g`'s turn has no offset: its translations only rotate.
    pub fn rotates_only(&self, g: usize) -> bool {
        self.turn[g].fixed_view::<3, 3>(0, 3).iter().all(|&v| v == 0.0)
    }
}

/// An element of the model: its kernel, id, grids and the solved DOF index of T1..R3
/// at each grid (`None` where constrained or not solved).
#[derive(Debug)]
pub struct Element {
    /// Element id from the deck.
    pub eid: i64,
    /// Its grids, in connection order.
    pub grids: Vec<i64>,
    /// Solved DOF index of T1..R3 at each grid.
    pub dofs: Vec<[Option<usize>; 6]>,
    /// What the element computes.
    pub kernel: Box<dyn BoxedKernel>,
    /// How its kernel's local DOFs are formed from its grids'; `None` when they are
    /// the same (a shell in the basic XY plane, numbered counter-clockwise about +z,
    /// on grids displaced in the basic system; any rod or mass on such grids).
    pub placement: Option<Arc<Placement>>,
    /// Terms each grid's components gain from other grids' solved DOFs, `Σ a·u[i]`
    /// per (grid, component), before the turn: a grid a rigid element ties to several
    /// grids (an RBE3's reference grid, an RBE2 of some components). `None` when no
    /// grid is so tied.
    pub links: Option<Arc<Links>>,
    /// β of the viscous damping β·K_e the element adds to its kernel's: GE/W4, its
    /// structural damping coefficient GE turned viscous at PARAM W4, as NASTRAN's
    /// direct transient solutions form it (B += K₄/W4, K₄ = Σ GE·K_e: NASTRAN-95
    /// User's Manual, 1.6.1, Eq. 5); 0 when it has none.
    pub stiffness_damping: f64,
}

/// Each grid's mass m when `l` (over `grids` grids) is m·I on every grid's
/// translations and nothing else (a lumped mass: diagonal, each (grid, component)
/// once, a grid's three translations equal; m = 0 for a grid it leaves out), as
/// [`Element::turned`] sums it into a grid's block (so −0 reads as +0); `None`
/// otherwise.
fn lumped_translations(l: &LocalMatrix, grids: usize) -> Option<Vec<f64>> {
    let k = l.at.len();
    if (0..k).any(|a| (0..k).any(|b| a != b && l.values[(a, b)] != 0.0)) {
        return None;
    }
    let mut m: Vec<Option<f64>> = vec![None; grids];
    let mut seen = vec![0u8; grids];
    for (a, &(g, c)) in l.at.iter().enumerate() {
        if c >= 3 || seen[g] & (1 << c) != 0 {
            return None;
        }
        seen[g] |= 1 << c;
        let v = 0.0 + l.values[(a, a)];
        match m[g] {
            None => m[g] = Some(v),
            Some(x) if x == v => {}
            Some(_) => return None,
        }
    }
    seen.iter()
        .all(|&s| s == 0 || s == 0b111)
        .then(|| m.into_iter().map(|m| m.unwrap_or(0.0)).collect())
}

/// Per grid of an element, per component T1..R3: the solved DOFs and coefficients
/// it is the sum of besides its own DOF.
pub type Links = Vec<[Vec<(usize, f64)>; 6]>;

impl Clone for Element {
    fn clone(&self) -> Self {
        Element {
            eid: self.eid,
            grids: self.grids.clone(),
            dofs: self.dofs.clone(),
            kernel: self.kernel.clone_box(),
            placement: self.placement.clone(),
            links: self.links.clone(),
            stiffness_damping: self.stiffness_damping,
        }
    }
}

impl Element {
    /// An element of kernel `kernel` on `grids`, with the solved DOFs of each grid.
    pub fn new(eid: i64, grids: Vec<i64>, dofs: Vec<[Option<usize>; 6]>, kernel: impl Kernel + Clone) -> Self {
        Element::boxed(eid, grids, dofs, Box::new(kernel))
    }

    /// An element of a boxed kernel (as [`Kind`]'s builders give it) on `grids`.
    pub fn boxed(eid: i64, grids: Vec<i64>, dofs: Vec<[Option<usize>; 6]>, kernel: Box<dyn BoxedKernel>) -> Self {
        debug_assert_eq!(grids.len(), dofs.len());
        debug_assert!(grids.len() <= MAX_GRIDS);
        Element {
            eid,
            grids,
            dofs,
            kernel,
            placement: None,
            links: None,
            stiffness_damping: 0.0,
        }
    }

    /// The element placed (see [`Placement`]).
    pub fn placed(mut self, placement: Placement) -> Self {
        debug_assert_eq!(placement.turn.len(), self.grids.len());
        self.placement = Some(Arc::new(placement));
        self
    }

    /// The element with its grids' links (see [`Element::links`]).
    pub fn linked(mut self, links: Links) -> Self {
        debug_assert_eq!(links.len(), self.grids.len());
        self.links = Some(Arc::new(links));
        self
    }

    /// The basic coordinates of the element's grids, in its grid order.
    pub fn points(&self) -> Vec<[f64; 3]> {
        match &self.placement {
            Some(p) => p.points.clone(),
            None => self.kernel.points(),
        }
    }

    /// The kernel as its concrete kind, if it is one.
    pub fn kind<K: Kernel>(&self) -> Option<&K> {
        self.kernel.as_any().downcast_ref()
    }

    /// The kernel as its concrete kind, mutably.
    pub fn kind_mut<K: Kernel>(&mut self) -> Option<&mut K> {
        self.kernel.as_any_mut().downcast_mut()
    }

    /// The element's local displacements (6 per grid; 0 where not solved), turned to
    /// its kernel's axes when it is placed.
    fn gather(&self, u: &[f64]) -> ([f64; 6 * MAX_GRIDS], usize) {
        let mut ue = [0.0; 6 * MAX_GRIDS];
        for (g, d) in self.dofs.iter().enumerate() {
            for (c, i) in d.iter().enumerate() {
                if let Some(i) = i {
                    ue[6 * g + c] = u[*i];
                }
            }
        }
        if let Some(links) = &self.links {
            for (g, l) in links.iter().enumerate() {
                for (c, terms) in l.iter().enumerate() {
                    ue[6 * g + c] += terms.iter().map(|&(i, a)| a * u[i]).sum::<f64>();
                }
            }
        }
        if let Some(p) = &self.placement {
            for (g, t) in p.turn.iter().enumerate() {
                let ug = nalgebra::Vector6::from_column_slice(&ue[6 * g..6 * g + 6]);
                ue[6 * g..6 * g + 6].copy_from_slice((t * ug).as_slice());
            }
        }
        (ue, 6 * self.dofs.len())
    }

    /// A load `f` on the kernel's six DOFs at the element's `k`-th grid as that grid's
    /// T1..R3 (in its displacement frame): Λₖᵀ f, the force and its moment about the
    /// grid where the kernel's corner stands off it; `f` itself when the element is
    /// not placed.
    pub fn load_at_grid(&self, k: usize, f: nalgebra::Vector6<f64>) -> nalgebra::Vector6<f64> {
        match &self.placement {
            Some(p) => p.turn[k].transpose() * f,
            None => f,
        }
    }

    /// Adds the element's stiffness and mass to global triplet lists (solved DOFs
    /// only; exact zeros skipped).
    pub fn scatter(&self, k: &mut Vec<(usize, usize, f64)>, m: &mut Vec<(usize, usize, f64)>) {
        for l in self.stiffness() {
            k.extend(self.expanded(&l));
        }
        for l in self.mass() {
            m.extend(self.expanded(&l));
        }
    }

    /// Adds the element's viscous damping to a global triplet list (solved DOFs only;
    /// exact zeros skipped): its kernel's and β·K_e ([`Element::stiffness_damping`]);
    /// nothing for an element that does not damp.
    pub fn scatter_damping(&self, c: &mut Vec<(usize, usize, f64)>) {
        for l in self.turned(self.kernel.damping()) {
            c.extend(self.expanded(&l));
        }
        if self.stiffness_damping != 0.0 {
            for mut l in self.stiffness() {
                l.values *= self.stiffness_damping;
                c.extend(self.expanded(&l));
            }
        }
    }

    /// True when the element damps: its kernel has a damping matrix, or its
    /// structural damping is turned viscous.
    pub fn damps(&self) -> bool {
        self.stiffness_damping != 0.0 || !self.kernel.damping().is_empty()
    }

    /// The element's stiffness matrices over its grids' DOFs.
    pub fn stiffness(&self) -> Vec<LocalMatrix> {
        self.turned(self.kernel.stiffness())
    }

    /// The element's mass matrices over its grids' DOFs.
    pub fn mass(&self) -> Vec<LocalMatrix> {
        self.turned(self.kernel.mass())
    }

    /// [`Element::mass`], or, when it is one lumped mass (m·I on each grid's
    /// translations in grid and component order and nothing else), each grid's m (a
    /// zero m for a grid it leaves out) without forming it. The kernel's mass is
    /// computed once either way.
    pub fn mass_or_lumped(&self) -> Result<Vec<f64>, Vec<LocalMatrix>> {
        let n = self.grids.len();
        let local = self.kernel.mass();
        if let [l] = local.as_slice() {
            let lumped = lumped_translations(l, n).filter(|_| match &self.placement {
                // Turned, such a mass is kept exactly m·I, over all DOFs in order.
                Some(p) => (0..n).all(|g| p.rotates_only(g)),
                None => l.at.windows(2).all(|w| w[0] < w[1]),
            });
            if let Some(m) = lumped {
                return Ok(m);
            }
        }
        Err(self.turned(local))
    }

    /// The kernel's matrices as they act on the grids' DOFs: unchanged when the element
    /// is not placed, `Λᵀ K Λ` over all of its grids' DOFs when it is. A grid's block
    /// that is m·I on its translations alone (a lumped mass) is kept exactly m·I when
    /// its turn only rotates: RᵀmIR = mI, which round-off would otherwise smear onto
    /// the other translations.
    fn turned(&self, local: Vec<LocalMatrix>) -> Vec<LocalMatrix> {
        let Some(p) = &self.placement else { return local };
        let n = 6 * self.grids.len();
        let at: Vec<(usize, usize)> = (0..n).map(|k| (k / 6, k % 6)).collect();
        let lambda = std::cell::LazyCell::new(|| {
            let mut lambda = DMatrix::zeros(n, n);
            for (g, t) in p.turn.iter().enumerate() {
                lambda.view_mut((6 * g, 6 * g), (6, 6)).copy_from(t);
            }
            lambda
        });
        let rotates_only = (0..self.grids.len()).all(|g| p.rotates_only(g));
        local
            .into_iter()
            .map(|l| {
                if let Some(m) = lumped_translations(&l, self.grids.len()).filter(|_| rotates_only) {
                    // What the product below gives such a matrix, without it.
                    let mut values = DMatrix::zeros(n, n);
                    for (g, m) in m.iter().enumerate() {
                        for c in 0..3 {
                            values[(6 * g + c, 6 * g + c)] = *m;
                        }
                    }
                    return LocalMatrix { at: at.clone(), values };
                }
                let mut full = DMatrix::zeros(n, n);
                for (a, &(ga, ca)) in l.at.iter().enumerate() {
                    for (b, &(gb, cb)) in l.at.iter().enumerate() {
                        full[(6 * ga + ca, 6 * gb + cb)] += l.values[(a, b)];
                    }
                }
                let mut values = lambda.transpose() * &full * &*lambda;
                for g in 0..self.grids.len() {
                    let r = 6 * g;
                    let m = full[(r, r)];
                    let isotropic = (0..n).all(|j| {
                        (0..6).all(|c| {
                            let v = full[(r + c, j)];
                            if j == r + c && c < 3 {
                                v == m
                            } else {
                                v == 0.0
                            }
                        })
                    });
                    if isotropic && p.rotates_only(g) {
                        values.view_mut((r, 0), (6, n)).fill(0.0);
                        values.view_mut((0, r), (n, 6)).fill(0.0);
                        for c in 0..3 {
                            values[(r + c, r + c)] = m;
                        }
                    }
                }
                LocalMatrix { at: at.clone(), values }
            })
            .collect()
    }

    /// The solved DOFs and coefficients a local (grid, component) is the sum of.
    fn terms(&self, g: usize, c: usize) -> Vec<(usize, f64)> {
        let own = self.dofs[g][c].map(|i| (i, 1.0));
        let linked = self.links.iter().flat_map(|l| l[g][c].iter().copied());
        own.into_iter().chain(linked).collect()
    }

    /// A local matrix over the solved DOFs: each nonzero entry (a, b) as c_a·v·c_b on
    /// every pair of the solved DOFs its rows and columns are sums of (one each, with
    /// coefficient 1, for a grid without links), in row-major order.
    fn expanded(&self, l: &LocalMatrix) -> Vec<(usize, usize, f64)> {
        let terms: Vec<Vec<(usize, f64)>> = l.at.iter().map(|&(g, c)| self.terms(g, c)).collect();
        let mut out = Vec::new();
        for (a, ta) in terms.iter().enumerate() {
            for (b, tb) in terms.iter().enumerate() {
                let v = l.values[(a, b)];
                if v == 0.0 {
                    continue;
                }
                for &(i, ca) in ta {
                    for &(j, cb) in tb {
                        out.push((i, j, ca * v * cb));
                    }
                }
            }
        }
        out
    }

    /// Strain energy at the displacements `u` of the solved DOFs.
    pub fn strain_energy(&self, u: &[f64]) -> f64 {
        let (ue, n) = self.gather(u);
        self.kernel.strain_energy(&ue[..n])
    }

    /// Kinetic energy ½ vᵀ M_e v at the velocities `v` of the solved DOFs (its mass
    /// matrices as they act on its grids' DOFs; unsolved DOFs at rest).
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        let mut ke = 0.0;
        for l in self.mass() {
            for (i, j, m) in self.expanded(&l) {
                ke += 0.5 * v[i] * m * v[j];
            }
        }
        ke
    }

    /// Recovered values at `u` (see [`Kernel::recover`]).
    pub fn recover(&self, u: &[f64], what: Output) -> Vec<f64> {
        let (ue, n) = self.gather(u);
        self.kernel.recover(&ue[..n], what)
    }

    /// The translational DOFs of each grid, for the paper's Eq. 16.
    pub fn translations(&self) -> Vec<[Option<usize>; 3]> {
        self.dofs.iter().map(|d| [d[0], d[1], d[2]]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// One kernel of each kind: a skewed rod in space, a distorted CQUAD4 and a scalene
    /// CTRIA3 with membrane and bending (each also coupled), a CONM2.
    fn kernels() -> Vec<Box<dyn BoxedKernel>> {
        let section = rod::RodSection {
            e: 1.0e7,
            g: 3.8e6,
            area: 0.2,
            torsion: 0.01,
            rho: 2.5e-4,
            nsm: 0.0,
            coupled_mass: false,
        };
        let g = Matrix3::new(4.3e6, 2.9e5, 0.0, 2.9e5, 2.8e6, 0.0, 0.0, 0.0, 5.7e5);
        let shell = shell::ShellSection {
            thickness: 0.15,
            g_membrane: Some(g),
            g_bending: Some(g * 1.3),
            g_coupling: None,
            shear: None,
            mass_per_area: 2.7e-5,
        };
        vec![
            Box::new(rod::Rod {
                card: "CROD",
                x: [[0.0, 0.0, 0.0], [0.3, 0.2, 0.1]],
                section,
            }),
            Box::new(quad4::Quad4::new(
                [[0.0, 0.0], [2.0, 0.3], [2.4, 1.7], [0.3, 1.2]],
                0.0,
                shell.clone(),
            )),
            // An unsymmetric laminate's: membrane and bending coupled.
            Box::new(quad4::Quad4::new(
                [[0.0, 0.0], [2.0, 0.3], [2.4, 1.7], [0.3, 1.2]],
                0.0,
                shell::ShellSection {
                    g_coupling: Some(Matrix3::new(
                        3.0e5, 1.0e4, 2.0e4, 1.0e4, -3.0e5, 5.0e3, 2.0e4, 5.0e3, 1.0e4,
                    )),
                    ..shell
                },
            )),
            Box::new(tria3::Tria3::new(
                [[0.1, -0.2], [2.3, 0.4], [0.7, 1.9]],
                0.0,
                shell.clone(),
            )),
            Box::new(tria3::Tria3::new(
                [[0.1, -0.2], [2.3, 0.4], [0.7, 1.9]],
                0.0,
                shell::ShellSection {
                    g_coupling: Some(Matrix3::new(
                        3.0e5, 1.0e4, 2.0e4, 1.0e4, -3.0e5, 5.0e3, 2.0e4, 5.0e3, 1.0e4,
                    )),
                    ..shell.clone()
                },
            )),
            // The shear-deformable CQUAD4, with an unsymmetric section.
            Box::new(mitc4::Mitc4::new(
                [[0.0, 0.0], [2.0, 0.3], [2.4, 1.7], [0.3, 1.2]],
                0.0,
                shell::ShellSection {
                    g_coupling: Some(Matrix3::new(
                        3.0e5, 1.0e4, 2.0e4, 1.0e4, -3.0e5, 5.0e3, 2.0e4, 5.0e3, 1.0e4,
                    )),
                    shear: Some(nalgebra::Matrix2::new(5.0e4, 3.0e3, 3.0e3, 4.0e4)),
                    ..shell.clone()
                },
            )),
            // A bar with I12 and a pin flag.
            Box::new(
                bar::Bar::build(
                    &[[0.0; 3], [1.7, 0.0, 0.0]],
                    bar::BarSpec {
                        card: "CBAR",
                        section: bar::BarSection {
                            torsional_inertia: 2.75e-5,
                            ..bar::sample_section()
                        },
                        released: [0, 0b100000],
                        coupled_mass: false,
                    },
                )
                .expect("a bar"),
            ),
            Box::new(mass::PointMass {
                x: [0.0; 3],
                mass: 1e-4,
                inertia: [1e-6, 0.0, 1e-6, 0.0, 0.0, 1e-6],
            }),
        ]
    }

    /// Goal: what the ledger books and what the recorder writes agree with the
    /// element's own matrices and names, for every kind: strain_energy(u) is ½uᵀKu of
    /// the local stiffness matrices it hands to assembly (to 1e-12, every local DOF
    /// displaced), recover gives exactly as many values as recovered names, with and
    /// without stresses, the stresses it recovers are its material law of the strains
    /// it recovers, and each names the deck card it comes from.
    #[test]
    fn every_kernel_books_half_utku_and_recovers_what_it_names() {
        for (kind, k) in [
            "CROD", "CQUAD4", "CQUAD4", "CTRIA3", "CTRIA3", "CQUAD4", "CBAR", "CONM2",
        ]
        .iter()
        .zip(kernels())
        {
            assert_eq!(k.card(), *kind);
            let n = 6 * k.points().len();
            let u: Vec<f64> = (0..n).map(|i| 1e-3 * ((i as f64) * 0.71 + 0.2).sin()).collect();
            let mut utku = 0.0;
            for l in k.stiffness() {
                for (a, &(ga, ca)) in l.at.iter().enumerate() {
                    for (b, &(gb, cb)) in l.at.iter().enumerate() {
                        utku += u[6 * ga + ca] * l.values[(a, b)] * u[6 * gb + cb];
                    }
                }
            }
            let e = k.strain_energy(&u);
            assert!(
                (e - 0.5 * utku).abs() <= 1e-12 * utku.abs().max(f64::MIN_POSITIVE),
                "{kind}: {e} vs {}",
                0.5 * utku
            );
            for what in [Output::Strain, Output::Stress, Output::Force] {
                assert_eq!(k.recover(&u, what).len(), k.recovered(what).len(), "{kind} {what:?}");
            }
            // The stresses it recovers are its material law of the strains it recovers.
            let with = k.recover(&u, Output::Stress);
            let stresses: Vec<f64> = k
                .recovered(Output::Stress)
                .iter()
                .zip(&with)
                .filter(|(r, _)| r.measure == Measure::Stress)
                .map(|(_, &v)| v)
                .collect();
            match k.material_law(&k.recover(&u, Output::Strain)) {
                Some(law) => {
                    let scale = stresses.iter().fold(0.0f64, |m, s| m.max(s.abs()));
                    assert_eq!(law.len(), stresses.len(), "{kind}");
                    assert!(
                        law.iter().zip(&stresses).all(|(l, s)| (l - s).abs() <= 1e-12 * scale),
                        "{kind}: {law:?} vs {stresses:?}"
                    );
                }
                None => assert!(stresses.is_empty(), "{kind} recovers stresses and answers no law"),
            }
        }
    }

    /// Goal: the resultants FORCE writes are the integrals of the stresses STRESS
    /// writes. Model: every kernel above at a displacement with every DOF nonzero.
    /// Reference: a rod's N = σA; a shell's (no membrane-bending coupling, whose
    /// resultant the fibre stresses do not show) N = T(σ₁ + σ₂)/2 and
    /// M = T²(σ₂ − σ₁)/12, σ being linear through the thickness, and Qx, Qy as the
    /// shear forces written with the stresses; a beam's N = EA times the mean of the
    /// strains at C, D, E, F (a rectangle's corners, where the plane strain field
    /// averages to its centroid's). Tolerance: 1e-12 of the largest.
    #[test]
    fn force_resultants_are_the_integrals_of_the_recovered_stresses() {
        for k in kernels() {
            let n = 6 * k.points().len();
            let u: Vec<f64> = (0..n).map(|i| 1e-3 * (1.0 + (i as f64 * 0.9).sin())).collect();
            let (stress, force) = (k.recover(&u, Output::Stress), k.recover(&u, Output::Force));
            let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-12 * scale;
            match k.family() {
                Family::Rod { section, .. } => assert!(close(force[0], stress[0] * section.area, force[0].abs())),
                Family::Shell(section) if section.g_coupling.is_none() => {
                    let t = section.thickness;
                    let scale = force.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for c in 0..3 {
                        let (s1, s2) = (stress[c], stress[3 + c]);
                        assert!(close(force[c], t * (s1 + s2) / 2.0, scale), "{}: N{c}", k.card());
                        assert!(
                            close(force[3 + c], t * t * (s2 - s1) / 12.0, scale),
                            "{}: M{c}",
                            k.card()
                        );
                    }
                    if section.shear.is_some() {
                        assert_eq!(force[6..], stress[stress.len() - 2..]);
                    }
                }
                Family::Beam { section, .. } => {
                    let strains = &stress[8..16];
                    for end in 0..2 {
                        let mean = strains[4 * end..4 * end + 4].iter().sum::<f64>() / 4.0;
                        let n = section.e * section.area * mean;
                        assert!(close(force[6 * end], n, n.abs()), "{} end {end}", k.card());
                    }
                }
                _ => {}
            }
        }
    }

    /// Goal: a history column's name says element, measure, fibre and component.
    #[test]
    fn recovered_values_are_named_by_element_fibre_and_component() {
        let axial = Recovered {
            measure: Measure::Strain,
            at: None,
        };
        assert_eq!(axial.name(72), "strain_72");
        let shell = Recovered {
            measure: Measure::Stress,
            at: Some(At::Fibre(Fibre::Z1, Plane::Xy)),
        };
        assert_eq!(shell.name(2525), "stress_2525_z1_xy");
        let q = Recovered {
            measure: Measure::ShearForce(Transverse::Qy),
            at: None,
        };
        assert_eq!(q.name(2525), "shear_force_2525_qy");
    }
}
