//! Constraints and rigid elements: SPC, SPC1, SPCADD, SPCD, RBE2, RBE3, CRIGD1.

use super::*;

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

/// SPCD: an enforced displacement of a static load set, on components a selected SPC
/// constrains (one SPCD card holds one or two of these).
#[derive(Debug, Clone)]
pub struct Spcd {
    /// The load set id (field 2).
    pub sid: i64,
    /// The grid (or scalar point).
    pub point: i64,
    /// Its components (none for a scalar point).
    pub c: Components,
    /// The enforced value D.
    pub d: f64,
    /// Where G is written.
    pub at_point: FieldRef,
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
/// independent grid GN's motion as a rigid body. COSMIC's CRIGD1 is the RBE2 of all six
/// components.
#[derive(Debug, Clone)]
pub struct Rbe2 {
    /// The card's name: `RBE2` or `CRIGD1`.
    pub card: &'static str,
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

/// SPC1.
pub(super) fn card_spc1(r: &mut Reader, b: &mut Bulk) {
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

/// SPC: SID G1 C1 D1 G2 C2 D2, each grid's components held (an SPC1 each), at D:
/// a static solution enforces it, a transient run refuses D ≠ 0.
pub(super) fn card_spc(r: &mut Reader, b: &mut Bulk) {
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

/// SPCD: SID G1 C1 D1 G2 C2 D2 (`manual/BULK.TXT`, SPCD): enforced displacements
/// of load set SID, "requested as a LOAD", on components a selected SPC constrains.
pub(super) fn card_spcd(r: &mut Reader, b: &mut Bulk) {
    let sid = r.id(0, "SID");
    let mut out = Vec::new();
    for (k, names) in [(1, ["G1", "C1", "D1"]), (4, ["G2", "C2", "D2"])] {
        if k == 4 && (4..7).all(|i| r.text(i).is_empty()) {
            break;
        }
        out.push(Spcd {
            sid,
            point: r.id(k, names[0]),
            c: r.components(k + 1, names[1]),
            d: r.real(k + 2, names[2]),
            at_point: r.field_ref(k, names[0]),
            at: r.at(),
        });
    }
    r.extra_fields(7);
    if r.ok {
        b.spcds.extend(out);
    }
}

/// SPCADD: SID S1 S2 …: the union of constraint sets.
pub(super) fn card_spcadd(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_rbe2(r: &mut Reader, b: &mut Bulk) {
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
    let gm = dependent_grids(r, 3, alpha.unwrap_or(n), gn, ["GM", "GN"]);
    if r.ok {
        b.rbe2s.push(Rbe2 {
            card: "RBE2",
            eid,
            gn,
            cm,
            gm,
            at: r.at(),
        });
    }
}

/// A rigid element's dependent grids, fields `from` up to `to` (THRU ranges allowed):
/// refused when none, or when one is the independent grid `independent` (named at the
/// field that names it, or ends the THRU range that holds it). `names`: the list's
/// field name and the independent grid's.
fn dependent_grids(r: &mut Reader, from: usize, to: usize, independent: i64, names: [&str; 2]) -> Vec<i64> {
    let gm = r.id_list_in(from, to, names[0]);
    if r.ok && gm.is_empty() {
        r.fail(from, names[0], "names no dependent grid");
    }
    if r.ok && gm.contains(&independent) {
        let int = |k: usize| parse_int(r.text(k)).unwrap_or(i64::MIN);
        let k = (from..to)
            .find(|&k| int(k) == independent)
            .or_else(|| {
                (from + 1..to.saturating_sub(1))
                    .find(|&k| {
                        r.text(k).eq_ignore_ascii_case("THRU") && int(k - 1) <= independent && independent <= int(k + 1)
                    })
                    .map(|k| k + 1)
            })
            .unwrap_or(from);
        r.fail(
            k,
            names[0],
            format!(
                "names the independent grid {} = {independent} as a dependent grid",
                names[1]
            ),
        );
    }
    gm
}

/// CRIGD1 (COSMIC): EID, IG, then the dependent grids G1, G2, … (or `GID1 THRU GID2`),
/// every one of whose six components follows the reference grid IG as a rigid body
/// (`manual/BULK.TXT`, CRIGD1): an RBE2 with CM = 123456.
pub(super) fn card_crigd1(r: &mut Reader, b: &mut Bulk) {
    let (eid, ig) = (r.id(0, "EID"), r.id(1, "IG"));
    let n = r.card.fields.len();
    let gm = dependent_grids(r, 2, n, ig, ["Gi", "IG"]);
    if r.ok {
        b.rbe2s.push(Rbe2 {
            card: "CRIGD1",
            eid,
            gn: ig,
            cm: Components(0b11_1111),
            gm,
            at: r.at(),
        });
    }
}

/// RBE3: EID, blank, REFGRID, REFC, then groups WTi Ci Gi,1 Gi,2 … (a real starts a
/// group; THRU ranges allowed), then ALPHA and its value (no temperature load is
/// applied, so it has no effect). UM, which moves the dependency to other DOFs, is
/// refused.
pub(super) fn card_rbe3(r: &mut Reader, b: &mut Bulk) {
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
