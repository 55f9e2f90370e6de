//! NASTRAN's printed element results (the `.f06` of MSC, the `.out` of NASTRAN-95),
//! read for the tables of the elements whose formulation is NASTRAN's own, and an
//! impactlab static run's `elements.csv` compared with them.
//!
//! The tables read, each value named as `elements.csv` names it:
//! - `F O R C E S   I N   B A R   E L E M E N T S` (CBAR): a row an element, `id`
//!   then BEND-MOMENT END-A PLANE 1, PLANE 2, END-B PLANE 1, PLANE 2, SHEAR PLANE 1,
//!   PLANE 2, AXIAL FORCE, TORQUE: `force_a_m1`, `force_a_m2`, `force_b_m1`,
//!   `force_b_m2`, and the shears, axial force and torque (constant along the bar) at
//!   both ends, `force_a_v1` and `force_b_v1` and so on.
//! - `S T R E S S E S   I N   B A R   E L E M E N T S` (CBAR): two rows an element,
//!   `0 id SA1 SA2 SA3 SA4 AXIAL SA-MAX SA-MIN [M.S.-T]` and `SB1 … SB4 SB-MAX SB-MIN
//!   [M.S.-C]`. SAi is the bending stress at point C, D, E, F of end A, without the
//!   axial stress (SA-MAX is AXIAL plus the largest SAi): impactlab's `stress_a_c` is
//!   SA1 + AXIAL.
//! - `F O R C E S   I N   R O D   E L E M E N T S` (CROD, CONROD, CTUBE): up to two
//!   elements a row, `id AXIAL-FORCE TORQUE`: `force_axial`, `force_torque`.
//! - `F O R C E S   I N   S C A L A R   S P R I N G S` (CELAS1-4): up to four a row,
//!   `id FORCE`: `force_axial`.
//! - `F O R C E S   I N   B U S H   E L E M E N T S` (CBUSH, MSC): `id` then FORCE-X,
//!   -Y, -Z, MOMENT-X, -Y, -Z: `force_fx` … `force_momz`.
//!
//! A table runs on over page breaks (each page prints its title again) and ends at a
//! line of another title. SUBCASE is read from each page's heading, as for the
//! displacements.

use super::printed::{format_error, open_csv, page_subcase, read_text, relative_to, PrintedError};
use std::collections::BTreeMap;
use std::path::Path;

/// Element results: per SUBCASE, (element, value name) → value.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ElementTables {
    /// SUBCASE → (element, name) → value.
    pub subcases: BTreeMap<i64, BTreeMap<(i64, String), f64>>,
}

/// A table this reader knows.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Table {
    BarForces,
    BarStresses,
    RodForces,
    SpringForces,
    BushForces,
}

impl Table {
    /// The table a title line opens, if it is one of these.
    fn of(title: &str) -> Option<Table> {
        let t = title.trim_start();
        [
            ("F O R C E S   I N   B A R   E L E M E N T S", Table::BarForces),
            ("S T R E S S E S   I N   B A R   E L E M E N T S", Table::BarStresses),
            ("F O R C E S   I N   R O D   E L E M E N T S", Table::RodForces),
            ("F O R C E S   I N   S C A L A R   S P R I N G S", Table::SpringForces),
            ("F O R C E S   I N   B U S H   E L E M E N T S", Table::BushForces),
        ]
        .into_iter()
        .find(|(head, _)| t.starts_with(head))
        .map(|(_, k)| k)
    }
}

/// A title line: spaced capitals (`F O R C E S   I N …`), most of its words one
/// letter.
fn is_title(line: &str) -> bool {
    let words: Vec<&str> = line.split_whitespace().collect();
    words.len() >= 6 && words.iter().filter(|w| w.len() == 1).count() * 5 >= words.len() * 4
}

