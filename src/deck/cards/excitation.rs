//! The dynamic load cards of transient response: DAREA, DELAY, TLOAD1, TLOAD2,
//! TABLED1-4 and MSC's LSEQ (DLOAD is read as LOAD is, in `loads.rs`), as NASTRAN-95's User's Manual (`manual/BULK.TXT`) defines
//! them, with MSC's additions read where they mean the same (TLOAD's TYPE field, a
//! real DELAY, TABLED1's axes).

use super::*;

/// DAREA: the scale factor A of a dynamic load on one DOF (one entry per P, C, A).
#[derive(Debug, Clone)]
pub struct Darea {
    /// Set id (field 2).
    pub sid: i64,
    /// Grid or scalar point P.
    pub p: i64,
    /// Its component C (0 for a scalar point).
    pub c: usize,
    /// Scale (area) factor A.
    pub a: f64,
    /// The card.
    pub at: CardRef,
}

/// DELAY: the time delay τ of a dynamic load on one DOF (one entry per P, C, T).
#[derive(Debug, Clone)]
pub struct Delay {
    /// Set id (field 2).
    pub sid: i64,
    /// Grid or scalar point P.
    pub p: i64,
    /// Its component C (0 for a scalar point).
    pub c: usize,
    /// Time delay T.
    pub t: f64,
    /// The card.
    pub at: CardRef,
}

/// A TLOAD's DELAY field (field 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DelayRef {
    /// Blank or 0: no delay.
    None,
    /// An integer: the DELAY set giving each DOF its delay (NASTRAN-95 and MSC).
    Set(i64),
    /// A real: the delay of every DOF of the load (MSC).
    Value(f64),
}

/// TLOAD2's time function: t̃^B·e^(C t̃)·cos(2πF t̃ + P) for T1 ≤ t ≤ T2 (t already
/// shifted by the delay, t̃ = t − T1), zero otherwise; P is in degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Formula {
    /// T1 (field 6).
    pub t1: f64,
    /// T2 (field 7).
    pub t2: f64,
    /// F, cycles per unit time (field 8).
    pub f: f64,
    /// P, the phase in degrees (field 9).
    pub p: f64,
    /// C, the exponential coefficient (continuation field 2).
    pub c: f64,
    /// B, the growth exponent (continuation field 3).
    pub b: f64,
}

impl Formula {
    /// The value at t − τ (NASTRAN-95 BULK.TXT, TLOAD2).
    pub fn value(&self, t: f64) -> f64 {
        if t < self.t1 || t > self.t2 {
            return 0.0;
        }
        let s = t - self.t1;
        s.powf(self.b) * (self.c * s).exp() * (2.0 * std::f64::consts::PI * self.f * s + self.p.to_radians()).cos()
    }
}

/// The time function of a TLOAD.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TloadShape {
    /// TLOAD1: P(t) = A·F(t − τ), F the TABLEDi with this id (field 6).
    Table(i64),
    /// TLOAD2: P(t) = A·f(t − τ), f its formula.
    Formula(Formula),
}

/// TLOAD1 or TLOAD2: a time-dependent load on the DOFs of a DAREA set.
#[derive(Debug, Clone)]
pub struct Tload {
    /// Set id (field 2).
    pub sid: i64,
    /// The DAREA set L (NASTRAN-95) or EXCITEID (MSC), field 3.
    pub excite: i64,
    /// DELAY (field 4).
    pub delay: DelayRef,
    /// The time function.
    pub shape: TloadShape,
    /// The card.
    pub at: CardRef,
}

/// The algorithm of a TABLEDi.
#[derive(Debug, Clone, PartialEq)]
pub enum TableFunction {
    /// TABLED1-3: y(x) by linear interpolation of the points at (x − X1)/X2 (X1 = 0,
    /// X2 = 1 for TABLED1; X2 = 1 for TABLED2), extrapolated linearly from the two
    /// end points; at a jump, the average of its two values.
    Points {
        /// X1.
        x1: f64,
        /// X2 (not 0).
        x2: f64,
        /// The (x, y) entries in ascending x (a descending table is reversed), SKIP
        /// entries left out.
        points: Vec<(f64, f64)>,
    },
    /// TABLED4: y(x) = Σ A_i ((x − X1)/X2)^i, x held to [X3, X4].
    Power {
        /// X1.
        x1: f64,
        /// X2 (not 0).
        x2: f64,
        /// X3.
        x3: f64,
        /// X4 (> X3).
        x4: f64,
        /// A_0, A_1, ….
        a: Vec<f64>,
    },
}

