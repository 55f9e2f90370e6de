//! A scene whose target is a deck: where the impactor strikes it, and the deck the
//! scene stands for (the deck's structural cards, then the impactor, its contact
//! and its initial velocity, written as the paper writes them).
//!
//! The contact acts along the impactor's travel d at the struck point, spread over
//! the struck element's grids by their shape functions Nᵢ there (¼ each only at a
//! quadrilateral's centre): the indentation α = d·u_imp − Σᵢ Nᵢ d·uᵢ (a TF onto an
//! EPOINT), the loads K α^1.5 on the impactor (against d) and Nᵢ K α^1.5 on each grid
//! (along d), as NOLIN3 cards on the components of d in each grid's displacement
//! frame. Each load's scale is K times its TF coefficient, so the contact derives
//! from the Hertz potential to the last bit and the ledger books no external work.

use super::{Scene, SceneIssue, Target};
use crate::deck::number::format_real;
use crate::deck::{Deck, ReadOptions};
use crate::model::{build_structure, Structure};
use nalgebra::Vector3;
use std::fmt::Write as _;

/// Cards of a deck target that the scene leaves out: the transient and impact cards
/// it writes itself, the static loads (a struck deck's load is its impactor), and
/// scalar points (a structure's EPOINT would be a DOF with no mass or stiffness once
/// its TF is gone).
const LEFT_OUT: [&str; 18] = [
    "TSTEP", "TF", "NOLIN3", "TIC", "EPOINT", "SPOINT", "FORCE", "MOMENT", "PLOAD", "PLOAD2", "PLOAD4", "GRAV", "LOAD",
    "SPCD", "TEMPRB", "PARAM", "INCLUDE", "ENDDATA",
];

/// Components of d in a grid's frame smaller than this are left out of the contact.
const NEGLIGIBLE: f64 = 1e-14;

