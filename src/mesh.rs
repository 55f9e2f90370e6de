//! Generated decks: the paper's clamped composite plate on an N×N mesh and its rod
//! with N elements, and the plate's model built from its deck.
//!
//! The 49×49 deck reproduces `reference-data/decks/plate.bdf` (with its INCLUDEd mesh)
//! card for card in meaning: grids id = B·row + col (B = 100, or 1000 when N ≥ 99),
//! x = (col − (N+2)/2)·6/N, y = (row − (N+2)/2)·6/N, CQUAD4 id = its lower-left grid,
//! connectivity (g, g+1, g+B+1, g+B), all four edges clamped, the impactor grid 999
//! over the centre element, the paper's PSHELL/MAT2 and NOLIN3/TF contact. N must be
//! odd so that an element sits at the centre.

use crate::deck::number::format_real;
use std::fmt::Write;

/// Side length of the paper's plate (in).
pub const PLATE_SIDE: f64 = 6.0;
/// Distances of the strain gages A and B from the plate centre along y (in): the
/// centres of elements 3325 and 4125 of the paper's 49×49 mesh.
pub const GAGE_Y: [f64; 2] = [8.0 * 6.0 / 49.0, 16.0 * 6.0 / 49.0];

/// A mesh size a generated deck cannot have, or its model that cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// An even, too small or too large plate mesh size.
    #[error("the plate mesh needs an odd N from 3 to 997 (an element at the centre; grid ids 1000·row + col unique), not {0}")]
    Plate(usize),
    /// An odd or too small rod element count.
    #[error("the rod mesh needs an even number of elements (at least 2), not {0}")]
    Rod(usize),
    /// A panel radius that is not a positive number, or too small for the plate's
    /// 6 in to wrap less than half way round.
    #[error(
        "the panel radius must be a number above 6/π in (the plate's 6 in wrapped less than half way round), not {0}"
    )]
    Radius(f64),
    /// A generated plate deck without the PSHELL a variant replaces.
    #[error("the generated plate deck has no {0}")]
    NoPshell(String),
    /// Stiffeners that do not fit the mesh.
    #[error("{0}")]
    Stiffeners(String),
    /// The generated deck's model could not be built.
    #[error("{0}")]
    Load(#[from] crate::model::LoadError),
}

/// Blade stiffeners under a square plate: `count` CBARs lines along x, each under the
/// grid row nearest to y = side·(k/(count + 1) − ½), k = 1..count (equally spaced,
/// edge to edge), on the plate's back face (+z, away from the impactor, which comes
/// from −z): each bar's axis (its section's centroid) offset by WA = WB =
/// (0, 0, T/2 + height/2) from the skin's grids, plane 1 the x-z plane, a PBARL BAR of
/// `width` × `height` of an isotropic material.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stiffeners {
    /// Number of stiffeners.
    pub count: usize,
    /// Blade thickness (across, along y).
    pub width: f64,
    /// Blade height (along z).
    pub height: f64,
    /// Young's modulus.
    pub e: f64,
    /// Poisson's ratio.
    pub nu: f64,
    /// Mass density.
    pub rho: f64,
}

impl Stiffeners {
    /// `count` blades of the paper's plate's thickness (0.15 in) and 0.5 in high, of an
    /// isotropic material with the skin's membrane modulus G11 (4.3e6 psi) and density
    /// (1.8e-4 lbf·s²/in⁴): blades of the skin's material, laid along their length.
    pub fn blade(count: usize) -> Self {
        Stiffeners {
            count,
            width: 0.15,
            height: 0.5,
            e: 4.3e6,
            nu: 0.3,
            rho: 1.8e-4,
        }
    }

    /// The grid rows (1-based) the stiffeners run under, on an N×N plate mesh.
    pub fn rows(&self, m: &PlateMesh) -> Vec<usize> {
        (1..=self.count)
            .map(|k| {
                let y = k as f64 / (self.count + 1) as f64 - 0.5; // in plate sides
                                                                  // Row r is at (r − (N+2)/2)/N sides.
                (y * m.n as f64 + (m.n as f64 + 2.0) / 2.0).round() as usize
            })
            .collect()
    }
}

/// The first element id of the stiffeners' CBARs on a mesh: 2·base², above every
/// shell and grid id and the indentation's EPOINT (base² + 1).
pub fn stiffener_ids(m: &PlateMesh) -> usize {
    2 * m.base * m.base
}

