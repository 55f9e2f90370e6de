//! The contact: the NOLIN3 loads, the impactor they find, its Hertz stiffness and the
//! part of the load that derives from no potential.

use super::*;

/// What the contact definition refers to.
pub(super) struct ContactRefs<'a> {
    pub(super) dependent: &'a [DependentPoint],
    pub(super) dep_index: &'a HashMap<i64, usize>,
    pub(super) elements: &'a [Element],
    pub(super) on_element: &'a FxHashSet<i64>,
    pub(super) labels: &'a [DofLabel],
}

pub(super) fn build_contact(
    cx: &mut Ctx,
    nolins: &[&crate::deck::cards::Nolin3],
    refs: &ContactRefs,
    lookup: impl Fn(&mut Ctx, &CardRef, &str, i64, usize) -> Option<usize>,
) -> Option<Contact> {
    // Errors already found (a missing material, a bad TF) make the checks of the
    // impactor fail as a consequence; they are reported only on an otherwise clean model.
    let prior_errors = cx.diags.iter().any(|d| d.is_error());
    let first = nolins.first()?;
    let (driver, driver_label, loads) = contact_loads(cx, nolins, refs, lookup)?;
    let imp = find_impactor(cx, first, &loads, refs.on_element, prior_errors)?;
    let mass = refs
        .elements
        .iter()
        .filter(|e| e.grids == [imp.label.point])
        .filter_map(|e| match e.kernel.family() {
            Family::Point { mass } => Some(mass),
            _ => None,
        })
        .sum::<f64>();
    if let Some(e) = refs
        .elements
        .iter()
        .find(|e| e.grids == [imp.label.point] && matches!(e.kernel.family(), Family::MassMatrix))
    {
        cx.err(imp.at.error(format!(
            "the impactor grid {} carries CONM1 {}: an impactor's mass is a CONM2's (the same along each \
             axis, which the contact's energy partition needs)",
            imp.label.point, e.eid
        )));
        return None;
    }
    if mass <= 0.0 {
        // After other errors the mass may be missing only because its grid is (an
        // unresolved location): that error says why.
        if !prior_errors {
            cx.err(
                imp.at
                    .error(format!("the impactor grid {} has no CONM2 mass", imp.label.point)),
            );
        }
        return None;
    }
    let stiffness = impactor_stiffness(cx, imp, &driver, driver_label, prior_errors)?;
    let nonconservative = nonconservative_remainder(cx, &loads, &driver, stiffness, refs.labels);
    let imp_grid = imp.label.point;
    let imp_dofs = impactor_dofs(refs.elements, imp);
    let imp_dof = imp.dof;
    Some(Contact {
        driver,
        driver_label,
        exponent: first.a,
        stiffness,
        impactor: Impactor {
            grid: imp_grid,
            dof: imp_dof,
            mass,
            dofs: imp_dofs,
        },
        loads,
        nonconservative,
        unloading: Default::default(),
    })
}

/// The NOLIN3 loads of one contact (one driver, one exponent), the driver as a
/// functional of the solved DOFs and its label.
pub(super) fn contact_loads(
    cx: &mut Ctx,
    nolins: &[&crate::deck::cards::Nolin3],
    refs: &ContactRefs,
    lookup: impl Fn(&mut Ctx, &CardRef, &str, i64, usize) -> Option<usize>,
) -> Option<(Functional, DofLabel, Vec<NonlinearLoad>)> {
    let (dependent, dep_index) = (refs.dependent, refs.dep_index);
    let first = nolins.first()?;
    // One driver and one exponent for all NOLIN3 loads: one contact.
    let mut ok = true;
    for n in nolins {
        if n.gj != first.gj || n.cj != first.cj {
            cx.err(n.at.error(format!(
                "NOLIN3 driven by point {} while another is driven by point {}: one contact (one driving DOF) is supported",
                n.gj, first.gj
            )));
            ok = false;
        }
        if n.a != first.a {
            cx.err(n.at.error(format!(
                "NOLIN3 exponent {} differs from {} on another card of the same contact",
                n.a, first.a
            )));
            ok = false;
        }
    }
    let (driver, driver_label) = match dep_index.get(&first.gj) {
        Some(&j) => (dependent[j].functional.clone(), dependent[j].label),
        None => {
            let i = lookup(cx, &first.at, "NOLIN3 driver", first.gj, first.cj)?;
            (
                vec![(i, 1.0)],
                DofLabel {
                    point: first.gj,
                    comp: first.cj as u8,
                },
            )
        }
    };
    let mut loads = Vec::new();
    for n in nolins {
        if dep_index.contains_key(&n.gi) {
            cx.err(n.at.error(format!(
                "NOLIN3 loads point {}, which a TF defines: it cannot carry a load",
                n.gi
            )));
            ok = false;
            continue;
        }
        if let Some(dof) = lookup(cx, &n.at, "NOLIN3", n.gi, n.ci) {
            loads.push(NonlinearLoad {
                dof,
                label: DofLabel {
                    point: n.gi,
                    comp: n.ci as u8,
                },
                scale: n.s,
                at: n.at.clone(),
            });
        } else {
            ok = false;
        }
    }
    ok.then_some((driver, driver_label, loads))
}

