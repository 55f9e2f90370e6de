//! Typed bulk data cards, read from raw cards field by field.
//!
//! Field index `k` is the card's data field counted from 0 (NASTRAN field 2 of the
//! first line), running on through continuation lines 8 fields a line.

use super::bulk::RawCard;
use super::diag::{Diagnostic, Diagnostics, Pos};
use super::number::{parse_int, parse_real, RealToken};

/// Where a card came from, for messages raised after reading (model building).
#[derive(Debug, Clone)]
pub struct CardRef {
    /// Card name.
    pub name: String,
    /// Where the card starts.
    pub pos: Pos,
    /// The card's source lines, for quoting.
    pub source: String,
}

impl CardRef {
    /// An error about this card, quoting it.
    pub fn error(&self, message: impl Into<String>) -> Diagnostic {
        Diagnostic::error(Some(self.pos.clone()), message)
            .card(&self.name)
            .quote(&self.source)
    }

    /// A warning about this card, quoting it.
    pub fn warning(&self, message: impl Into<String>) -> Diagnostic {
        Diagnostic::warning(Some(self.pos.clone()), message)
            .card(&self.name)
            .quote(&self.source)
    }

    /// An error about one field of this card, pointing at it.
    pub fn field_error(&self, f: &FieldRef, message: impl Into<String>) -> Diagnostic {
        let d = Diagnostic::error(Some(f.pos.clone()), message)
            .card(&self.name)
            .field(f.number, f.name)
            .quote(&self.source);
        if f.token.is_empty() {
            d
        } else {
            d.token(&f.token)
        }
    }
}

/// Where one field of a card was written, for messages raised after reading (a
/// coordinate system that does not exist, three points on a line).
#[derive(Debug, Clone)]
pub struct FieldRef {
    /// Where the field starts (the card's start when the field is absent).
    pub pos: Pos,
    /// NASTRAN field number on its line.
    pub number: usize,
    /// The field's name.
    pub name: &'static str,
    /// The field as written, trimmed; empty when blank.
    pub token: String,
}

/// A set of DOF components 1-6 (bit i-1 for component i); empty for scalar points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Components(pub u8);

impl Components {
    /// True when component `c` (1-6) is in the set.
    pub fn contains(self, c: usize) -> bool {
        (1..=6).contains(&c) && self.0 & (1 << (c - 1)) != 0
    }
    /// The components in the set, ascending.
    pub fn iter(self) -> impl Iterator<Item = usize> {
        (1..=6).filter(move |&c| self.contains(c))
    }
}

/// GRID: a grid point (six DOFs) at a location.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Grid id (field 2).
    pub id: i64,
    /// Coordinate system of the location, CP (field 3); `None` when blank (GRDSET's
    /// applies), `Some(0)` for the basic system.
    pub cp: Option<i64>,
    /// Location X1, X2, X3 (fields 4-6), in system CP's coordinates: x, y, z
    /// (rectangular), R, θ in degrees, z (cylindrical), R, θ, φ in degrees (spherical).
    pub x: [f64; 3],
    /// Displacement coordinate system, CD (field 7); `None` when blank (GRDSET's
    /// applies). The grid's T1..R3 are along that system's axes at the grid.
    pub cd: Option<i64>,
    /// Where CP and CD were written.
    pub cp_at: FieldRef,
    /// See `cp_at`.
    pub cd_at: FieldRef,
    /// Permanent single-point constraints, PS (field 8); `None` when blank (GRDSET applies).
    pub ps: Option<Components>,
    /// The card.
    pub at: CardRef,
}

/// GRDSET: defaults for blank GRID fields.
#[derive(Debug, Clone, Default)]
pub struct GrdSet {
    /// Default CP.
    pub cp: i64,
    /// Default CD.
    pub cd: i64,
    /// Default PS.
    pub ps: Components,
    /// The card, when the deck has one.
    pub at: Option<CardRef>,
}

/// The three kinds of coordinate system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoordKind {
    /// x, y, z (CORD1R, CORD2R).
    Rectangular,
    /// R, θ (degrees), z (CORD1C, CORD2C).
    Cylindrical,
    /// R, θ (degrees from z), φ (degrees about z from x) (CORD1S, CORD2S).
    Spherical,
}

/// How a coordinate system's origin and axes are given.
#[derive(Debug, Clone)]
pub enum CordDef {
    /// CORD2R/C/S: origin A, a point B on the z axis, a point C in the xz-plane, in
    /// the coordinates of system RID (0: basic).
    Points {
        /// RID.
        rid: i64,
        /// Where RID was written.
        rid_at: FieldRef,
        /// A, B, C.
        abc: [[f64; 3]; 3],
    },
    /// CORD1R/C/S: the same three points as grids G1, G2, G3.
    Grids {
        /// G1, G2, G3.
        g: [i64; 3],
        /// Where each was written.
        g_at: [FieldRef; 3],
    },
}

/// A coordinate system card (CORD1R, CORD1C, CORD1S carry two each).
#[derive(Debug, Clone)]
pub struct Cord {
    /// Its id CID.
    pub cid: i64,
    /// Rectangular, cylindrical or spherical.
    pub kind: CoordKind,
    /// Its definition.
    pub def: CordDef,
    /// Where C (CORD2x) or G3 (CORD1x) was written: the point that, on the line
    /// through the other two, leaves the axes undefined.
    pub third_at: FieldRef,
    /// The card.
    pub at: CardRef,
}

/// An element card of [`crate::elements::KINDS`] (CROD, CQUAD4, CTRIA3): the element
/// and the grids it connects.
#[derive(Debug, Clone)]
pub struct Connection {
    /// Its kind.
    pub kind: &'static crate::elements::Kind,
    /// Element id (field 2).
    pub eid: i64,
    /// Property id (field 3; the element id when blank).
    pub pid: i64,
    /// Grids G1..Gn (fields 4 on; a shell's corners counter-clockwise).
    pub g: Vec<i64>,
    /// A shell's material orientation (THETA/MCID, after its grids).
    pub orientation: Orientation,
    /// Where THETA/MCID was written.
    pub orientation_at: Option<FieldRef>,
    /// A shell's ZOFFS: its reference plane this far along its normal from its grids
    /// (0.0 for other kinds).
    pub zoffs: f64,
    /// A bar's orientation, offsets and pin flags (CBAR, CBEAM).
    pub bar: Option<BarCard>,
    /// A CONROD's own property (its PID is its EID).
    pub rod: Option<Prod>,
    /// The property card a COSMIC plate names (CQDMEM1's PQDMEM1): COSMIC numbers
    /// each property card's ids apart, so PID is looked up among that card's.
    pub property_card: Option<&'static str>,
    /// The card.
    pub at: CardRef,
}

/// The fields of a CBAR or CBEAM after its grids.
#[derive(Debug, Clone)]
pub struct BarCard {
    /// The orientation vector v or the grid G0 it points to from GA.
    pub orientation: BarOrientation,
    /// v is in the basic system (OFFT's first letter B) rather than in GA's
    /// displacement frame (G).
    pub orientation_basic: bool,
    /// The offsets WA, WB are in the basic system (OFFT's second and third letters B)
    /// rather than in their grids' displacement frames (G).
    pub offsets_basic: [bool; 2],
    /// Pin flags PA, PB: the components released at each end, in element axes.
    pub released: [Components; 2],
    /// Offsets WA, WB from GA and GB to the bar's ends.
    pub offsets: [[f64; 3]; 2],
    /// Where X1/G0 was written.
    pub orientation_at: FieldRef,
}

/// How a bar's plane 1 is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BarOrientation {
    /// The vector (X1, X2, X3).
    Vector([f64; 3]),
    /// From GA to grid G0.
    Grid(i64),
}

/// A bar's section as a property card gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum BarDims {
    /// PBAR, PBEAM: the constants themselves.
    Constants(crate::elements::section::Constants),
    /// PBARL, PBEAML: a section type and its dimensions.
    Shape(crate::elements::section::Shape, Vec<f64>),
}

/// PBAR, PBARL, PBEAM or PBEAML (one constant section).
#[derive(Debug, Clone)]
pub struct BarProperty {
    /// Property id (field 2).
    pub pid: i64,
    /// MAT1 id (field 3).
    pub mid: i64,
    /// The section.
    pub dims: BarDims,
    /// Non-structural mass per unit length.
    pub nsm: f64,
    /// The card.
    pub at: CardRef,
}

/// A shell's material x axis, as NASTRAN's CQUAD4 and CTRIA3 give it in their
/// THETA/MCID field: a real is THETA, an integer MCID.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// THETA degrees from the G1→G2 side, counter-clockwise about the element's
    /// normal (blank: 0.0).
    Theta(f64),
    /// The x axis of coordinate system MCID projected onto the element.
    Mcid(i64),
}

/// PROD: rod properties.
#[derive(Debug, Clone)]
pub struct Prod {
    /// Property id (field 2).
    pub pid: i64,
    /// MAT1 id (field 3).
    pub mid: i64,
    /// Cross-section area A (field 4).
    pub a: f64,
    /// Torsional constant J (field 5).
    pub j: f64,
    /// Non-structural mass per unit length, NSM (field 7).
    pub nsm: f64,
    /// The card.
    pub at: CardRef,
}

/// PSHELL: shell properties.
#[derive(Debug, Clone)]
pub struct Pshell {
    /// Property id (field 2).
    pub pid: i64,
    /// Membrane material MID1 (field 3); `None` when blank.
    pub mid1: Option<i64>,
    /// Thickness T (field 4).
    pub t: f64,
    /// Bending material MID2 (field 5); `None` when blank.
    pub mid2: Option<i64>,
    /// 12 I / T^3.
    pub bend_ratio: f64,
    /// Transverse shear material MID3 (field 7); `None` when blank.
    pub mid3: Option<i64>,
    /// Transverse shear thickness over membrane thickness TS/T (field 8; 0.833333,
    /// the shear correction factor 5/6, when blank).
    pub ts_t: f64,
    /// Membrane-bending coupling material MID4 (the continuation's field 4, after Z1 and Z2);
    /// `None` when blank.
    pub mid4: Option<i64>,
    /// Non-structural mass per unit area, NSM (field 9).
    pub nsm: f64,
    /// The card.
    pub at: CardRef,
}

/// MAT1: an isotropic material.
#[derive(Debug, Clone)]
pub struct Mat1 {
    /// Material id (field 2).
    pub mid: i64,
    /// Young's modulus E (field 3).
    pub e: f64,
    /// Shear modulus G (field 4).
    pub g: f64,
    /// Poisson's ratio NU (field 5).
    pub nu: f64,
    /// Mass density RHO (field 6).
    pub rho: f64,
    /// The card.
    pub at: CardRef,
}

/// Anisotropic 2-D material: `[G11 G12 G13; G12 G22 G23; G13 G23 G33]`.
#[derive(Debug, Clone)]
pub struct Mat2 {
    /// Material id (field 2).
    pub mid: i64,
    /// The symmetric material matrix, from G11, G12, G13, G22, G23, G33 (fields 3-8).
    pub g: [[f64; 3]; 3],
    /// Mass density RHO (field 9).
    pub rho: f64,
    /// The card.
    pub at: CardRef,
}

/// MAT8: an orthotropic material for shells (a ply), in its own axes 1 (fibre) and 2.
#[derive(Debug, Clone)]
pub struct Mat8 {
    /// Material id (field 2).
    pub mid: i64,
    /// Modulus along the fibres E1 (field 3).
    pub e1: f64,
    /// Modulus across the fibres E2 (field 4).
    pub e2: f64,
    /// Poisson's ratio NU12 (field 5): strain in 2 over strain in 1 under stress in 1.
    pub nu12: f64,
    /// In-plane shear modulus G12 (field 6).
    pub g12: f64,
    /// Transverse shear moduli G1Z, G2Z (fields 7, 8); `None` when blank.
    pub g1z: Option<f64>,
    /// See `g1z`.
    pub g2z: Option<f64>,
    /// Mass density RHO (field 9).
    pub rho: f64,
    /// Allowables Xt, Xc, Yt, Yc, S (continuation fields 5-9); `None` when blank.
    pub allowables: [Option<f64>; 5],
    /// The Tsai-Wu interaction term F12 (second continuation, field 3).
    pub f12: Option<f64>,
    /// STRN (second continuation, field 4): 1.0 when the allowables are strains.
    pub strn: f64,
    /// The card.
    pub at: CardRef,
}

/// One ply of a PCOMP, its blank fields resolved (MID and T repeat the ply above).
#[derive(Debug, Clone, PartialEq)]
pub struct Ply {
    /// MAT8 (or MAT1) id.
    pub mid: i64,
    /// Thickness.
    pub t: f64,
    /// Fibre angle in degrees, from the element's material x axis, counter-clockwise
    /// about the element normal.
    pub theta: f64,
    /// Stress and strain output asked for (SOUT = YES).
    pub sout: bool,
}