/// Reads the element tables of a printed output's text.
pub fn read_element_tables(text: &str) -> ElementTables {
    let mut out = ElementTables::default();
    let mut subcase = 1;
    let mut table = None;
    // A bar stress's first row waits for its second.
    let mut pending: Option<(i64, Vec<f64>)> = None;
    for line in text.lines() {
        let trimmed = line.trim_end();
        if let Some(n) = page_subcase(trimmed) {
            subcase = n;
            continue;
        }
        if is_title(trimmed) {
            table = Table::of(trimmed);
            pending = None;
            continue;
        }
        let Some(kind) = table else { continue };
        let words: Vec<&str> = trimmed.trim_start_matches('0').split_whitespace().collect();
        let numbers: Option<Vec<f64>> = words.iter().map(|w| w.parse::<f64>().ok()).collect();
        let Some(numbers) = numbers.filter(|n| !n.is_empty()) else {
            continue;
        };
        let id = |k: usize| {
            let w = words[k];
            w.parse::<i64>().ok().filter(|_| !w.contains(['.', 'E', 'e']))
        };
        let t = out.subcases.entry(subcase).or_default();
        let mut put = |e: i64, name: &str, v: f64| {
            t.insert((e, name.to_string()), v);
        };
        match kind {
            Table::BarForces => {
                let (Some(e), [m1a, m2a, m1b, m2b, v1, v2, n, tq]) = (id(0), &numbers[1..]) else {
                    continue;
                };
                for (name, v) in [("m1", m1a), ("m2", m2a)] {
                    put(e, &format!("force_a_{name}"), *v);
                }
                for (name, v) in [("m1", m1b), ("m2", m2b)] {
                    put(e, &format!("force_b_{name}"), *v);
                }
                for end in ["a", "b"] {
                    for (name, v) in [("v1", v1), ("v2", v2), ("axial", n), ("torque", tq)] {
                        put(e, &format!("force_{end}_{name}"), *v);
                    }
                }
            }
            Table::BarStresses => {
                // The first row starts with `0` and the element's id.
                match (line.starts_with('0'), pending.take()) {
                    (true, _) => {
                        if let (Some(e), true) = (id(0), numbers.len() >= 6) {
                            pending = Some((e, numbers[1..].to_vec()));
                        }
                    }
                    (false, Some((e, a))) if numbers.len() >= 4 => {
                        let axial = a[4];
                        for (end, values) in [("a", &a[..4]), ("b", &numbers[..4])] {
                            for (point, v) in ["c", "d", "e", "f"].iter().zip(values) {
                                put(e, &format!("stress_{end}_{point}"), v + axial);
                            }
                        }
                    }
                    _ => {}
                }
            }
            Table::RodForces => {
                for k in (0..words.len()).step_by(3) {
                    if let (Some(e), Some(n), Some(tq)) = (id(k), numbers.get(k + 1), numbers.get(k + 2)) {
                        put(e, "force_axial", *n);
                        put(e, "force_torque", *tq);
                    }
                }
            }
            Table::SpringForces => {
                for k in (0..words.len()).step_by(2) {
                    if let (Some(e), Some(f)) = (id(k), numbers.get(k + 1)) {
                        put(e, "force_axial", *f);
                    }
                }
            }
            Table::BushForces => {
                let (Some(e), 7) = (id(0), numbers.len()) else { continue };
                for (name, v) in ["fx", "fy", "fz", "momx", "momy", "momz"].iter().zip(&numbers[1..]) {
                    put(e, &format!("force_{name}"), *v);
                }
            }
        }
    }
    out.subcases.retain(|_, t| !t.is_empty());
    out
}

/// Reads a printed output file's element tables (none is not an error: a deck may
/// print none).
pub fn read_element_tables_file(path: &Path) -> Result<ElementTables, PrintedError> {
    Ok(read_element_tables(&read_text(path)?))
}

/// An impactlab static run's element results (`elements.csv` of its directory; an
/// empty set when it wrote none).
pub fn read_run_elements(dir: &Path) -> Result<ElementTables, PrintedError> {
    let path = dir.join("elements.csv");
    if !path.exists() {
        return Ok(ElementTables::default());
    }
    let (mut r, headers, name) = open_csv(&path)?;
    let col = |h: &str| headers.iter().position(|x| x == h);
    let (Some(element), Some(quantity), Some(value)) = (col("element"), col("quantity"), col("value")) else {
        return Err(format_error(
            &name,
            1,
            "is not a static run's elements.csv (no element, quantity and value columns)".into(),
        ));
    };
    let subcase = col("subcase");
    let mut out = ElementTables::default();
    for (k, row) in r.records().enumerate() {
        let line = k + 2;
        let row = row.map_err(|e| format_error(&name, line, e.to_string()))?;
        let int = |i: usize| row.get(i).and_then(|t| t.parse::<i64>().ok());
        let bad = |what: &str| format_error(&name, line, format!("{what} is not a number"));
        let sc = match subcase {
            Some(i) => int(i).ok_or_else(|| bad("subcase"))?,
            None => 1,
        };
        let e = int(element).ok_or_else(|| bad("element"))?;
        let v = row
            .get(value)
            .and_then(|t| t.parse::<f64>().ok())
            .ok_or_else(|| bad("value"))?;
        let q = row.get(quantity).unwrap_or_default().to_string();
        out.subcases.entry(sc).or_default().insert((e, q), v);
    }
    Ok(out)
}

