//! `impactlab check`: will impactlab take this deck? Its structure surveyed
//! ([`super::survey_structure`]: built element by element, counted and weighed,
//! none kept), with every card that is not taken: those that would change the
//! structure (not supported) and those that do not (loads, temperatures, eigenvalue
//! and solution controls, output and design cards, PARAMs: ignored).

use super::{survey_structure, MassProperties};
use crate::deck::cards::CoordKind;
use crate::deck::{Deck, Diagnostic};
use serde::Serialize;
use std::collections::BTreeMap;

/// Bulk data cards that do not change a structure's stiffness, mass or constraints:
/// loads, temperatures, eigenvalue and solution controls, tables, design and output
/// cards. A deck's card of these kinds is listed as ignored, not as unsupported.
pub const NON_STRUCTURAL: [&str; 65] = [
    // Static and dynamic loads.
    "FORCE", "FORCE1", "FORCE2", "MOMENT", "MOMENT1", "MOMENT2", "PLOAD1", "PLOADX1", "GRAV", "LOAD", "ACCEL", "ACCEL1",
    "RFORCE", "DAREA", "DLOAD", "TLOAD1", "TLOAD2", "RLOAD1", "RLOAD2", "LSEQ", "DELAY", "DPHASE",
    "SLOAD",  // Temperatures.
    "TEMPAX", // Eigenvalue and solution controls.
    "EIGC", "EIGB", "FREQ", "FREQ1", "FREQ2", "FREQ3", "FREQ4", "FREQ5", "TSTEPNL", "NLPARM", "NLPCI",
    "TABDMP1", // Tables.
    "TABLED1", "TABLED2", "TABLED3", "TABLED4", "TABLEM1", "TABLEM2", "TABLEM3", "TABLEM4", "TABLES1", "TABLEST",
    "TABRND1", // Design and output.
    "DESVAR", "DRESP1", "DRESP2", "DCONSTR", "DCONADD", "DOPTPRM", "DVPREL1", "DVPREL2", "DLINK", "MONPNT1", "PLOTEL",
    "SET1", "SET3", // Sequencing, congruence hints and heat-transfer materials.
    "SEQGP", "SEQEP", "CNGRNT", "MAT4", "MAT5",
];

/// Temperature-dependent material tables: they change nothing unless the deck has a
/// temperature field, and are ignored where it has none.
const TEMPERATURE_TABLES: [&str; 5] = ["MATT1", "MATT2", "MATT3", "MATT4", "MATT5"];

/// The cards impactlab does not type that give a temperature field (TEMPRB, TEMPP1,
/// TEMP and TEMPD it types).
const TEMPERATURES: [&str; 1] = ["TEMPAX"];

/// Cards of one name the deck holds and impactlab does not take.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CardCount {
    /// The card's name.
    pub card: String,
    /// How many the deck has.
    pub count: usize,
    /// Where the first is (file:line:column).
    pub first_at: String,
    /// Its first line as written.
    pub first_line: String,
}

/// A coordinate system of the deck and its use.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemUse {
    /// Its id.
    pub cid: i64,
    /// The card that defines it.
    pub card: String,
    /// Rectangular, cylindrical or spherical.
    pub kind: &'static str,
    /// Grids located in it (CP).
    pub located: usize,
    /// Grids displaced in it (CD).
    pub displaced: usize,
}

/// The mass properties as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Weight {
    /// The mass along basic x, y, z.
    pub mass: [f64; 3],
    /// The centre of gravity (basic).
    pub centre: Option<[f64; 3]>,
    /// The inertia tensor about it (basic axes; products with their minus sign).
    pub inertia: [[f64; 3]; 3],
    /// The principal moments.
    pub principal: [f64; 3],
}

impl Weight {
    /// The weight before PARAM WTMASS `w` (masses and inertias divided by it; the
    /// centre of gravity unchanged).
    fn in_input_units(mut self, w: f64) -> Self {
        if w == 1.0 {
            return self;
        }
        self.mass = self.mass.map(|m| m / w);
        self.inertia = self.inertia.map(|row| row.map(|v| v / w));
        self.principal = self.principal.map(|v| v / w);
        self
    }
}

impl From<MassProperties> for Weight {
    fn from(m: MassProperties) -> Self {
        Weight {
            mass: m.mass,
            centre: m.centre,
            inertia: m.inertia,
            principal: m.principal,
        }
    }
}