/// What a generated square is laid on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Surface {
    /// The plane z = 0.
    Flat,
    /// A cylinder of this radius whose axis is parallel to y through (0, 0, radius):
    /// the square's x is wrapped onto it as arc length, the centre stays at the
    /// origin with its normal along z, and the edges curve away from z < 0, where the
    /// impactor comes from (x = R sin(s/R), z = R(1 − cos(s/R))).
    Cylinder {
        /// The radius.
        radius: f64,
    },
}

/// An N×N plate mesh: grid id = base·row + col (rows and columns from 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateMesh {
    /// Elements per side.
    pub n: usize,
    /// Row multiplier of the grid ids (100, or 1000 past 99 grids a side).
    pub base: usize,
}

impl PlateMesh {
    /// The largest mesh: 998 grids a side keep 1000·row + col unique.
    pub const MAX_N: usize = 997;

    /// The mesh of `n` elements a side (odd, from 3 to [`Self::MAX_N`]).
    pub fn new(n: usize) -> Result<Self, MeshError> {
        if n < 3 || n % 2 == 0 || n > Self::MAX_N {
            return Err(MeshError::Plate(n));
        }
        Ok(PlateMesh {
            n,
            base: if n + 1 < 100 { 100 } else { 1000 },
        })
    }

    /// The EPOINT of the indentation: 10001 as in the paper's deck, base² + 1 in
    /// general, above every grid id (the largest is base·(base − 1) + base − 1).
    pub fn indentation_point(&self) -> usize {
        self.base * self.base + 1
    }

    /// The id of the grid at `row`, `col`.
    pub fn grid(&self, row: usize, col: usize) -> usize {
        self.base * row + col
    }

    /// The element under the impactor.
    pub fn centre_element(&self) -> usize {
        let c = self.n.div_ceil(2);
        self.grid(c, c)
    }

    /// The elements whose centres are nearest the gages A and B.
    pub fn gage_elements(&self) -> [usize; 2] {
        let c = self.n.div_ceil(2);
        GAGE_Y.map(|y| self.grid(c + (y * self.n as f64 / PLATE_SIDE).round() as usize, c))
    }

    /// Coordinate of grid line k (1-based) of a square plate of the given side,
    /// centred on the origin: (k − (N+2)/2)·side/N.
    fn coord(&self, k: usize, side: f64) -> f64 {
        (k as f64 - (self.n as f64 + 2.0) / 2.0) * side / self.n as f64
    }

    /// The stiffeners' cards (MAT1 401, PBARL 401, and one CBAR per element length
    /// along each stiffened row: id [`stiffener_ids`] + base·row + col) under a plate
    /// of `thickness` (see [`Stiffeners`]).
    pub fn write_stiffeners(&self, w: &mut String, thickness: f64, s: &Stiffeners) -> Result<(), MeshError> {
        let rows = s.rows(self);
        let ok = |x: f64| x.is_finite() && x > 0.0;
        if !(ok(s.width) && ok(s.height) && ok(s.e) && s.rho >= 0.0 && s.nu > -1.0 && s.nu < 0.5) {
            return Err(MeshError::Stiffeners(format!(
                "a stiffener needs a positive width, height and E, ρ ≥ 0 and −1 < ν < 0.5, not {s:?}"
            )));
        }
        let mut distinct = rows.clone();
        distinct.dedup();
        if s.count > 0 && (distinct.len() != rows.len() || rows[0] < 2 || rows[rows.len() - 1] > self.n) {
            return Err(MeshError::Stiffeners(format!(
                "{} stiffeners do not fit a {}×{} mesh: each needs its own interior grid row",
                s.count, self.n, self.n
            )));
        }
        if s.count == 0 {
            return Ok(());
        }
        let z = format_real(0.5 * thickness + 0.5 * s.height);
        let _ = writeln!(
            w,
            "$ Stiffeners: {} blades {} x {} under grid rows {} (offset {z} to the back face)",
            s.count,
            format_real(s.width),
            format_real(s.height),
            rows.iter().map(|r| r.to_string()).collect::<Vec<_>>().join(", ")
        );
        let _ = writeln!(
            w,
            "MAT1,401,{},,{},{}",
            format_real(s.e),
            format_real(s.nu),
            format_real(s.rho)
        );
        let _ = writeln!(
            w,
            "PBARL,401,401,,BAR\n,{},{}",
            format_real(s.width),
            format_real(s.height)
        );
        let first = stiffener_ids(self);
        for &r in &rows {
            for c in 1..=self.n {
                let (a, b) = (self.grid(r, c), self.grid(r, c + 1));
                let _ = writeln!(
                    w,
                    "CBAR,{},401,{a},{b},0.0,0.0,1.0\n,,,0.0,0.0,{z},0.0,0.0,{z}",
                    first + self.base * r + c
                );
            }
        }
        Ok(())
    }

