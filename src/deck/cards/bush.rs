//! The bushing: CBUSH, a spring of six stiffnesses between two grids (or a grid and
//! ground), and its property PBUSH. MSC's cards (NASTRAN-95 has neither); their
//! fields as MSC's Quick Reference Guide gives them.

use super::*;

/// How a CBUSH's element axes are given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BushAxes {
    /// Those of system CID (0: basic), at GA.
    System(i64),
    /// x from GA to GB, the xy plane through the orientation vector or grid G0.
    Oriented(BarOrientation),
    /// None given: the card names neither CID nor GO/X1-X3.
    Missing,
}

/// CBUSH: EID PID GA GB GO/X1 X2 X3 CID, then S OCID S1 S2 S3.
#[derive(Debug, Clone)]
pub struct Cbush {
    /// Element id (field 2).
    pub eid: i64,
    /// Its PBUSH (field 3; the element id when blank).
    pub pid: i64,
    /// Grid GA (field 4).
    pub ga: i64,
    /// Grid GB (field 5); `None` when blank: the spring goes to ground.
    pub gb: Option<i64>,
    /// Its element axes.
    pub axes: BushAxes,
    /// The spring's place on the line GA-GB, as a fraction S from GA (0.5 when blank).
    pub s: f64,
    /// Where GO/X1 is written.
    pub orientation_at: FieldRef,
    /// The card.
    pub at: CardRef,
}

/// PBUSH: its six stiffnesses (`K` line), dampers (`B`) and structural damping
/// (`GE`).
#[derive(Debug, Clone)]
pub struct Pbush {
    /// Property id.
    pub pid: i64,
    /// K1..K6, in the element's axes (blank: 0).
    pub k: [f64; 6],
    /// B1..B6, viscous damping in the element's axes (blank: 0).
    pub b: [f64; 6],
    /// GE1, the element's structural damping coefficient (blank: 0).
    pub ge: f64,
    /// The card.
    pub at: CardRef,
}

/// CBUSH (MSC Quick Reference Guide, CBUSH). GO/X1: an integer with X2, X3 blank is
/// GO, reals are the vector X (in GA's displacement frame, as a CBAR's). CID ≥ 0
/// overrides them: "the element x-axis is along T1, the element y-axis is along T2,
/// and the element z-axis is along T3 of the CID coordinate system". OCID ≥ 0 (an
/// offset S1-S3 in system OCID) is refused: the spring is placed on the line GA-GB.
pub(super) fn card_cbush(r: &mut Reader, b: &mut Bulk) {
    let eid = r.id(0, "EID");
    let pid = if r.text(1).is_empty() { eid } else { r.id(1, "PID") };
    let ga = r.id(2, "GA");
    let gb = r.int_opt(3, "GB");
    if gb.is_some_and(|g| g <= 0) {
        r.fail(3, "GB", "must be a grid id (or blank for ground)");
    }
    if gb == Some(ga) {
        r.fail(3, "GB", "is the same grid as GA");
    }
    let orientation_at = r.field_ref(4, "GO/X1");
    let cid = r.int_opt(7, "CID");
    let axes = match (cid, parse_real(r.text(4))) {
        (Some(cid), _) => {
            if cid < 0 {
                r.fail(7, "CID", "must be 0 (basic) or a coordinate system id");
            }
            BushAxes::System(cid)
        }
        (None, None) if r.text(4).is_empty() => BushAxes::Missing,
        (None, Some(RealToken::Integer(_))) if r.text(5).is_empty() && r.text(6).is_empty() => {
            BushAxes::Oriented(BarOrientation::Grid(r.id(4, "GO")))
        }
        _ => {
            let v = [r.real(4, "X1"), r.real_or(5, "X2", 0.0), r.real_or(6, "X3", 0.0)];
            if r.ok && v.iter().all(|&x| x == 0.0) {
                r.fail(
                    4,
                    "X1",
                    "the orientation vector (X1, X2, X3) is zero: it gives no xy plane",
                );
            }
            BushAxes::Oriented(BarOrientation::Vector(v))
        }
    };
    let s = r.real_or(8, "S", 0.5);
    if !(0.0..=1.0).contains(&s) {
        r.fail(8, "S", "must be between 0.0 and 1.0 (the spring's place from GA to GB)");
    }
    if r.int_or(9, "OCID", -1) >= 0 {
        r.fail(
            9,
            "OCID",
            "an offset S1-S3 in system OCID is not taken: leave OCID blank and place the spring on the line GA-GB by S",
        );
    } else {
        r.extra_fields_in(10, 13);
    }
    r.extra_fields(13);
    if r.ok {
        b.cbushes.push(Cbush {
            eid,
            pid,
            ga,
            gb,
            axes,
            s,
            orientation_at,
            at: r.at(),
        });
    }
}