/// How a PCOMP lists its plies (LAM).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lam {
    /// Every ply listed, bottom to top.
    All,
    /// The plies listed are the bottom half; the top half mirrors them (LAM = SYM).
    Sym,
}

/// PCOMP: a layered composite shell, plies from the bottom (Z0) up.
#[derive(Debug, Clone)]
pub struct Pcomp {
    /// Property id (field 2).
    pub pid: i64,
    /// Distance from the reference plane to the bottom surface Z0 (field 3); `None`
    /// when blank (−½ the total thickness).
    pub z0: Option<f64>,
    /// Non-structural mass per unit area NSM (field 4).
    pub nsm: f64,
    /// Allowable interlaminar shear stress SB (field 5).
    pub sb: Option<f64>,
    /// Failure theory FT (field 6): HILL, HOFF, TSAI or STRN.
    pub ft: Option<String>,
    /// The plies as listed (before LAM = SYM mirrors them).
    pub plies: Vec<Ply>,
    /// LAM (field 9).
    pub lam: Lam,
    /// The card.
    pub at: CardRef,
}

impl Pcomp {
    /// The laminate's plies bottom to top, mirrored when LAM = SYM.
    pub fn stack(&self) -> Vec<Ply> {
        let mut s = self.plies.clone();
        if self.lam == Lam::Sym {
            s.extend(self.plies.iter().rev().cloned());
        }
        s
    }
}

/// CONM2: a concentrated mass at a grid.
#[derive(Debug, Clone)]
pub struct Conm2 {
    /// Element id (field 2).
    pub eid: i64,
    /// Grid G (field 3).
    pub g: i64,
    /// Mass M (field 5).
    pub mass: f64,
    /// I11, I21, I22, I31, I32, I33.
    pub inertia: [f64; 6],
    /// Coordinate system CID of the offset and inertia (0: basic; −1: the offset is
    /// the mass's basic location, not an offset).
    pub cid: i64,
    /// Offset (X1, X2, X3) of the mass from its grid, in CID (basic when CID = −1: its
    /// location).
    pub offset: [f64; 3],
    /// The card.
    pub at: CardRef,
}

/// SPC1: single-point constraints of a set of components on grids.
#[derive(Debug, Clone)]
pub struct Spc1 {
    /// Constraint set id (field 2).
    pub sid: i64,
    /// Constrained components C (field 3).
    pub c: Components,
    /// Constrained grids (fields 4 on, THRU ranges expanded).
    pub grids: Vec<i64>,
    /// An SPC's enforced value D when it is not zero, with where it is written.
    pub enforced: Option<(f64, FieldRef)>,
    /// The card.
    pub at: CardRef,
}

/// SPCADD: a constraint set that is the union of others.
#[derive(Debug, Clone)]
pub struct SpcAdd {
    /// Its set id (field 2).
    pub sid: i64,
    /// The sets it joins (fields 3 on).
    pub sets: Vec<i64>,
    /// The card.
    pub at: CardRef,
}

/// RBE2: a rigid element; the components CM of each dependent grid GMi follow the
/// independent grid GN's motion as a rigid body.
#[derive(Debug, Clone)]
pub struct Rbe2 {
    /// Element id (field 2).
    pub eid: i64,
    /// Independent grid GN (field 3).
    pub gn: i64,
    /// Dependent components CM (field 4).
    pub cm: Components,
    /// Dependent grids GM1, GM2, … (fields 5 on; THRU ranges allowed).
    pub gm: Vec<i64>,
    /// The card.
    pub at: CardRef,
}

/// RBE3: an interpolation element; the components REFC of the reference grid move as
/// the weighted least-squares rigid fit of the components Ci of its independent grids.
#[derive(Debug, Clone)]
pub struct Rbe3 {
    /// Element id (field 2).
    pub eid: i64,
    /// The reference (dependent) grid, REFGRID (field 4).
    pub refgrid: i64,
    /// Its dependent components, REFC (field 5).
    pub refc: Components,
    /// The weighted groups of independent grids: WTi, Ci, Gi,j.
    pub groups: Vec<Rbe3Group>,
    /// The card.
    pub at: CardRef,
}

/// One group of an RBE3: a weight, the components it applies to and its grids.
#[derive(Debug, Clone)]
pub struct Rbe3Group {
    /// Weight WTi.
    pub weight: f64,
    /// Components Ci, in each grid's displacement frame.
    pub c: Components,
    /// Grids Gi,1, Gi,2, …
    pub grids: Vec<i64>,
}

/// One term of a TF card's continuation: a coefficient polynomial on an input DOF.
#[derive(Debug, Clone)]
pub struct TfTerm {
    /// Input grid or scalar point.
    pub g: i64,
    /// Its component (0 for a scalar point).
    pub c: usize,
    /// A0, A1, A2: coefficients of 1, p, p².
    pub a: [f64; 3],
}

/// TF: a transfer function, B(p)·u_d + Σ A_i(p)·u_i = 0, defining a dependent DOF.
#[derive(Debug, Clone)]
pub struct Tf {
    /// Set id (field 2).
    pub sid: i64,
    /// Dependent grid or point GD (field 3).
    pub gd: i64,
    /// Its component CD (field 4; 0 for a scalar point).
    pub cd: usize,
    /// B0, B1, B2 (fields 5-7): coefficients of 1, p, p² on the dependent DOF.
    pub b: [f64; 3],
    /// The input terms (continuation lines).
    pub terms: Vec<TfTerm>,
    /// The card.
    pub at: CardRef,
}

/// TSTEP: time steps of a transient solution.
#[derive(Debug, Clone)]
pub struct Tstep {
    /// Set id (field 2).
    pub sid: i64,
    /// Number of steps N (field 3).
    pub n: usize,
    /// Time step DT (field 4).
    pub dt: f64,
    /// Output every NO-th step (field 5).
    pub every: usize,
    /// Where a second interval (N(2), on the continuation) is written: a run refuses
    /// it, a structure check reads past it.
    pub further: Option<FieldRef>,
    /// The card.
    pub at: CardRef,
}

/// NOLIN3: a nonlinear load P = S·x^A on DOF (GI, CI), x the displacement of (GJ, CJ) when positive.
#[derive(Debug, Clone)]
pub struct Nolin3 {
    /// Set id (field 2).
    pub sid: i64,
    /// Loaded grid or point GI (field 3).
    pub gi: i64,
    /// Its component CI (field 4).
    pub ci: usize,
    /// Scale factor S (field 5).
    pub s: f64,
    /// Driving grid or point GJ (field 6).
    pub gj: i64,
    /// Its component CJ (field 7).
    pub cj: usize,
    /// Exponent A (field 8).
    pub a: f64,
    /// The card.
    pub at: CardRef,
}

/// TIC: an initial condition on one DOF.
#[derive(Debug, Clone)]
pub struct Tic {
    /// Set id (field 2).
    pub sid: i64,
    /// Grid or point G (field 3).
    pub g: i64,
    /// Its component C (field 4).
    pub c: usize,
    /// Initial displacement U0 (field 5).
    pub u0: f64,
    /// Initial velocity V0 (field 6).
    pub v0: f64,
    /// The card.
    pub at: CardRef,
}

/// FORCE or MOMENT: a static load F·(N1, N2, N3) on a grid, its direction in system
/// CID (at the grid's location, for a cylindrical or spherical CID).
#[derive(Debug, Clone)]
pub struct PointLoad {
    /// Load set id (field 2).
    pub sid: i64,
    /// Grid G (field 3).
    pub g: i64,
    /// Coordinate system CID of the direction (field 4; 0 basic).
    pub cid: i64,
    /// F·(N1, N2, N3) (fields 5-8).
    pub vector: [f64; 3],
    /// A MOMENT (acting on the rotations), not a FORCE.
    pub moment: bool,
    /// The card.
    pub at: CardRef,
}

/// PLOAD4 on shells: a pressure over each element's face, P1..P4 at its corners
/// (blank P2-P4 take P1), along the element's normal or along CID's (N1, N2, N3).
#[derive(Debug, Clone)]
pub struct Pload4 {
    /// Load set id (field 2).
    pub sid: i64,
    /// The loaded elements (EID, or EID THRU EID2).
    pub eids: Vec<i64>,
    /// Pressures at the corners (P1-P4).
    pub p: [f64; 4],
    /// Direction system CID (continuation field 2).
    pub cid: i64,
    /// Direction (N1, N2, N3); `None`: the element's normal.
    pub direction: Option<[f64; 3]>,
    /// The card.
    pub at: CardRef,
}

/// GRAV: an acceleration A·(N1, N2, N3) in rectangular system CID, loading every
/// mass by M·a.
#[derive(Debug, Clone)]
pub struct Grav {
    /// Load set id (field 2).
    pub sid: i64,
    /// Coordinate system CID (field 3; 0 basic).
    pub cid: i64,
    /// A·(N1, N2, N3) (fields 4-7).
    pub vector: [f64; 3],
    /// The card.
    pub at: CardRef,
}

/// LOAD: the load set S·Σ Sᵢ·(set Lᵢ).
#[derive(Debug, Clone)]
pub struct LoadCombination {
    /// Its set id (field 2).
    pub sid: i64,
    /// Overall scale S (field 3).
    pub scale: f64,
    /// (Sᵢ, Lᵢ) pairs.
    pub terms: Vec<(f64, i64)>,
    /// The card.
    pub at: CardRef,
}

/// CELAS1-4 and CMASS1-4: a scalar spring or mass between two DOFs.
#[derive(Debug, Clone)]
pub struct ScalarCard {
    /// Element id (field 2).
    pub eid: i64,
    /// A spring (CELASi) rather than a mass (CMASSi).
    pub spring: bool,
    /// Its value: through its property (PELAS, PMASS) or on the card.
    pub value: ScalarValue,
    /// Its two terminals (point, component 0-6): a grid's component 1-6, a scalar
    /// point's 0; point 0 is ground.
    pub terminals: [(i64, usize); 2],
    /// Where G1 (S1) is written.
    pub first_at: FieldRef,
    /// The card.
    pub at: CardRef,
}

/// Where a scalar element's stiffness or mass is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScalarValue {
    /// A PELAS or PMASS id.
    Property(i64),
    /// K or M on the card (CELAS2, CELAS4, CMASS2, CMASS4).
    Value(f64),
}

/// PELAS (PID K GE S) or PMASS (PID M).
#[derive(Debug, Clone)]
pub struct ScalarProperty {
    /// Property id.
    pub pid: i64,
    /// K or M.
    pub value: f64,
    /// The card.
    pub at: CardRef,
}

/// All bulk data of a deck, typed.
#[derive(Debug, Clone, Default)]
pub struct Bulk {
    /// GRID cards.
    pub grids: Vec<Grid>,
    /// The GRDSET card, or its defaults.
    pub grdset: GrdSet,
    /// Coordinate systems (CORD1R/C/S, CORD2R/C/S), in deck order.
    pub cords: Vec<Cord>,
    /// EPOINT ids (extra points), each with its card.
    pub epoints: Vec<(i64, CardRef)>,
    /// SPOINT ids (scalar points), each with its card.
    pub spoints: Vec<(i64, CardRef)>,
    /// Element cards (CROD, CQUAD4, CTRIA3), in deck order.
    pub elements: Vec<Connection>,
    /// PROD cards.
    pub prods: Vec<Prod>,
    /// PBAR, PBARL, PBEAM and PBEAML cards.
    pub bar_properties: Vec<BarProperty>,
    /// PSHELL cards.
    pub pshells: Vec<Pshell>,
    /// COSMIC's plate properties (PQUAD1 ... PTRMEM) as the PSHELL they describe, by
    /// their card (COSMIC numbers each card's ids apart).
    pub cosmic_plates: Vec<(&'static str, Pshell)>,
    /// MAT1 cards.
    pub mat1s: Vec<Mat1>,
    /// MAT2 cards.
    pub mat2s: Vec<Mat2>,
    /// MAT8 cards.
    pub mat8s: Vec<Mat8>,
    /// PCOMP cards.
    pub pcomps: Vec<Pcomp>,
    /// CONM2 cards.
    pub conm2s: Vec<Conm2>,
    /// CELAS1-4 and CMASS1-4 cards.
    pub scalars: Vec<ScalarCard>,
    /// PELAS cards.
    pub pelas: Vec<ScalarProperty>,
    /// PMASS cards.
    pub pmass: Vec<ScalarProperty>,
    /// SPC1 cards, and each grid of an SPC card as one.
    pub spc1s: Vec<Spc1>,
    /// SPCADD cards.
    pub spcadds: Vec<SpcAdd>,
    /// RBE2 cards.
    pub rbe2s: Vec<Rbe2>,
    /// RBE3 cards.
    pub rbe3s: Vec<Rbe3>,
    /// TF cards.
    pub tfs: Vec<Tf>,
    /// TSTEP cards.
    pub tsteps: Vec<Tstep>,
    /// NOLIN3 cards.
    pub nolin3s: Vec<Nolin3>,
    /// TIC cards.
    pub tics: Vec<Tic>,
    /// FORCE and MOMENT cards.
    pub point_loads: Vec<PointLoad>,
    /// PLOAD4 cards.
    pub pload4s: Vec<Pload4>,
    /// GRAV cards.
    pub gravs: Vec<Grav>,
    /// LOAD cards.
    pub load_combinations: Vec<LoadCombination>,
    /// PARAM WTMASS when the deck sets it, with its card: every mass of the deck
    /// (densities, non-structural and concentrated masses) has been multiplied by it.
    pub wtmass: Option<(f64, CardRef)>,
    /// How fields that COSMIC and MSC read differently were read: the reading, and
    /// on how many cards.
    pub readings: std::collections::BTreeMap<&'static str, usize>,
}

/// Reads the fields of one raw card, recording every problem.
struct Reader<'a> {
    card: &'a RawCard,
    diags: &'a mut Diagnostics,
    /// What is left of [`super::Limits::max_listed_ids`].
    ids_left: &'a mut usize,
    ok: bool,
    /// Readings of dialect-dependent fields made on this card ([`Bulk::readings`]).
    readings: Vec<&'static str>,
}

