//! Static loads: FORCE, MOMENT, PLOAD4, GRAV and their LOAD combinations, and the
//! temperature fields of a thermal load (TEMPRB, TEMPP1, TEMP, TEMPD).

use super::*;

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

/// PLOAD: a pressure P on the triangle or quadrilateral of three or four grids.
#[derive(Debug, Clone)]
pub struct Pload {
    /// Load set id (field 2).
    pub sid: i64,
    /// The pressure P (field 3).
    pub p: f64,
    /// Its grids G1..G3 (G4).
    pub grids: Vec<i64>,
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

/// TEMPRB: a temperature field on bars, for a thermal load (BULK.TXT, TEMPRB).
#[derive(Debug, Clone)]
pub struct Temprb {
    /// Temperature set id (field 2).
    pub sid: i64,
    /// The elements it applies to: EID1 (field 3) and those of the second and later
    /// continuations (with THRU).
    pub eids: Vec<i64>,
    /// TA, TB and the effective gradients T′1a, T′1b, T′2a, T′2b (fields 4-9). The
    /// first continuation's point temperatures serve NASTRAN's stress recovery only,
    /// which a static run of impactlab does not write: they are read and not used.
    pub temperature: crate::elements::bar::BarTemperature,
    /// The card.
    pub at: CardRef,
}

/// TEMPP1: a plate's temperature, its average T over the cross-section and its
/// effective linear gradient T′ (BULK.TXT, TEMPP1); one entry an element.
#[derive(Debug, Clone)]
pub struct Tempp1 {
    /// Temperature set id (field 2).
    pub sid: i64,
    /// The element.
    pub eid: i64,
    /// T (field 4).
    pub average: f64,
    /// T′ (field 5; "not used for membranes").
    pub gradient: f64,
    /// The card.
    pub at: CardRef,
}

/// TEMP (a grid's temperature; one entry a grid) or TEMPD (the default of every grid
/// a TEMP does not give; `grid` is `None`).
#[derive(Debug, Clone)]
pub struct GridTemperature {
    /// Temperature set id.
    pub sid: i64,
    /// The grid; `None` for a TEMPD default.
    pub grid: Option<i64>,
    /// The temperature.
    pub t: f64,
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

/// The vector F·(N1, N2, N3) of fields `k`.. (`k + 3`), named after the card's.
pub(super) fn scaled_vector(r: &mut Reader, k: usize, names: [&str; 4]) -> [f64; 3] {
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
pub(super) fn system_id(r: &mut Reader, k: usize) -> i64 {
    let cid = r.int_or(k, "CID", 0);
    if cid < 0 {
        r.fail(k, "CID", "must be 0 (basic) or a coordinate system id");
    }
    cid
}

/// FORCE and MOMENT: SID G CID F N1 N2 N3.
pub(super) fn card_point_load(r: &mut Reader, b: &mut Bulk) {
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
/// PLOAD (`manual/BULK.TXT`): SID P G1 G2 G3 (G4; 0 or blank for a triangle).
pub(super) fn card_pload(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let p = r.real(1, "P");
    let mut grids: Vec<i64> = (0..3).map(|k| r.id(2 + k, &format!("G{}", k + 1))).collect();
    if !matches!(r.text(5), "" | "0") {
        grids.push(r.id(5, "G4"));
    }
    let mut unique = grids.clone();
    unique.sort_unstable();
    unique.dedup();
    if r.ok && unique.len() != grids.len() {
        r.fail(2, "G1-G4", "the grids must be distinct");
    }
    r.extra_fields(6);
    if r.ok {
        b.ploads.push(Pload {
            sid,
            p,
            grids,
            at: r.at(),
        });
    }
}

/// PLOAD2 (`manual/BULK.TXT`): SID P EID … (THRU ranges; 0 or blank for an omitted
/// entry): a uniform pressure P on each listed shell, read as a PLOAD4 of P at every
/// corner along the element's normal (G1→G2→G3, PLOAD's +r12 × r13). On a triangle and
/// a parallelogram its nodal forces are NASTRAN-95's (a third, a quarter of P·A); on
/// another quadrilateral NASTRAN-95 averages four triangles, the consistent forces
/// differ by the shape's departure from a parallelogram.
pub(super) fn card_pload2(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let p = r.real(1, "P");
    let n = r.card.fields.len();
    let mut eids: Vec<i64> = Vec::new();
    let mut k = 2;
    while r.ok && k < n {
        let t = r.text(k);
        if t.is_empty() || t == "0" {
            k += 1;
            continue;
        }
        if t.eq_ignore_ascii_case("THRU") {
            let (Some(&a), last) = (eids.last(), r.id(k + 1, "EID")) else {
                r.fail(k, "EID", "THRU has no element before it");
                break;
            };
            if r.ok && last < a {
                r.fail(
                    k + 1,
                    "EID",
                    format!("ends a THRU range that is reversed ({a} THRU {last})"),
                );
            }
            if let Err(e) = crate::deck::take_ids(r.ids_left, (last - a).max(0) as u128) {
                r.fail(k + 1, "EID", e);
            }
            if r.ok {
                eids.extend(a + 1..=last);
            }
            k += 2;
            continue;
        }
        eids.push(r.id(k, "EID"));
        k += 1;
    }
    if r.ok && eids.is_empty() {
        r.fail(2, "EID", "names no element");
    }
    if r.ok {
        b.pload4s.push(Pload4 {
            sid,
            eids,
            p: [p; 4],
            cid: 0,
            direction: None,
            at: r.at(),
        });
    }
}

pub(super) fn card_pload4(r: &mut Reader, b: &mut Bulk) {
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
            if let Err(e) = crate::deck::take_ids(r.ids_left, (last - eid) as u128) {
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
pub(super) fn card_grav(r: &mut Reader, b: &mut Bulk) {
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

/// TEMPRB: SID EID1 TA TB T′1a T′1b T′2a T′2b, the point temperatures TCa … TFb,
/// then EID2 … (THRU allowed) on the cards after.
pub(super) fn card_temprb(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let mut eids = vec![r.id(1, "EID1")];
    let v: Vec<f64> = (2..8)
        .map(|k| r.real_or(k, ["TA", "TB", "T'1a", "T'1b", "T'2a", "T'2b"][k - 2], 0.0))
        .collect();
    for k in 8..16 {
        r.real_or(k, ["TCa", "TDa", "TEa", "TFa", "TCb", "TDb", "TEb", "TFb"][k - 8], 0.0);
    }
    eids.extend(r.id_list(16, "EIDn"));
    let t = Temprb {
        sid,
        eids,
        temperature: crate::elements::bar::BarTemperature {
            average: [v[0], v[1]],
            gradient: [[v[2], v[3]], [v[4], v[5]]],
        },
        at: r.at(),
    };
    if r.ok {
        b.temprbs.push(t);
    }
}

/// TEMPP1: `SID EID1 T T′ T1 T2`, then continuations of further EIDs (THRU allowed).
/// T1 and T2 serve NASTRAN's stress recovery only, which impactlab does not make under
/// a thermal load: read and not used.
pub(super) fn card_tempp1(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let mut eids = vec![r.id(1, "EID1")];
    let average = r.real(2, "T");
    let gradient = r.real_or(3, "T'", 0.0);
    r.real_or(4, "T1", 0.0);
    r.real_or(5, "T2", 0.0);
    r.extra_fields_in(6, 8);
    eids.extend(r.id_list(8, "EIDn"));
    if r.ok {
        let at = r.at();
        b.tempp1s.extend(eids.into_iter().map(|eid| Tempp1 {
            sid,
            eid,
            average,
            gradient,
            at: at.clone(),
        }));
    }
}

/// TEMP (`SID G1 T1 G2 T2 G3 T3`, "from one to three grid point temperatures") and
/// TEMPD (`SID1 T1 … SID4 T4`, "from one to four default temperatures").
pub(super) fn card_temp(r: &mut Reader, b: &mut Bulk) {
    let default = r.card.name == "TEMPD";
    let mut read = Vec::new();
    let (pairs, last) = if default {
        (vec![0, 2, 4, 6], 8)
    } else {
        (vec![1, 3, 5], 7)
    };
    let sid = if default { 0 } else { r.id(0, "SID") };
    for k in pairs {
        if r.text(k).is_empty() && r.text(k + 1).is_empty() {
            continue;
        }
        read.push(match default {
            true => (r.id(k, "SID"), None, r.real(k + 1, "T")),
            false => (sid, Some(r.id(k, "G")), r.real(k + 1, "T")),
        });
    }
    r.extra_fields(last);
    if r.ok {
        let at = r.at();
        b.temperatures
            .extend(read.into_iter().map(|(sid, grid, t)| GridTemperature {
                sid,
                grid,
                t,
                at: at.clone(),
            }));
    }
}

/// LOAD and DLOAD: `SID S S1 L1 S2 L2 …`, the static (LOAD) or dynamic (DLOAD) load
/// S Σ Sᵢ Pᵢ. Both cards' remarks (BULK.TXT): "The Li must be unique"; a set does not
/// include itself (DLOAD: "SID must be different from all Li").
pub(super) fn card_load(r: &mut Reader, b: &mut Bulk) {
    let name = r.card.name.clone();
    let sid = r.id(0, "SID");
    let scale = r.real(1, "S");
    let mut terms: Vec<(f64, i64)> = Vec::new();
    let mut k = 2;
    while k < r.card.fields.len() {
        if r.text(k).is_empty() && r.text(k + 1).is_empty() {
            k += 2;
            continue;
        }
        let s = r.real(k, "Si");
        let l = r.id(k + 1, "Li");
        if r.ok && l == sid {
            r.fail(k + 1, "Li", format!("{name} {sid} cannot include itself"));
        }
        if r.ok && terms.iter().any(|&(_, x)| x == l) {
            r.fail(k + 1, "Li", "is listed twice (\"The Li must be unique\")");
        }
        terms.push((s, l));
        k += 2;
    }
    if r.ok && terms.is_empty() {
        r.fail(2, "S1", format!("{name} combines no set"));
    }
    let l = LoadCombination {
        sid,
        scale,
        terms,
        at: r.at(),
    };
    if r.ok {
        match name.as_str() {
            "DLOAD" => b.dloads.push(l),
            _ => b.load_combinations.push(l),
        }
    }
}