/// PBUSH (MSC Quick Reference Guide, PBUSH): PID, then lines each opened by a flag in
/// its first field, "K", "B", "GE" or "RCV", with its values after it. K1..K6 are
/// taken, B1..B6 (viscous damping) and GE1, the element's structural damping (which
/// the transient solutions turn viscous at PARAM W4); GE2..GE6, damping per direction
/// in other codes' PBUSH, are refused rather than read in a sense the deck may not
/// mean. RCV's stress and strain recovery
/// coefficients are read and not used (no stress or strain is recovered for a CBUSH).
pub(super) fn card_pbush(r: &mut Reader, b: &mut Bulk) {
    let pid = r.id(0, "PID");
    let mut k = [0.0; 6];
    let mut damping = [0.0; 6];
    let mut seen_k = false;
    let mut ge = 0.0;
    // A flag opens the first line's field 3 and any continuation's field 2.
    let n = r.card.fields.len();
    let mut at = 1;
    while at < n {
        let flag = r.word(at, "flag").to_ascii_uppercase();
        let values = if at == 1 { 2..8 } else { at + 1..at + 8 };
        match flag.as_str() {
            "" => {}
            "K" => {
                seen_k = true;
                for (i, f) in values.clone().take(6).enumerate() {
                    k[i] = r.real_or(f, K_NAMES[i], 0.0);
                    r.non_negative(f, K_NAMES[i], k[i]);
                }
                r.extra_fields_in(values.start + 6, values.end);
            }
            "B" => {
                for (i, f) in values.clone().take(6).enumerate() {
                    damping[i] = r.real_or(f, B_NAMES[i], 0.0);
                    r.non_negative(f, B_NAMES[i], damping[i]);
                }
                r.extra_fields_in(values.start + 6, values.end);
            }
            "GE" => {
                ge = r.real_or(values.start, "GE1", 0.0);
                r.non_negative(values.start, "GE1", ge);
                if let Some(f) = (values.start + 1..values.end).find(|&f| !r.text(f).is_empty()) {
                    let name = format!("GE{}", f - values.start + 1);
                    r.fail(
                        f,
                        &name,
                        "is damping per direction, which is not read: a PBUSH's GE line has one value, GE1, the \
                         whole element's structural damping (MSC's form); give damping per direction as B1..B6",
                    );
                }
            }
            "RCV" => {
                for f in values.clone().take(4) {
                    r.real_or(f, "SA/ST/EA/ET", 1.0);
                }
                r.extra_fields_in(values.start + 4, values.end);
            }
            _ => {
                r.fail(at, "flag", "is not a PBUSH flag (K, B, GE or RCV)");
                break;
            }
        }
        at = if at == 1 { 8 } else { at + 8 };
    }
    if !seen_k && r.ok {
        r.fail(1, "K", "PBUSH has no K line: the bushing would have no stiffness");
    }
    if r.ok {
        b.pbushes.push(Pbush {
            pid,
            k,
            b: damping,
            ge,
            at: r.at(),
        });
    }
}

const K_NAMES: [&str; 6] = ["K1", "K2", "K3", "K4", "K5", "K6"];
const B_NAMES: [&str; 6] = ["B1", "B2", "B3", "B4", "B5", "B6"];