impl<'a> Reader<'a> {
    fn new(card: &'a RawCard, diags: &'a mut Diagnostics, ids_left: &'a mut usize) -> Self {
        Reader {
            card,
            diags,
            ids_left,
            ok: true,
            readings: Vec::new(),
        }
    }

    /// Records how a field that COSMIC and MSC read differently was read.
    fn reading(&mut self, what: &'static str) {
        self.readings.push(what);
    }

    fn at(&self) -> CardRef {
        CardRef {
            name: self.card.name.clone(),
            pos: self.card.pos.clone(),
            source: self.card.source.clone(),
        }
    }

    fn text(&self, k: usize) -> &'a str {
        self.card.text(k)
    }

    /// Where data field `k` was written (the card's start when it is absent).
    fn field_ref(&self, k: usize, name: &'static str) -> FieldRef {
        let (pos, number) = match self.card.field(k) {
            Some(f) => (f.pos.clone(), f.number),
            None => (self.card.pos.clone(), k % 8 + 2),
        };
        FieldRef {
            pos,
            number,
            name,
            token: self.text(k).to_string(),
        }
    }

    fn fail(&mut self, k: usize, name: &str, message: impl Into<String>) {
        let (pos, number) = match self.card.field(k) {
            Some(f) => (f.pos.clone(), f.number),
            None => (self.card.pos.clone(), k % 8 + 2),
        };
        let mut d = Diagnostic::error(Some(pos), message)
            .card(&self.card.name)
            .field(number, name)
            .quote(&self.card.source);
        let t = self.text(k);
        if !t.is_empty() {
            d = d.token(t);
        }
        if let Some(r) = &self.card.replicated_at {
            d.message.push_str(&format!(" (card generated by replication at {r})"));
        }
        self.diags.push(d);
        self.ok = false;
    }

    fn warn(&mut self, k: usize, name: &str, message: impl Into<String>) {
        let (pos, number) = match self.card.field(k) {
            Some(f) => (f.pos.clone(), f.number),
            None => (self.card.pos.clone(), k % 8 + 2),
        };
        let mut d = Diagnostic::warning(Some(pos), message)
            .card(&self.card.name)
            .field(number, name)
            .quote(&self.card.source);
        let t = self.text(k);
        if !t.is_empty() {
            d = d.token(t);
        }
        self.diags.push(d);
    }

    fn int_opt(&mut self, k: usize, name: &str) -> Option<i64> {
        let t = self.text(k);
        if t.is_empty() {
            return None;
        }
        match parse_int(t) {
            Some(v) => Some(v),
            None => {
                self.fail(k, name, "is not an integer");
                None
            }
        }
    }

    fn int(&mut self, k: usize, name: &str) -> i64 {
        if self.text(k).is_empty() {
            self.fail(k, name, "is blank: an integer is required");
            return 0;
        }
        self.int_opt(k, name).unwrap_or(0)
    }

    /// A required identification number: a positive integer.
    fn id(&mut self, k: usize, name: &str) -> i64 {
        let v = self.int(k, name);
        if self.text(k).is_empty() || parse_int(self.text(k)).is_none() {
            return v;
        }
        if v <= 0 {
            self.fail(k, name, "must be a positive integer");
        }
        v
    }

    fn int_or(&mut self, k: usize, name: &str, default: i64) -> i64 {
        self.int_opt(k, name).unwrap_or(default)
    }

    fn real_opt(&mut self, k: usize, name: &str) -> Option<f64> {
        let t = self.text(k);
        if t.is_empty() {
            return None;
        }
        match parse_real(t) {
            Some(RealToken::Real(v)) if v != 0.0 && v.abs() < f64::MIN_POSITIVE => {
                self.fail(
                    k,
                    name,
                    "is subnormal (nonzero, below 2.2e-308 in magnitude): too small to compute with at full precision",
                );
                None
            }
            Some(RealToken::Real(v)) => Some(v),
            Some(RealToken::Integer(v)) => {
                self.warn(
                    k,
                    name,
                    "is an integer where NASTRAN expects a real (no decimal point); read as a real",
                );
                Some(v)
            }
            None => {
                self.fail(k, name, "is not a real number");
                None
            }
        }
    }

    fn real(&mut self, k: usize, name: &str) -> f64 {
        if self.text(k).is_empty() {
            self.fail(k, name, "is blank: a real number is required");
            return 0.0;
        }
        self.real_opt(k, name).unwrap_or(0.0)
    }

    fn real_or(&mut self, k: usize, name: &str, default: f64) -> f64 {
        self.real_opt(k, name).unwrap_or(default)
    }

    fn positive(&mut self, k: usize, name: &str, v: f64) {
        if self.text(k).is_empty() || parse_real(self.text(k)).is_none() {
            return;
        }
        if v <= 0.0 {
            self.fail(k, name, "must be positive");
        }
    }

    fn non_negative(&mut self, k: usize, name: &str, v: f64) {
        if v < 0.0 {
            self.fail(k, name, "must not be negative");
        }
    }

    /// Component list such as `123456`; blank gives the empty set.
    fn components(&mut self, k: usize, name: &str) -> Components {
        let t = self.text(k);
        let mut c = 0u8;
        for ch in t.chars() {
            match ch.to_digit(10) {
                Some(d @ 1..=6) if c & (1 << (d - 1)) == 0 => c |= 1 << (d - 1),
                Some(0) if t.len() == 1 => {}
                _ => {
                    self.fail(k, name, "is not a component list (distinct digits 1-6)");
                    return Components(0);
                }
            }
        }
        Components(c)
    }

    /// A single component: 0 or blank for a scalar point, 1-6 for a grid.
    fn component(&mut self, k: usize, name: &str) -> usize {
        let v = self.int_or(k, name, 0);
        if !(0..=6).contains(&v) {
            self.fail(k, name, "is not a component number (0-6)");
            return 0;
        }
        v as usize
    }

    /// Reads ids from field k on, with `THRU` ranges.
    fn id_list(&mut self, from: usize, name: &str) -> Vec<i64> {
        self.id_list_in(from, self.card.fields.len(), name)
    }

    /// Reads ids from field `from` up to (not including) field `n`, with `THRU` ranges.
    fn id_list_in(&mut self, from: usize, n: usize, name: &str) -> Vec<i64> {
        let mut out = Vec::new();
        let mut k = from;
        while k < n {
            let t = self.text(k);
            if t.is_empty() {
                k += 1;
                continue;
            }
            if t.eq_ignore_ascii_case("THRU") {
                let Some(&a) = out.last() else {
                    self.fail(k, name, "THRU has no start id before it");
                    return out;
                };
                let b = self.int(k + 1, name);
                if !self.ok {
                    return out;
                }
                if b < a {
                    self.fail(
                        k + 1,
                        name,
                        format!("ends a THRU range that is reversed ({a} THRU {b})"),
                    );
                    return out;
                }
                if let Err(e) = super::take_ids(self.ids_left, (b as i128 - a as i128) as u128) {
                    self.fail(k + 1, name, e);
                    return out;
                }
                out.extend(a + 1..=b);
                k += 2;
                continue;
            }
            let v = self.id(k, name);
            if self.ok {
                if let Err(e) = super::take_ids(self.ids_left, 1) {
                    self.fail(k, name, e);
                    return out;
                }
                out.push(v);
            }
            k += 1;
        }
        out
    }

    fn extra_fields(&mut self, max: usize) {
        for k in max..self.card.fields.len() {
            if !self.text(k).is_empty() {
                self.fail(
                    k,
                    "unused",
                    format!("{} has no field here; this value would be ignored", self.card.name),
                );
                return;
            }
        }
    }
}

/// Cards the reader knows. `PARAM` is accepted and ignored with a warning.
/// Element cards are those of [`crate::elements::KINDS`] besides these.
pub const KNOWN_CARDS: [&str; 66] = [
    "GRID", "GRDSET", "CORD1R", "CORD1C", "CORD1S", "CORD2R", "CORD2C", "CORD2S", "EPOINT", "SPOINT", "PROD", "PBAR",
    "PBARL", "PBEAM", "PBEAML", "PSHELL", "PCOMP", "MAT1", "MAT2", "MAT8", "CONM2", "RBE2", "RBE3", "SPC1", "SPC",
    "SPCADD", "TF", "TSTEP", "NOLIN3", "TIC", "FORCE", "MOMENT", "PLOAD4", "GRAV", "LOAD", "PARAM", "INCLUDE",
    "ENDDATA", "BAROR", "PTUBE", "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CMASS1", "CMASS2", "CMASS3", "CMASS4",
    "PELAS", "PMASS", "CQUAD1", "CQUAD2", "CQDMEM", "CQDMEM1", "CQDMEM2", "CTRIA1", "CTRIA2", "CTRMEM", "PQUAD1",
    "PTRIA1", "PQUAD2", "PTRIA2", "PQDMEM", "PQDMEM1", "PQDMEM2", "PTRMEM",
];

/// Every card the reader types: the element cards of [`crate::elements::KINDS`] and
/// [`KNOWN_CARDS`], in alphabetical order.
pub fn supported() -> Vec<&'static str> {
    let mut all: Vec<&'static str> = crate::elements::KINDS
        .iter()
        .map(|k| k.card)
        .chain(KNOWN_CARDS)
        .collect();
    all.sort_unstable();
    all
}