/// What a value is measured in, for its scale: a stress, a moment or a force.
fn class(name: &str) -> &'static str {
    if name.starts_with("stress") {
        "stress"
    } else if ["m1", "m2", "torque", "momx", "momy", "momz"]
        .iter()
        .any(|m| name.ends_with(m))
    {
        "moment"
    } else {
        "force"
    }
}

/// One value compared.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementDifference {
    /// The SUBCASE.
    pub subcase: i64,
    /// The element.
    pub element: i64,
    /// The value's name (`force_a_m1`).
    pub name: String,
    /// impactlab's value.
    pub ours: f64,
    /// NASTRAN's printed value.
    pub theirs: f64,
    /// |ours − theirs| over the largest printed value of its class (stress, moment
    /// or force) in its SUBCASE.
    pub relative: f64,
}

/// A run's element results against the printed ones.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ElementComparison {
    /// Every value both give, the largest relative difference first.
    pub differences: Vec<ElementDifference>,
    /// Printed values the run does not have: (SUBCASE, element, name).
    pub missing: Vec<(i64, i64, String)>,
}

impl ElementComparison {
    /// The largest relative difference (0 when nothing was compared).
    pub fn worst(&self) -> f64 {
        self.differences.first().map_or(0.0, |d| d.relative)
    }
}

/// Compares the run's element results with the printed ones, SUBCASE by SUBCASE;
/// each difference relative to the largest printed value of its class in its SUBCASE
/// (0 where both are 0, infinite where only the difference is not).
pub fn compare_elements(ours: &ElementTables, theirs: &ElementTables) -> ElementComparison {
    let mut out = ElementComparison::default();
    for (&sc, printed) in &theirs.subcases {
        let run = ours.subcases.get(&sc);
        let mut scale: BTreeMap<&str, f64> = BTreeMap::new();
        for ((_, name), v) in printed {
            let s = scale.entry(class(name)).or_default();
            *s = s.max(v.abs());
        }
        for ((e, name), &v) in printed {
            match run.and_then(|r| r.get(&(*e, name.clone()))) {
                Some(&o) => out.differences.push(ElementDifference {
                    subcase: sc,
                    element: *e,
                    name: name.clone(),
                    ours: o,
                    theirs: v,
                    relative: relative_to(o - v, scale[class(name)]),
                }),
                None => out.missing.push((sc, *e, name.clone())),
            }
        }
    }
    out.differences.sort_by(|a, b| b.relative.total_cmp(&a.relative));
    out
}