/// What `impactlab check` answers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckReport {
    /// The deck's name.
    pub deck: String,
    /// The SOL statement, as written.
    pub solution: Option<String>,
    /// True when the structure builds and no card that would change it is left out:
    /// impactlab takes the deck.
    pub takes: bool,
    /// Grids.
    pub grids: usize,
    /// Elements by kind (CONM2 masses included; not the drilling supports a run adds).
    pub elements: BTreeMap<String, usize>,
    /// Grid DOFs left free by PS, GRDSET and the selected SPC.
    pub free_dofs: usize,
    /// Grid DOFs constrained.
    pub constrained_dofs: usize,
    /// Rigid elements by kind (RBE2, RBE3).
    pub rigid: BTreeMap<String, usize>,
    /// Grid DOFs the rigid elements make dependent.
    pub dependent_dofs: usize,
    /// Scalar points.
    pub scalar_points: usize,
    /// Mass, centre of gravity and inertia in the deck's input units, as NASTRAN's
    /// grid point weight generator prints them: before PARAM WTMASS (`None` when the
    /// structure does not build).
    pub weight: Option<Weight>,
    /// PARAM WTMASS, when the deck sets it.
    pub wtmass: Option<f64>,
    /// The mass along basic x, y, z as solutions use it: `weight`'s times WTMASS.
    pub scaled_mass: Option<[f64; 3]>,
    /// How fields that COSMIC and MSC read differently were read, and on how many cards.
    pub readings: BTreeMap<String, usize>,
    /// Output requests of quantities impactlab does not write.
    pub not_written: Vec<String>,
    /// The coordinate systems.
    pub systems: Vec<SystemUse>,
    /// Cards that would change the structure and are not supported.
    pub unsupported: Vec<CardCount>,
    /// Cards that do not change the structure, ignored (PARAM among them).
    pub ignored: Vec<CardCount>,
    /// The lowest natural frequencies (cycles per unit time), when asked for and found
    /// (`check --modes N`; why they could not be is among the warnings).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lowest_frequencies: Option<Vec<f64>>,
    /// Why the structure does not build (the model builder's errors), when it does not.
    pub errors: Vec<String>,
    /// Warnings of the reader and the model builder.
    pub warnings: Vec<String>,
}