/// Types all raw cards. Unknown card names are collected and returned. `ids_left` is
/// what remains of [`super::Limits::max_listed_ids`].
pub fn type_cards(raw: &[RawCard], ids_left: &mut usize, diags: &mut Diagnostics) -> (Bulk, Vec<super::UnknownCard>) {
    let mut b = Bulk::default();
    let mut unknown = Vec::new();
    let mut barors = raw.iter().filter(|c| c.name == "BAROR");
    let baror = barors.next();
    for extra in barors {
        let first = baror.map(|c| c.pos.to_string()).unwrap_or_default();
        diags.push(
            Diagnostic::error(
                Some(extra.pos.clone()),
                format!("only one BAROR card may appear in the bulk data (the first is at {first})"),
            )
            .card("BAROR")
            .quote(&extra.source),
        );
    }
    for whole in raw {
        for piece in pieces(whole, baror) {
            let card: &RawCard = &piece;
            let mut r = Reader::new(card, diags, ids_left);
            match card.name.as_str() {
                "BAROR" => r.extra_fields(8),
                "GRID" => card_grid(&mut r, &mut b),
                "GRDSET" => card_grdset(&mut r, &mut b),
                "CORD1R" | "CORD1C" | "CORD1S" => card_cord1(&mut r, &mut b),
                "CORD2R" | "CORD2C" | "CORD2S" => card_cord2(&mut r, &mut b),
                "EPOINT" | "SPOINT" => card_points(&mut r, &mut b, card),
                "PROD" => card_prod(&mut r, &mut b),
                "PTUBE" => card_ptube(&mut r, &mut b),
                "CELAS1" | "CELAS2" | "CELAS3" | "CELAS4" | "CMASS1" | "CMASS2" | "CMASS3" | "CMASS4" => {
                    card_scalar(&mut r, &mut b)
                }
                "PELAS" | "PMASS" => card_scalar_property(&mut r, &mut b),
                "CQUAD1" | "CQUAD2" | "CQDMEM" | "CQDMEM1" | "CQDMEM2" | "CTRIA1" | "CTRIA2" | "CTRMEM" => {
                    card_cosmic_plate(&mut r, &mut b)
                }
                "PQUAD1" | "PTRIA1" | "PQUAD2" | "PTRIA2" | "PQDMEM" | "PQDMEM1" | "PQDMEM2" | "PTRMEM" => {
                    card_cosmic_plate_property(&mut r, &mut b)
                }
                "CONROD" => card_conrod(&mut r, &mut b),
                "PBAR" | "PBEAM" => card_pbar(&mut r, &mut b),
                "PBARL" | "PBEAML" => card_pbarl(&mut r, &mut b),
                "PSHELL" => card_pshell(&mut r, &mut b),
                "MAT1" => card_mat1(&mut r, &mut b),
                "MAT2" => card_mat2(&mut r, &mut b),
                "MAT8" => card_mat8(&mut r, &mut b),
                "PCOMP" => card_pcomp(&mut r, &mut b),
                "CONM2" => card_conm2(&mut r, &mut b),
                "SPC1" => card_spc1(&mut r, &mut b),
                "SPC" => card_spc(&mut r, &mut b),
                "SPCADD" => card_spcadd(&mut r, &mut b),
                "RBE2" => card_rbe2(&mut r, &mut b),
                "RBE3" => card_rbe3(&mut r, &mut b),
                "TF" => card_tf(&mut r, &mut b, card),
                "TSTEP" => card_tstep(&mut r, &mut b, card),
                "NOLIN3" => card_nolin3(&mut r, &mut b),
                "TIC" => card_tic(&mut r, &mut b),
                "FORCE" | "MOMENT" => card_point_load(&mut r, &mut b),
                "PLOAD4" => card_pload4(&mut r, &mut b),
                "GRAV" => card_grav(&mut r, &mut b),
                "LOAD" => card_load(&mut r, &mut b),
                "PARAM" => card_param(&mut r, &mut b, card),
                name => match crate::elements::kind(name) {
                    Some(kind) => card_element(&mut r, &mut b, kind),
                    None => unknown.push(super::UnknownCard {
                        name: card.name.clone(),
                        pos: card.pos.clone(),
                        line: card.source.lines().next().unwrap_or("").to_string(),
                    }),
                },
            }
            for what in r.readings {
                *b.readings.entry(what).or_default() += 1;
            }
        }
    }
    if let Some((w, _)) = &b.wtmass {
        let w = *w;
        b.scale_masses(w);
    }
    implicit_scalar_points(&mut b);
    (b, unknown)
}

/// Scalar points defined by their use: "a scalar point ... referenced on a scalar
/// connection card need not be defined on an SPOINT card" (BULK.TXT, SPOINT): a
/// scalar element's terminal of component 0 that no GRID, SPOINT or EPOINT defines.
fn implicit_scalar_points(b: &mut Bulk) {
    let known: std::collections::HashSet<i64> = b
        .grids
        .iter()
        .map(|g| g.id)
        .chain(b.spoints.iter().chain(&b.epoints).map(|(i, _)| *i))
        .collect();
    let mut added = std::collections::HashSet::new();
    for c in &b.scalars {
        for &(g, comp) in &c.terminals {
            if g > 0 && comp == 0 && !known.contains(&g) && added.insert(g) {
                b.spoints.push((g, c.at.clone()));
            }
        }
    }
}

/// Cards that define up to two elements or properties (fields 2-5 and 6-9; "one or
/// two ROD elements may be defined on a single card", COSMIC's CROD), or four (PMASS,
/// PDAMP: fields 2-3, 4-5, 6-7, 8-9): the fields of one.
fn per_card(name: &str) -> Option<usize> {
    match name {
        "CROD" | "CELAS3" | "CELAS4" | "CMASS3" | "CMASS4" | "CDAMP3" | "CDAMP4" | "PELAS" | "PQUAD2" | "PTRIA2"
        | "PQDMEM" | "PQDMEM1" | "PQDMEM2" | "PTRMEM" | "PSHEAR" => Some(4),
        "PMASS" | "PDAMP" => Some(2),
        _ => None,
    }
}

/// The cards one raw card stands for: one for each element or property written on a
/// card of several ([`per_card`]); a CBAR with its blank fields 3 and 6-9 taken from
/// BAROR ("the contents of fields on this card will be assumed for any CBAR card
/// whose corresponding fields are blank"); the card itself otherwise.
fn pieces<'a>(card: &'a RawCard, baror: Option<&RawCard>) -> Vec<std::borrow::Cow<'a, RawCard>> {
    use std::borrow::Cow;
    if let Some(w) = per_card(&card.name).filter(|&w| card.fields.len() > w) {
        let first_line = card.fields.len().min(8);
        let mut out: Vec<RawCard> = (0..first_line)
            .step_by(w)
            .filter(|&k| {
                card.fields[k..(k + w).min(first_line)]
                    .iter()
                    .any(|f| !f.text.is_empty())
            })
            .map(|k| RawCard {
                fields: card.fields[k..(k + w).min(first_line)].to_vec(),
                ..card.clone()
            })
            .collect();
        // Continuation fields, if any, go to the last for its reader to refuse.
        if let Some(last) = out.last_mut() {
            last.fields.extend(card.fields.iter().skip(8).cloned());
        }
        return out.into_iter().map(Cow::Owned).collect();
    }
    match baror {
        Some(d) if card.name == "CBAR" => {
            let mut c = card.clone();
            let g0_given =
                parse_int(card.text(7)) == Some(2) || parse_int(d.text(7)) == Some(2) && card.text(7).is_empty();
            for k in [1, 4, 5, 6, 7] {
                if g0_given && (k == 5 || k == 6) {
                    continue;
                }
                if c.text(k).is_empty() && !d.text(k).is_empty() {
                    while c.fields.len() <= k {
                        c.fields.push(super::bulk::Field {
                            text: String::new(),
                            pos: c.pos.clone(),
                            number: c.fields.len() % 8 + 2,
                        });
                    }
                    c.fields[k] = d.fields[k].clone();
                }
            }
            vec![Cow::Owned(c)]
        }
        _ => vec![Cow::Borrowed(card)],
    }
}

/// The vector F·(N1, N2, N3) of fields `k`.. (`k + 3`), named after the card's.
fn scaled_vector(r: &mut Reader, k: usize, names: [&str; 4]) -> [f64; 3] {
    let f = r.real_or(k, names[0], 0.0);
    let n = [
        r.real_or(k + 1, names[1], 0.0),
        r.real_or(k + 2, names[2], 0.0),
        r.real_or(k + 3, names[3], 0.0),
    ];
    if r.ok && f != 0.0 && n.iter().all(|&x| x == 0.0) {
        r.fail(
            k + 1,
            names[1],
            format!("{} has a magnitude but no direction (N1 = N2 = N3 = 0)", r.card.name),
        );
    }
    n.map(|x| f * x)
}

/// A coordinate system id field: blank or 0 is the basic system.
fn system_id(r: &mut Reader, k: usize) -> i64 {
    let cid = r.int_or(k, "CID", 0);
    if cid < 0 {
        r.fail(k, "CID", "must be 0 (basic) or a coordinate system id");
    }
    cid
}

/// FORCE and MOMENT: SID G CID F N1 N2 N3.
fn card_point_load(r: &mut Reader, b: &mut Bulk) {
    let l = PointLoad {
        sid: r.id(0, "SID"),
        g: r.id(1, "G"),
        cid: system_id(r, 2),
        vector: scaled_vector(
            r,
            3,
            if r.card.name == "FORCE" {
                ["F", "N1", "N2", "N3"]
            } else {
                ["M", "N1", "N2", "N3"]
            },
        ),
        moment: r.card.name == "MOMENT",
        at: r.at(),
    };
    r.extra_fields(7);
    if r.ok {
        b.point_loads.push(l);
    }
}

/// PLOAD4 on shells: SID EID P1 P2 P3 P4 (G1 G3 blank, or THRU EID2), then CID N1 N2
/// N3 (SORL blank or SURF; LDIR blank or NORM).
fn card_pload4(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let eid = r.id(1, "EID");
    let p1 = r.real(2, "P1");
    let p = [
        p1,
        r.real_or(3, "P2", p1),
        r.real_or(4, "P3", p1),
        r.real_or(5, "P4", p1),
    ];
    let mut eids = vec![eid];
    if r.text(6).eq_ignore_ascii_case("THRU") {
        let last = r.id(7, "EID2");
        if r.ok && last < eid {
            r.fail(
                7,
                "EID2",
                format!("ends a THRU range that is reversed ({eid} THRU {last})"),
            );
        }
        if r.ok {
            if let Err(e) = super::take_ids(r.ids_left, (last - eid) as u128) {
                r.fail(7, "EID2", e);
            } else {
                eids = (eid..=last).collect();
            }
        }
    } else {
        for (k, name) in [(6, "G1"), (7, "G3")] {
            if !r.text(k).is_empty() {
                r.fail(
                    k,
                    name,
                    "G1 and G3 name a face of a solid element; a shell's PLOAD4 leaves them blank",
                );
            }
        }
    }
    let cid = system_id(r, 8);
    let n = [
        r.real_or(9, "N1", 0.0),
        r.real_or(10, "N2", 0.0),
        r.real_or(11, "N3", 0.0),
    ];
    if cid != 0 && n.iter().all(|&x| x == 0.0) {
        r.fail(
            8,
            "CID",
            "a direction system is given but no direction (N1 = N2 = N3 = 0)",
        );
    }
    for (k, name, allowed) in [(12, "SORL", "SURF"), (13, "LDIR", "NORM")] {
        let t = r.text(k);
        if !t.is_empty() && !t.eq_ignore_ascii_case(allowed) {
            r.fail(
                k,
                name,
                format!("only {allowed} (a pressure on the shell's surface) is supported"),
            );
        }
    }
    r.extra_fields(14);
    let l = Pload4 {
        sid,
        eids,
        p,
        cid,
        direction: n.iter().any(|&x| x != 0.0).then_some(n),
        at: r.at(),
    };
    if r.ok {
        b.pload4s.push(l);
    }
}

/// GRAV: SID CID A N1 N2 N3 (MB blank or 0).
fn card_grav(r: &mut Reader, b: &mut Bulk) {
    let g = Grav {
        sid: r.id(0, "SID"),
        cid: system_id(r, 1),
        vector: scaled_vector(r, 2, ["A", "N1", "N2", "N3"]),
        at: r.at(),
    };
    if r.int_or(6, "MB", 0) != 0 {
        r.fail(6, "MB", "only MB = 0 (the main bulk data) is supported");
    }
    r.extra_fields(7);
    if r.ok {
        b.gravs.push(g);
    }
}

/// LOAD: SID S S1 L1 S2 L2 ….
fn card_load(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let scale = r.real(1, "S");
    let mut terms = Vec::new();
    let mut k = 2;
    while k < r.card.fields.len() {
        if r.text(k).is_empty() && r.text(k + 1).is_empty() {
            k += 2;
            continue;
        }
        let s = r.real(k, "Si");
        let l = r.id(k + 1, "Li");
        if r.ok && l == sid {
            r.fail(k + 1, "Li", format!("LOAD {sid} cannot include itself"));
        }
        terms.push((s, l));
        k += 2;
    }
    if r.ok && terms.is_empty() {
        r.fail(2, "S1", "LOAD combines no set");
    }
    let l = LoadCombination {
        sid,
        scale,
        terms,
        at: r.at(),
    };
    if r.ok {
        b.load_combinations.push(l);
    }
}

/// PARAM: not used by impactlab and ignored with a warning, except WTMASS other than
/// 1.0, which scales every mass of the deck and is refused (masses are taken as
/// written: multiply the densities and masses by it and remove the PARAM).
fn card_param(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
    if r.text(0).eq_ignore_ascii_case("WTMASS") {
        let w = r.real_or(1, "V1", 1.0);
        r.positive(1, "V1", w);
        if r.ok {
            b.wtmass = Some((w, r.at()));
        }
        return;
    }
    r.diags.push(
        Diagnostic::warning(Some(card.pos.clone()), "PARAM cards are not used by impactlab; ignored")
            .card("PARAM")
            .quote(&card.source),
    );
}