/// Where a deck target is struck, and with what.
#[derive(Debug, Clone)]
pub struct Strike {
    /// The deck, read for its structure.
    pub deck: Deck,
    /// Its structure.
    pub structure: Structure,
    /// The struck element (card, id), if a point was struck.
    pub element: Option<(&'static str, i64)>,
    /// The grids the contact is spread over, with their weights.
    pub weights: Vec<(i64, f64)>,
    /// The struck point (basic).
    pub point: Vector3<f64>,
    /// The impactor's travel (unit, basic).
    pub direction: Vector3<f64>,
    /// Hertz K.
    pub k: f64,
    /// Where K comes from.
    pub how: String,
}

/// The impactor's direction as the scene gives it: a vector, or `None` for "normal".
pub(super) fn direction_of(v: Option<&toml::Value>) -> Result<Option<Vector3<f64>>, SceneIssue> {
    let bad = || SceneIssue("impactor.direction must be three numbers, not all zero, or \"normal\"".into());
    match v {
        None => Err(SceneIssue(
            "impactor.direction is needed for a deck target: a vector, or \"normal\"".into(),
        )),
        Some(toml::Value::String(n)) if n == "normal" => Ok(None),
        Some(toml::Value::Array(a)) if a.len() == 3 => {
            let c: Vec<f64> = a
                .iter()
                .map(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
                .collect::<Option<_>>()
                .ok_or_else(bad)?;
            let d = Vector3::new(c[0], c[1], c[2]);
            if d.iter().all(|x| x.is_finite()) && d.norm() > 0.0 {
                Ok(Some(d.normalize()))
            } else {
                Err(bad())
            }
        }
        Some(_) => Err(bad()),
    }
}

/// Where the scene's impactor strikes its deck target.
pub fn strike(s: &Scene) -> Result<Strike, SceneIssue> {
    let Target::Deck { deck: path } = &s.target else {
        unreachable!("a strike is a deck target's")
    };
    let full = s.dir.join(path);
    let read = ReadOptions {
        structure: true,
        keep_cards: true,
        ..Default::default()
    };
    let deck = crate::deck::read_deck(&full, read).map_err(|e| SceneIssue(format!("target.deck: {e}")))?;
    if deck.units.declared() {
        let (d, u) = (&deck.units, &s.units);
        if (&d.length, &d.force, &d.time) != (&u.length, &u.force, &u.time) {
            return Err(SceneIssue(format!(
                "target.deck declares units {}, {}, {} but the scene {}, {}, {}: impactlab never converts units",
                d.length, d.force, d.time, u.length, u.force, u.time
            )));
        }
    }
    let report = crate::model::check::check(&deck);
    if !report.takes {
        let mut why: Vec<String> = report.errors.clone();
        why.extend(
            report
                .unsupported
                .iter()
                .map(|c| format!("{} ×{} is not supported (first at {})", c.card, c.count, c.first_at)),
        );
        return Err(SceneIssue(format!(
            "target.deck {}: impactlab does not take it (`impactlab check` says why):\n{}",
            full.display(),
            why.join("\n")
        )));
    }
    let (structure, _) = build_structure(&deck).map_err(|e| SceneIssue(e.to_string()))?;
    let given = super::direction_of(s.impactor.direction.as_ref())?;
    let shells = || {
        structure
            .elements
            .iter()
            .filter(|e| e.kernel.family().shell().is_some())
    };
    let (element, weights, point, normal) = match (s.impactor.at, s.impactor.grid) {
        (Some(at), _) => {
            let mut best: Option<(f64, &crate::elements::Element, crate::geometry::OnShell)> = None;
            let mut nearest: Option<(f64, &crate::elements::Element)> = None;
            for e in shells() {
                let Some(o) = crate::geometry::on_shell(&e.points(), at) else {
                    continue;
                };
                let off = o.height + o.outside * o.size;
                if nearest.is_none_or(|(d, _)| off < d) {
                    nearest = Some((off, e));
                }
                if o.outside <= 1e-9 && o.height <= 0.05 * o.size && best.as_ref().is_none_or(|b| o.height < b.0) {
                    best = Some((o.height, e, o));
                }
            }
            let Some((_, e, o)) = best else {
                return Err(SceneIssue(match nearest {
                    Some((d, e)) => format!(
                        "impactor.at = {at:?} is on no shell's surface: the nearest is {} {}, about {d:.4e} away",
                        e.kernel.card(),
                        e.eid
                    ),
                    None => format!("impactor.at = {at:?}: the deck has no shell to strike"),
                }));
            };
            let weights = e.grids.iter().copied().zip(o.weights.iter().copied()).collect();
            (
                Some((e.kernel.card(), e.eid)),
                weights,
                Vector3::from(at),
                Vector3::from(o.normal),
            )
        }
        (None, Some(g)) => {
            let x = structure
                .geometry
                .positions
                .get(&g)
                .ok_or_else(|| SceneIssue(format!("impactor.grid = {g}: the deck has no grid {g}")))?;
            let normals: Vec<Vector3<f64>> = shells()
                .filter(|e| e.grids.contains(&g))
                .filter_map(|e| crate::geometry::shell_frame(&e.points()).ok())
                .map(|f| f.axes.column(2).into_owned())
                .collect();
            let normal = normals.iter().sum::<Vector3<f64>>();
            if given.is_none() && normal.norm() == 0.0 {
                return Err(SceneIssue(format!(
                    "impactor.grid = {g}: direction = \"normal\", but no shell at grid {g} gives a normal"
                )));
            }
            (None, vec![(g, 1.0)], Vector3::from(*x), normal.normalize())
        }
        (None, None) => unreachable!("validated"),
    };
    // + 0.0: a component that is −0.0 is written as 0.0.
    let direction = given.unwrap_or(normal).map(|c| c + 0.0);
    let (k, how) = hertz(s, &deck, element.map(|(_, eid)| eid), &weights)?;
    Ok(Strike {
        deck,
        structure,
        element,
        weights,
        point,
        direction,
        k,
        how,
    })
}

/// Hertz K: given, or Eq. 5 from the struck element's isotropic material (PSHELL MID1,
/// a MAT1), or Eq. 18 with k_t the transverse modulus E2 of its PCOMP's MAT8 plies
/// (a ply transversely isotropic about its fibres: E33 = E2), each printed.
fn hertz(s: &Scene, deck: &Deck, eid: Option<i64>, weights: &[(i64, f64)]) -> Result<(f64, String), SceneIssue> {
    if let Some(given) = super::given_k(s) {
        return given;
    }
    let which = s.contact.k.as_str().unwrap_or("");
    if which != "eq5" && which != "eq18" {
        return Err(SceneIssue(format!(
            "contact.k must be a number, \"eq5\" or \"eq18\", not '{which}'"
        )));
    }
    let (r, mi) = match (s.impactor.radius, s.impactor.material) {
        (Some(r), Some(m)) => (r, m),
        _ => {
            return Err(SceneIssue(
                "contact.k = \"eq5\"/\"eq18\" needs impactor.radius and impactor.material".into(),
            ))
        }
    };
    let b = &deck.bulk;
    let grids: Vec<i64> = weights.iter().map(|w| w.0).collect();
    let element = b
        .elements
        .iter()
        .find(|c| Some(c.eid) == eid || (eid.is_none() && c.g.iter().any(|g| grids.contains(g))))
        .ok_or_else(|| SceneIssue("contact.k = \"eq5\"/\"eq18\": no element at the struck point".into()))?;
    let pid = element.pid;
    let ki = crate::physics::plane_strain_modulus(mi.e, mi.nu);
    let (kt, eq) = if which == "eq5" {
        let m = b
            .pshells
            .iter()
            .find(|p| p.pid == pid)
            .and_then(|p| p.mid1)
            .and_then(|mid| b.mat1s.iter().find(|m| m.mid == mid))
            .ok_or_else(|| {
                SceneIssue(format!(
                    "contact.k = \"eq5\" needs an isotropic target: {} {}'s property {pid} is no PSHELL with a MAT1 \
                     MID1",
                    element.kind.card, element.eid
                ))
            })?;
        (
            crate::physics::plane_strain_modulus(m.e, m.nu),
            format!("Eq. 5, MAT1 {} of {} {}", m.mid, element.kind.card, element.eid),
        )
    } else {
        let p = b.pcomps.iter().find(|p| p.pid == pid).ok_or_else(|| {
            SceneIssue(format!(
                "contact.k = \"eq18\" needs a laminate: {} {}'s property {pid} is no PCOMP (give contact.k as a number)",
                element.kind.card, element.eid
            ))
        })?;
        let e2: Vec<f64> = p
            .plies
            .iter()
            .filter_map(|ply| b.mat8s.iter().find(|m| m.mid == ply.mid).map(|m| m.e2))
            .collect();
        if e2.len() != p.plies.len() || e2.iter().any(|&e| e != e2[0]) {
            return Err(SceneIssue(format!(
                "contact.k = \"eq18\" takes E33 = E2 of the plies' MAT8; PCOMP {pid}'s plies are not all of one MAT8 E2 \
                 (give contact.k as a number)"
            )));
        }
        (e2[0], format!("Eq. 18, k_t = E33 = E2 of PCOMP {pid}'s MAT8"))
    };
    let kk = crate::physics::hertz_stiffness(r, ki, kt);
    Ok((
        kk,
        format!("{eq}: 4/3 √r k_i k_t/(k_i + k_t), r = {r}, k_i = {ki:.4e}, k_t = {kt:.4e}"),
    ))
}

/// The case control and bulk data of a deck target's scene.
pub(super) fn deck_bulk(w: &mut String, s: &Scene, st: &Strike, tstep: &str) {
    let b = &st.deck.bulk;
    let d = st.direction;
    let max_point = b
        .grids
        .iter()
        .map(|g| g.id)
        .chain(b.epoints.iter().chain(&b.spoints).map(|p| p.0))
        .max()
        .unwrap_or(0);
    let (gi, ep) = (max_point + 1, max_point + 2);
    let eid = b
        .elements
        .iter()
        .map(|c| c.eid)
        .chain(b.conm1s.iter().map(|c| c.eid))
        .chain(b.conm2s.iter().map(|c| c.eid))
        .chain(b.scalars.iter().map(|c| c.eid))
        .chain(b.genels.iter().map(|c| c.eid))
        .chain(b.cbushes.iter().map(|c| c.eid))
        .max()
        .unwrap_or(0)
        + 1;
    // The impactor moves along one component: a basic axis, or T3 of a system of its own.
    let axis = (0..3).find(|&c| d == Vector3::ith(c, 1.0));
    let cid = b.cords.iter().map(|c| c.cid).max().unwrap_or(0) + 1;
    let (imp_cd, imp_comp) = match axis {
        Some(c) => (0, c + 1),
        None => (cid, 3),
    };
    let centre = st.point - d * s.impactor.radius.unwrap_or(0.0);
    if let Some(sel) = &st.deck.case.spc {
        let _ = writeln!(w, "  SPC = {}", sel.id);
    }
    let _ = writeln!(w, "  IC = 3\n  NONLINEAR = 5\n  TSTEP = 1\n  TFL = 111");
    let mut pts = vec![gi];
    pts.extend(st.weights.iter().map(|p| p.0));
    pts.extend(s.output.points.iter().copied());
    let mut gages: Vec<i64> = st.element.map(|e| e.1).into_iter().collect();
    gages.extend(s.output.gages.iter().copied());
    let _ = writeln!(w, "  SET 15 = {}", super::join(&pts));
    let _ = writeln!(w, "  NLLOAD = 15\n  DISP = 15");
    if !gages.is_empty() {
        let _ = writeln!(w, "  SET 20 = {}\n  STRESS = 20", super::join(&gages));
    }
    let _ = writeln!(w, "BEGIN BULK");
    let where_ = match st.element {
        Some((card, e)) => format!("{card} {e}"),
        None => format!("grid {}", st.weights[0].0),
    };
    let _ = writeln!(
        w,
        "$ The structure of {} (its SOL, loads and transient cards left out), struck at ({}, {}, {}) on {where_}",
        st.deck.name,
        format_real(st.point.x),
        format_real(st.point.y),
        format_real(st.point.z)
    );
    let _ = writeln!(
        w,
        "$ along ({}, {}, {}); contact weights {}",
        format_real(d.x),
        format_real(d.y),
        format_real(d.z),
        st.weights
            .iter()
            .map(|(g, n)| format!("{g}: {}", format_real(*n)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for c in
        st.deck.cards.iter().filter(|c| {
            crate::deck::cards::supported().contains(&c.name.as_str()) && !LEFT_OUT.contains(&c.name.as_str())
        })
    {
        w.push_str(&c.free_field());
    }
    let _ = writeln!(w, "$ The impactor, its contact and its initial velocity");
    let _ = writeln!(w, "EPOINT,{ep}");
    if imp_cd != 0 {
        // z along the travel, x along any direction across it.
        let across = if d.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let (a, bz, c) = (centre, centre + d, centre + across);
        let _ = writeln!(
            w,
            "CORD2R,{cid},0,{},{},{},{},{},{}\n,{},{},{}",
            format_real(a.x),
            format_real(a.y),
            format_real(a.z),
            format_real(bz.x),
            format_real(bz.y),
            format_real(bz.z),
            format_real(c.x),
            format_real(c.y),
            format_real(c.z)
        );
    }
    let held: String = (1..=6).filter(|&c| c != imp_comp).map(|c| c.to_string()).collect();
    let _ = writeln!(
        w,
        "GRID,{gi},,{},{},{},{},{held}",
        format_real(centre.x),
        format_real(centre.y),
        format_real(centre.z),
        if imp_cd == 0 { String::new() } else { imp_cd.to_string() }
    );
    let _ = writeln!(w, "CONM2,{eid},{gi},0,{}", format_real(s.impactor.mass));
    let _ = writeln!(w, "{tstep}");
    // Each grid's components of d in its own frame, and their TF coefficients.
    let mut terms: Vec<(i64, usize, f64)> = vec![(gi, imp_comp, -1.0)];
    for &(g, n) in &st.weights {
        let t = st.structure.geometry.frame(g);
        let dc = t.transpose() * d;
        for c in 0..3 {
            if dc[c].abs() > NEGLIGIBLE && n != 0.0 {
                terms.push((g, c + 1, n * dc[c]));
            }
        }
    }
    for &(g, c, a) in &terms {
        let _ = writeln!(w, "NOLIN3,5,{g},{c},{},{ep},0,1.5", format_real(st.k * a));
    }
    let _ = write!(w, "TF,111,{ep},0,1.0,0.0,0.0");
    for (g, c, a) in &terms {
        let _ = write!(w, "\n,{g},{c},{},0.0,0.0", format_real(*a));
    }
    let _ = writeln!(w);
    let _ = writeln!(w, "TIC,3,{gi},{imp_comp},0.0,{}", format_real(s.impactor.velocity));
}