impl TableFunction {
    /// The table's value at x, by the algorithm of its TABLEDi (BULK.TXT remark 6).
    pub fn value(&self, x: f64) -> f64 {
        match self {
            TableFunction::Points { x1, x2, points } => interpolate(points, (x - x1) / x2),
            TableFunction::Power { x1, x2, x3, x4, a } => {
                let s = (x.clamp(*x3, *x4) - x1) / x2;
                a.iter().rev().fold(0.0, |acc, &ai| acc * s + ai)
            }
        }
    }
}

/// Linear interpolation in ascending points (at least two), linear extrapolation
/// from the two end points, the average at a jump.
fn interpolate(points: &[(f64, f64)], x: f64) -> f64 {
    let n = points.len();
    let line = |(x0, y0): (f64, f64), (x1, y1): (f64, f64)| y0 + (y1 - y0) * (x - x0) / (x1 - x0);
    if x <= points[0].0 {
        return if x == points[0].0 {
            points[0].1
        } else {
            line(points[0], points[1])
        };
    }
    if x >= points[n - 1].0 {
        return if x == points[n - 1].0 {
            points[n - 1].1
        } else {
            line(points[n - 2], points[n - 1])
        };
    }
    // The first point at or beyond x.
    let k = points.partition_point(|p| p.0 < x);
    if points[k].0 == x {
        // At a tabulated x: the average of every value listed there (a jump).
        let same: Vec<f64> = points[k..].iter().take_while(|p| p.0 == x).map(|p| p.1).collect();
        return same.iter().sum::<f64>() / same.len() as f64;
    }
    line(points[k - 1], points[k])
}

/// TABLED1-4.
#[derive(Debug, Clone)]
pub struct Tabled {
    /// Table id (field 2).
    pub id: i64,
    /// Its algorithm and entries.
    pub function: TableFunction,
    /// The card.
    pub at: CardRef,
}

/// DAREA and DELAY: one or two (P, C, value) triples.
pub(super) fn card_darea_delay(r: &mut Reader, b: &mut Bulk, delay: bool) {
    let sid = r.id(0, "SID");
    let value = if delay { "T" } else { "A" };
    for k in [1, 4] {
        if k == 4 && (4..7).all(|i| r.text(i).is_empty()) {
            break;
        }
        let p = r.id(k, "P");
        let c = r.component(k + 1, "C");
        let v = r.real(k + 2, value);
        if !r.ok {
            return;
        }
        if delay {
            b.delays.push(Delay {
                sid,
                p,
                c,
                t: v,
                at: r.at(),
            });
        } else {
            b.dareas.push(Darea {
                sid,
                p,
                c,
                a: v,
                at: r.at(),
            });
        }
    }
    r.extra_fields(7);
}

/// LSEQ (MSC): the static load set LID (FORCE, MOMENT, PLOAD, PLOAD2, PLOAD4, GRAV or
/// a LOAD of them) as the spatial distribution of the dynamic load sets whose
/// EXCITEID is this card's, selected by case control LOADSET.
#[derive(Debug, Clone)]
pub struct Lseq {
    /// Set id (field 2), which LOADSET selects.
    pub sid: i64,
    /// EXCITEID (field 3): the TLOADs' L it stands for.
    pub excite: i64,
    /// LID (field 4): the static load set.
    pub lid: i64,
    /// The card.
    pub at: CardRef,
}

/// LSEQ: `LSEQ SID EXCITEID LID TID`; a thermal TID is refused.
pub(super) fn card_lseq(r: &mut Reader, b: &mut Bulk) {
    let l = Lseq {
        sid: r.id(0, "SID"),
        excite: r.id(1, "EXCITEID"),
        lid: r.id(2, "LID"),
        at: r.at(),
    };
    if !r.text(3).is_empty() {
        r.fail(
            3,
            "TID",
            "is a thermal load set, which impactlab does not apply in a transient run",
        );
    }
    r.extra_fields(4);
    if r.ok {
        b.lseqs.push(l);
    }
}