impl Bulk {
    /// Multiplies every term of the mass by PARAM WTMASS, as NASTRAN does ("the terms
    /// of the structural mass matrix are multiplied by the value of this parameter"):
    /// the materials' densities, the properties' non-structural masses and the
    /// concentrated masses and inertias.
    fn scale_masses(&mut self, w: f64) {
        for m in &mut self.mat1s {
            m.rho *= w;
        }
        for m in &mut self.mat2s {
            m.rho *= w;
        }
        for m in &mut self.mat8s {
            m.rho *= w;
        }
        for p in self
            .prods
            .iter_mut()
            .chain(self.elements.iter_mut().filter_map(|c| c.rod.as_mut()))
        {
            p.nsm *= w;
        }
        for p in &mut self.bar_properties {
            p.nsm *= w;
        }
        for p in self
            .pshells
            .iter_mut()
            .chain(self.cosmic_plates.iter_mut().map(|(_, p)| p))
        {
            p.nsm *= w;
        }
        for p in &mut self.pcomps {
            p.nsm *= w;
        }
        for p in &mut self.pmass {
            p.value *= w;
        }
        for c in self.scalars.iter_mut().filter(|c| !c.spring) {
            if let ScalarValue::Value(m) = &mut c.value {
                *m *= w;
            }
        }
        for c in &mut self.conm2s {
            c.mass *= w;
            for i in &mut c.inertia {
                *i *= w;
            }
        }
    }
}

/// GRID.
fn card_grid(r: &mut Reader, b: &mut Bulk) {
    let cp = r.int_opt(1, "CP");
    let cd = r.int_opt(5, "CD");
    for (k, name, v) in [(1, "CP", cp), (5, "CD", cd)] {
        if v.is_some_and(|v| v < 0) {
            r.fail(k, name, "must be 0 (basic) or a coordinate system id");
        }
    }
    let g = Grid {
        id: r.id(0, "ID"),
        cp,
        x: [
            r.real_or(2, "X1", 0.0),
            r.real_or(3, "X2", 0.0),
            r.real_or(4, "X3", 0.0),
        ],
        cd,
        cp_at: r.field_ref(1, "CP"),
        cd_at: r.field_ref(5, "CD"),
        ps: if r.text(6).is_empty() {
            None
        } else {
            Some(r.components(6, "PS"))
        },
        at: r.at(),
    };
    r.extra_fields(8);
    if r.ok {
        b.grids.push(g);
    }
}

/// GRDSET.
fn card_grdset(r: &mut Reader, b: &mut Bulk) {
    b.grdset = GrdSet {
        cp: r.int_or(1, "CP", 0),
        cd: r.int_or(5, "CD", 0),
        ps: r.components(6, "PS"),
        at: Some(r.at()),
    };
    for (k, name, v) in [(1, "CP", b.grdset.cp), (5, "CD", b.grdset.cd)] {
        if v < 0 {
            r.fail(k, name, "must be 0 (basic) or a coordinate system id");
        }
    }
    r.extra_fields(8);
}

/// The kind of a CORDnx card from its last letter.
fn coord_kind(name: &str) -> CoordKind {
    match name.as_bytes().last() {
        Some(b'C') => CoordKind::Cylindrical,
        Some(b'S') => CoordKind::Spherical,
        _ => CoordKind::Rectangular,
    }
}

/// CORD1R, CORD1C, CORD1S: CIDA G1A G2A G3A CIDB G1B G2B G3B, one or two systems,
/// each from three distinct grids.
fn card_cord1(r: &mut Reader, b: &mut Bulk) {
    let kind = coord_kind(&r.card.name);
    for (half, names) in [(0, ["CIDA", "G1A", "G2A", "G3A"]), (4, ["CIDB", "G1B", "G2B", "G3B"])] {
        if half == 4 && (4..8).all(|k| r.text(k).is_empty()) {
            break;
        }
        let cid = r.id(half, names[0]);
        let g = [1, 2, 3].map(|i| r.id(half + i, names[i]));
        if r.ok && (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) {
            r.fail(half + 1, names[1], "G1, G2 and G3 must be three distinct grids");
        }
        let g_at = [1, 2, 3].map(|i| r.field_ref(half + i, names[i]));
        if r.ok {
            b.cords.push(Cord {
                cid,
                kind,
                third_at: g_at[2].clone(),
                def: CordDef::Grids { g, g_at },
                at: r.at(),
            });
        }
    }
    r.extra_fields(8);
}

/// CORD2R, CORD2C, CORD2S: CID RID A1 A2 A3 B1 B2 B3 / C1 C2 C3.
fn card_cord2(r: &mut Reader, b: &mut Bulk) {
    let kind = coord_kind(&r.card.name);
    let cid = r.id(0, "CID");
    let rid = r.int_or(1, "RID", 0);
    if rid < 0 {
        r.fail(1, "RID", "must be 0 (basic) or a coordinate system id");
    }
    if r.ok && rid == cid {
        r.fail(1, "RID", format!("system {cid} cannot be defined in itself"));
    }
    const NAMES: [&str; 9] = ["A1", "A2", "A3", "B1", "B2", "B3", "C1", "C2", "C3"];
    let mut v = [0.0; 9];
    for (i, name) in NAMES.iter().enumerate() {
        // A1..B3 are fields 4-9 of the first line, C1..C3 fields 2-4 of the second.
        let k = if i < 6 { 2 + i } else { 8 + i - 6 };
        v[i] = r.real_or(k, name, 0.0);
    }
    r.extra_fields(11);
    let c = Cord {
        cid,
        kind,
        def: CordDef::Points {
            rid,
            rid_at: r.field_ref(1, "RID"),
            abc: [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]],
        },
        third_at: r.field_ref(8, "C1"),
        at: r.at(),
    };
    if r.ok {
        b.cords.push(c);
    }
}

/// EPOINT or SPOINT.
fn card_points(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
    let ids = r.id_list(0, "ID");
    if r.ok {
        let at = r.at();
        let list = if card.name == "EPOINT" {
            &mut b.epoints
        } else {
            &mut b.spoints
        };
        list.extend(ids.into_iter().map(|i| (i, at.clone())));
    }
}

/// An element card of the kinds' table: EID, PID (blank: EID), G1..Gn; a shell's
/// THETA/MCID after its grids (a real: THETA in degrees, an integer: MCID) and its
/// ZOFFS; a bar's orientation, offsets and pin flags ([`card_bar`]).
fn card_element(r: &mut Reader, b: &mut Bulk, kind: &'static crate::elements::Kind) {
    let n = kind.grids;
    let shell = matches!(kind.build, crate::elements::Build::Shell(_));
    let mut c = Connection {
        kind,
        eid: r.id(0, "EID"),
        pid: r.int_or(1, "PID", 0),
        g: (0..n).map(|k| r.id(2 + k, &format!("G{}", k + 1))).collect(),
        orientation: Orientation::Theta(0.0),
        orientation_at: shell.then(|| r.field_ref(2 + n, "THETA/MCID")),
        zoffs: 0.0,
        bar: None,
        rod: None,
        property_card: None,
        at: r.at(),
    };
    let pid = if r.text(1).is_empty() { c.eid } else { c.pid };
    if shell {
        let t = r.text(2 + n);
        c.orientation = match parse_real(t) {
            _ if t.is_empty() => Orientation::Theta(0.0),
            Some(RealToken::Integer(_)) => {
                let mcid = r.int(2 + n, "THETA/MCID");
                if mcid < 0 {
                    r.fail(2 + n, "THETA/MCID", "MCID must be 0 (basic) or a coordinate system id");
                }
                Orientation::Mcid(mcid)
            }
            _ => Orientation::Theta(r.real_or(2 + n, "THETA/MCID", 0.0)),
        };
        c.zoffs = r.real_or(3 + n, "ZOFFS", 0.0);
    }
    let mut gs = c.g.clone();
    gs.sort();
    gs.dedup();
    if gs.len() != n && r.ok {
        if n == 2 {
            r.fail(3, "G2", "is the same grid as G1");
        } else {
            r.fail(2, &format!("G1-G{n}"), "the corner grids must be distinct");
        }
    }
    if matches!(kind.build, crate::elements::Build::Bar(_)) {
        c.bar = Some(card_bar(r));
    } else if !shell {
        r.extra_fields(2 + n);
    }
    if r.ok {
        b.elements.push(Connection { pid, ..c });
    }
}

/// CBAR and CBEAM after their grids: X1/G0 X2 X3 OFFT, PA PB W1A W2A W3A W1B W2B
/// W3B (a CBEAM's SA, SB, its warping grids, must be blank). X1 an integer with X2,
/// X3 blank is G0. OFFT's letters say in which frame v, WA and WB are given: G (the
/// grid's displacement frame, GA's for v) or B (basic); O (element) is refused.
///
/// Field 9 of a CBAR is COSMIC's F flag where it holds an integer: "F = 1: X1 X2
/// X3; F = 2: G0" in field 6 (NASTRAN-95's BULK.TXT, CBAR), v and the offsets then in
/// the grids' displacement frames, as OFFT = GGG; MSC's OFFT where it holds letters.
fn card_bar(r: &mut Reader) -> BarCard {
    let orientation_at = r.field_ref(4, "X1/G0");
    let flag = parse_int(r.text(7)).filter(|_| r.card.name == "CBAR");
    if flag.is_some() {
        r.reading("CBAR field 9 read as COSMIC's F flag (1: X1, X2, X3; 2: G0 in field 6)");
    }
    let orientation = match (flag, parse_real(r.text(4))) {
        (Some(2), _) => BarOrientation::Grid(r.id(4, "G0")),
        (None, Some(RealToken::Integer(_))) if r.text(5).is_empty() && r.text(6).is_empty() => {
            BarOrientation::Grid(r.id(4, "G0"))
        }
        _ => {
            let v = [r.real(4, "X1"), r.real_or(5, "X2", 0.0), r.real_or(6, "X3", 0.0)];
            if r.ok && v.iter().all(|&x| x == 0.0) {
                r.fail(
                    4,
                    "X1",
                    "the orientation vector (X1, X2, X3) is zero: it gives no plane 1",
                );
            }
            BarOrientation::Vector(v)
        }
    };
    let offt = match (flag, r.text(7)) {
        (Some(1 | 2), _) | (None, "") => "GGG".to_string(),
        (Some(_), _) => {
            r.fail(
                7,
                "F",
                "is not an orientation flag: F is 1 (X1, X2, X3) or 2 (G0 in field 6)",
            );
            "GGG".to_string()
        }
        (None, t) => t.to_ascii_uppercase(),
    };
    let letters: Vec<char> = offt.chars().collect();
    let valid = letters.len() == 3 && letters.iter().all(|&c| c == 'G' || c == 'B' || c == 'O');
    if !valid || letters[0] == 'O' {
        r.fail(
            7,
            "OFFT",
            "is not an offset type: three letters, the first G or B (the orientation vector), the others \
             G, B or O (the offsets); or COSMIC's F flag, 1 or 2",
        );
    } else if letters[1..].contains(&'O') {
        r.fail(
            7,
            "OFFT",
            "offsets in the element's own system (O) are not supported: give WA and WB in the grids' \
             displacement frames (G) or the basic system (B)",
        );
    }
    let basic = |k: usize| letters.get(k) == Some(&'B');
    let released = [r.components(8, "PA"), r.components(9, "PB")];
    let w = |r: &mut Reader, k: usize, names: [&str; 3]| -> [f64; 3] {
        std::array::from_fn(|i| r.real_or(k + i, names[i], 0.0))
    };
    let offsets = [w(r, 10, ["W1A", "W2A", "W3A"]), w(r, 13, ["W1B", "W2B", "W3B"])];
    if r.card.name == "CBEAM" {
        for (k, name) in [(16, "SA"), (17, "SB")] {
            if !r.text(k).is_empty() {
                r.fail(
                    k,
                    name,
                    "warping scalar points are not supported: the beam has no warping DOF; leave SA, SB blank",
                );
            }
        }
        r.extra_fields(18);
    } else {
        r.extra_fields(16);
    }
    BarCard {
        orientation,
        orientation_basic: basic(0),
        offsets_basic: [basic(1), basic(2)],
        released,
        offsets,
        orientation_at,
    }
}

/// Stress recovery points C1 C2 D1 D2 E1 E2 F1 F2 of PBAR and PBEAM, from field `k`.
fn recovery_points(r: &mut Reader, k: usize) -> [[f64; 2]; 4] {
    const NAMES: [&str; 8] = ["C1", "C2", "D1", "D2", "E1", "E2", "F1", "F2"];
    std::array::from_fn(|p| std::array::from_fn(|i| r.real_or(k + 2 * p + i, NAMES[2 * p + i], 0.0)))
}