    /// The four corners of the centre element, which the impactor loads.
    pub fn contact_grids(&self) -> [usize; 4] {
        let e = self.centre_element();
        [e, e + 1, e + self.base, e + self.base + 1]
    }

    /// GRID cards of a square plate of the given side (z = 0) and its shell cards
    /// (PSHELL 1): see [`Cells`] for their ids.
    pub fn write_grids_and_shells(&self, w: &mut String, side: f64, cells: Cells) {
        self.write_surface(w, side, Surface::Flat, cells);
    }

    /// GRID cards of a square of the given side laid on `surface` and its shell cards
    /// (PSHELL 1): see [`Cells`] for their ids.
    pub fn write_surface(&self, w: &mut String, side: f64, surface: Surface, cells: Cells) {
        let (n, base) = (self.n, self.base);
        for r in 1..=n + 1 {
            for c in 1..=n + 1 {
                let (x, y) = (self.coord(c, side), self.coord(r, side));
                let g = self.grid(r, c);
                match surface {
                    Surface::Flat => {
                        let _ = writeln!(w, "GRID,{g},,{},{},0.0", format_real(x), format_real(y));
                    }
                    Surface::Cylinder { radius } => {
                        let phi = x / radius;
                        let _ = writeln!(
                            w,
                            "GRID,{g},,{},{},{}",
                            format_real(radius * phi.sin()),
                            format_real(y),
                            format_real(radius * (1.0 - phi.cos()))
                        );
                    }
                }
            }
        }
        for r in 1..=n {
            for c in 1..=n {
                let g = self.grid(r, c);
                let (ne, nw) = (g + base + 1, g + base);
                match cells {
                    Cells::Quad4 => {
                        let _ = writeln!(w, "CQUAD4,{g},1,{g},{},{ne},{nw}", g + 1);
                    }
                    Cells::Tria3 => {
                        // The diagonal points away from the centre: SW-NE where the
                        // element centre's x and y have the same sign (the centre
                        // element included), SE-NW elsewhere. Each triangle starts
                        // on its side along x (G1→G2 at 0° or 180°), the material x
                        // axis a PCOMP's ply angles are measured from.
                        let centre = n.div_ceil(2) as i64;
                        let (dx, dy) = (c as i64 - centre, r as i64 - centre);
                        let (a, b) = if dx * dy >= 0 {
                            ([g, g + 1, ne], [ne, nw, g])
                        } else {
                            ([g, g + 1, nw], [ne, nw, g + 1])
                        };
                        for (id, t) in [(2 * g, a), (2 * g + 1, b)] {
                            let _ = writeln!(w, "CTRIA3,{id},1,{},{},{}", t[0], t[1], t[2]);
                        }
                    }
                }
            }
        }
    }

    /// The elements standing for quadrilateral element `q` (its id, the lower-left
    /// grid): itself, or its two triangles.
    pub fn elements_of(&self, q: usize, cells: Cells) -> Vec<usize> {
        match cells {
            Cells::Quad4 => vec![q],
            Cells::Tria3 => vec![2 * q, 2 * q + 1],
        }
    }

    /// The TF defining the indentation ([`Self::indentation_point`]) as the
    /// impactor's T3 minus the mean T3 of the contact grids.
    pub fn write_indentation_tf(&self, w: &mut String) {
        let _ = writeln!(
            w,
            "TF,111,{},0,+1.0,0.0,0.0,,,+TF-1\n+TF-1,999,3,-1.0,0.0,0.0,,,,+TF-2",
            self.indentation_point()
        );
        for (k, g) in self.contact_grids().iter().enumerate() {
            let next = if k < 3 {
                format!(",,,,+TF-{}", k + 3)
            } else {
                String::new()
            };
            let _ = writeln!(w, "+TF-{},{g},3,+0.25,0.0,0.0{next}", k + 2);
        }
    }
}

/// The shell elements a generated plate is meshed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cells {
    /// CQUAD4, id = its lower-left grid: the paper's mesh.
    #[default]
    Quad4,
    /// Each quadrilateral cut along a diagonal into two CTRIA3 (ids 2q and 2q + 1 for
    /// the quadrilateral q), the diagonals pointing away from the plate centre.
    Tria3,
}

