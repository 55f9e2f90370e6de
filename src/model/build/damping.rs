//! The structure's proportional damping from the deck's damping PARAMs, as NASTRAN's
//! direct transient solutions form it ([`crate::model::Damping`]).

use super::*;
use crate::deck::cards::{DampingParam, DampingSetting};

/// PARAM W4 when it is set and not zero: the circular frequency (radians per time
/// unit) at which the elements' structural damping GE is turned viscous, each element
/// adding (GE/W4)·K_e to C ([`crate::elements::Element::stiffness_damping`]).
pub(super) fn element_damping_frequency(deck: &Deck) -> Option<&DampingSetting> {
    deck.bulk
        .damping
        .iter()
        .find(|s| s.param == DampingParam::W4)
        .filter(|s| s.value != 0.0)
}

/// a₁ = ALPHA1 and a₂ = ALPHA2 + G/W3, with the cards they come from, or `None` when
/// nothing damps the structure. G without W3 is left out with a warning, as NASTRAN's
/// transient solutions leave it out (W3 = 0 by default); W3 without G turns nothing
/// viscous. `structurally_damped` elements have a GE (the first given on the card
/// named): W4 turns it viscous (named among the sources, a₁ and a₂ unchanged), and
/// without W4 it is left out with a warning, as NASTRAN leaves it out.
pub(super) fn proportional_damping(
    cx: &mut Ctx,
    deck: &Deck,
    structurally_damped: &(usize, Option<CardRef>),
) -> Option<Damping> {
    let settings = &deck.bulk.damping;
    let get = |p: DampingParam| settings.iter().find(|s| s.param == p);
    let value = |s: Option<&DampingSetting>| s.map_or(0.0, |s| s.value);
    let said = |s: &DampingSetting| format!("PARAM {} {:e} at {}", s.param.name(), s.value, s.at.pos);
    let (g, w3) = (get(DampingParam::G), get(DampingParam::W3));
    let mut from = Vec::new();
    let mut stiffness = 0.0;
    match (g.filter(|s| s.value != 0.0), w3.filter(|s| s.value != 0.0)) {
        (Some(g), Some(w3)) => {
            stiffness += g.value / w3.value;
            from.push(format!("{} turned viscous at {}", said(g), said(w3)));
        }
        (Some(g), None) => cx.warn(g.at.error(format!(
            "PARAM G {:e} without W3 (or with W3 = 0): NASTRAN's transient solutions leave structural damping \
             out, and so does impactlab; set PARAM W3, the circular frequency (radians per time unit) at which G \
             is turned viscous",
            g.value
        ))),
        (None, Some(w3)) => cx.warn(w3.at.error(format!(
            "PARAM W3 {:e} without G: there is no structural damping to turn viscous",
            w3.value
        ))),
        (None, None) => {}
    }
    match (element_damping_frequency(deck), structurally_damped) {
        (Some(w4), (n, Some(first))) => from.push(format!(
            "{} turns the structural damping GE of {n} element{} viscous (the first from {} at {})",
            said(w4),
            if *n == 1 { "" } else { "s" },
            first.name,
            first.pos
        )),
        (Some(w4), _) => cx.warn(w4.at.error(format!(
            "PARAM W4 {:e} without an element whose material or property gives GE: there is no structural \
             damping to turn viscous",
            w4.value
        ))),
        (None, (n, Some(first))) => cx.warn(first.error(format!(
            "{n} element{} a structural damping GE ({} is the first), which NASTRAN's transient solutions \
             leave out without PARAM W4, and so does impactlab; set PARAM W4, the circular frequency (radians per \
             time unit) at which GE is turned viscous",
            if *n == 1 { " has" } else { "s have" },
            first.name
        ))),
        (None, _) => {}
    }
    let mass = value(get(DampingParam::Alpha1));
    for s in [get(DampingParam::Alpha1), get(DampingParam::Alpha2)]
        .into_iter()
        .flatten()
    {
        if s.value != 0.0 {
            from.push(said(s));
        }
    }
    stiffness += value(get(DampingParam::Alpha2));
    (!from.is_empty()).then_some(Damping { mass, stiffness, from })
}