/// PBAR (PID MID A I1 I2 J NSM; C1..F2; K1 K2 I12) and a constant PBEAM (PID MID A
/// I1 I2 I12 J NSM; C1..F2). K1, K2 (shear flexibility) and a PBEAM's further
/// stations are refused: the element is Euler-Bernoulli and of one section.
fn card_pbar(r: &mut Reader, b: &mut Bulk) {
    let beam = r.card.name == "PBEAM";
    let (pid, mid, a) = (r.id(0, "PID"), r.id(1, "MID"), r.real(2, "A"));
    let (i1, i2) = (r.real_or(3, "I1", 0.0), r.real_or(4, "I2", 0.0));
    let (i12, j, nsm) = if beam {
        (
            r.real_or(5, "I12", 0.0),
            r.real_or(6, "J", 0.0),
            r.real_or(7, "NSM", 0.0),
        )
    } else {
        (
            r.real_or(18, "I12", 0.0),
            r.real_or(5, "J", 0.0),
            r.real_or(6, "NSM", 0.0),
        )
    };
    let points = recovery_points(r, 8);
    r.positive(2, "A", a);
    r.non_negative(3, "I1", i1);
    r.non_negative(4, "I2", i2);
    r.non_negative(if beam { 6 } else { 5 }, "J", j);
    if r.ok && i1 * i2 < i12 * i12 {
        r.fail(
            if beam { 5 } else { 18 },
            "I12",
            format!(
                "I1·I2 = {:e} is below I12² = {:e}: no section has these moments",
                i1 * i2,
                i12 * i12
            ),
        );
    }
    if beam {
        if let Some(k) = (16..r.card.fields.len()).find(|&k| !r.text(k).is_empty()) {
            r.fail(
                k,
                "SO",
                "a PBEAM of more than one station (tapered), or with shear factors K1/K2, warping or \
                 non-structural mass offsets, is not supported: give one constant section (its first two \
                 lines) or a PBEAML",
            );
        }
    } else {
        for (k, name) in [(16, "K1"), (17, "K2")] {
            if !r.text(k).is_empty() {
                r.fail(
                    k,
                    name,
                    "shear flexibility is not supported: the bar is Euler-Bernoulli; leave K1, K2 blank",
                );
            }
        }
        r.extra_fields(19);
    }
    let p = BarProperty {
        pid,
        mid,
        dims: BarDims::Constants(crate::elements::section::Constants {
            area: a,
            i1,
            i2,
            i12,
            j,
            points,
        }),
        nsm,
        at: r.at(),
    };
    if r.ok {
        b.bar_properties.push(p);
    }
}

/// PBARL (PID MID GROUP TYPE; DIM1 … DIMn NSM) and a constant PBEAML (the same, with
/// an end B, if written, of the same dimensions: SO X/XB DIM1 … NSM).
fn card_pbarl(r: &mut Reader, b: &mut Bulk) {
    use crate::elements::section::Shape;
    let (pid, mid) = (r.id(0, "PID"), r.id(1, "MID"));
    let group = r.text(2);
    if !group.is_empty() && !group.eq_ignore_ascii_case("MSCBML0") {
        r.fail(
            2,
            "GROUP",
            "only the standard section library (GROUP blank or MSCBML0) is supported",
        );
    }
    let shape = Shape::named(r.text(3));
    if shape.is_none() {
        let list: Vec<&str> = Shape::ALL.iter().map(|s| s.1).collect();
        r.fail(
            3,
            "TYPE",
            format!("is not a supported section type: {}", list.join(", ")),
        );
    }
    for k in 4..8 {
        if !r.text(k).is_empty() {
            r.fail(
                k,
                "unused",
                format!("{} has no field here; this value would be ignored", r.card.name),
            );
        }
    }
    let Some(shape) = shape else { return };
    let n = shape.dims();
    let names: Vec<String> = (1..=n).map(|i| format!("DIM{i}")).collect();
    let dims: Vec<f64> = (0..n).map(|i| r.real(8 + i, &names[i])).collect();
    let nsm = r.real_or(8 + n, "NSM", 0.0);
    let mut last = 9 + n;
    if r.card.name == "PBEAML" && !r.text(last).is_empty() {
        // End B: SO X/XB DIM1 … DIMn NSM, the same section.
        let xb = r.real_or(last + 1, "X/XB", 1.0);
        let end_b: Vec<f64> = (0..n).map(|i| r.real(last + 2 + i, &names[i])).collect();
        let nsm_b = r.real_or(last + 2 + n, "NSM", nsm);
        if r.ok && (xb != 1.0 || end_b != dims || nsm_b != nsm) {
            r.fail(
                last,
                "SO",
                "a tapered PBEAML (stations of other dimensions) is not supported: give one section",
            );
        }
        last += 3 + n;
    }
    r.extra_fields(last);
    if let (true, Err(e)) = (r.ok, crate::elements::section::constants(shape, &dims)) {
        r.fail(8, "DIM1", format!("{} {}: {}", r.card.name, shape.name(), e.0));
    }
    let p = BarProperty {
        pid,
        mid,
        dims: BarDims::Shape(shape, dims),
        nsm,
        at: r.at(),
    };
    if r.ok {
        b.bar_properties.push(p);
    }
}

/// PROD.
fn card_prod(r: &mut Reader, b: &mut Bulk) {
    let p = Prod {
        pid: r.id(0, "PID"),
        mid: r.id(1, "MID"),
        a: r.real(2, "A"),
        j: r.real_or(3, "J", 0.0),
        nsm: r.real_or(5, "NSM", 0.0),
        at: r.at(),
    };
    r.real_opt(4, "C");
    r.positive(2, "A", p.a);
    r.non_negative(3, "J", p.j);
    r.extra_fields(6);
    if r.ok {
        b.prods.push(p);
    }
}

/// PTUBE: PID MID OD T NSM (OD2): a tube's area and torsional constant,
/// A = π/4 (OD² − ID²), J = π/32 (OD⁴ − ID⁴), ID = OD − 2T; "if T is zero, a solid
/// circular rod is assumed". A tapered tube (OD2 ≠ OD) is refused.
fn card_ptube(r: &mut Reader, b: &mut Bulk) {
    let (pid, mid, od) = (r.id(0, "PID"), r.id(1, "MID"), r.real(2, "OD"));
    let t = r.real_or(3, "T", 0.0);
    let nsm = r.real_or(4, "NSM", 0.0);
    r.positive(2, "OD", od);
    r.non_negative(3, "T", t);
    if r.ok && 2.0 * t > od {
        r.fail(3, "T", format!("is more than half the outside diameter (OD = {od:e})"));
    }
    if let Some(od2) = r.real_opt(5, "OD2") {
        if od2 != od {
            r.fail(
                5,
                "OD2",
                "a tapered tube is not supported: OD2 must be blank or equal to OD",
            );
        }
    }
    r.extra_fields(6);
    let id = if t == 0.0 { 0.0 } else { od - 2.0 * t };
    let p = Prod {
        pid,
        mid,
        a: std::f64::consts::PI / 4.0 * (od * od - id * id),
        j: std::f64::consts::PI / 32.0 * (od.powi(4) - id.powi(4)),
        nsm,
        at: r.at(),
    };
    if r.ok {
        b.prods.push(p);
    }
}

/// CELAS1 (EID PID G1 C1 G2 C2), CELAS2 (EID K G1 C1 G2 C2 GE S), CELAS3 (EID PID
/// S1 S2), CELAS4 (EID K S1 S2), and CMASS1-4 alike with M: "scalar points may be
/// used for G1 and/or G2, in which case the corresponding C1 and/or C2 must be zero
/// or blank. Zero or blank may be used to indicate a grounded terminal".
fn card_scalar(r: &mut Reader, b: &mut Bulk) {
    let name = r.card.name.as_str();
    let spring = name.starts_with("CELAS");
    let n = name.as_bytes()[name.len() - 1] - b'0';
    let eid = r.id(0, "EID");
    let value = if n % 2 == 1 {
        ScalarValue::Property(r.int_or(1, "PID", eid))
    } else {
        ScalarValue::Value(r.real(1, if spring { "K" } else { "M" }))
    };
    let terminals = if n <= 2 {
        [
            (r.int_or(2, "G1", 0), r.component(3, "C1")),
            (r.int_or(4, "G2", 0), r.component(5, "C2")),
        ]
    } else {
        [(r.int_or(2, "S1", 0), 0), (r.int_or(3, "S2", 0), 0)]
    };
    let first_at = r.field_ref(2, if n <= 2 { "G1" } else { "S1" });
    for (k, (g, _)) in terminals.iter().enumerate() {
        if *g < 0 {
            let f = if n <= 2 { 2 + 2 * k } else { 2 + k };
            r.fail(f, "G", "must be a point id, or 0 or blank for ground");
        }
    }
    if r.ok && terminals[0].0 == 0 && terminals[1].0 == 0 {
        r.fail(2, "G1", "both terminals are ground: the element connects nothing");
    }
    if r.ok && terminals[0] == terminals[1] {
        r.fail(4, "G2", "the two connection points must be distinct");
    }
    if n == 2 && spring {
        if r.real_or(6, "GE", 0.0) != 0.0 {
            r.warn(
                6,
                "GE",
                "structural damping is not applied: impactlab's structure is undamped",
            );
        }
        r.real_opt(7, "S");
        r.extra_fields(8);
    } else {
        r.extra_fields(if n <= 2 { 6 } else { 4 });
    }
    if r.ok {
        b.scalars.push(ScalarCard {
            eid,
            spring,
            value,
            terminals,
            first_at,
            at: r.at(),
        });
    }
}

/// PELAS (PID K GE S) and PMASS (PID M).
fn card_scalar_property(r: &mut Reader, b: &mut Bulk) {
    let spring = r.card.name == "PELAS";
    let p = ScalarProperty {
        pid: r.id(0, "PID"),
        value: r.real(1, if spring { "K" } else { "M" }),
        at: r.at(),
    };
    if spring {
        if r.real_or(2, "GE", 0.0) != 0.0 {
            r.warn(
                2,
                "GE",
                "structural damping is not applied: impactlab's structure is undamped",
            );
        }
        r.real_opt(3, "S");
        r.extra_fields(4);
        if r.ok {
            b.pelas.push(p);
        }
    } else {
        r.extra_fields(2);
        if r.ok {
            b.pmass.push(p);
        }
    }
}

/// COSMIC's plates, EID PID G1 G2 G3 (G4) THETA, read as impactlab's CQUAD4 and
/// CTRIA3 of the same property: QUAD1, TRIA1 (membrane, bending and transverse shear
/// of their PQUAD1, PTRIA1), QUAD2, TRIA2 (homogeneous thin plates) and QDMEM,
/// QDMEM1, QDMEM2, TRMEM (membranes). The structure is the deck's; the element is
/// impactlab's (NASTRAN-95's are other formulations), and `check` says so.
fn card_cosmic_plate(r: &mut Reader, b: &mut Bulk) {
    let quad = r.card.name.starts_with("CQ");
    let (own, reading) = if quad {
        (
            "CQUAD4",
            "COSMIC's CQUAD1, CQUAD2, CQDMEM, CQDMEM1, CQDMEM2 read as impactlab's CQUAD4 (another formulation)",
        )
    } else {
        (
            "CTRIA3",
            "COSMIC's CTRIA1, CTRIA2, CTRMEM read as impactlab's CTRIA3 (another formulation)",
        )
    };
    r.reading(reading);
    let kind = crate::elements::kind(own).expect("a shell kind");
    let property = match r.card.name.as_str() {
        "CQUAD1" => "PQUAD1",
        "CQUAD2" => "PQUAD2",
        "CQDMEM" => "PQDMEM",
        "CQDMEM1" => "PQDMEM1",
        "CQDMEM2" => "PQDMEM2",
        "CTRIA1" => "PTRIA1",
        "CTRIA2" => "PTRIA2",
        _ => "PTRMEM",
    };
    let n = b.elements.len();
    card_element(r, b, kind);
    if let Some(c) = b.elements.get_mut(n) {
        c.property_card = Some(property);
    }
}

