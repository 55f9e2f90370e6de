//! Grids, scalar and extra points, and coordinate systems: GRID, GRDSET, SPOINT,
//! EPOINT, CORD1R/C/S, CORD2R/C/S.

use super::*;

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

/// GRID.
pub(super) fn card_grid(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_grdset(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn coord_kind(name: &str) -> CoordKind {
    match name.as_bytes().last() {
        Some(b'C') => CoordKind::Cylindrical,
        Some(b'S') => CoordKind::Spherical,
        _ => CoordKind::Rectangular,
    }
}

/// CORD1R, CORD1C, CORD1S: CIDA G1A G2A G3A CIDB G1B G2B G3B, one or two systems,
/// each from three distinct grids.
pub(super) fn card_cord1(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_cord2(r: &mut Reader, b: &mut Bulk) {
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
pub(super) fn card_points(r: &mut Reader, b: &mut Bulk, card: &RawCard) {
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
