//! The contact law over a step, and the history a hysteretic law keeps.
//!
//! Hertz's law φ(α) = max(α, 0)^A (the contact force is K φ) is elastic: the contact
//! unloads along the curve it loaded on, and one function holds at every step. Yang
//! and Sun's law for laminates (S. H. Yang and C. T. Sun, "Indentation law for
//! composite laminates", ASTM STP 787, 1982; used by Tan and Sun, J. Appl. Mech. 52,
//! 1985) is not:
//!
//! - loading: φ = α^A, the Hertz curve (A = 1.5), α_m the largest indentation so far;
//! - unloading from (α_m, φ_m): φ = φ_m ((α − α0)/(α_m − α0))^q, q = 2.5 in their
//!   tests, with the permanent indentation α0 = 0 for α_m ≤ α_cr and
//!   α0 = α_m [1 − (α_cr/α_m)^(2/5)] above the critical indentation α_cr;
//! - reloading after the contact has opened: φ = φ_m ((α − α0)/(α_m − α0))^A up to
//!   α_m, then on along the loading curve.
//!
//! Where the sources are silent, two choices, each keeping φ continuous (so that the
//! condensed contact equation keeps a nondecreasing load factor):
//! - an unloading begun on the reloading curve below α_m, at (α_t, φ_t), goes down the
//!   power-q curve through (α_t, φ_t) to the same α0;
//! - a reloading begun before the contact has opened climbs back up the curve it came
//!   down (an unloading curve is elastic below its top), then on along the upper
//!   curve. The sources' reloading curve meets an unloading curve only at their ends:
//!   stepping onto it from inside one would make the force jump.
//!
//! A step's law is fixed by the state at its start ([`History::step_law`]): an
//! unloading begins at the start of the step in which α first decreases. The step's
//! law is then one continuous nondecreasing piecewise power law of α(n+1)
//! ([`StepLaw`]), and the unloading curve's top is late by less than a step, which
//! moves α_m by O(Δt²) at a smooth maximum: the schemes keep their order (the tests
//! below and in `scheme_tests` show it).
//!
//! Energies, divided by K. The contact holds what the unloading curve from its
//! current point would return, E = ∫_{α0}^{α} φ_unloading ([`History::stored`]); the
//! work done on it beyond that is dissipated, D ([`History::dissipated`]). Going down
//! an unloading curve, or back up it, dissipates nothing; a climb along the upper
//! curve dissipates ∫ δ dα, δ = φ − dE/dα ≥ 0:
//! - where α0 stays (reloading, or loading below α_cr): δ = φ (q − A)/(q + 1);
//! - loading above α_cr, where α0 grows with α_m: E = α_cr^(2/5) α^(A+3/5)/(q + 1),
//!   δ = α^A − (A + 3/5) α_cr^(2/5) α^(A−2/5)/(q + 1).
//!
//! The work the law takes over a step (∫ of the step's law) is then exactly the
//! change of E + D, so the ledger's balance measures the scheme's error in the work,
//! as it does for Hertz's law. A full loading and unloading dissipates the area
//! between the curves: with q = 2.5, A = 1.5 the coefficient of restitution against
//! a rigid wall is e² = (α_m − α0)/(1.4 α_m). With α_cr → ∞ and q = A every curve
//! is the loading curve, and the law is evaluated as Hertz's, bit for bit.

use super::contact::{discrete_gradient, GL5};
use super::ContactEnergy;
use crate::model::{Contact, Unloading, YangSun};

/// One power piece φ = coef (α − origin)^power, valid from `from` up to the next
/// piece's `from`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    from: f64,
    origin: f64,
    coef: f64,
    power: f64,
}

impl Piece {
    fn value(&self, x: f64) -> f64 {
        self.coef * (x - self.origin).powf(self.power)
    }

    fn slope(&self, x: f64) -> f64 {
        self.coef * self.power * (x - self.origin).powf(self.power - 1.0)
    }

    /// ∫ from the origin to x.
    fn primitive(&self, x: f64) -> f64 {
        self.coef * (x - self.origin).powf(self.power + 1.0) / (self.power + 1.0)
    }