/// COSMIC's plate properties as the PSHELL they are: PQUAD1, PTRIA1 (PID MID1 T1 MID2
/// I MID3 T3 NSM: MID1, T = T1, MID2, 12I/T³ = 12 I/T1³, MID3, TS/T = T3/T1, NSM);
/// PQUAD2, PTRIA2 (PID MID T NSM: MID1 = MID2 = MID, 12I/T³ = 1); PQDMEM, PQDMEM1,
/// PQDMEM2, PTRMEM (PID MID T NSM: a membrane, MID1 = MID).
fn card_cosmic_plate_property(r: &mut Reader, b: &mut Bulk) {
    let name = r.card.name.clone();
    let pid = r.id(0, "PID");
    let p = if name.ends_with('1') && !name.starts_with("PQDMEM") {
        let mid1 = r.int_opt(1, "MID1");
        // A plate of bending alone may leave T1 blank: its bending thickness is then
        // (12 I)^(1/3), which gives the plate its D = E I.
        let t = match (mid1, r.real_opt(2, "T1")) {
            (_, Some(t)) => t,
            (None, None) => {
                let t = (12.0 * r.real_or(4, "I", 0.0)).cbrt();
                r.warn(
                    2,
                    "T1",
                    format!(
                        "is blank (no membrane): the plate bends as one of thickness (12 I)^(1/3) = {t:e}, which \
                         also carries MID2's density (NASTRAN-95 gives such a plate the NSM alone)"
                    ),
                );
                t
            }
            (Some(_), None) => r.real(2, "T1"),
        };
        let mid2 = r.int_opt(3, "MID2");
        let i = r.real_or(4, "I", 0.0);
        let mid3 = r.int_opt(5, "MID3");
        let t3 = r.real_or(6, "T3", 0.0);
        let nsm = r.real_or(7, "NSM", 0.0);
        for (k, name) in [(8, "Z1"), (9, "Z2")] {
            r.real_opt(k, name);
        }
        r.extra_fields(10);
        if !r.text(2).is_empty() {
            r.positive(2, "T1", t);
        }
        if mid2.is_some() {
            r.positive(4, "I", i);
        }
        if mid3.is_some() {
            r.positive(6, "T3", t3);
        }
        Pshell {
            pid,
            mid1,
            t,
            mid2,
            bend_ratio: if t > 0.0 { 12.0 * i / t.powi(3) } else { 1.0 },
            mid3,
            ts_t: if t > 0.0 && t3 > 0.0 { t3 / t } else { 0.833333 },
            mid4: None,
            nsm,
            at: r.at(),
        }
    } else {
        let membrane = name.contains("MEM");
        let mid = r.id(1, "MID");
        let t = r.real(2, "T");
        let nsm = r.real_or(3, "NSM", 0.0);
        r.positive(2, "T", t);
        r.extra_fields(4);
        Pshell {
            pid,
            mid1: Some(mid),
            t,
            mid2: (!membrane).then_some(mid),
            bend_ratio: 1.0,
            mid3: None,
            ts_t: 0.833333,
            mid4: None,
            nsm,
            at: r.at(),
        }
    };
    r.reading("COSMIC's plate properties (PQUAD1, PQUAD2, PQDMEM, PTRIA1, ...) read as the PSHELL they describe");
    if r.ok {
        let card = super::case::static_name(&name, &COSMIC_PLATE_PROPERTIES);
        b.cosmic_plates.push((card, p));
    }
}

/// COSMIC's plate property cards.
const COSMIC_PLATE_PROPERTIES: [&str; 8] = [
    "PQUAD1", "PTRIA1", "PQUAD2", "PTRIA2", "PQDMEM", "PQDMEM1", "PQDMEM2", "PTRMEM",
];

/// CONROD: EID G1 G2 MID A J C NSM, a rod with its property on its card.
fn card_conrod(r: &mut Reader, b: &mut Bulk) {
    let kind = crate::elements::kind("CONROD").expect("CONROD is an element kind");
    let eid = r.id(0, "EID");
    let g = vec![r.id(1, "G1"), r.id(2, "G2")];
    let p = Prod {
        pid: eid,
        mid: r.id(3, "MID"),
        a: r.real(4, "A"),
        j: r.real_or(5, "J", 0.0),
        nsm: r.real_or(7, "NSM", 0.0),
        at: r.at(),
    };
    r.real_opt(6, "C");
    r.positive(4, "A", p.a);
    r.non_negative(5, "J", p.j);
    if r.ok && g[0] == g[1] {
        r.fail(2, "G2", "is the same grid as G1");
    }
    r.extra_fields(8);
    if r.ok {
        b.elements.push(Connection {
            kind,
            eid,
            pid: eid,
            g,
            orientation: Orientation::Theta(0.0),
            orientation_at: None,
            zoffs: 0.0,
            bar: None,
            rod: Some(p),
            property_card: None,
            at: r.at(),
        });
    }
}

/// PSHELL.
fn card_pshell(r: &mut Reader, b: &mut Bulk) {
    let p = Pshell {
        pid: r.id(0, "PID"),
        mid1: r.int_opt(1, "MID1"),
        t: r.real(2, "T"),
        mid2: r.int_opt(3, "MID2"),
        bend_ratio: r.real_or(4, "12I/T**3", 1.0),
        mid3: r.int_opt(5, "MID3"),
        ts_t: r.real_or(6, "TS/T", 0.833333),
        mid4: r.int_opt(10, "MID4"),
        nsm: r.real_or(7, "NSM", 0.0),
        at: r.at(),
    };
    r.positive(2, "T", p.t);
    r.positive(6, "TS/T", p.ts_t);
    if p.mid3.is_some() && p.mid2.is_none() && r.ok {
        r.fail(5, "MID3", "a transverse shear material needs a bending material (MID2)");
    }
    r.positive(4, "12I/T**3", p.bend_ratio);
    if r.ok {
        b.pshells.push(p);
    }
}

/// MAT1.
fn card_mat1(r: &mut Reader, b: &mut Bulk) {
    let e = r.real_opt(1, "E");
    let g = r.real_opt(2, "G");
    let nu = r.real_opt(3, "NU");
    let rho = r.real_or(4, "RHO", 0.0);
    let (e, g, nu) = match (e, g, nu) {
        (Some(e), Some(g), Some(nu)) => (e, g, nu),
        (Some(e), None, Some(nu)) => (e, e / (2.0 * (1.0 + nu)), nu),
        (Some(e), Some(g), None) => (e, g, e / (2.0 * g) - 1.0),
        (None, Some(g), Some(nu)) => (2.0 * g * (1.0 + nu), g, nu),
        (Some(e), None, None) => (e, 0.0, 0.0),
        _ => {
            if r.ok {
                r.fail(1, "E", "MAT1 needs E, or two of E, G and NU");
            }
            (0.0, 0.0, 0.0)
        }
    };
    if r.ok {
        if e <= 0.0 {
            r.fail(1, "E", format!("Young's modulus must be positive (E = {e})"));
        }
        if !(-1.0..0.5).contains(&nu) {
            r.fail(3, "NU", format!("Poisson's ratio must lie in (-1, 0.5) (NU = {nu})"));
        }
        r.non_negative(4, "RHO", rho);
    }
    let m = Mat1 {
        mid: r.id(0, "MID"),
        e,
        g,
        nu,
        rho,
        at: r.at(),
    };
    if r.ok {
        b.mat1s.push(m);
    }
}

/// MAT2.
fn card_mat2(r: &mut Reader, b: &mut Bulk) {
    let v: Vec<f64> = (1..=6)
        .map(|k| r.real_or(k, ["", "G11", "G12", "G13", "G22", "G23", "G33"][k], 0.0))
        .collect();
    let rho = r.real_or(7, "RHO", 0.0);
    r.non_negative(7, "RHO", rho);
    for (k, name) in [
        (8, "A1"),
        (9, "A2"),
        (10, "A3"),
        (11, "TREF"),
        (12, "GE"),
        (13, "ST"),
        (14, "SC"),
        (15, "SS"),
    ] {
        r.real_opt(k, name);
    }
    let g = [[v[0], v[1], v[2]], [v[1], v[3], v[4]], [v[2], v[4], v[5]]];
    let m = Mat2 {
        mid: r.id(0, "MID"),
        g,
        rho,
        at: r.at(),
    };
    if r.ok {
        b.mat2s.push(m);
    }
}

/// MAT8: MID E1 E2 NU12 G12 G1Z G2Z RHO / A1 A2 TREF Xt Xc Yt Yc S / GE F12 STRN.
/// E1, E2 and G12 are required and positive, NU12 must leave the ply's compliance
/// positive definite (NU12² < E1/E2); the allowables, when given, are positive (Xc
/// and Yc as magnitudes, as NASTRAN takes them); a blank Xc is Xt and a blank Yc is
/// Yt (NASTRAN's defaults), with a warning.
fn card_mat8(r: &mut Reader, b: &mut Bulk) {
    let mid = r.id(0, "MID");
    let e1 = r.real(1, "E1");
    let e2 = r.real(2, "E2");
    let nu12 = r.real_or(3, "NU12", 0.0);
    let g12 = r.real(4, "G12");
    let g1z = r.real_opt(5, "G1Z");
    let g2z = r.real_opt(6, "G2Z");
    let rho = r.real_or(7, "RHO", 0.0);
    for (k, name, v) in [(1, "E1", e1), (2, "E2", e2), (4, "G12", g12)] {
        r.positive(k, name, v);
    }
    if let Some(v) = g1z {
        r.positive(5, "G1Z", v);
    }
    if let Some(v) = g2z {
        r.positive(6, "G2Z", v);
    }
    r.non_negative(7, "RHO", rho);
    if r.ok && nu12 * nu12 >= e1 / e2 {
        r.fail(
            3,
            "NU12",
            format!(
                "NU12² = {:e} must be below E1/E2 = {:e}: the ply's stiffness would not be positive definite",
                nu12 * nu12,
                e1 / e2
            ),
        );
    }
    for (k, name) in [(8, "A1"), (9, "A2"), (10, "TREF"), (16, "GE")] {
        r.real_opt(k, name);
    }
    let names = ["Xt", "Xc", "Yt", "Yc", "S"];
    // Xc and Yc are magnitudes; NASTRAN-95 writes them "Real" of either sign (MAT8).
    let mut allowables: [Option<f64>; 5] = std::array::from_fn(|i| {
        let v = r.real_opt(11 + i, names[i]);
        match v {
            Some(v) if (i == 1 || i == 3) && v < 0.0 => Some(-v),
            Some(v) => {
                r.positive(11 + i, names[i], v);
                Some(v)
            }
            None => None,
        }
    });
    // A blank compressive allowable is the tensile one, as NASTRAN takes it.
    for (c, t) in [(1, 0), (3, 2)] {
        if let (None, Some(tension)) = (allowables[c], allowables[t]) {
            allowables[c] = Some(tension);
            r.warn(
                11 + c,
                names[c],
                format!(
                    "is blank: {} = {} = {tension:e}, as NASTRAN takes it",
                    names[c], names[t]
                ),
            );
        }
    }
    let f12 = r.real_opt(17, "F12");
    let strn = r.real_or(18, "STRN", 0.0);
    if strn != 0.0 && strn != 1.0 {
        r.fail(
            18,
            "STRN",
            "must be blank, 0.0 (stress allowables) or 1.0 (strain allowables)",
        );
    }
    r.extra_fields(19);
    let m = Mat8 {
        mid,
        e1,
        e2,
        nu12,
        g12,
        g1z,
        g2z,
        rho,
        allowables,
        f12,
        strn,
        at: r.at(),
    };
    if r.ok {
        b.mat8s.push(m);
    }
}

/// PCOMP: PID Z0 NSM SB FT TREF GE LAM / then per ply MID T THETA SOUT, four plies a
/// line. A ply exists when any of its four fields is given; a blank MID or T repeats
/// the ply above (the first ply needs both), a blank THETA is 0.0, a blank SOUT is NO.
/// LAM is blank or SYM (the plies listed are then the bottom half).
fn card_pcomp(r: &mut Reader, b: &mut Bulk) {
    let pid = r.id(0, "PID");
    let z0 = r.real_opt(1, "Z0");
    let nsm = r.real_or(2, "NSM", 0.0);
    let sb = r.real_opt(3, "SB");
    if let Some(v) = sb {
        r.positive(3, "SB", v);
    }
    let ft = match r.text(4).to_ascii_uppercase().as_str() {
        "" => None,
        f @ ("HILL" | "HOFF" | "TSAI" | "STRN") => Some(f.to_string()),
        _ => {
            r.fail(4, "FT", "must be HILL, HOFF, TSAI or STRN (or blank)");
            None
        }
    };
    r.real_opt(5, "TREF");
    r.real_opt(6, "GE");
    let lam = match r.text(7).to_ascii_uppercase().as_str() {
        "" => Lam::All,
        "SYM" => Lam::Sym,
        other => {
            r.fail(
                7,
                "LAM",
                format!("LAM = {other} is not supported: leave it blank (every ply listed) or SYM"),
            );
            Lam::All
        }
    };
    let mut plies: Vec<Ply> = Vec::new();
    let groups = r.card.fields.len().saturating_sub(8).div_ceil(4);
    for i in 0..groups {
        let k = 8 + 4 * i;
        let n = i + 1;
        if (k..k + 4).all(|j| r.text(j).is_empty()) {
            continue;
        }
        let (mid_name, t_name, theta_name, sout_name) = (
            format!("MID{n}"),
            format!("T{n}"),
            format!("THETA{n}"),
            format!("SOUT{n}"),
        );
        let above = plies.last().cloned();
        let mid = match (r.int_opt(k, &mid_name), &above) {
            (Some(m), _) => m,
            (None, Some(p)) => p.mid,
            (None, None) => {
                r.fail(k, &mid_name, "is blank: the first ply needs a material");
                0
            }
        };
        if !r.text(k).is_empty() && mid <= 0 && r.ok {
            r.fail(k, &mid_name, "must be a positive integer");
        }
        let t = match (r.real_opt(k + 1, &t_name), &above) {
            (Some(t), _) => {
                r.positive(k + 1, &t_name, t);
                t
            }
            (None, Some(p)) => p.t,
            (None, None) => {
                r.fail(k + 1, &t_name, "is blank: the first ply needs a thickness");
                0.0
            }
        };
        let theta = r.real_or(k + 2, &theta_name, 0.0);
        let sout = match r.text(k + 3).to_ascii_uppercase().as_str() {
            "" | "NO" => false,
            "YES" => true,
            _ => {
                r.fail(k + 3, &sout_name, "must be YES or NO (or blank)");
                false
            }
        };
        plies.push(Ply { mid, t, theta, sout });
    }
    if plies.is_empty() && r.ok {
        r.fail(8, "MID1", "PCOMP has no ply");
    }
    let p = Pcomp {
        pid,
        z0,
        nsm,
        sb,
        ft,
        plies,
        lam,
        at: r.at(),
    };
    if r.ok {
        b.pcomps.push(p);
    }
}

