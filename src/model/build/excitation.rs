//! The dynamic load stage: the case control's DLOAD resolved to an [`Excitation`].
//! A TLOAD's L names the DAREA set and the LSEQ cards (of the case control's LOADSET)
//! whose EXCITEID it is: each DAREA entry loads its DOF with A; each LSEQ's static
//! load set LID (FORCE, MOMENT, PLOAD, PLOAD2, PLOAD4, GRAV, LOAD) is assembled as a
//! static solution assembles it ([`crate::model::loads`]), its components on the
//! solved DOFs (a dependent grid's carried by the grids it follows, those on
//! constrained DOFs dropped, as a static solution's) each a term of the load.

use super::*;
use crate::deck::cards::{DelayRef, Tload, TloadShape};
use crate::model::excitation::{Excitation, LoadTerm, TimeFunction};

/// The dynamic load the case control's DLOAD selects: a DLOAD card's combination of
/// TLOAD sets, or one TLOAD set; `None` without a DLOAD request (TLOAD cards are then
/// warned about: they are not applied).
pub(super) fn excitation(cx: &mut Ctx, deck: &Deck, num: &Numbering) -> Option<Excitation> {
    let b = &deck.bulk;
    let Some(sel) = &deck.case.dload else {
        if let Some(t) = b.tloads.first() {
            cx.warn(t.at.error(format!(
                "{} TLOAD card(s), but case control has no DLOAD request: no dynamic load is applied",
                b.tloads.len()
            )));
        }
        return None;
    };
    for (k, t) in b.tloads.iter().enumerate() {
        if let Some(first) = b.tloads[..k].iter().find(|o| o.sid == t.sid) {
            cx.err(t.at.error(format!(
                "TLOAD set {} is defined again (first at {}): \"SID must be unique for all TLOAD1, TLOAD2\" cards",
                t.sid, first.at.pos
            )));
        }
    }
    let dloads: Vec<_> = b.dloads.iter().filter(|d| d.sid == sel.id).collect();
    if let [first, second, ..] = dloads.as_slice() {
        cx.err(
            second
                .at
                .error(format!("DLOAD {} is defined twice (first at {})", sel.id, first.at.pos)),
        );
    }
    let (sets, source): (Vec<(f64, i64, &CardRef)>, &CardRef) = match dloads.first() {
        Some(d) => {
            if let Some(t) = b.tloads.iter().find(|t| t.sid == d.sid) {
                cx.err(t.at.error(format!(
                    "has SID {}, which a DLOAD also has (at {}): DLOAD = {} is ambiguous",
                    t.sid, d.at.pos, sel.id
                )));
            }
            (d.terms.iter().map(|&(s, l)| (d.scale * s, l, &d.at)).collect(), &d.at)
        }
        None => match b.tloads.iter().find(|t| t.sid == sel.id) {
            Some(t) => (vec![(1.0, sel.id, &t.at)], &t.at),
            None => {
                cx.err(
                    Diagnostic::error(
                        Some(sel.pos.clone()),
                        format!(
                            "case control DLOAD = {} selects no DLOAD, TLOAD1 or TLOAD2 card",
                            sel.id
                        ),
                    )
                    .card("DLOAD"),
                );
                return None;
            }
        },
    };
    let mut structure = None;
    let mut ex = Excitation {
        terms: Vec::new(),
        functions: Vec::new(),
        source: format!("{} {} at {}", source.name, sel.id, source.pos),
    };
    for (scale, l, at) in sets {
        let Some(t) = b.tloads.iter().find(|t| t.sid == l) else {
            cx.err(at.error(format!(
                "DLOAD combines load set {l}, which no TLOAD1 or TLOAD2 defines"
            )));
            continue;
        };
        let Some(function) = time_function(cx, deck, t) else {
            continue;
        };
        ex.functions.push(function);
        let function = ex.functions.len() - 1;
        if let DelayRef::Set(m) = t.delay {
            if !b.delays.iter().any(|e| e.sid == m) {
                cx.err(t.at.error(format!("its M = {m} names no DELAY set")));
            }
        }
        // A DOF the DELAY set does not list is not delayed.
        let delay = |p: i64, c: usize| match t.delay {
            DelayRef::None => 0.0,
            DelayRef::Value(tau) => tau,
            DelayRef::Set(m) => b
                .delays
                .iter()
                .find(|e| e.sid == m && e.p == p && e.c == c)
                .map_or(0.0, |e| e.t),
        };
        let dareas: Vec<_> = b.dareas.iter().filter(|d| d.sid == t.excite).collect();
        let lseqs: Vec<_> = match &deck.case.loadset {
            Some(ls) => b
                .lseqs
                .iter()
                .filter(|l| l.sid == ls.id && l.excite == t.excite)
                .collect(),
            None => Vec::new(),
        };
        if dareas.is_empty() && lseqs.is_empty() {
            cx.err(t.at.error(format!(
                "its L = {} names no DAREA set{}",
                t.excite,
                match &deck.case.loadset {
                    Some(ls) => format!(" and no LSEQ of LOADSET {} has it as EXCITEID", ls.id),
                    None => String::new(),
                }
            )));
        }
        for d in dareas {
            let Some(dof) = num.lookup(cx, &d.at, "DAREA", d.p, d.c) else {
                continue;
            };
            ex.terms.push(LoadTerm {
                dof,
                scale: scale * d.a,
                delay: delay(d.p, d.c),
                function,
            });
        }
        for l in lseqs {
            let Some(s) = static_structure(cx, deck, &mut structure) else {
                break;
            };
            let sel = Selection {
                id: l.lid,
                pos: l.at.pos.clone(),
            };
            let loads = match crate::model::loads::static_load_of(deck, s, Some(&sel), None) {
                Ok(loads) => loads,
                Err(e) => {
                    e.diagnostics.into_iter().for_each(|d| cx.err(d));
                    continue;
                }
            };
            for (g, l) in loads {
                for (g, l) in s.rigid.carry(g, l) {
                    for (c, v) in l.into_iter().enumerate().filter(|(_, v)| *v != 0.0) {
                        let label = DofLabel {
                            point: g,
                            comp: c as u8 + 1,
                        };
                        if let Some(dof) = num.index(&label) {
                            ex.terms.push(LoadTerm {
                                dof,
                                scale: scale * v,
                                delay: delay(g, c + 1),
                                function,
                            });
                        }
                    }
                }
            }
        }
    }
    Some(ex)
}

/// The deck's structure, built once for the static load sets an LSEQ names (their
/// pressures and gravity need its elements); `None` when it does not build (the
/// model's own stages report why).
fn static_structure<'s>(cx: &mut Ctx, deck: &Deck, structure: &'s mut Option<Structure>) -> Option<&'s Structure> {
    if structure.is_none() && !cx.diags.iter().any(|d| d.is_error()) {
        *structure = build_structure(deck).ok().map(|(s, _)| s);
    }
    structure.as_ref()
}

/// A TLOAD's time function: TLOAD2's formula, or TLOAD1's table.
fn time_function(cx: &mut Ctx, deck: &Deck, t: &Tload) -> Option<TimeFunction> {
    match t.shape {
        TloadShape::Formula(f) => Some(TimeFunction::Formula(f)),
        TloadShape::Table(tid) => match deck.bulk.tableds.iter().find(|d| d.id == tid) {
            Some(d) => Some(TimeFunction::Table(d.function.clone())),
            None => {
                cx.err(t.at.error(format!("its TID = {tid} names no TABLED1, TABLED2, TABLED3 or TABLED4")));
                None
            }
        },
    }
}
