//! The structure's proportional damping from the deck's damping PARAMs, as NASTRAN's
//! direct transient solutions form it ([`crate::model::Damping`]).

use super::*;
use crate::deck::cards::{DampingParam, DampingSetting};

/// a₁ = ALPHA1 and a₂ = ALPHA2 + G/W3, or `None` when they are all zero. G without
/// W3 is left out with a warning, as NASTRAN's transient solutions leave it out
/// (W3 = 0 by default); W3 without G turns nothing viscous. Element damping GE turned
/// viscous at PARAM W4 is refused: impactlab does not form it, and would run a
/// structure with less damping than asked for.
pub(super) fn proportional_damping(cx: &mut Ctx, deck: &Deck) -> Option<Damping> {
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
    if let Some(w4) = get(DampingParam::W4).filter(|s| s.value != 0.0) {
        cx.err(w4.at.error(
            "PARAM W4 turns the elements' damping GE viscous, which impactlab does not form: the run would be \
             less damped than asked for. Give the structure's damping as PARAM G with W3, or ALPHA1 and ALPHA2, \
             or with damping elements (CDAMP1-4, CVISC), and remove PARAM W4",
        ));
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
    (mass != 0.0 || stiffness != 0.0).then_some(Damping { mass, stiffness, from })
}