    /// The same curve as another (whatever their `from`).
    fn same_curve(&self, o: &Piece) -> bool {
        self.origin == o.origin && self.coef == o.coef && self.power == o.power
    }
}

/// ∫ of f over [l, h], f's antiderivative `prim`: the difference of `prim` when the
/// interval is long, five-point Gauss-Legendre when it is short (where the
/// difference would lose digits; f is smooth inside a piece).
fn segment(l: f64, h: f64, prim: impl Fn(f64) -> f64, f: impl Fn(f64) -> f64) -> f64 {
    let d = h - l;
    if d <= 0.0 {
        return 0.0;
    }
    if d < 1e-2 * l.abs().max(h.abs()) {
        d * GL5.iter().map(|&(x, w)| w * f(l + x * d)).sum::<f64>()
    } else {
        prim(h) - prim(l)
    }
}

/// The contact's law over one step: φ(α(n+1)) given the state at the step's start.
#[derive(Debug, Clone, Copy)]
pub enum StepLaw<'a> {
    /// Hertz's law, evaluated as [`Contact::law`] does.
    Elastic(&'a Contact),
    /// A continuous nondecreasing piecewise power law, zero below its first piece.
    Pieces {
        /// The pieces in increasing `from`; the first `len` are used.
        pieces: [Piece; 3],
        /// How many.
        len: usize,
    },
}

impl StepLaw<'_> {
    fn pieces(&self) -> &[Piece] {
        match self {
            StepLaw::Elastic(_) => &[],
            StepLaw::Pieces { pieces, len } => &pieces[..*len],
        }
    }

    /// The piece α lies on (above its `from`), if any.
    fn piece(&self, x: f64) -> Option<&Piece> {
        self.pieces().iter().rev().find(|p| x > p.from)
    }

    /// φ(α).
    pub fn phi(&self, x: f64) -> f64 {
        match self {
            StepLaw::Elastic(c) => c.law(x),
            _ => self.piece(x).map_or(0.0, |p| p.value(x)),
        }
    }

    /// dφ/dα.
    pub fn slope(&self, x: f64) -> f64 {
        match self {
            StepLaw::Elastic(c) => c.law_slope(x),
            _ => self.piece(x).map_or(0.0, |p| p.slope(x)),
        }
    }

    /// The mean of φ over [a0, a1] (φ(a0) when they are equal): the discrete gradient
    /// of its integral, to round-off, piece by piece.
    pub fn mean(&self, a0: f64, a1: f64) -> f64 {
        match self {
            StepLaw::Elastic(c) => discrete_gradient(a0, a1, |x| c.law_integral(x), |x| c.law(x)),
            _ => {
                if a0 == a1 {
                    return self.phi(a0);
                }
                let (lo, hi) = if a0 < a1 { (a0, a1) } else { (a1, a0) };
                let ps = self.pieces();
                let mut sum = 0.0;
                for (k, p) in ps.iter().enumerate() {
                    let to = ps.get(k + 1).map_or(f64::INFINITY, |q| q.from);
                    let (l, h) = (lo.max(p.from), hi.min(to));
                    sum += segment(l, h, |x| p.primitive(x), |x| p.value(x));
                }
                sum / (hi - lo)
            }
        }
    }
}

/// The state of a contact's law: what it has been through.
#[derive(Debug, Clone)]
pub struct History<'a> {
    contact: &'a Contact,
    /// Yang and Sun's parameters; `None` for an elastic law.
    yang_sun: Option<YangSun>,
    /// α at the last committed state.
    alpha: f64,
    /// α_m, the largest α so far (0 before any contact).
    max: f64,
    /// α0, the permanent indentation of α_m.
    origin: f64,
    /// The unloading curve the contact is on, and its top; `None` on the upper
    /// (loading or reloading) curve.
    branch: Option<(Piece, f64)>,
    /// E/K at the committed state.
    stored: f64,
    /// D/K so far.
    dissipated: f64,
}

