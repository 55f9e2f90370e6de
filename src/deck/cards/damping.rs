//! What damps a transient response: PARAM G, W3, W4, ALPHA1 and ALPHA2, and the
//! viscous rod damper CVISC with its PVISC
//! (`manual/BULK.TXT`; MSC's ALPHA1 and ALPHA2, Rayleigh damping). The scalar dampers
//! CDAMP1-4 and their PDAMP are read with the scalar springs and masses
//! ([`super::card_scalar`], [`super::card_scalar_property`]).

use super::reader::Reader;
use super::{Bulk, CardRef};

/// A PARAM that damps a transient response.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DampingParam {
    /// G: the structural damping coefficient of the whole structure.
    G,
    /// W3: the frequency (radians per time unit) at which G is turned viscous.
    W3,
    /// W4: the frequency at which the elements' GE is turned viscous.
    W4,
    /// ALPHA1: the mass-proportional (Rayleigh) coefficient, C += ALPHA1·M.
    Alpha1,
    /// ALPHA2: the stiffness-proportional (Rayleigh) coefficient, C += ALPHA2·K.
    Alpha2,
}

impl DampingParam {
    /// The parameter a PARAM's name gives, if it damps.
    pub fn of_name(name: &str) -> Option<DampingParam> {
        [
            ("G", DampingParam::G),
            ("W3", DampingParam::W3),
            ("W4", DampingParam::W4),
            ("ALPHA1", DampingParam::Alpha1),
            ("ALPHA2", DampingParam::Alpha2),
        ]
        .into_iter()
        .find(|(n, _)| name.eq_ignore_ascii_case(n))
        .map(|(_, p)| p)
    }

    /// Its name on a PARAM card.
    pub fn name(self) -> &'static str {
        match self {
            DampingParam::G => "G",
            DampingParam::W3 => "W3",
            DampingParam::W4 => "W4",
            DampingParam::Alpha1 => "ALPHA1",
            DampingParam::Alpha2 => "ALPHA2",
        }
    }
}

/// A damping PARAM as the deck sets it.
#[derive(Debug, Clone)]
pub struct DampingSetting {
    /// Which.
    pub param: DampingParam,
    /// Its value V1.
    pub value: f64,
    /// The card.
    pub at: CardRef,
}

/// PARAM G, W3, W4, ALPHA1 or ALPHA2: V1 a real. G and the Rayleigh coefficients
/// may be of any sign NASTRAN takes (a negative value is refused: it feeds energy
/// in); W3 and W4 are frequencies, zero meaning "not set", as NASTRAN's default.
/// A second card for one parameter is refused.
pub(super) fn card_damping_param(r: &mut Reader, b: &mut Bulk, param: DampingParam) {
    let value = r.real(1, "V1");
    r.non_negative(1, "V1", value);
    r.extra_fields(2);
    if let Some(first) = b.damping.iter().find(|s| s.param == param) {
        let first = first.at.pos.clone();
        r.fail(
            0,
            "N",
            format!("PARAM {} is set twice (first at {first})", param.name()),
        );
    }
    if r.ok {
        b.damping.push(DampingSetting {
            param,
            value,
            at: r.at(),
        });
    }
}

/// PVISC (PID C1 C2), up to two on a card: a viscous damper's property.
#[derive(Debug, Clone)]
pub struct Pvisc {
    /// Property id.
    pub pid: i64,
    /// C1: the damping coefficient along the damper.
    pub extension: f64,
    /// C2: the rotational damping coefficient about it.
    pub rotation: f64,
    /// The card.
    pub at: CardRef,
}

/// PVISC (PID C1 C2): one property of the card's up to two, C1 extensional and
/// C2 rotational ("viscous coefficients for extension and rotation").
pub(super) fn card_pvisc(r: &mut Reader, b: &mut Bulk) {
    let p = Pvisc {
        pid: r.id(0, "PID"),
        extension: r.real_or(1, "C1", 0.0),
        rotation: r.real_or(2, "C2", 0.0),
        at: r.at(),
    };
    r.extra_fields(4);
    if r.ok {
        b.pviscs.push(p);
    }
}

/// CVISC (EID PID G1 G2): a viscous damper along the line of its two grids.
#[derive(Debug, Clone)]
pub struct Cvisc {
    /// Element id.
    pub eid: i64,
    /// Its PVISC (blank: EID).
    pub pid: i64,
    /// Its grids.
    pub grids: [i64; 2],
    /// The card.
    pub at: CardRef,
}

/// CVISC (EID PID G1 G2): one of the card's up to two ("one or two VISC elements
/// may be defined on a single card").
pub(super) fn card_cvisc(r: &mut Reader, b: &mut Bulk) {
    let eid = r.id(0, "EID");
    let c = Cvisc {
        eid,
        pid: r.int_or(1, "PID", eid),
        grids: [r.id(2, "G1"), r.id(3, "G2")],
        at: r.at(),
    };
    if r.ok && c.grids[0] == c.grids[1] {
        r.fail(3, "G2", "the two grids must be distinct");
    }
    r.extra_fields(4);
    if r.ok {
        b.cviscs.push(c);
    }
}