/// TLOAD1 (`TLOAD1 SID L M TYPE TID`) and TLOAD2 (`TLOAD2 SID L M TYPE T1 T2 F P`,
/// `+ C B`). NASTRAN-95 leaves field 5 blank ("Field 5 must be blank"); MSC's TYPE
/// there is read when it is 0 or LOAD, the applied load NASTRAN-95 means.
pub(super) fn card_tload(r: &mut Reader, b: &mut Bulk, two: bool) {
    let sid = r.id(0, "SID");
    let excite = r.id(1, "L");
    let delay = match r.text(2) {
        "" => DelayRef::None,
        t if parse_int(t).is_some() => match r.int(2, "M") {
            0 => DelayRef::None,
            n if n < 0 => {
                r.fail(2, "M", "is not a DELAY set (a positive integer) or a delay (a real)");
                DelayRef::None
            }
            n => DelayRef::Set(n),
        },
        _ => DelayRef::Value(r.real(2, "M")),
    };
    match r.word(3, "TYPE").to_ascii_uppercase().as_str() {
        "" | "0" | "L" | "LO" | "LOA" | "LOAD" => {}
        _ => r.fail(
            3,
            "TYPE",
            "is an enforced motion (displacement, velocity or acceleration): impactlab applies loads only \
             (TYPE blank, 0 or LOAD)",
        ),
    }
    let shape = if two {
        let t1 = r.real_or(4, "T1", 0.0);
        let t2 = r.real_or(5, "T2", 0.0);
        r.non_negative(4, "T1", t1);
        if r.ok && t2 <= t1 {
            r.fail(5, "T2", format!("must be greater than T1 ({t1})"));
        }
        let f = r.real_or(6, "F", 0.0);
        r.non_negative(6, "F", f);
        TloadShape::Formula(Formula {
            t1,
            t2,
            f,
            p: r.real_or(7, "P", 0.0),
            c: r.real_or(8, "C", 0.0),
            b: r.real_or(9, "B", 0.0),
        })
    } else {
        TloadShape::Table(r.id(4, "TID"))
    };
    let (us0, vs0) = if two { (10, 11) } else { (5, 6) };
    for (k, name) in [(us0, "US0"), (vs0, "VS0")] {
        if r.real_opt(k, name).is_some_and(|v| v != 0.0) {
            r.fail(
                k,
                name,
                "is an initial value of an enforced motion, which impactlab does not apply",
            );
        }
    }
    r.extra_fields(us0.max(vs0) + 1);
    if r.ok {
        b.tloads.push(Tload {
            sid,
            excite,
            delay,
            shape,
            at: r.at(),
        });
    }
}

/// TABLED1-4 (`n` = 1-4): the parameters of line one, then the entries from the
/// continuation up to ENDT.
pub(super) fn card_tabled(r: &mut Reader, b: &mut Bulk, n: u8) {
    let id = r.id(0, "ID");
    let fields = r.card.fields.len();
    let end = (8..fields).find(|&k| r.text(k).eq_ignore_ascii_case("ENDT"));
    let Some(end) = end else {
        r.fail(fields.max(8), "ENDT", "the table has no ENDT after its last entry");
        return;
    };
    if let Some(k) = (end + 1..fields).find(|&k| !r.text(k).is_empty()) {
        r.fail(k, "unused", "follows ENDT, which ends the table");
    }
    let function = if n == 4 {
        let x: Vec<f64> = (1..5).map(|k| r.real(k, ["", "X1", "X2", "X3", "X4"][k])).collect();
        if r.ok && x[1] == 0.0 {
            r.fail(2, "X2", "must not be 0");
        }
        if r.ok && x[2] >= x[3] {
            r.fail(4, "X4", format!("must be greater than X3 ({})", x[2]));
        }
        r.extra_fields_in(5, 8);
        let a: Vec<f64> = (8..end).map(|k| r.real(k, "A(i)")).collect();
        if r.ok && a.is_empty() {
            r.fail(8, "A(0)", "the table has no coefficient: at least one is required");
        }
        TableFunction::Power {
            x1: x[0],
            x2: x[1],
            x3: x[2],
            x4: x[3],
            a,
        }
    } else {
        let (x1, x2) = match n {
            1 => {
                for (k, name) in [(1, "XAXIS"), (2, "YAXIS")] {
                    let t = r.text(k).to_ascii_uppercase();
                    if !(t.is_empty() || t == "LINEAR") {
                        r.fail(
                            k,
                            name,
                            "is not LINEAR: impactlab interpolates linearly, as NASTRAN-95 defines TABLED1",
                        );
                    }
                }
                if r.int_opt(7, "EXTRAP").is_some_and(|e| e != 0) {
                    r.fail(
                        7,
                        "EXTRAP",
                        "asks for another extrapolation than the linear one NASTRAN-95 defines (0 or blank)",
                    );
                }
                r.extra_fields_in(3, 7);
                (0.0, 1.0)
            }
            2 => {
                let x1 = r.real(1, "X1");
                r.extra_fields_in(2, 8);
                (x1, 1.0)
            }
            _ => {
                let x1 = r.real(1, "X1");
                let x2 = r.real(2, "X2");
                if r.ok && x2 == 0.0 {
                    r.fail(2, "X2", "must not be 0");
                }
                r.extra_fields_in(3, 8);
                (x1, x2)
            }
        };
        let points = table_points(r, end);
        TableFunction::Points { x1, x2, points }
    };
    if r.ok {
        b.tableds.push(Tabled {
            id,
            function,
            at: r.at(),
        });
    }
}

