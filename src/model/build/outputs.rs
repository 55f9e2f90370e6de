//! The output requests: which DOFs and elements each writes.

use super::*;

/// What case control asks to be written: DISP, VELO, NLLOAD, STRESS, STRAIN, FORCE
/// (or ELFORCE).
pub(super) fn output_plan(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    (dependent, tied): (&Dependent, &BTreeMap<i64, [Option<usize>; 6]>),
    built: &Elements,
    contact: Option<&Contact>,
) -> OutputPlan {
    let elements = &built.list;
    let case = &deck.case;
    let (grids, scalar) = (&num.grids, &num.scalar);
    let (dep_index, dependent) = (&dependent.index, &dependent.points);
    let mut outputs = OutputPlan::default();
    let set_members = |req: Option<&crate::deck::case::OutputRequest>| -> Option<Vec<i64>> {
        match req.map(|r| &r.set) {
            None | Some(OutputSet::None) => None,
            Some(OutputSet::All) => Some(Vec::new()),
            Some(OutputSet::Set(id)) => case.sets.get(id).map(|s| s.members.clone()),
        }
    };
    let all_points = || -> Vec<i64> { grids.keys().copied().chain(scalar.keys().copied()).collect() };
    for (key, target) in [("DISP", 0), ("VELO", 1)] {
        let req = case.outputs.get(key);
        let Some(mut members) = set_members(req) else { continue };
        if matches!(req.map(|r| &r.set), Some(OutputSet::All)) {
            members = all_points();
        }
        let mut list = Vec::new();
        for p in members {
            if let Some(&j) = dep_index.get(&p) {
                list.push((dependent[j].label, Source::Dependent(j)));
            } else if grids.contains_key(&p) || scalar.contains_key(&p) {
                let comps: Vec<u8> = if scalar.contains_key(&p) {
                    vec![0]
                } else {
                    (1..=6).collect()
                };
                for comp in comps {
                    let l = DofLabel { point: p, comp };
                    if let Some(j) = tied.get(&p).and_then(|t| t[comp as usize - 1]) {
                        list.push((l, Source::Dependent(j)));
                    } else if let Some(i) = num.index(&l) {
                        list.push((l, Source::Dof(i)));
                    }
                }
            }
        }
        if target == 0 {
            outputs.disp = list;
        } else {
            outputs.velo = list;
        }
    }
    if let (Some(members), Some(c)) = (set_members(case.outputs.get("NLLOAD")), contact) {
        let all = members.is_empty();
        outputs.nlload = (0..c.loads.len())
            .filter(|&k| all || members.contains(&c.loads[k].label.point))
            .collect();
    }
    [outputs.stress, outputs.strain, outputs.force] = element_requests(case, elements);
    // Ply results of every written laminate element, in the order its element's
    // results are written.
    outputs.plies = outputs
        .written()
        .filter(|(_, what)| *what != crate::elements::Output::Force)
        .filter_map(|(e, _)| Some((e, built.plies.get(&e)?.clone())))
        .collect();
    outputs.failure_fields = built
        .plies
        .iter()
        .filter(|(_, p)| p.iter().any(|l| !l.criteria.is_empty()))
        .map(|(e, p)| (*e, p.clone()))
        .collect();
    outputs.failure_fields.sort_by_key(|(e, _)| *e);
    if case.outputs.contains_key("ACCEL") {
        cx.warn(Diagnostic::warning(
            case.outputs.get("ACCEL").map(|r| r.pos.clone()),
            "ACCEL output is not written (accelerations are not part of every scheme's state); ignored",
        ));
    }
    let accel = case.outputs.contains_key("ACCEL").then(|| "ACCEL".to_string());
    for name in case.not_written.iter().map(|(k, _)| k.clone()).chain(accel) {
        if !outputs.not_written.contains(&name) {
            outputs.not_written.push(name);
        }
    }

    outputs
}

/// The elements (indices into `elements`) case control's STRESS, STRAIN and FORCE (or
/// ELFORCE) ask for, in that order: every element but the concentrated masses, in
/// element order, for ALL (or a SET of ALL), the SET's members in its order otherwise.
pub(crate) fn element_requests(case: &crate::deck::case::CaseControl, elements: &[Element]) -> [Vec<usize>; 3] {
    let elem_pos: HashMap<i64, usize> = elements
        .iter()
        .enumerate()
        .filter(|(_, e)| !matches!(e.kernel.family(), Family::Point { .. }))
        .map(|(i, e)| (e.eid, i))
        .collect();
    ["STRESS", "STRAIN", "FORCE"].map(|key| {
        let req = match key {
            "FORCE" => case.outputs.get("FORCE").or(case.outputs.get("ELFORCE")),
            _ => case.outputs.get(key),
        };
        let members = match req.map(|r| &r.set) {
            None | Some(OutputSet::None) => return Vec::new(),
            Some(OutputSet::All) => Vec::new(),
            Some(OutputSet::Set(id)) => match case.sets.get(id) {
                Some(s) => s.members.clone(),
                None => return Vec::new(),
            },
        };
        if members.is_empty() {
            let mut v: Vec<usize> = elem_pos.values().copied().collect();
            v.sort();
            v
        } else {
            members.iter().filter_map(|m| elem_pos.get(m).copied()).collect()
        }
    })
}