impl Cells {
    /// The element card.
    pub fn card(self) -> &'static str {
        match self {
            Cells::Quad4 => "CQUAD4",
            Cells::Tria3 => "CTRIA3",
        }
    }

    /// What a generated model's name gains for these cells: nothing, or `-tria3`.
    fn suffix(self) -> &'static str {
        match self {
            Cells::Quad4 => "",
            Cells::Tria3 => "-tria3",
        }
    }

    /// A [`square_plate_deck`] in these cells: as written, or cut into triangles
    /// ([`in_triangles`]).
    pub fn cut(self, deck: String) -> String {
        match self {
            Cells::Quad4 => deck,
            Cells::Tria3 => in_triangles(&deck),
        }
    }
}

/// How the plate's four edges are held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edges {
    /// All six components fixed: the paper's plate.
    Clamped,
    /// Translations fixed, rotations free (w = 0, M_n = 0): the Navier plate. The
    /// membrane of a symmetric laminate struck transversely stays at rest either way.
    SimplySupported,
}

impl Edges {
    /// The SPC1 components on the edges.
    fn components(self) -> &'static str {
        match self {
            Edges::Clamped => "123456",
            Edges::SimplySupported => "123",
        }
    }
}

/// The paper's plate deck on an N×N mesh.
pub fn plate_deck(n: usize) -> Result<String, MeshError> {
    plate_deck_with(n, Edges::Clamped, Cells::Quad4)
}

/// The paper's plate on an N×N mesh, its structure alone: [`plate_deck`] with the
/// impactor, contact and transient cards taken out and SOL 103, as an analyst's
/// normal modes deck would hold it (no METHOD: add one, or `check --modes`).
pub fn plate_structure_deck(n: usize) -> Result<String, MeshError> {
    const IMPACT: [&str; 16] = [
        "GRID,999",
        "CONM2",
        "+CON2",
        "SPC1,1,12456,999",
        "NOLIN3",
        "TF",
        "+TF",
        "TIC",
        "EPOINT",
        "  IC",
        "  NONLINEAR",
        "  TSTEP",
        "  TFL",
        "  SET 15",
        "  NLLOAD",
        "  DISP",
    ];
    Ok(plate_deck(n)?
        .lines()
        .filter(|l| !IMPACT.iter().any(|p| l.starts_with(p)))
        .map(|l| {
            if l == "SOL 27" {
                "SOL 103\n".to_string()
            } else {
                format!("{l}\n")
            }
        })
        .collect())
}

/// The paper's plate deck on an N×N mesh with its edges held as `edges` says, meshed
/// in `cells`.
pub fn plate_deck_with(n: usize, edges: Edges, cells: Cells) -> Result<String, MeshError> {
    surface_deck(n, edges, cells, Surface::Flat, None)
}

/// The paper's plate deck on an N×N mesh with blade stiffeners under it (see
/// [`Stiffeners`]; none when their count is 0: [`plate_deck_with`]).
pub fn stiffened_plate_deck(n: usize, cells: Cells, stiffeners: &Stiffeners) -> Result<String, MeshError> {
    surface_deck(n, Edges::Clamped, cells, Surface::Flat, Some(stiffeners))
}

/// The paper's plate wrapped onto a cylinder of radius `radius` ([`Surface::Cylinder`])
/// on an N×N mesh: its 6 in × 6 in as arc length and width, clamped, struck at the
/// centre along z by the paper's impactor with the paper's contact. The panel's
/// grids leave R3 free (no GRDSET PS 6): on a curved panel it is no shell's drilling
/// rotation, and the grids whose rotations some direction does not stiffen get
/// their drilling supports from the model.
pub fn panel_deck(n: usize, radius: f64, cells: Cells) -> Result<String, MeshError> {
    if !(radius.is_finite() && radius > PLATE_SIDE / std::f64::consts::PI) {
        return Err(MeshError::Radius(radius));
    }
    surface_deck(n, Edges::Clamped, cells, Surface::Cylinder { radius }, None)
}

