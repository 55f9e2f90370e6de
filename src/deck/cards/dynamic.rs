//! The transient cards of the paper's impact (TF, TSTEP, NOLIN3, TIC) and the
//! eigenvalue extraction cards of normal modes (EIGR, EIGRL).

use super::*;

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

/// TF.
pub(super) fn card_tf(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
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
pub(super) fn card_tstep(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
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
pub(super) fn card_nolin3(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_tic(r: &mut Reader, b: &mut Bulk) {
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

/// How eigenvectors are scaled (EIGR's NORM; EIGRL's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Norm {
    /// Unit generalised mass φᵀMφ.
    Mass,
    /// Unit largest component (of the solved DOFs).
    Max,
    /// Unit component C of point G.
    Point(i64, usize),
}

/// EIGR (NASTRAN-95 and MSC) or EIGRL (MSC): which real eigenvalues a normal modes
/// solution extracts, and how their eigenvectors are scaled.
#[derive(Debug, Clone)]
pub struct Eigr {
    /// Set id (field 2).
    pub sid: i64,
    /// EIGR's METHOD (field 3: INV, DET, GIV, MGIV, FEER, …), upper case; `LAN` for
    /// an EIGRL.
    pub method: String,
    /// F1 and F2 (EIGR fields 4-5) or V1 and V2 (EIGRL fields 3-4): the frequency
    /// range, in cycles per unit time.
    pub range: [Option<f64>; 2],
    /// EIGR's NE (field 6): the estimated number of roots in range.
    pub ne: Option<i64>,
    /// ND (EIGR field 7, EIGRL field 5): the number of roots desired.
    pub nd: Option<i64>,
    /// NORM (EIGR continuation field 2 with G and C; EIGRL field 9). MASS when blank.
    pub norm: Norm,
    /// The card.
    pub at: CardRef,
}

/// EIGR's methods: NASTRAN-95's (BULK.TXT, EIGR) and MSC's.
const EIGR_METHODS: [&str; 15] = [
    "INV", "DET", "GIV", "MGIV", "FEER", "FEER-Q", "FEER-X", "UINV", "UDET", "SINV", "HOU", "MHOU", "AHOU", "LAN",
    "AGIV",
];

/// EIGR: `EIGR SID METHOD F1 F2 NE ND NZ E` and `+ NORM G C`.
pub(super) fn card_eigr(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let method = r.word(1, "METHOD").to_ascii_uppercase();
    if !EIGR_METHODS.contains(&method.as_str()) {
        r.fail(
            1,
            "METHOD",
            format!("is not an eigenvalue extraction method ({})", EIGR_METHODS.join(", ")),
        );
    }
    let range = [r.real_opt(2, "F1"), r.real_opt(3, "F2")];
    for (k, f) in range.iter().enumerate() {
        if let Some(f) = f {
            r.non_negative(2 + k, ["F1", "F2"][k], *f);
        }
    }
    let ne = r.int_opt(4, "NE");
    let nd = root_count(r, 5);
    r.int_opt(6, "NZ");
    r.real_opt(7, "E");
    let norm = norm(r, 8, Some((9, 10)));
    r.extra_fields(11);
    if r.ok {
        b.eigrs.push(Eigr {
            sid,
            method,
            range,
            ne,
            nd,
            norm,
            at: r.at(),
        });
    }
}

/// EIGRL (MSC): `EIGRL SID V1 V2 ND MSGLVL MAXSET SHFSCL NORM`; its continuation of
/// options (ALPH, NUMS, Fi) is not read.
pub(super) fn card_eigrl(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let range = [r.real_opt(1, "V1"), r.real_opt(2, "V2")];
    let nd = root_count(r, 3);
    r.int_opt(4, "MSGLVL");
    r.int_opt(5, "MAXSET");
    r.real_opt(6, "SHFSCL");
    let norm = norm(r, 7, None);
    for k in 8..r.card.fields.len() {
        if !r.text(k).is_empty() {
            r.fail(
                k,
                "option",
                "EIGRL's options (ALPH, NUMS, Fi) are not read by impactlab",
            );
            break;
        }
    }
    if r.ok {
        b.eigrs.push(Eigr {
            sid,
            method: "LAN".into(),
            range,
            ne: None,
            nd,
            norm,
            at: r.at(),
        });
    }
}

/// ND at field `k`: the number of roots desired, when positive (0 reads as blank).
fn root_count(r: &mut Reader, k: usize) -> Option<i64> {
    let nd = r.int_opt(k, "ND");
    if nd.is_some_and(|n| n < 0) {
        r.fail(k, "ND", "must not be negative");
    }
    nd.filter(|&n| n > 0)
}

/// NORM at field `k` (MASS when blank), with POINT's G and C at fields `point`.
fn norm(r: &mut Reader, k: usize, point: Option<(usize, usize)>) -> Norm {
    match r.word(k, "NORM").to_ascii_uppercase().as_str() {
        "" | "MASS" => Norm::Mass,
        "MAX" => Norm::Max,
        "POINT" => match point {
            Some((g, c)) => {
                let g = r.id(g, "G");
                Norm::Point(g, r.component(c, "C"))
            }
            None => {
                r.fail(k, "NORM", "is MASS or MAX on an EIGRL");
                Norm::Mass
            }
        },
        _ => {
            r.fail(k, "NORM", "is not MASS, MAX or POINT");
            Norm::Mass
        }
    }
}