/// CONM2.
fn card_conm2(r: &mut Reader, b: &mut Bulk) {
    let cid = r.int_or(2, "CID", 0);
    if cid < -1 {
        r.fail(
            2,
            "CID",
            "must be −1 (X1-X3 the mass's basic location), 0 (basic) or a coordinate system id",
        );
    }
    let offset = [
        r.real_or(4, "X1", 0.0),
        r.real_or(5, "X2", 0.0),
        r.real_or(6, "X3", 0.0),
    ];
    let names = ["I11", "I21", "I22", "I31", "I32", "I33"];
    let mut inertia = [0.0; 6];
    for (i, name) in names.iter().enumerate() {
        inertia[i] = r.real_or(8 + i, name, 0.0);
    }
    let c = Conm2 {
        eid: r.id(0, "EID"),
        g: r.id(1, "G"),
        mass: r.real(3, "M"),
        inertia,
        cid,
        offset,
        at: r.at(),
    };
    r.positive(3, "M", c.mass);
    for (i, k) in [(0, 8), (2, 10), (5, 13)] {
        r.non_negative(k, names[i], inertia[i]);
    }
    if inertia[4] != 0.0 && inertia[5] == 0.0 {
        r.warn(
            12,
            "I32",
            "CONM2 inertia has a product of inertia I32 but no I33: a value meant for I33 may sit one field early",
        );
    }
    r.extra_fields(14);
    if r.ok {
        b.conm2s.push(c);
    }
}

/// SPC1.
fn card_spc1(r: &mut Reader, b: &mut Bulk) {
    let s = Spc1 {
        sid: r.id(0, "SID"),
        c: r.components(1, "C"),
        grids: r.id_list(2, "G"),
        enforced: None,
        at: r.at(),
    };
    if r.ok && s.grids.is_empty() {
        r.fail(2, "G1", "SPC1 names no grid");
    }
    if r.ok && s.c.0 == 0 && !r.text(1).is_empty() && r.text(1) != "0" {
        r.fail(1, "C", "names no component");
    }
    if r.ok {
        b.spc1s.push(s);
    }
}

/// SPC: SID G1 C1 D1 G2 C2 D2, each grid's components held at zero (an SPC1 each);
/// an enforced displacement D ≠ 0 is not supported.
fn card_spc(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let mut out = Vec::new();
    for (k, names) in [(1, ["G1", "C1", "D1"]), (4, ["G2", "C2", "D2"])] {
        if k == 4 && (4..7).all(|i| r.text(i).is_empty()) {
            break;
        }
        // A blank or 0 component: a scalar point ("C ... blank or zero for scalar
        // points", BULK.TXT, SPC); a grid so named is refused when the SPC is used.
        let g = r.id(k, names[0]);
        let c = r.components(k + 1, names[1]);
        let d = r.real_or(k + 2, names[2], 0.0);
        out.push(Spc1 {
            sid,
            c,
            grids: vec![g],
            enforced: (d != 0.0).then(|| (d, r.field_ref(k + 2, names[2]))),
            at: r.at(),
        });
    }
    r.extra_fields(7);
    if r.ok {
        b.spc1s.extend(out);
    }
}

/// SPCADD: SID S1 S2 …: the union of constraint sets.
fn card_spcadd(r: &mut Reader, b: &mut Bulk) {
    let a = SpcAdd {
        sid: r.id(0, "SID"),
        sets: r.id_list(1, "S"),
        at: r.at(),
    };
    if r.ok && a.sets.is_empty() {
        r.fail(1, "S1", "SPCADD joins no set");
    }
    if r.ok && a.sets.contains(&a.sid) {
        r.fail(1, "S1", format!("SPCADD {} cannot join itself", a.sid));
    }
    if r.ok {
        b.spcadds.push(a);
    }
}

/// RBE2: EID GN CM GM1 GM2 … (THRU ranges allowed), then ALPHA (a real, the thermal
/// expansion coefficient: no temperature load is applied, so it has no effect).
fn card_rbe2(r: &mut Reader, b: &mut Bulk) {
    let (eid, gn, cm) = (r.id(0, "EID"), r.id(1, "GN"), r.components(2, "CM"));
    if r.ok && cm.0 == 0 {
        r.fail(
            2,
            "CM",
            "names no component: an RBE2 makes components of its GMi dependent",
        );
    }
    // ALPHA: a real in the last written field; the grids come before it.
    let n = r.card.fields.len();
    let last = (3..n).rev().find(|&k| !r.text(k).is_empty());
    let alpha = last.filter(|&k| matches!(parse_real(r.text(k)), Some(RealToken::Real(_))));
    let gm = r.id_list_in(3, alpha.unwrap_or(n), "GM");
    if r.ok && gm.is_empty() {
        r.fail(3, "GM1", "names no dependent grid");
    }
    if r.ok {
        if let Some(&g) = gm.iter().find(|&&g| g == gn) {
            r.fail(
                3,
                "GM",
                format!("grid {g} is both the independent grid GN and a dependent grid"),
            );
        }
    }
    if r.ok {
        b.rbe2s.push(Rbe2 {
            eid,
            gn,
            cm,
            gm,
            at: r.at(),
        });
    }
}

/// RBE3: EID, blank, REFGRID, REFC, then groups WTi Ci Gi,1 Gi,2 … (a real starts a
/// group; THRU ranges allowed), then ALPHA and its value (no temperature load is
/// applied, so it has no effect). UM, which moves the dependency to other DOFs, is
/// refused.
fn card_rbe3(r: &mut Reader, b: &mut Bulk) {
    let (eid, refgrid, refc) = (r.id(0, "EID"), r.id(2, "REFGRID"), r.components(3, "REFC"));
    if r.ok && refc.0 == 0 {
        r.fail(
            3,
            "REFC",
            "names no component: an RBE3 makes components of its REFGRID dependent",
        );
    }
    let n = r.card.fields.len();
    let mut groups: Vec<Rbe3Group> = Vec::new();
    let mut k = 4;
    while r.ok && k < n {
        let t = r.text(k);
        if t.is_empty() {
            k += 1;
            continue;
        }
        if t.eq_ignore_ascii_case("UM") {
            r.fail(
                k,
                "UM",
                "moves the dependent DOFs off the reference grid, which is not supported: REFGRID's REFC \
                 components are the dependent ones",
            );
            return;
        }
        if t.eq_ignore_ascii_case("ALPHA") {
            r.real_or(k + 1, "ALPHA", 0.0);
            r.extra_fields(k + 2);
            break;
        }
        if !matches!(parse_real(t), Some(RealToken::Real(_))) {
            r.fail(
                k,
                "WT",
                "is not a real weight: each group starts with its weight WTi (a real)",
            );
            return;
        }
        let weight = r.real(k, "WT");
        if r.ok && weight <= 0.0 {
            r.fail(k, "WT", "must be positive");
        }
        let c = r.components(k + 1, "C");
        if r.ok && c.0 == 0 {
            r.fail(
                k + 1,
                "C",
                "names no component: a group weights some components of its grids",
            );
        }
        // The group's grids run to the next real, UM or ALPHA.
        let end = (k + 2..n)
            .find(|&j| {
                let t = r.text(j);
                t.eq_ignore_ascii_case("UM")
                    || t.eq_ignore_ascii_case("ALPHA")
                    || matches!(parse_real(t), Some(RealToken::Real(_)))
            })
            .unwrap_or(n);
        let grids = r.id_list_in(k + 2, end, "G");
        if r.ok && grids.is_empty() {
            r.fail(k + 2, "G", "names no grid: each weighted group needs one");
        }
        if let Some(&g) = grids.iter().find(|&&g| g == refgrid) {
            if r.ok {
                r.fail(
                    k + 2,
                    "G",
                    format!("grid {g} is the reference grid REFGRID: it cannot also be independent"),
                );
            }
        }
        groups.push(Rbe3Group { weight, c, grids });
        k = end;
    }
    if r.ok && groups.is_empty() {
        r.fail(
            4,
            "WT1",
            "is blank: an RBE3 needs a weighted group of independent grids",
        );
    }
    if r.ok {
        b.rbe3s.push(Rbe3 {
            eid,
            refgrid,
            refc,
            groups,
            at: r.at(),
        });
    }
}

/// TF.
fn card_tf(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
    let mut t = Tf {
        sid: r.id(0, "SID"),
        gd: r.id(1, "GD"),
        cd: r.component(2, "CD"),
        b: [
            r.real_or(3, "B0", 0.0),
            r.real_or(4, "B1", 0.0),
            r.real_or(5, "B2", 0.0),
        ],
        terms: Vec::new(),
        at: r.at(),
    };
    let nlines = card.fields.len().div_ceil(8);
    for line in 1..nlines {
        let k = 8 * line;
        if (k..k + 8).all(|i| r.text(i).is_empty()) {
            continue;
        }
        let term = TfTerm {
            g: r.id(k, "G(i)"),
            c: r.component(k + 1, "C(i)"),
            a: [
                r.real_or(k + 2, "A0(i)", 0.0),
                r.real_or(k + 3, "A1(i)", 0.0),
                r.real_or(k + 4, "A2(i)", 0.0),
            ],
        };
        for i in k + 5..k + 8 {
            if !r.text(i).is_empty() {
                r.fail(i, "unused", "TF continuation holds one term in fields 2-6");
            }
        }
        t.terms.push(term);
    }
    if r.ok {
        b.tfs.push(t);
    }
}

/// TSTEP.
fn card_tstep(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
    let t = Tstep {
        sid: r.id(0, "SID"),
        n: r.int(1, "N(1)").max(0) as usize,
        dt: r.real(2, "DT(1)"),
        every: r.int_or(3, "NO(1)", 1).max(0) as usize,
        further: (card.fields.len() > 8).then(|| r.field_ref(9, "N(2)")),
        at: r.at(),
    };
    if r.ok && t.n == 0 {
        r.fail(1, "N(1)", "the number of steps must be positive");
    }
    r.positive(2, "DT(1)", t.dt);
    if r.ok && t.every == 0 {
        r.fail(3, "NO(1)", "the output interval must be positive");
    }
    for k in (8..card.fields.len()).filter(|k| k % 8 != 0) {
        let name = ["", "N", "DT", "NO"][k % 8 % 4];
        match k % 8 {
            1 | 3 => {
                r.int_opt(k, name);
            }
            2 => {
                r.real_opt(k, name);
            }
            _ => r.fail(k, "unused", "TSTEP has no field here"),
        }
    }
    if r.ok {
        b.tsteps.push(t);
    }
}

/// NOLIN3.
fn card_nolin3(r: &mut Reader, b: &mut Bulk) {
    let n = Nolin3 {
        sid: r.id(0, "SID"),
        gi: r.id(1, "GI"),
        ci: r.component(2, "CI"),
        s: r.real(3, "S"),
        gj: r.id(4, "GJ"),
        cj: r.component(5, "CJ"),
        a: r.real(6, "A"),
        at: r.at(),
    };
    if r.ok && n.a <= 0.0 {
        r.fail(6, "A", "the exponent must be positive");
    }
    r.extra_fields(7);
    if r.ok {
        b.nolin3s.push(n);
    }
}

/// TIC.
fn card_tic(r: &mut Reader, b: &mut Bulk) {
    let t = Tic {
        sid: r.id(0, "SID"),
        g: r.id(1, "G"),
        c: r.component(2, "C"),
        u0: r.real_or(3, "U0", 0.0),
        v0: r.real_or(4, "V0", 0.0),
        at: r.at(),
    };
    r.extra_fields(5);
    if r.ok {
        b.tics.push(t);
    }
}