/// The paper's plate deck laid on `surface`, with stiffeners under it if given.
fn surface_deck(
    n: usize,
    edges: Edges,
    cells: Cells,
    surface: Surface,
    stiffeners: Option<&Stiffeners>,
) -> Result<String, MeshError> {
    let m = PlateMesh::new(n)?;
    let (e, base) = (m.centre_element(), m.base);
    let contact = m.contact_grids();
    let [ga, gb] = m.gage_elements();
    let last = n + 1;
    let mut d = String::new();
    let w = &mut d;
    let _ = writeln!(
        w,
        "$ The plate of \"Low Velocity Impact Analysis with NASTRAN\" (plate.bdf) on a {n}x{n} mesh,"
    );
    let (option, ids) = match cells {
        Cells::Quad4 => ("", "CQUAD4 id = lower-left grid"),
        Cells::Tria3 => (" --cells tria3", "CTRIA3 ids = 2*(lower-left grid) + 0, 1"),
    };
    let stiffened = match stiffeners {
        Some(s) if s.count > 0 => format!(" --stiffeners {}", s.count),
        _ => String::new(),
    };
    let command = match surface {
        Surface::Flat => format!("plate --n {n}{option}{stiffened}"),
        Surface::Cylinder { radius } => format!("panel --n {n} --radius {}{option}", format_real(radius)),
    };
    let _ = writeln!(
        w,
        "$ generated by `impactlab mesh {command}`. Grid id = {base}*row + col,"
    );
    let _ = writeln!(
        w,
        "$ x = (col - {})*6/{n}, y = (row - {})*6/{n}; {ids}.",
        (n as f64 + 2.0) / 2.0,
        (n as f64 + 2.0) / 2.0
    );
    let list = |q: usize| {
        m.elements_of(q, cells)
            .iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join(",")
    };
    let (e, ga, gb) = (list(e), list(ga), list(gb));
    if let Surface::Cylinder { radius } = surface {
        let _ = writeln!(
            w,
            "$ Wrapped onto a cylinder of radius R = {}, axis along y through (0, 0, R):",
            format_real(radius)
        );
        let _ = writeln!(w, "$ x = R sin(s/R), z = R(1 - cos(s/R)) for the flat x = s.");
    }
    let _ = writeln!(w, "$ Gages A and B: elements {ga} and {gb}. Units: in, lbf, s");
    if edges == Edges::SimplySupported {
        let _ = writeln!(w, "$ Edges simply supported (translations fixed), not clamped.");
    }
    let _ = writeln!(w, "$ Units: in, lbf, s");
    let _ = writeln!(w, "ID IMPACT,PLATE\nSOL 27\nCEND");
    let _ = writeln!(w, "  TITLE = IMPACT OF PLATE {n}X{n} : CENTERED ELEMENT");
    let _ = writeln!(w, "  SPC = 1\n  IC = 3\n  NONLINEAR = 5\n  TSTEP = 1\n  TFL = 111");
    let _ = writeln!(
        w,
        "  SET 15 = 999,{},{},{},{}",
        contact[0], contact[1], contact[2], contact[3]
    );
    let _ = writeln!(w, "  NLLOAD = 15\n  DISP = 15");
    // The stiffener nearest the centre: its bar at the centre column, its stresses
    // and its resultants written.
    let bar = stiffeners.filter(|s| s.count > 0).map(|s| {
        let rows = s.rows(&m);
        let c = n.div_ceil(2);
        let r = rows[(rows.len() - 1) / 2];
        stiffener_ids(&m) + m.base * r + c
    });
    let _ = writeln!(
        w,
        "  SET 20 = {e},{ga},{gb}{}\n  STRESS = 20",
        bar.map(|b| format!(",{b}")).unwrap_or_default()
    );
    if let Some(b) = bar {
        let _ = writeln!(w, "  SET 21 = {b}\n  FORCE = 21");
    }
    let _ = writeln!(w, "BEGIN BULK");
    let ep = m.indentation_point();
    let _ = writeln!(w, "EPOINT,{ep}\nGRID,999,,0.0,0.0,-0.1875");
    let _ = writeln!(
        w,
        "CONM2,200,999,0,8.096-5,0.0,0.0,0.0,,+CON2-2\n+CON2-2,7.459-6,,7.459-6,,,1.423-6"
    );
    m.write_surface(w, PLATE_SIDE, surface, cells);
    if let Some(s) = stiffeners {
        m.write_stiffeners(w, 0.15, s)?;
    }
    let _ = writeln!(w, "{PAPER_PSHELL}");
    let _ = writeln!(
        w,
        "MAT2,101,4.3E+06,2.9E+05,-1.7E-03,2.8E+06,-3.4E-02,5.7E+05,1.8E-04,+A101"
    );
    let _ = writeln!(w, "+A101,5.8E-06,8.9E-06,5.0E-13");
    let _ = writeln!(w, "MAT2,201,5.7E+06,2.9E+05,-1.9E-04,1.4E+06,-3.8E-03,5.7E+05");
    let c = edges.components();
    let _ = writeln!(w, "SPC1,1,{c},{},THRU,{}", m.grid(1, 1), m.grid(1, last));
    let _ = writeln!(w, "SPC1,1,{c},{},THRU,{}", m.grid(last, 1), m.grid(last, last));
    for r in 2..last {
        let _ = writeln!(w, "SPC1,1,{c},{},{}", m.grid(r, 1), m.grid(r, last));
    }
    let _ = writeln!(w, "SPC1,1,12456,999");
    if surface == Surface::Flat {
        let _ = writeln!(w, "GRDSET,,,,,,,6");
    }
    let _ = writeln!(w, "TSTEP,1,2000,1.0-7,10");
    for g in contact {
        let _ = writeln!(w, "NOLIN3,5,{g},3,+1.945+5,{ep},0,1.5");
    }
    let _ = writeln!(w, "NOLIN3,5,999,3,-7.779+5,{ep},0,1.5");
    m.write_indentation_tf(w);
    let _ = writeln!(w, "TIC,3,999,3,0.0,1470.0\nENDDATA");
    Ok(d)
}