/// The (x, y) entries of a TABLED1-3 from field index 8 up to `end` (ENDT), SKIP
/// pairs left out, checked as BULK.TXT's remarks ask: at least two, in one order, a
/// jump not at an end; returned in ascending x.
fn table_points(r: &mut Reader, end: usize) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    // The field index of each entry's x, for messages.
    let mut at = Vec::new();
    let mut k = 8;
    while k < end {
        let skip = |t: &str| t.eq_ignore_ascii_case("SKIP");
        if skip(r.text(k)) || skip(r.text(k + 1)) {
            k += 2;
            continue;
        }
        if k + 1 >= end {
            r.fail(k, "y(i)", "the last entry has an x but no y before ENDT");
            return points;
        }
        points.push((r.real(k, "x(i)"), r.real(k + 1, "y(i)")));
        at.push(k);
        k += 2;
    }
    if !r.ok {
        return points;
    }
    if points.len() < 2 {
        r.fail(
            8,
            "x(1)",
            "the table has fewer than two entries (\"At least two entries must be present\")",
        );
        return points;
    }
    let n = points.len();
    // The order is the first and last x's; the first entry against it breaks it.
    let rising = points[n - 1].0 > points[0].0;
    let against = points
        .windows(2)
        .position(|w| if rising { w[1].0 < w[0].0 } else { w[1].0 > w[0].0 });
    if let Some(i) = against.or((points[0].0 == points[n - 1].0).then_some(n - 2)) {
        r.fail(
            at[i + 1],
            "x(i)",
            "breaks the order of the x entries (\"either ascending or descending order but not both\")",
        );
        return points;
    }
    if points[0].0 == points[1].0 || points[n - 2].0 == points[n - 1].0 {
        let k = if points[0].0 == points[1].0 { at[1] } else { at[n - 1] };
        r.fail(
            k,
            "x(i)",
            "the table jumps at an end point (\"Jumps ... are allowed, but not at the end points\")",
        );
    }
    if !rising {
        points.reverse();
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(p: &[(f64, f64)]) -> TableFunction {
        TableFunction::Points {
            x1: 0.0,
            x2: 1.0,
            points: p.to_vec(),
        }
    }

    /// BULK.TXT, TABLED1 remark 6: "linear interpolation within the table and linear
    /// extrapolation outside the table using the last two end points at the
    /// appropriate table end. At jump points the average yT(x) is used."
    #[test]
    fn tabled1_interpolates_extrapolates_and_averages_jumps() {
        let t = points(&[(0.0, 0.0), (1.0, 2.0), (1.0, 4.0), (3.0, 0.0)]);
        assert_eq!(t.value(0.5), 1.0);
        assert_eq!(t.value(1.0), 3.0);
        assert_eq!(t.value(2.0), 2.0);
        assert_eq!(t.value(-1.0), -2.0);
        assert_eq!(t.value(4.0), -2.0);
        assert_eq!(t.value(3.0), 0.0);
    }

    /// TABLED3 remark 6: "x = (X-X1)/X2"; TABLED4 remark 3: the power series in
    /// (X − X1)/X2, "Whenever X < X3, use X3 for X; whenever X > X4, use X4 for X".
    #[test]
    fn tabled3_shifts_and_scales_and_tabled4_holds_its_range() {
        let t3 = TableFunction::Points {
            x1: 10.0,
            x2: 2.0,
            points: vec![(0.0, 0.0), (1.0, 1.0)],
        };
        assert_eq!(t3.value(11.0), 0.5);
        let t4 = TableFunction::Power {
            x1: 1.0,
            x2: 2.0,
            x3: 0.0,
            x4: 5.0,
            a: vec![1.0, 2.0, 3.0],
        };
        // s = (3 − 1)/2 = 1: 1 + 2 + 3.
        assert_eq!(t4.value(3.0), 6.0);
        // held at X4 = 5: s = 2, 1 + 4 + 12.
        assert_eq!(t4.value(9.0), 17.0);
        // held at X3 = 0: s = −0.5, 1 − 1 + 0.75.
        assert_eq!(t4.value(-3.0), 0.75);
    }
}