/// The check of a deck read with [`crate::deck::ReadOptions::structure`].
pub fn check(deck: &Deck) -> CheckReport {
    let b = &deck.bulk;
    let mut unsupported: BTreeMap<String, CardCount> = BTreeMap::new();
    let mut ignored: BTreeMap<String, CardCount> = BTreeMap::new();
    let has_temperatures = !b.temprbs.is_empty()
        || !b.tempp1s.is_empty()
        || !b.temperatures.is_empty()
        || deck.unknown.iter().any(|u| TEMPERATURES.contains(&u.name.as_str()));
    for u in &deck.unknown {
        let name = u.name.as_str();
        let to = if NON_STRUCTURAL.contains(&name) || (TEMPERATURE_TABLES.contains(&name) && !has_temperatures) {
            &mut ignored
        } else {
            &mut unsupported
        };
        to.entry(u.name.clone())
            .or_insert_with(|| CardCount {
                card: u.name.clone(),
                count: 0,
                first_at: u.pos.to_string(),
                first_line: u.line.clone(),
            })
            .count += 1;
    }
    for w in deck.warnings.iter().filter(|w| w.card.as_deref() == Some("PARAM")) {
        ignored
            .entry("PARAM".into())
            .or_insert_with(|| CardCount {
                card: "PARAM".into(),
                count: 0,
                first_at: w.pos.as_ref().map(|p| p.to_string()).unwrap_or_default(),
                first_line: w
                    .quote
                    .as_deref()
                    .and_then(|q| q.lines().next())
                    .unwrap_or("")
                    .to_string(),
            })
            .count += 1;
    }
    // The static loads and eigenvalue extraction cards are read (a SOL 101 or 103
    // deck's `impactlab run` uses them) but do not change the structure.
    let loads = b
        .point_loads
        .iter()
        .map(|l| &l.at)
        .chain(b.pload4s.iter().map(|l| &l.at))
        .chain(b.ploads.iter().map(|l| &l.at))
        .chain(b.gravs.iter().map(|l| &l.at))
        .chain(b.spcds.iter().map(|l| &l.at))
        .chain(b.temprbs.iter().map(|l| &l.at))
        .chain(b.tempp1s.iter().map(|l| &l.at))
        .chain(b.temperatures.iter().map(|l| &l.at))
        .chain(b.load_combinations.iter().map(|l| &l.at))
        .chain(b.eigrs.iter().map(|l| &l.at));
    // A card of several entries (SPCD, TEMP, TEMPP1's elements) counts once.
    let mut last = None;
    for at in loads {
        if last.replace(&at.pos) == Some(&at.pos) {
            continue;
        }
        ignored
            .entry(at.name.to_string())
            .or_insert_with(|| CardCount {
                card: at.name.to_string(),
                count: 0,
                first_at: at.pos.to_string(),
                first_line: at.source.lines().next().unwrap_or("").to_string(),
            })
            .count += 1;
    }
    let mut warnings: Vec<String> = deck
        .warnings
        .iter()
        .filter(|w| w.card.as_deref() != Some("PARAM"))
        .map(Diagnostic::to_string)
        .collect();
    let systems = b
        .cords
        .iter()
        .map(|c| SystemUse {
            cid: c.cid,
            card: c.at.name.to_string(),
            kind: match c.kind {
                CoordKind::Rectangular => "rectangular",
                CoordKind::Cylindrical => "cylindrical",
                CoordKind::Spherical => "spherical",
            },
            located: b
                .grids
                .iter()
                .filter(|g| crate::geometry::grid_systems(g, b).0 == c.cid)
                .count(),
            displaced: b
                .grids
                .iter()
                .filter(|g| crate::geometry::grid_systems(g, b).1 == c.cid)
                .count(),
        })
        .collect();
    let mut report = CheckReport {
        deck: deck.name.clone(),
        solution: deck.executive.solution.clone(),
        takes: false,
        grids: b.grids.len(),
        elements: BTreeMap::new(),
        free_dofs: 0,
        constrained_dofs: 0,
        rigid: b
            .rbe2s
            .iter()
            .map(|r| r.card)
            .chain(b.rbe3s.iter().map(|_| "RBE3"))
            .fold(BTreeMap::new(), |mut m, card| {
                *m.entry(card.to_string()).or_insert(0) += 1;
                m
            }),
        dependent_dofs: 0,
        scalar_points: 0,
        weight: None,
        wtmass: b.wtmass.as_ref().map(|(w, _)| *w),
        scaled_mass: None,
        readings: b.readings.iter().map(|(k, n)| (k.to_string(), *n)).collect(),
        not_written: deck.case.not_written.iter().map(|(k, _)| k.clone()).collect(),
        systems,
        unsupported: unsupported.into_values().collect(),
        ignored: ignored.into_values().collect(),
        lowest_frequencies: None,
        errors: Vec::new(),
        warnings: Vec::new(),
    };
    let elsewhere = match (&deck.executive.restart, &deck.executive.generated) {
        (Some((statement, at)), _) => Some(format!(
            "{at}: a restart deck ({statement}): its structure is on the old problem tape of an earlier run, \
             which impactlab does not read; check the deck that made it"
        )),
        (None, Some((statement, at))) => Some(format!(
            "{at}: the structure is generated by NASTRAN's INPUT module ({}), which impactlab does not run",
            statement.split('$').next().unwrap_or("").trim()
        )),
        _ => None,
    };
    if let Some(e) = elsewhere {
        report.errors = vec![e];
        report.warnings = warnings;
        return report;
    }
    match survey_structure(deck) {
        Ok((s, diags)) => {
            report.elements = s.elements.iter().map(|(k, n)| (k.to_string(), *n)).collect();
            report.free_dofs = s.free_dofs;
            report.constrained_dofs = s.constrained_dofs;
            report.dependent_dofs = s.dependent_dofs;
            report.scalar_points = s.scalar_points;
            let m = s.mass;
            let w = report.wtmass.unwrap_or(1.0);
            report.scaled_mass = report.wtmass.map(|_| m.mass);
            report.weight = Some(Weight::from(m).in_input_units(w));
            warnings.extend(diags.iter().map(Diagnostic::to_string));
            report.takes = report.unsupported.is_empty();
            if b.grids.is_empty() && report.elements.is_empty() && report.unsupported.is_empty() {
                // A DMAP or matrix deck: nothing to take.
                report.takes = false;
                report.errors = vec![format!(
                    "{}: the deck defines no structure (no grid, scalar point or element)",
                    deck.name
                )];
            }
        }
        Err(e) => {
            report.errors = e
                .diagnostics
                .iter()
                .filter(|d| d.is_error())
                .map(Diagnostic::to_string)
                .collect();
            warnings.extend(
                e.diagnostics
                    .iter()
                    .filter(|d| !d.is_error())
                    .map(Diagnostic::to_string),
            );
        }
    }
    report.warnings = warnings;
    report
}