/// The model of [`panel_deck`] (CQUAD4).
pub fn panel_model(n: usize, radius: f64) -> Result<crate::model::Model, MeshError> {
    let text = panel_deck(n, radius, Cells::Quad4)?;
    Ok(crate::model_from_text(&format!("panel{n}"), &text)?)
}

/// The paper's rod deck (`reference-data/decks/rod.bdf`) with N elements instead of
/// 144: the same 36 in rod, ball, contact and TSTEP; the two elements at mid-rod are
/// requested for output (N even); the CONM2 is renumbered 99999.
pub fn rod_deck(n: usize) -> Result<String, MeshError> {
    if n < 2 || n % 2 != 0 {
        return Err(MeshError::Rod(n));
    }
    let text = include_str!("../reference-data/decks/rod.bdf");
    let (a, b) = (n / 2, n / 2 + 1);
    let out = text
        .replace("SET 30 = 1,72,73,999,1001", &format!("SET 30 = 1,{a},{b},999,1001"))
        .replace(
            "=(144),*(1),=,*(0.25),=",
            &format!("=({n}),*(1),=,*({}),=", format_real(36.0 / n as f64)),
        )
        .replace("=(143),*(1),=,*(1),*(1)", &format!("=({}),*(1),=,*(1),*(1)", n - 1))
        .replace("SPC1,4,23456,1,THRU,145", &format!("SPC1,4,23456,1,THRU,{}", n + 1))
        // CROD ids run 1..N: keep the CONM2 id clear of them.
        .replace("CONM2,200,", "CONM2,99999,");
    Ok(format!(
        "$ Generated by impactlab from the paper's rod deck with {n} elements (mid-rod elements {a}, {b}).\n{out}"
    ))
}

/// The paper's plate on an n×n mesh, built from the generated deck (through the deck
/// reader, as a user's deck would be).
pub fn plate_model(n: usize) -> Result<crate::model::Model, MeshError> {
    plate_model_with(n, Cells::Quad4)
}

/// The paper's plate on an n×n mesh of `cells`, built from the generated deck.
pub fn plate_model_with(n: usize, cells: Cells) -> Result<crate::model::Model, MeshError> {
    let text = plate_deck_with(n, Edges::Clamped, cells)?;
    Ok(crate::model_from_text(
        &format!("plate-{n}x{n}{}", cells.suffix()),
        &text,
    )?)
}

/// The paper's PSHELL in the generated plate decks: T = 0.15 in, MID1 101 and MID2 201
/// (its MAT2 cards), 12I/T³ = 1.
pub const PAPER_PSHELL: &str = "PSHELL,1,101,0.15,201,1.0";

/// The paper's plate made shear-deformable: PSHELL MID3 naming a MAT2 of the
/// cross-ply's through-thickness average transverse shear moduli (∫C̄ dz / t of the
/// plies' G1Z, G2Z in `reference-data/decks/plate-pcomp-shear.bdf`: G11 (xz) =
/// (10·5.7e5 + 5·4.59e5)/15, G22 (yz) = (10·4.59e5 + 5·5.7e5)/15 psi), TS/T blank
/// (5/6): the MAT2 twin of the shear laminate.
pub const MID3: &str = "MAT2,301,5.33+5,0.0,,4.96+5";

