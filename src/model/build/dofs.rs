//! The constraints and the solved DOFs: the selected SPCs and enforced values, the
//! rigid elements' dependent components, the numbering of the solved DOFs, and the
//! points that are functionals of them (TF points, rigid elements' dependents).

use super::*;

/// The SPC1 (and SPC) cards the case control's SPC selects: those of its set, or of
/// every set an SPCADD of that id joins (an SPCADD naming an SPCADD, or a set no card
/// has, is an error).
pub(super) fn select_spcs<'d>(cx: &mut Ctx, deck: &'d Deck) -> Vec<&'d crate::deck::cards::Spc1> {
    let (b, case) = (&deck.bulk, &deck.case);
    let Some(add) = case.spc.as_ref().and_then(|s| b.spcadds.iter().find(|a| a.sid == s.id)) else {
        return cx.select("SPC1", "SPC", &case.spc, &b.spc1s, |c| c.sid, |c| &c.at);
    };
    for &set in &add.sets {
        if b.spcadds.iter().any(|a| a.sid == set) {
            cx.err(add.at.error(format!(
                "SPCADD {} joins set {set}, itself an SPCADD: join SPC1/SPC sets only",
                add.sid
            )));
        } else if !b.spc1s.iter().any(|c| c.sid == set) {
            cx.err(add.at.error(format!(
                "SPCADD {} joins set {set}, which no SPC1 or SPC card has",
                add.sid
            )));
        }
    }
    let chosen: Vec<_> = b.spc1s.iter().filter(|c| add.sets.contains(&c.sid)).collect();
    let ignored = b.spc1s.len() - chosen.len();
    if ignored > 0 {
        let first = b
            .spc1s
            .iter()
            .find(|c| !add.sets.contains(&c.sid))
            .expect("one is ignored");
        cx.warn(first.at.error(format!(
            "{ignored} SPC1 card(s) not selected (case control selects SPC = {}, SPCADD of sets {:?}); ignored",
            add.sid, add.sets
        )));
    }
    chosen
}

/// The scalar points of the deck (EPOINT, SPOINT).
pub(super) fn scalar_points(deck: &Deck) -> BTreeMap<i64, &CardRef> {
    let b = &deck.bulk;
    b.epoints
        .iter()
        .chain(b.spoints.iter())
        .map(|(id, at)| (*id, at))
        .collect()
}

/// The selected TFs that define a scalar point from B0 and A0 terms, by point.
pub(super) fn transfer_functions<'d>(
    cx: &mut Ctx,
    sel: &Selected<'d>,
    deck: &Deck,
) -> BTreeMap<i64, &'d crate::deck::cards::Tf> {
    let tfs = &sel.tfs;
    let scalar = scalar_points(deck);
    let mut tf_of: BTreeMap<i64, &crate::deck::cards::Tf> = BTreeMap::new();
    for t in tfs {
        if !scalar.contains_key(&t.gd) {
            cx.err(t.at.error(format!(
                "TF dependent point {} must be an EPOINT or SPOINT (a TF on a structural DOF is not supported)",
                t.gd
            )));
            continue;
        }
        if t.b[1] != 0.0 || t.b[2] != 0.0 || t.terms.iter().any(|x| x.a[1] != 0.0 || x.a[2] != 0.0) {
            cx.err(t.at.error(
                "TF with velocity or acceleration terms (B1, B2, A1, A2 nonzero) is not supported: only B0 and A0",
            ));
            continue;
        }
        if t.b[0] == 0.0 {
            cx.err(t.at.error("TF B0 is zero: the dependent point is not defined"));
            continue;
        }
        if t.terms.iter().any(|x| x.g == t.gd) {
            cx.err(t.at.error(format!(
                "TF references itself: point {} is both dependent and independent",
                t.gd
            )));
            continue;
        }
        if tf_of.insert(t.gd, t).is_some() {
            cx.err(t.at.error(format!("point {} is defined by more than one TF", t.gd)));
        }
    }

    tf_of
}