impl<'a> History<'a> {
    /// A contact at α (taken as loaded to there when it starts indented).
    pub fn new(contact: &'a Contact, alpha: f64) -> Self {
        let yang_sun = match contact.unloading {
            Unloading::Elastic => None,
            Unloading::YangSun(y) => Some(y),
        };
        let mut h = History {
            contact,
            yang_sun,
            alpha,
            max: 0.0,
            origin: 0.0,
            branch: None,
            stored: 0.0,
            dissipated: 0.0,
        };
        h.raise(alpha);
        h.stored = h.stored_at(alpha);
        h
    }

    /// The indentation at the committed state.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// K·E: the energy the contact holds at the committed state (for Hertz's law its
    /// potential, [`Contact::potential`]).
    pub fn stored(&self) -> f64 {
        self.contact.stiffness * self.stored
    }

    /// K·D: the energy the contact has dissipated so far.
    pub fn dissipated(&self) -> f64 {
        self.contact.stiffness * self.dissipated
    }

    /// K·E and K·D at the committed state.
    pub fn energy(&self) -> ContactEnergy {
        ContactEnergy {
            stored: self.stored(),
            dissipated: self.dissipated(),
        }
    }

    /// φ at the committed state: the load factor acting there.
    pub fn load_factor(&self) -> f64 {
        match (self.yang_sun, self.branch) {
            (None, _) => self.contact.law(self.alpha),
            (Some(_), Some((b, _))) if self.alpha > self.origin => b.value(self.alpha),
            (Some(_), Some(_)) => 0.0,
            (Some(_), None) => self.upper_value(self.alpha),
        }
    }

