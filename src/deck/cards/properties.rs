//! Element properties: PROD, PTUBE, PBAR, PBARL, PBEAM, PBEAML, PSHELL, PCOMP,
//! COSMIC's plate properties as the PSHELL they describe, PELAS and PMASS.

use super::*;

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

/// PSHEAR: shear panel properties.
#[derive(Debug, Clone)]
pub struct Pshear {
    /// Property id (field 2).
    pub pid: i64,
    /// MAT1 id (field 3).
    pub mid: i64,
    /// Thickness T (field 4).
    pub t: f64,
    /// Non-structural mass per unit area, NSM (field 5).
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
    /// The laminate's structural damping coefficient GE (field 8; 0.0 when blank).
    pub ge: f64,
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

/// PELAS (PID K GE S), PMASS (PID M) or PDAMP (PID B).
#[derive(Debug, Clone)]
pub struct ScalarProperty {
    /// Property id.
    pub pid: i64,
    /// K, M or B.
    pub value: f64,
    /// A PELAS's structural damping coefficient GE (0 when blank, and for PMASS and
    /// PDAMP).
    pub ge: f64,
    /// The card.
    pub at: CardRef,
}

/// Stress recovery points C1 C2 D1 D2 E1 E2 F1 F2 of PBAR and PBEAM, from field `k`.
pub(super) fn recovery_points(r: &mut Reader, k: usize) -> [[f64; 2]; 4] {
    const NAMES: [&str; 8] = ["C1", "C2", "D1", "D2", "E1", "E2", "F1", "F2"];
    std::array::from_fn(|p| std::array::from_fn(|i| r.real_or(k + 2 * p + i, NAMES[2 * p + i], 0.0)))
}

/// PBAR (PID MID A I1 I2 J NSM; C1..F2; K1 K2 I12) and a constant PBEAM (PID MID A
/// I1 I2 I12 J NSM; C1..F2). K1, K2 (shear flexibility) and a PBEAM's further
/// stations are refused: the element is Euler-Bernoulli and of one section.
pub(super) fn card_pbar(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_pbarl(r: &mut Reader, b: &mut Bulk) {
    use crate::elements::section::Shape;
    let (pid, mid) = (r.id(0, "PID"), r.id(1, "MID"));
    let group = r.word(2, "GROUP");
    if !group.is_empty() && !group.eq_ignore_ascii_case("MSCBML0") {
        r.fail(
            2,
            "GROUP",
            "only the standard section library (GROUP blank or MSCBML0) is supported",
        );
    }
    let shape = Shape::named(r.word(3, "TYPE"));
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
pub(super) fn card_prod(r: &mut Reader, b: &mut Bulk) {
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

/// PSHEAR: PID MID T NSM, then MSC's F1 F2 (the edges' effectiveness in
/// extension): blank or 0 (a panel of shear only, NASTRAN-95's and MSC's default);
/// other values are refused, the panel's extension is not modelled. COSMIC writes a
/// second property in fields 6-9 ([`super::pieces`] splits it off when field 6 is an
/// integer).
pub(super) fn card_pshear(r: &mut Reader, b: &mut Bulk) {
    let p = Pshear {
        pid: r.id(0, "PID"),
        mid: r.id(1, "MID"),
        t: r.real(2, "T"),
        nsm: r.real_or(3, "NSM", 0.0),
        at: r.at(),
    };
    r.positive(2, "T", p.t);
    r.non_negative(3, "NSM", p.nsm);
    for (k, name) in [(4, "F1"), (5, "F2")] {
        if r.real_or(k, name, 0.0) != 0.0 && r.ok {
            r.fail(
                k,
                name,
                "gives the panel's edges extensional stiffness, which is not supported: leave it blank",
            );
        }
    }
    r.extra_fields(6);
    if r.ok {
        b.pshears.push(p);
    }
}

/// PTUBE: PID MID OD T NSM (OD2): a tube's area and torsional constant,
/// A = π/4 (OD² − ID²), J = π/32 (OD⁴ − ID⁴), ID = OD − 2T; "if T is zero, a solid
/// circular rod is assumed". A tapered tube (OD2 ≠ OD) is refused.
pub(super) fn card_ptube(r: &mut Reader, b: &mut Bulk) {
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

/// PELAS (PID K GE S), PMASS (PID M) and PDAMP (PID B): a scalar element's
/// property, PMASS and PDAMP up to four on a card.
pub(super) fn card_scalar_property(r: &mut Reader, b: &mut Bulk) {
    let role = match r.card.name.as_str() {
        "PELAS" => ScalarRole::Spring,
        "PMASS" => ScalarRole::Mass,
        _ => ScalarRole::Damper,
    };
    let mut p = ScalarProperty {
        pid: r.id(0, "PID"),
        value: r.real(1, role.value_name()),
        ge: 0.0,
        at: r.at(),
    };
    if role == ScalarRole::Spring {
        p.ge = r.real_or(2, "GE", 0.0);
        r.non_negative(2, "GE", p.ge);
        r.real_opt(3, "S");
        r.extra_fields(4);
    } else {
        r.extra_fields(2);
    }
    if r.ok {
        match role {
            ScalarRole::Spring => b.pelas.push(p),
            ScalarRole::Mass => b.pmass.push(p),
            ScalarRole::Damper => b.pdamps.push(p),
        }
    }
}

/// COSMIC's plate properties as the PSHELL they are: PQUAD1, PTRIA1 (PID MID1 T1 MID2
/// I MID3 T3 NSM: MID1, T = T1, MID2, 12I/T³ = 12 I/T1³, MID3, TS/T = T3/T1, NSM);
/// PQUAD2, PTRIA2 (PID MID T NSM: MID1 = MID2 = MID, 12I/T³ = 1); PQDMEM, PQDMEM1,
/// PQDMEM2, PTRMEM (PID MID T NSM: a membrane, MID1 = MID).
pub(super) fn card_cosmic_plate_property(r: &mut Reader, b: &mut Bulk) {
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
        let card = crate::deck::case::static_name(&name, &COSMIC_PLATE_PROPERTIES);
        b.cosmic_plates.push((card, p));
    }
}

/// COSMIC's plate property cards.
pub(super) const COSMIC_PLATE_PROPERTIES: [&str; 8] = [
    "PQUAD1", "PTRIA1", "PQUAD2", "PTRIA2", "PQDMEM", "PQDMEM1", "PQDMEM2", "PTRMEM",
];

/// PSHELL.
pub(super) fn card_pshell(r: &mut Reader, b: &mut Bulk) {
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

/// PCOMP: PID Z0 NSM SB FT TREF GE LAM / then per ply MID T THETA SOUT, four plies a
/// line. A ply exists when any of its four fields is given; a blank MID or T repeats
/// the ply above (the first ply needs both), a blank THETA is 0.0, a blank SOUT is NO.
/// LAM is blank or SYM (the plies listed are then the bottom half).
pub(super) fn card_pcomp(r: &mut Reader, b: &mut Bulk) {
    let pid = r.id(0, "PID");
    let z0 = r.real_opt(1, "Z0");
    let nsm = r.real_or(2, "NSM", 0.0);
    let sb = r.real_opt(3, "SB");
    if let Some(v) = sb {
        r.positive(3, "SB", v);
    }
    let ft = match r.word(4, "FT").to_ascii_uppercase().as_str() {
        "" => None,
        f @ ("HILL" | "HOFF" | "TSAI" | "STRN") => Some(f.to_string()),
        _ => {
            r.fail(4, "FT", "must be HILL, HOFF, TSAI or STRN (or blank)");
            None
        }
    };
    r.real_opt(5, "TREF");
    let ge = r.real_or(6, "GE", 0.0);
    r.non_negative(6, "GE", ge);
    let lam = match r.word(7, "LAM").to_ascii_uppercase().as_str() {
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
        let t = ply_thickness(r, k + 1, &t_name, above.as_ref());
        let theta = r.real_or(k + 2, &theta_name, 0.0);
        let sout = match r.word(k + 3, &sout_name).to_ascii_uppercase().as_str() {
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
        ge,
        plies,
        lam,
        at: r.at(),
    };
    if r.ok {
        b.pcomps.push(p);
    }
}

/// COSMIC's PCOMP1 (PID ZOC NSM SBOND FT MID TPLY LOPT / TH1 TH2 ...: every ply of one
/// material and one thickness) and PCOMP2 (PID ZOC NSM SBOND FT MID _ LOPT / T1 TH1
/// T2 TH2 ...: every ply of one material) as the PCOMP they describe. "If any of ...
/// THi are blank, then the last non-blank values ... will be used". LOPT = SYM is
/// read as MSC's LAM = SYM (the listed plies mirrored), and `check` says so; MEM and
/// SYMMEM (laminates of membrane plies) and FT = STRESS are refused.
pub(super) fn card_pcomp_uniform(r: &mut Reader, b: &mut Bulk) {
    let one_thickness = r.card.name == "PCOMP1";
    let pid = r.id(0, "PID");
    let z0 = r.real_opt(1, "ZOC");
    let nsm = r.real_or(2, "NSM", 0.0);
    let sb = r.real_opt(3, "SBOND");
    if let Some(v) = sb {
        r.positive(3, "SBOND", v);
    }
    let ft = match r.word(4, "FT").to_ascii_uppercase().as_str() {
        "" => None,
        f @ ("HILL" | "HOFF" | "TSAI") => Some(f.to_string()),
        "STRAIN" => Some("STRN".to_string()),
        _ => {
            r.fail(
                4,
                "FT",
                "must be HILL, HOFF, TSAI or STRAIN (or blank): maximum stress is not supported",
            );
            None
        }
    };
    let mid = r.id(5, "MID");
    let tply = if one_thickness {
        let t = r.real(6, "TPLY");
        r.positive(6, "TPLY", t);
        t
    } else {
        0.0
    };
    let lam = match r.word(7, "LAM").to_ascii_uppercase().as_str() {
        "" | "ALL" => Lam::All,
        "SYM" => Lam::Sym,
        other => {
            r.fail(
                7,
                "LOPT",
                format!("LOPT = {other} (membrane plies) is not supported: ALL or SYM"),
            );
            Lam::All
        }
    };
    let width = if one_thickness { 1 } else { 2 };
    let mut plies: Vec<Ply> = Vec::new();
    for (i, k) in (8..r.card.fields.len()).step_by(width).enumerate() {
        let n = i + 1;
        let above = plies.last().cloned();
        let t = if one_thickness {
            tply
        } else {
            ply_thickness(r, k, &format!("T{n}"), above.as_ref())
        };
        let th = k + width - 1;
        let theta = match r.real_opt(th, &format!("TH{n}")) {
            Some(v) => v,
            None => above.map(|p| p.theta).unwrap_or(0.0),
        };
        plies.push(Ply {
            mid,
            t,
            theta,
            sout: false,
        });
    }
    if plies.is_empty() && r.ok {
        r.fail(8, "TH1", "lists no ply");
    }
    r.reading("COSMIC's PCOMP1 and PCOMP2 read as the PCOMP they describe (LOPT = SYM as MSC's LAM = SYM)");
    let p = Pcomp {
        pid,
        z0,
        nsm,
        sb,
        ft,
        ge: 0.0,
        plies,
        lam,
        at: r.at(),
    };
    if r.ok {
        b.pcomps.push(p);
    }
}

/// A ply's thickness in field `k`: as written (positive), or the ply's below it when
/// blank ("the last non-blank values ... will be used"); the first ply needs one.
fn ply_thickness(r: &mut Reader, k: usize, name: &str, above: Option<&Ply>) -> f64 {
    match (r.real_opt(k, name), above) {
        (Some(t), _) => {
            r.positive(k, name, t);
            t
        }
        (None, Some(p)) => p.t,
        (None, None) => {
            r.fail(k, name, "is blank: the first ply needs a thickness");
            0.0
        }
    }
}