/// The components a static solution prescribes (see [`Structure::prescribed`]), each
/// with its selected SPC's D: those held at D ≠ 0, and every component an SPCD names,
/// which a selected SPC must hold (SPCD remark 1).
pub(super) fn prescribed_values(
    cx: &mut Ctx,
    deck: &Deck,
    sel: &Selected,
    constrained: &FxHashMap<i64, u8>,
) -> BTreeMap<DofLabel, f64> {
    let mut out = BTreeMap::new();
    for s in &sel.spcs {
        if let Some((d, _)) = &s.enforced {
            for &g in &s.grids {
                for comp in s.c.iter() {
                    out.insert(
                        DofLabel {
                            point: g,
                            comp: comp as u8,
                        },
                        *d,
                    );
                }
            }
        }
    }
    for p in &deck.bulk.spcds {
        if p.c.0 == 0 {
            cx.err(p.at.field_error(
                &p.at_point,
                format!(
                    "SPCD {} names point {} with no component: a scalar point's value cannot be enforced",
                    p.sid, p.point
                ),
            ));
        }
        for comp in p.c.iter() {
            let l = DofLabel {
                point: p.point,
                comp: comp as u8,
            };
            let held = constrained.get(&p.point).is_some_and(|c| c & (1 << (comp - 1)) != 0);
            if !held {
                cx.err(p.at.field_error(
                    &p.at_point,
                    format!(
                        "SPCD {} enforces grid {} component {comp}, which no selected SPC (nor PS) holds: an SPCD \
                         sets the value of a constrained component",
                        p.sid, p.point
                    ),
                ));
                continue;
            }
            out.entry(l).or_insert(0.0);
        }
    }
    out
}

/// The selected SPCs' nonzero enforced values, as errors to raise where they cannot
/// be applied.
pub(super) fn enforced_values(sel: &Selected) -> Vec<Diagnostic> {
    sel.spcs
        .iter()
        .filter_map(|s| {
            let (d, at) = s.enforced.as_ref()?;
            Some(s.at.field_error(
                at,
                format!("an enforced displacement (D = {d:e}) is not supported: impactlab holds constrained components at zero"),
            ))
        })
        .collect()
}

/// The grids and their constrained components (PS, GRDSET and the selected SPC1s),
/// each in the grid's displacement frame.
pub(super) fn constrained_grids(cx: &mut Ctx, deck: &Deck, sel: &Selected) -> FxHashMap<i64, u8> {
    let b = &deck.bulk;
    let spcs = &sel.spcs;
    let scalar = scalar_points(deck);
    let mut constrained: FxHashMap<i64, u8> = FxHashMap::default();
    for g in &b.grids {
        let ps = g.ps.unwrap_or(b.grdset.ps);
        constrained.insert(g.id, ps.0);
    }
    for s in spcs {
        for gid in &s.grids {
            match constrained.get_mut(gid) {
                Some(_) if s.c.0 == 0 => cx.err(s.at.error(format!(
                    "constrains grid {gid} in no component (a blank or 0 component names a scalar point)"
                ))),
                Some(c) => *c |= s.c.0,
                None if scalar.contains_key(gid) => cx.err(s.at.error(format!(
                    "SPC1 constrains point {gid}, a scalar point: only grids are supported"
                ))),
                None => cx.err(s.at.error(format!("SPC1 references grid {gid}, which does not exist"))),
            }
        }
    }

    constrained
}

/// The numbering of the solved DOFs: the components of each grid that no SPC
/// constrains and no rigid element makes dependent, in id order, then the scalar points no TF defines.
pub(super) fn number_dofs<'d>(
    deck: &'d Deck,
    constrained: &FxHashMap<i64, u8>,
    tf_of: &BTreeMap<i64, &crate::deck::cards::Tf>,
    rigid: &'d crate::model::rigid::Rigid,
) -> Numbering<'d> {
    let grids: BTreeMap<i64, &crate::deck::cards::Grid> = deck.bulk.grids.iter().map(|g| (g.id, g)).collect();
    let scalar = scalar_points(deck);
    let solved: Vec<(i64, u8)> = grids
        .keys()
        .map(|&id| (id, !(constrained[&id] | rigid.dependent(id)) & 0b11_1111))
        .collect();
    let free_scalars = scalar.keys().filter(|id| !tf_of.contains_key(id)).count();
    let mut dofs = Vec::with_capacity(solved.iter().map(|s| s.1.count_ones() as usize).sum::<usize>() + free_scalars);
    let mut grid_first = FxHashMap::with_capacity_and_hasher(grids.len(), Default::default());
    for (id, solved) in solved {
        grid_first.insert(id, (dofs.len(), solved));
        for comp in (1..=6u8).filter(|c| solved & (1 << (c - 1)) != 0) {
            dofs.push(DofLabel { point: id, comp });
        }
    }
    let mut scalar_index = FxHashMap::default();
    for &id in scalar.keys() {
        if !tf_of.contains_key(&id) {
            scalar_index.insert(id, dofs.len());
            dofs.push(DofLabel { point: id, comp: 0 });
        }
    }
    Numbering {
        grids,
        scalar,
        dofs,
        grid_first,
        scalar_index,
        rigid,
    }
}