/// A generated plate deck ([`plate_deck_with`] or a variant of it) made
/// shear-deformable: its PSHELL names [`MID3`].
pub fn with_mid3(text: &str) -> Result<String, MeshError> {
    let pshell = format!("{PAPER_PSHELL}\n");
    if !text.contains(&pshell) {
        return Err(MeshError::NoPshell(PAPER_PSHELL.to_string()));
    }
    Ok(text.replace(&pshell, &format!("{PAPER_PSHELL},301\n{MID3}\n")))
}

/// The paper's plate on an n×n mesh of `cells`, built from the generated deck with
/// its PSHELL naming [`MID3`] (the shear-deformable plate).
pub fn plate_model_mid3(n: usize, cells: Cells) -> Result<crate::model::Model, MeshError> {
    let text = with_mid3(&plate_deck_with(n, Edges::Clamped, cells)?)?;
    Ok(crate::model_from_text(
        &format!("plate-mid3-{n}x{n}{}", cells.suffix()),
        &text,
    )?)
}

/// A simply supported square plate side × side on an n×n mesh of `cells` (w = 0 on
/// the edges, rotations free; in-plane DOFs and drilling fixed by GRDSET PS = 126),
/// with a bending material G (MAT2, stress/strain: G11, G12, G13, G22, G23, G33),
/// density ρ and thickness t: the Navier plate of the frequency check, built through
/// the deck reader. With a transverse shear stiffness `shear` (K55 in xz, K44 in yz,
/// force/length: PSHELL MID3 = a MAT2 of G11 = K55/t, G22 = K44/t, TS/T = 1), the
/// shear-deformable plate on Navier's "hard" supports: the rotation along each edge
/// held too (R1 on x = 0 and side, R2 on y = 0 and side), which the closed form
/// assumes and a shear-deformable plate feels (with the edge rotation free it has
/// boundary layers and a lower frequency).
pub fn navier_plate(
    n: usize,
    side: f64,
    thickness: f64,
    g: [f64; 6],
    rho: f64,
    shear: Option<[f64; 2]>,
    cells: Cells,
) -> Result<crate::model::Model, crate::model::LoadError> {
    let material = format!(
        "MAT2,1,{:?},{:?},{:?},{:?},{:?},{:?},{rho:?}",
        g[0], g[1], g[2], g[3], g[4], g[5]
    );
    let (name, cards, supports) = match shear {
        None => (
            "navier-plate",
            format!("PSHELL,1,1,{thickness:?},1,1.0\n{material}"),
            String::new(),
        ),
        Some([k55, k44]) => (
            "mindlin-plate",
            format!(
                "PSHELL,1,1,{thickness:?},1,1.0,2,1.0\n{material}\nMAT2,2,{:?},0.0,,{:?}",
                k55 / thickness,
                k44 / thickness
            ),
            hard_supports(n),
        ),
    };
    let deck = square_plate_deck(n, side, "3", "126", &cards).replace("ENDDATA", &format!("{supports}ENDDATA"));
    crate::model_from_text(&format!("{name}-{n}x{n}{}", cells.suffix()), &cells.cut(deck))
}

/// SPC1 cards (set 1) holding the rotation along each edge of [`square_plate_deck`]'s
/// n×n plate: R1 on the edges x = 0 and side, R2 on y = 0 and side (both at the
/// corners). With w = 0 there, Navier's "hard" simple support of a shear-deformable
/// plate.
pub fn hard_supports(n: usize) -> String {
    let id = |r: usize, c: usize| 1000 * (r + 1) + c + 1;
    let mut hard = String::new();
    for r in 0..=n {
        for c in 0..=n {
            let comps: String = [(c == 0 || c == n, '4'), (r == 0 || r == n, '5')]
                .iter()
                .filter(|(on, _)| *on)
                .map(|(_, k)| *k)
                .collect();
            if !comps.is_empty() {
                let _ = writeln!(hard, "SPC1,1,{comps},{}", id(r, c));
            }
        }
    }
    hard
}

