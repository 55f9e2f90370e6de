//! Element connections: the cards of [`crate::elements::KINDS`] (CROD, CQUAD4, CTRIA3,
//! CBAR, CBEAM), CONROD, COSMIC's plates read as impactlab's shells, the scalar
//! springs and masses (CELAS1-4, CMASS1-4), and the concentrated masses CONM1 and CONM2.

use super::*;

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
    pub bar: Option<Box<BarCard>>,
    /// A CONROD's own property (its PID is its EID).
    pub rod: Option<Box<Prod>>,
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

/// CONM1: a 6×6 symmetric mass matrix at a grid.
#[derive(Debug, Clone)]
pub struct Conm1 {
    /// Element id (field 2).
    pub eid: i64,
    /// Grid G (field 3).
    pub g: i64,
    /// Coordinate system CID whose axes the matrix is written in (0: basic).
    pub cid: i64,
    /// The lower triangle by rows: M11; M21, M22; M31 … M33; … M61 … M66.
    pub lower: [f64; 21],
    /// The card.
    pub at: CardRef,
}

/// What a scalar element is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScalarRole {
    /// A spring (CELASi, property PELAS).
    Spring,
    /// A mass (CMASSi, property PMASS).
    Mass,
    /// A viscous damper (CDAMPi, property PDAMP).
    Damper,
}

impl ScalarRole {
    /// The role of a scalar element card (`CELAS2`, `CMASS1`, `CDAMP4`).
    pub fn of_card(name: &str) -> ScalarRole {
        if name.starts_with("CELAS") {
            ScalarRole::Spring
        } else if name.starts_with("CMASS") {
            ScalarRole::Mass
        } else {
            ScalarRole::Damper
        }
    }

    /// Its value's name on the card: K, M or B.
    pub fn value_name(self) -> &'static str {
        match self {
            ScalarRole::Spring => "K",
            ScalarRole::Mass => "M",
            ScalarRole::Damper => "B",
        }
    }

    /// Its property card.
    pub fn property(self) -> &'static str {
        match self {
            ScalarRole::Spring => "PELAS",
            ScalarRole::Mass => "PMASS",
            ScalarRole::Damper => "PDAMP",
        }
    }
}

/// CELAS1-4, CMASS1-4 and CDAMP1-4: a scalar spring, mass or damper between two
/// DOFs.
#[derive(Debug, Clone)]
pub struct ScalarCard {
    /// Element id (field 2).
    pub eid: i64,
    /// Spring, mass or damper.
    pub role: ScalarRole,
    /// Its value: through its property (PELAS, PMASS, PDAMP) or on the card.
    pub value: ScalarValue,
    /// A CELAS2's structural damping coefficient GE (0 when blank, and for every
    /// other card: a CELAS1's is its PELAS's).
    pub ge: f64,
    /// Its two terminals (point, component 0-6): a grid's component 1-6, a scalar
    /// point's 0; point 0 is ground.
    pub terminals: [(i64, usize); 2],
    /// Where G1 (S1) is written.
    pub first_at: FieldRef,
    /// The card.
    pub at: CardRef,
}