/// The rigid elements resolved (their dependent components are left out of the
/// solved DOFs by [`number_dofs`]): an SPC on a dependent DOF is an error naming both
/// cards; a PS (GRID or GRDSET) on it yields to the tie, with a warning.
pub(super) fn rigid_elements(cx: &mut Ctx, deck: &Deck, geo: &Geometry, sel: &Selected) -> crate::model::rigid::Rigid {
    let mut errors = Vec::new();
    let rigid = crate::model::rigid::resolve(&deck.bulk, geo, &mut errors);
    for d in errors {
        cx.err(d);
    }
    for s in &sel.spcs {
        for (gm, t) in s.grids.iter().filter_map(|g| Some((g, rigid.ties.get(g)?))) {
            if s.c.0 & t.dependent == 0 {
                continue;
            }
            cx.err(s.at.error(match t.whole() {
                Some((gn, _)) => format!(
                    "SPC1 constrains grid {gm}, which {} (at {}) makes dependent: constrain its independent grid \
                     {gn} instead",
                    t.name, t.at.pos
                ),
                None => format!(
                    "SPC1 constrains components of grid {gm} that {} (at {}) makes dependent: constrain the grids \
                     they follow instead",
                    t.name, t.at.pos
                ),
            }));
        }
    }
    let b = &deck.bulk;
    let ps: HashMap<i64, u8> = b.grids.iter().map(|g| (g.id, g.ps.unwrap_or(b.grdset.ps).0)).collect();
    for (gm, t) in &rigid.ties {
        let held = |g: &i64| ps.get(g).copied().unwrap_or(0);
        match t.whole() {
            Some((gn, _)) if held(gm) & !held(&gn) != 0 => cx.warn(t.at.warning(format!(
                "grid {gm}'s PS holds components its independent grid {gn} does not: {} ties them to grid \
                 {gn}'s motion instead",
                t.name
            ))),
            None if held(gm) & t.dependent != 0 => cx.warn(t.at.warning(format!(
                "grid {gm}'s PS holds components {} makes dependent: they follow the tie instead",
                t.name
            ))),
            _ => {}
        }
    }
    rigid
}

/// Each TF's dependent point as a functional of the solved DOFs.
pub(super) fn dependent_points(
    cx: &mut Ctx,
    tf_of: &BTreeMap<i64, &crate::deck::cards::Tf>,
    num: &Numbering,
) -> Dependent {
    let mut dependent = Vec::new();
    let mut dep_index: HashMap<i64, usize> = HashMap::new();
    for (&gd, t) in tf_of {
        let mut f = Functional::new();
        let mut ok = true;
        for term in &t.terms {
            if tf_of.contains_key(&term.g) {
                cx.err(t.at.error(format!(
                    "TF independent point {} is itself defined by a TF: chained transfer functions are not supported",
                    term.g
                )));
                ok = false;
                continue;
            }
            match num.lookup(cx, &t.at, "TF", term.g, term.c) {
                Some(i) => f.push((i, -term.a[0] / t.b[0])),
                None => ok = false,
            }
        }
        if ok {
            dep_index.insert(gd, dependent.len());
            dependent.push(DependentPoint {
                label: DofLabel { point: gd, comp: 0 },
                functional: f,
                at: t.at.clone(),
                tied: false,
            });
        }
    }

    Dependent {
        points: dependent,
        index: dep_index,
    }
}

/// The rigid elements' dependent components as dependent points (functionals of the
/// solved DOFs: the rows of their ties), appended to `dependent` after the TF points,
/// for the output requests: grid → the index there of each dependent component.
pub(super) fn tied_points(
    rigid: &crate::model::rigid::Rigid,
    num: &Numbering,
    dependent: &mut Dependent,
) -> BTreeMap<i64, [Option<usize>; 6]> {
    let mut out = BTreeMap::new();
    for (&gm, t) in &rigid.ties {
        let mut at = [None; 6];
        for (c, slot) in at.iter_mut().enumerate().filter(|(c, _)| t.ties(*c)) {
            *slot = Some(dependent.points.len());
            dependent.points.push(DependentPoint {
                label: DofLabel {
                    point: gm,
                    comp: c as u8 + 1,
                },
                functional: t.functional(c, &|g| num.grid_dofs(g)),
                at: t.at.clone(),
                tied: true,
            });
        }
        out.insert(gm, at);
    }
    out
}