    /// The law of the step from the committed state.
    pub fn step_law(&self) -> StepLaw<'a> {
        if self.yang_sun.is_none() {
            return StepLaw::Elastic(self.contact);
        }
        // At most three pieces: a branch, the reloading curve, the loading curve.
        let mut pieces = [self.hertz(0.0); 3];
        let mut len = 0;
        let mut push = |p: Piece| {
            // Adjacent pieces on one curve are one piece.
            if len == 0 || !p.same_curve(&pieces[len - 1]) {
                pieces[len] = p;
                len += 1;
            }
        };
        let start = match self.branch {
            Some((b, top)) => {
                push(b);
                top
            }
            None if self.alpha > self.origin => {
                push(self.unloading_from(self.alpha));
                self.alpha
            }
            None => self.origin,
        };
        self.upper(start, &mut push);
        if len == 1 && pieces[0] == self.hertz(0.0) {
            return StepLaw::Elastic(self.contact);
        }
        StepLaw::Pieces { pieces, len }
    }

    /// Makes α the committed state, the step having been taken with
    /// [`History::step_law`] from the previous one; returns the load factor there
    /// ([`History::load_factor`]).
    pub fn commit(&mut self, alpha: f64) -> f64 {
        if let Some(ys) = self.yang_sun {
            let a = self.alpha;
            match self.branch {
                None if alpha >= a => {
                    self.dissipated += self.climb(ys, a, alpha);
                    self.raise(alpha);
                }
                None if a > self.origin => self.branch = Some((self.unloading_from(a), a)),
                None => {}
                Some((_, top)) if alpha > top => {
                    self.dissipated += self.climb(ys, top, alpha);
                    self.branch = None;
                    self.raise(alpha);
                }
                Some(_) => {}
            }
            if alpha <= self.origin {
                // Opened: the next loading is a reloading.
                self.branch = None;
            }
        }
        self.alpha = alpha;
        self.stored = self.stored_at(alpha);
        self.load_factor()
    }

    /// E at α on the committed curve.
    fn stored_at(&self, alpha: f64) -> f64 {
        match (self.yang_sun, self.branch) {
            (None, _) => self.contact.law_integral(alpha),
            _ if alpha <= self.origin => 0.0,
            (Some(_), Some((b, _))) => b.primitive(alpha),
            (Some(_), None) => self.unloading_from(alpha).primitive(alpha),
        }
    }

    /// Makes α_m at least α, and α0 that of α_m.
    fn raise(&mut self, alpha: f64) {
        if alpha > self.max {
            self.max = alpha;
            self.origin = self.yang_sun.map_or(0.0, |ys| ys.permanent(alpha));
        }
    }

    /// The loading curve from `from`.
    fn hertz(&self, from: f64) -> Piece {
        Piece {
            from,
            origin: 0.0,
            coef: 1.0,
            power: self.contact.exponent,
        }
    }

    /// The power curve from the origin α0 through (at, value); the loading curve
    /// itself when it is one (origin 0, the loading exponent, through a point of it).
    fn through(&self, power: f64, at: f64, value: f64) -> Piece {
        let a = self.contact.exponent;
        if self.origin == 0.0 && power == a && value == at.powf(a) {
            return self.hertz(self.origin);
        }
        Piece {
            from: self.origin,
            origin: self.origin,
            coef: value / (at - self.origin).powf(power),
            power,
        }
    }

    /// The unloading curve from α on the upper curve.
    fn unloading_from(&self, alpha: f64) -> Piece {
        let q = self.yang_sun.map_or(self.contact.exponent, |y| y.power);
        self.through(q, alpha, self.upper_value(alpha))
    }

    /// The reloading curve: from α0 through (α_m, φ_m).
    fn reloading(&self) -> Piece {
        self.through(self.contact.exponent, self.max, self.max.powf(self.contact.exponent))
    }

    /// φ on the upper curve: 0 up to α0, the reloading curve up to α_m, the loading
    /// curve beyond.
    fn upper_value(&self, alpha: f64) -> f64 {
        if alpha <= self.origin {
            0.0
        } else if alpha < self.max {
            self.reloading().value(alpha)
        } else {
            self.hertz(0.0).value(alpha)
        }
    }

    /// The upper curve's pieces from `start` (at least α0) on.
    fn upper(&self, start: f64, push: &mut impl FnMut(Piece)) {
        if start < self.max {
            push(Piece {
                from: start,
                ..self.reloading()
            });
            push(self.hertz(self.max));
        } else {
            push(self.hertz(start));
        }
    }

    /// ∫ δ over a climb along the upper curve from `lo` to `hi` (the state's α0 and
    /// α_m those before it).
    fn climb(&self, ys: YangSun, lo: f64, hi: f64) -> f64 {
        let a = self.contact.exponent;
        let q1 = ys.power + 1.0;
        let kappa = (ys.power - a) / q1;
        let reload = self.reloading();
        let hertz = self.hertz(0.0);
        // α0 stays: the reloading curve, then the loading curve below α_cr.
        let mut d = kappa
            * (segment(
                lo.max(self.origin),
                hi.min(self.max),
                |x| reload.primitive(x),
                |x| reload.value(x),
            ) + segment(
                lo.max(self.max),
                hi.min(ys.critical),
                |x| hertz.primitive(x),
                |x| hertz.value(x),
            ));
        // α0 grows with α_m above α_cr.
        let (l, h) = (lo.max(self.max).max(ys.critical), hi);
        if h > l {
            let c = ys.critical.powf(0.4) / q1;
            d += segment(
                l,
                h,
                |x| hertz.primitive(x) - c * x.powf(a + 0.6),
                |x| x.powf(a) - (a + 0.6) * c * x.powf(a - 0.4),
            );
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::test_models;

    fn yang_sun(critical: f64, power: f64) -> Contact {
        let mut c = test_models::hertz_wall().model.contact.unwrap();
        c.unloading = Unloading::YangSun(YangSun { critical, power });
        c
    }

    /// Walks the law through the indentations `path`, returning the last state.
    fn walk<'a>(c: &'a Contact, path: &[f64]) -> History<'a> {
        let mut h = History::new(c, path[0]);
        for &a in &path[1..] {
            h.commit(a);
        }
        h
    }

    /// Goal: a full load-unload cycle of the law dissipates the area between its
    /// loading curve and its unloading curve, and returns E = φ_m(α_m − α0)/(q + 1);
    /// below and above α_cr. Reference: Yang and Sun's curves integrated in closed
    /// form (loading work α_m^(A+1)/(A+1)). Tolerance 1e-12 (round-off of the sums).
    #[test]
    fn a_cycle_dissipates_the_loop() {
        for &(critical, top) in &[(1.0, 0.5), (1.0, 3.0), (f64::INFINITY, 2.0)] {
            let c = yang_sun(critical, 2.5);
            let k = c.stiffness;
            let up: Vec<f64> = (0..=400).map(|i| top * i as f64 / 400.0).collect();
            let h = walk(&c, &up);
            let a0 = if top > critical {
                top * (1.0 - (critical / top).powf(0.4))
            } else {
                0.0
            };
            let loading = top.powf(2.5) / 2.5;
            let returned = top.powf(1.5) * (top - a0) / 3.5;
            assert!((h.stored() / k - returned).abs() <= 1e-12 * loading, "{critical} {top}");
            assert!(((h.stored() + h.dissipated()) / k - loading).abs() <= 1e-12 * loading);
            // Down to the permanent indentation: the stored energy is all returned.
            let down: Vec<f64> = (0..=400).map(|i| top - (top - a0) * i as f64 / 400.0).collect();
            let mut h2 = h.clone();
            let mut returned_work = 0.0;
            let mut prev = top;
            for &a in &down[1..] {
                let law = h2.step_law();
                returned_work += law.mean(prev, a) * (prev - a);
                h2.commit(a);
                prev = a;
            }
            assert!(h2.stored().abs() <= 1e-12 * k * loading, "{}", h2.stored());
            assert!((returned_work - returned).abs() <= 1e-12 * loading);
            assert_eq!(h2.dissipated(), h.dissipated(), "unloading dissipates nothing");
            assert_eq!(h2.load_factor(), 0.0);
        }
    }

    /// Goal: the step law is continuous and nondecreasing in α on every kind of step
    /// (loading, unloading from the loading and from the reloading curve, reloading
    /// after opening, climbing back up an unloading curve); a step's work is the
    /// change of E + D. Reference: the law's own pieces; tolerance 1e-12 relative.
    #[test]
    fn step_laws_are_continuous_nondecreasing_and_balance() {
        let c = yang_sun(0.5, 2.5);
        let path = [
            0.0, 0.4, 0.9, 1.2, 1.0, 0.8, 1.0, 1.3, 1.1, 0.2, 0.0, 0.3, 0.5, 0.45, 0.7, 1.5,
        ];
        let mut h = History::new(&c, path[0]);
        for w in path.windows(2) {
            let law = h.step_law();
            let xs: Vec<f64> = (0..=1000).map(|i| -0.1 + 1.8 * i as f64 / 1000.0).collect();
            for p in xs.windows(2) {
                let (f0, f1) = (law.phi(p[0]), law.phi(p[1]));
                assert!(f1 >= f0 * (1.0 - 1e-12), "decreasing at {} after {w:?}", p[1]);
                assert!(
                    f1 - f0 <= 2.0 * 1.8e-3 * law.slope(p[1]).max(law.slope(p[0])) + 1e-12,
                    "jump at {}",
                    p[1]
                );
            }
            let before = h.stored + h.dissipated;
            let work = law.mean(w[0], w[1]) * (w[1] - w[0]);
            h.commit(w[1]);
            let after = h.stored + h.dissipated;
            assert!(
                (after - before - work).abs() <= 1e-12 * after.max(1.0),
                "{w:?}: {} vs {work}",
                after - before
            );
            assert!(
                (h.load_factor() - law.phi(w[1])).abs() <= 1e-14 * law.phi(w[1]).max(1.0),
                "{w:?}"
            );
        }
    }

    /// Goal: with α_cr = ∞ and q = A the law is Hertz's: every step law is the elastic
    /// one, the stored energy is the potential bit for bit, nothing is dissipated.
    #[test]
    fn infinite_critical_indentation_and_q_equal_a_is_hertz() {
        let c = yang_sun(f64::INFINITY, 1.5);
        let mut h = History::new(&c, 0.0);
        for a in [0.3, 0.7, 0.5, 0.9, -0.1, 0.4] {
            assert!(matches!(h.step_law(), StepLaw::Elastic(_)));
            h.commit(a);
            assert_eq!(h.stored(), c.potential(a));
            assert_eq!(h.load_factor(), c.law(a));
            assert_eq!(h.dissipated(), 0.0);
        }
    }
}