/// The comparison as a table: how many values, the largest relative difference and
/// the `top` largest differences by SUBCASE, element and value.
pub fn render_elements(c: &ElementComparison, top: usize) -> String {
    let mut s = format!(
        "element results: {} values; largest difference {:.2e} of the largest printed value of its kind (stress, \
         moment or force) in its SUBCASE\n",
        c.differences.len(),
        c.worst()
    );
    if let Some((sc, e, name)) = c.missing.first() {
        s += &format!(
            "  not in the run: {} value(s), first SUBCASE {sc} element {e} {name} (ask for them with STRESS or FORCE)\n",
            c.missing.len()
        );
    }
    s += &format!(
        "  {:>7} {:>9} {:<16} {:>14} {:>14} {:>10}\n",
        "subcase", "element", "value", "impactlab", "NASTRAN", "relative"
    );
    for d in c.differences.iter().take(top) {
        s += &format!(
            "  {:>7} {:>9} {:<16} {:>14.6e} {:>14.6e} {:>10.2e}\n",
            d.subcase, d.element, d.name, d.ours, d.theirs, d.relative
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: NASTRAN-95's bar force and stress tables (as printed for its
    /// demonstration problems D01-14-1A and T01-34-1A) are read row by row, over a
    /// page break and into another SUBCASE, each value under its impactlab name; a
    /// bar stress is SAi plus the axial stress; a table of another title (SPC forces)
    /// is not read.
    #[test]
    fn bar_tables_of_nastran_95() {
        let text = "1     STATIC ANALYSIS     PAGE    10
0                                                                                            SUBCASE 2
                                 F O R C E S   I N   B A R   E L E M E N T S         ( C B A R )
0    ELEMENT         BEND-MOMENT END-A            BEND-MOMENT END-B                - SHEAR -               AXIAL
       ID.         PLANE 1       PLANE 2        PLANE 1       PLANE 2        PLANE 1       PLANE 2         FORCE         TORQUE
            6     9.999695E-01  0.0           -3.051758E-05  0.0            1.000000E+00  0.0            2.0            0.0
1     STATIC ANALYSIS     PAGE    11
0                                                                                            SUBCASE 3
                                 S T R E S S E S   I N   B A R   E L E M E N T S          ( C B A R )
  ELEMENT        SA1            SA2            SA3            SA4           AXIAL          SA-MAX         SA-MIN     M.S.-T
    ID.          SB1            SB2            SB3            SB4           STRESS         SB-MAX         SB-MIN     M.S.-C
0      1     0.0            0.0            0.0            0.0            5.0            0.0            0.0
            -1.905150E+04  -1.905150E+04   1.905150E+04   1.905150E+04                  1.905150E+04  -1.905150E+04
                               F O R C E S   O F   S I N G L E - P O I N T   C O N S T R A I N T
0               3      G      0.0            0.0            0.0            0.0            0.0            0.0
";
        let t = read_element_tables(text);
        let v = |sc: i64, e: i64, n: &str| t.subcases[&sc][&(e, n.to_string())];
        assert_eq!(v(2, 6, "force_a_m1"), 9.999695e-1);
        assert_eq!(v(2, 6, "force_b_m1"), -3.051758e-5);
        assert_eq!((v(2, 6, "force_a_v1"), v(2, 6, "force_b_v1")), (1.0, 1.0));
        assert_eq!(v(2, 6, "force_b_axial"), 2.0);
        assert_eq!(v(3, 1, "stress_a_c"), 5.0);
        assert_eq!(v(3, 1, "stress_b_e"), 1.905150e4 + 5.0);
        assert_eq!(t.subcases[&2].len(), 12);
        assert_eq!(t.subcases[&3].len(), 8);
    }

    /// Goal: rod and spring forces, several elements a row, are read whole; a run's
    /// values are compared with them relative to the largest printed value of their
    /// kind, the largest difference first, and a printed value the run lacks is
    /// listed.
    #[test]
    fn rod_and_spring_rows_and_their_comparison() {
        let text = "0                                                                  SUBCASE 1
                          F O R C E S   I N   R O D   E L E M E N T S     ( C R O D )
       ELEMENT       AXIAL                           ELEMENT       AXIAL
         ID.         FORCE         TORQUE              ID.         FORCE         TORQUE
            1     1.000000E+02   0.0                      2    -5.000000E+01   1.0
                 F O R C E S   I N   S C A L A R   S P R I N G S        ( C E L A S 2 )
    ELEMENT         FORCE            ELEMENT         FORCE            ELEMENT         FORCE
      ID.                              ID.                              ID.
        10      3.0                     11      -4.0                    12      0.0
";
        let theirs = read_element_tables(text);
        let mut ours = theirs.clone();
        let t = ours.subcases.get_mut(&1).unwrap();
        *t.get_mut(&(2, "force_axial".to_string())).unwrap() = -49.0;
        t.remove(&(12, "force_axial".to_string()));
        let c = compare_elements(&ours, &theirs);
        assert_eq!(c.differences.len(), 6);
        assert_eq!((c.differences[0].element, c.differences[0].relative), (2, 0.01));
        assert_eq!(c.missing, [(1, 12, "force_axial".to_string())]);
        // Torques are moments: their scale is the largest printed torque.
        assert!(c.differences.iter().all(|d| d.relative == 0.0 || d.element == 2));
    }
}