/// A deck of a square plate side × side on an n×n CQUAD4 mesh (property 1) in the
/// z = 0 plane, grid `1000(r+1) + c + 1` at row r, column c: `edge` the SPC1
/// components on the boundary, `ps` the GRDSET PS, `cards` the PSHELL 1 and material
/// cards.
pub fn square_plate_deck(n: usize, side: f64, edge: &str, ps: &str, cards: &str) -> String {
    let mut d = String::from("SOL 9\nCEND\nTSTEP = 1\nSPC = 1\nBEGIN BULK\nTSTEP,1,1,1.0-6,1\n");
    let id = |r: usize, c: usize| 1000 * (r + 1) + c + 1;
    for r in 0..=n {
        for c in 0..=n {
            let (x, y) = (side * c as f64 / n as f64, side * r as f64 / n as f64);
            let _ = writeln!(d, "GRID,{},,{x:?},{y:?},0.0", id(r, c));
            if r == 0 || c == 0 || r == n || c == n {
                let _ = writeln!(d, "SPC1,1,{edge},{}", id(r, c));
            }
        }
    }
    for r in 0..n {
        for c in 0..n {
            let _ = writeln!(
                d,
                "CQUAD4,{},1,{},{},{},{}",
                id(r, c),
                id(r, c),
                id(r, c + 1),
                id(r + 1, c + 1),
                id(r + 1, c)
            );
        }
    }
    let _ = writeln!(d, "GRDSET,,,,,,,{ps}\n{cards}\nENDDATA");
    d
}

/// A deck of [`square_plate_deck`] with every CQUAD4 cut along its diagonal from its
/// first grid into two CTRIA3 (ids 2q and 2q + 1 for the quadrilateral q, same
/// property): the same plate meshed in triangles, all diagonals parallel, each
/// triangle starting on its side along x (G1→G2 at 0° or 180°).
pub fn in_triangles(deck: &str) -> String {
    let mut out = String::with_capacity(deck.len() * 2);
    for line in deck.lines() {
        match line.strip_prefix("CQUAD4,") {
            Some(rest) => {
                let f: Vec<&str> = rest.split(',').collect();
                let id: usize = f[0].parse().expect("square_plate_deck's element ids are integers");
                let (p, g) = (f[1], &f[2..6]);
                let _ = writeln!(out, "CTRIA3,{},{p},{},{},{}", 2 * id, g[0], g[1], g[2]);
                let _ = writeln!(out, "CTRIA3,{},{p},{},{},{}", 2 * id + 1, g[2], g[3], g[0]);
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    out
}

/// A simply supported closed cylinder (R = 1, L = 2, thickness t, E = 1, ν = 0.3,
/// ρ = 1; lumped mass, no rotary inertia) on `around` × `along` CQUAD4, its grids
/// located and displaced in a cylindrical CORD2C about the axis (T1 radial, T2
/// circumferential, T3 axial): the diaphragms at both ends hold T1 and T2, and T3 is
/// held on the mid-length ring against the rigid axial motion (every odd-m mode's
/// u = A cos λs vanishes there; a single held grid would leave the cylinder free to
/// slide about it, a spurious mode whose frequency falls to zero with h, as a point
/// support of a membrane holds nothing in the limit). `along` even.
pub fn cylinder_model(t: f64, around: usize, along: usize) -> Result<crate::model::Model, MeshError> {
    let id = |i: usize, j: usize| 1000 * (i + 1) + j % around + 1;
    let mut d = format!(
        "$ Units: unspecified\nSOL 27\nCEND\n  SPC = 1\n  TSTEP = 1\nBEGIN BULK\nTSTEP,1,1,1.0,1\n\
         CORD2C,1,0,0.0,0.0,0.0,0.0,0.0,1.0\n,1.0,0.0,0.0\nMAT1,1,1.0,,0.3,1.0\nPSHELL,1,1,{t:?},1\n"
    );
    for i in 0..=along {
        for j in 0..around {
            let (theta, z) = (360.0 * j as f64 / around as f64, 2.0 * i as f64 / along as f64);
            d += &format!("GRID,{},1,1.0,{theta:?},{z:?},1\n", id(i, j));
        }
    }
    for i in 0..along {
        for j in 0..around {
            d += &format!(
                "CQUAD4,{},1,{},{},{},{}\n",
                id(i, j),
                id(i, j),
                id(i, j + 1),
                id(i + 1, j + 1),
                id(i + 1, j)
            );
        }
    }
    for j in 0..around {
        d += &format!(
            "SPC1,1,12,{},{}\nSPC1,1,3,{}\n",
            id(0, j),
            id(along, j),
            id(along / 2, j)
        );
    }
    d += "ENDDATA\n";
    Ok(crate::model_from_text(&format!("cylinder-{around}x{along}"), &d)?)
}