/// GENEL: a general element, its stiffness given as a matrix over listed DOFs.
#[derive(Debug, Clone)]
pub struct GenelCard {
    /// Element id (field 2).
    pub eid: i64,
    /// The independent DOFs {uᵢ}: (point, component; 0 for a scalar point).
    pub ui: Vec<(i64, usize)>,
    /// The dependent DOFs {u_d}, after `UD`; empty when none.
    pub ud: Vec<(i64, usize)>,
    /// The matrix after `K` (stiffness) or `Z` (flexibility): true for `Z`.
    pub flexibility: bool,
    /// Its lower triangle by columns from the diagonal, m(m+1)/2 values.
    pub lower: Vec<f64>,
    /// \[S\] by rows (m × n) after `S`; `None` when not given.
    pub s: Option<Vec<f64>>,
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

/// An element card of the kinds' table: EID, PID (blank: EID), G1..Gn; a shell's
/// THETA/MCID after its grids (a real: THETA in degrees, an integer: MCID) and its
/// ZOFFS; a bar's orientation, offsets and pin flags ([`card_bar`]).
pub(super) fn card_element(r: &mut Reader, b: &mut Bulk, kind: &'static crate::elements::Kind) {
    let n = kind.grids;
    let shell = matches!(kind.build, crate::elements::Build::Shell(_));
    let eid = r.id(0, "EID");
    let mut c = Connection {
        kind,
        eid,
        pid: r.int_or(1, "PID", eid),
        g: (0..n).map(|k| r.id(2 + k, &format!("G{}", k + 1))).collect(),
        orientation: Orientation::Theta(0.0),
        orientation_at: shell.then(|| r.field_ref(2 + n, "THETA/MCID")),
        zoffs: 0.0,
        bar: None,
        rod: None,
        property_card: None,
        at: r.at(),
    };
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
        c.bar = Some(Box::new(card_bar(r)));
    } else if !shell {
        r.extra_fields(2 + n);
    }
    if r.ok {
        b.elements.push(c);
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
pub(super) fn card_bar(r: &mut Reader) -> BarCard {
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
    let offt = match (flag, r.word(7, "OFFT")) {
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

/// CELAS1 (EID PID G1 C1 G2 C2), CELAS2 (EID K G1 C1 G2 C2 GE S), CELAS3 (EID PID
/// S1 S2), CELAS4 (EID K S1 S2), and CMASS1-4 and CDAMP1-4 alike with M and B:
/// "scalar points may be used for G1 and/or G2, in which case the corresponding C1
/// and/or C2 must be zero or blank. Zero or blank may be used to indicate a grounded
/// terminal".
pub(super) fn card_scalar(r: &mut Reader, b: &mut Bulk) {
    let name = r.card.name.as_str();
    let role = ScalarRole::of_card(name);
    let spring = role == ScalarRole::Spring;
    let n = name.as_bytes()[name.len() - 1] - b'0';
    let eid = r.id(0, "EID");
    let value = if n % 2 == 1 {
        ScalarValue::Property(r.int_or(1, "PID", eid))
    } else {
        ScalarValue::Value(r.real(1, role.value_name()))
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
    let mut ge = 0.0;
    if n == 2 && spring {
        ge = r.real_or(6, "GE", 0.0);
        r.non_negative(6, "GE", ge);
        r.real_opt(7, "S");
        r.extra_fields(8);
    } else {
        r.extra_fields(if n <= 2 { 6 } else { 4 });
    }
    if r.ok {
        b.scalars.push(ScalarCard {
            eid,
            role,
            value,
            ge,
            terminals,
            first_at,
            at: r.at(),
        });
    }
}

/// GENEL: EID, blank, then the {uᵢ} list as pairs UIj CIj from field 4 on, then at
/// the start of a continuation `UD` (field 3 blank) and the {u_d} pairs, `K` or `Z`
/// and the lower triangle of the m × m matrix by columns from the diagonal (m the
/// length of {uᵢ}), and `S` and \[S\] by rows (m × n, n the length of {u_d}):
/// `manual/BULK.TXT`, GENEL. Blank fields are skipped; the counts must match.
pub(super) fn card_genel(r: &mut Reader, b: &mut Bulk) {
    let eid = r.id(0, "EID");
    let n = r.card.fields.len();
    let keyword = |t: &str| {
        ["UD", "K", "Z", "S"]
            .iter()
            .find(|w| t.eq_ignore_ascii_case(w))
            .copied()
    };
    // Sections: (keyword, first field after it, end); the UI list first.
    let mut marks: Vec<(&str, usize)> = vec![("UI", 2)];
    for k in 2..n {
        if let Some(w) = keyword(r.text(k)) {
            if k % 8 != 0 {
                r.fail(
                    k,
                    w,
                    "starts a section of the GENEL: it belongs in field 2 of a continuation",
                );
                return;
            }
            marks.push((w, k + 1));
        }
    }
    let mut ui = Vec::new();
    let mut ud = Vec::new();
    let mut matrix: Option<(bool, Vec<f64>)> = None;
    let mut s_rows = None;
    for (i, &(w, from)) in marks.iter().enumerate() {
        let to = marks.get(i + 1).map(|m| m.1 - 1).unwrap_or(n);
        if marks[..i]
            .iter()
            .any(|m| m.0 == w || (m.0 == "K" || m.0 == "Z") && (w == "K" || w == "Z"))
        {
            r.fail(from - 1, w, "is given twice");
            return;
        }
        match w {
            "UI" | "UD" => {
                // Pairs start in fields 4, 6, 8 of the first line and 2, 4, 6, 8 of a
                // continuation; UD's field 3 is blank.
                let start = if w == "UD" { from + 1 } else { from };
                if w == "UD" && !r.text(from).is_empty() {
                    r.fail(from, "UD", "field 3 after UD must be blank");
                    return;
                }
                let list = if w == "UI" { &mut ui } else { &mut ud };
                let mut k = start;
                while k < to && k < n {
                    if r.text(k).is_empty() && r.text(k + 1).is_empty() {
                        k += 2;
                        continue;
                    }
                    let name = if w == "UI" { ("UI", "CI") } else { ("UD", "CD") };
                    let (p, c) = (r.id(k, name.0), r.component(k + 1, name.1));
                    list.push((p, c));
                    k += 2;
                }
            }
            _ => {
                let mut values = Vec::new();
                for k in from..to.min(n) {
                    if !r.text(k).is_empty() {
                        values.push(r.real(k, w));
                    }
                }
                if w == "S" {
                    s_rows = Some(values);
                } else {
                    matrix = Some((w == "Z", values));
                }
            }
        }
        if !r.ok {
            return;
        }
    }
    let m = ui.len();
    if m == 0 {
        r.fail(2, "UI1", "names no independent DOF");
        return;
    }
    let Some((flexibility, lower)) = matrix else {
        r.fail(2, "K/Z", "gives no K or Z matrix");
        return;
    };
    let at_of = |w: &str| marks.iter().find(|x| x.0 == w).map(|x| x.1 - 1).unwrap_or(2);
    if lower.len() != m * (m + 1) / 2 {
        let k = at_of(if flexibility { "Z" } else { "K" });
        r.fail(
            k,
            if flexibility { "Z" } else { "K" },
            format!(
                "has {} values: the lower triangle of a {m} × {m} matrix (the UI list's length) has {}",
                lower.len(),
                m * (m + 1) / 2
            ),
        );
        return;
    }
    if let Some(sv) = &s_rows {
        if ud.is_empty() {
            r.fail(at_of("S"), "S", "is given without a UD list");
            return;
        }
        if sv.len() != m * ud.len() {
            r.fail(
                at_of("S"),
                "S",
                format!(
                    "has {} values: [S] is {m} × {} (UI by UD), {} values",
                    sv.len(),
                    ud.len(),
                    m * ud.len()
                ),
            );
            return;
        }
    }
    let mut all: Vec<(i64, usize)> = ui.iter().chain(&ud).copied().collect();
    all.sort_unstable();
    if let Some(w) = all.windows(2).find(|w| w[0] == w[1]) {
        r.fail(2, "UI/UD", format!("lists point {} component {} twice", w[0].0, w[0].1));
        return;
    }
    b.genels.push(GenelCard {
        eid,
        ui,
        ud,
        flexibility,
        lower,
        s: s_rows,
        at: r.at(),
    });
}

/// COSMIC's plates, EID PID G1 G2 G3 (G4) THETA, read as impactlab's CQUAD4 and
/// CTRIA3 of the same property: QUAD1, TRIA1 (membrane, bending and transverse shear
/// of their PQUAD1, PTRIA1), QUAD2, TRIA2 (homogeneous thin plates) and QDMEM,
/// QDMEM1, QDMEM2, TRMEM (membranes). The structure is the deck's; the element is
/// impactlab's (NASTRAN-95's are other formulations), and `check` says so.
pub(super) fn card_cosmic_plate(r: &mut Reader, b: &mut Bulk) {
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

/// CONROD: EID G1 G2 MID A J C NSM, a rod with its property on its card.
pub(super) fn card_conrod(r: &mut Reader, b: &mut Bulk) {
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
            rod: Some(Box::new(p)),
            property_card: None,
            at: r.at(),
        });
    }
}

/// CONM1 (`manual/BULK.TXT`, CONM1: "Defines a 6x6 symmetric mass matrix at a
/// geometric grid point"; CID "for the mass matrix (Integer >= 0)").
pub(super) fn card_conm1(r: &mut Reader, b: &mut Bulk) {
    let cid = r.int_or(2, "CID", 0);
    if cid < 0 {
        r.fail(2, "CID", "must be 0 (basic) or a coordinate system id");
    }
    let mut lower = [0.0; 21];
    let mut k = 0;
    for row in 1..=6 {
        for col in 1..=row {
            lower[k] = r.real_or(3 + k, CONM1_NAMES[k], 0.0);
            if row == col {
                r.non_negative(3 + k, CONM1_NAMES[k], lower[k]);
            }
            k += 1;
        }
    }
    let c = Conm1 {
        eid: r.id(0, "EID"),
        g: r.id(1, "G"),
        cid,
        lower,
        at: r.at(),
    };
    r.extra_fields(24);
    if r.ok {
        b.conm1s.push(c);
    }
}

/// The names of CONM1's 21 mass fields, in card order.
const CONM1_NAMES: [&str; 21] = [
    "M11", "M21", "M22", "M31", "M32", "M33", "M41", "M42", "M43", "M44", "M51", "M52", "M53", "M54", "M55", "M61",
    "M62", "M63", "M64", "M65", "M66",
];

/// CONM2.
pub(super) fn card_conm2(r: &mut Reader, b: &mut Bulk) {
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