/// The impactor: the loaded grid that no structural element touches.
pub(super) fn find_impactor<'l>(
    cx: &mut Ctx,
    first: &crate::deck::cards::Nolin3,
    loads: &'l [NonlinearLoad],
    on_element: &FxHashSet<i64>,
    prior_errors: bool,
) -> Option<&'l NonlinearLoad> {
    let free: Vec<&NonlinearLoad> = loads
        .iter()
        .filter(|l| l.label.comp != 0 && !on_element.contains(&l.label.point))
        .collect();
    match free.as_slice() {
        [one] => Some(*one),
        [] => {
            if prior_errors {
                return None;
            }
            cx.err(first.at.error(
                "cannot identify the impactor: every grid loaded by NOLIN3 is attached to an element \
                 (the impactor is a point mass loaded by the contact and attached to nothing else)",
            ));
            None
        }
        many => {
            if prior_errors {
                return None;
            }
            cx.err(first.at.error(format!(
                "cannot identify the impactor: {} grids loaded by NOLIN3 carry no element ({})",
                many.len(),
                many.iter().map(|l| l.label.point.to_string()).collect::<Vec<_>>().join(", ")
            )));
            None
        }
    }
}

/// The Hertz K the impactor's load implies, K = −S/(∂α/∂u), which must be positive.
pub(super) fn impactor_stiffness(
    cx: &mut Ctx,
    imp: &NonlinearLoad,
    driver: &Functional,
    driver_label: DofLabel,
    prior_errors: bool,
) -> Option<f64> {
    let c_imp: f64 = driver.iter().filter(|(j, _)| *j == imp.dof).map(|(_, c)| c).sum();
    if c_imp == 0.0 {
        if prior_errors {
            return None;
        }
        cx.err(imp.at.error(format!(
            "the contact's driving point {driver_label} does not depend on the impactor DOF {}",
            imp.label
        )));
        return None;
    }
    let stiffness = -imp.scale / c_imp;
    if stiffness <= 0.0 {
        cx.err(imp.at.error(format!(
            "the impactor load S = {} pushes the impactor into the target as the indentation grows \
             (S·∂α/∂u = {} must be negative for a repulsive contact)",
            imp.scale,
            imp.scale * c_imp
        )));
        return None;
    }
    Some(stiffness)
}

/// The non-conservative remainder S_i + K ∂α/∂u_i of the loads over all DOFs touched,
/// each nonzero entry warned about.
pub(super) fn nonconservative_remainder(
    cx: &mut Ctx,
    loads: &[NonlinearLoad],
    driver: &Functional,
    stiffness: f64,
    labels: &[DofLabel],
) -> Functional {
    let mut rem: BTreeMap<usize, f64> = BTreeMap::new();
    for l in loads {
        *rem.entry(l.dof).or_default() += l.scale;
    }
    for &(j, c) in driver {
        *rem.entry(j).or_default() += stiffness * c;
    }
    let nonconservative: Functional = rem.into_iter().filter(|(_, v)| *v != 0.0).collect();
    for &(j, v) in &nonconservative {
        let load = loads.iter().find(|l| l.dof == j);
        let msg = format!(
            "contact load on {} is not derivable from the Hertz potential of the impactor's K = {stiffness:.6e}: \
             remainder {v:+.4e} ({:.2e} of K); its work is booked as external work. A balanced deck uses S = {:.6e}",
            labels[j],
            (v / stiffness).abs(),
            load.map(|l| l.scale - v).unwrap_or(-v),
        );
        match load {
            Some(l) => cx.warn(l.at.error(msg)),
            None => cx.warn(Diagnostic::warning(None, msg)),
        }
    }
    nonconservative
}

/// Every solved DOF of the impactor's grid (its CONM2's and the loaded one).
pub(super) fn impactor_dofs(elements: &[Element], imp: &NonlinearLoad) -> Vec<usize> {
    let imp_grid = imp.label.point;
    let mut v = Vec::new();
    for e in elements.iter().filter(|e| e.grids == [imp_grid]) {
        if matches!(e.kernel.family(), Family::Point { .. }) {
            v.extend(e.dofs.iter().flatten().flatten().copied());
        }
    }
    if !v.contains(&imp.dof) {
        v.push(imp.dof);
    }
    v.sort();
    v.dedup();
    v
}
