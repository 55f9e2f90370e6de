//! A transient deck's dynamic load, as the schemes apply it: the DLOAD the case
//! control selects, resolved through its TLOAD1/TLOAD2 cards to DAREA scale factors,
//! DELAY delays and time functions (TABLEDi or TLOAD2's formula):
//!
//!   P(t) = Σ_k S_k A_k f_k(t − τ_k) e_(dof_k)
//!
//! with S_k the DLOAD's S·S_i, A_k the DAREA factor and τ_k the DELAY of the DOF.

use crate::deck::cards::{Formula, TableFunction};

/// The time function of one TLOAD.
#[derive(Debug, Clone, PartialEq)]
pub enum TimeFunction {
    /// TLOAD1: the TABLEDi's value at t − τ (NASTRAN-95 BULK.TXT, TLOAD1:
    /// {P(t)} = {A·F(t − τ)}; the table extrapolates linearly outside its range).
    Table(TableFunction),
    /// TLOAD2's formula at t − τ.
    Formula(Formula),
}

impl TimeFunction {
    /// The function's value at a time already shifted by the delay (t − τ).
    pub fn value(&self, t: f64) -> f64 {
        match self {
            TimeFunction::Table(table) => table.value(t),
            TimeFunction::Formula(f) => f.value(t),
        }
    }
}

/// One term of the load: a DOF, its factor, delay and time function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadTerm {
    /// The solved DOF loaded.
    pub dof: usize,
    /// S·A: the DLOAD's scale times the DAREA factor.
    pub scale: f64,
    /// τ.
    pub delay: f64,
    /// Index into [`Excitation::functions`].
    pub function: usize,
}

/// The dynamic load of a transient run.
#[derive(Debug, Clone, PartialEq)]
pub struct Excitation {
    /// The terms, in the order of the DLOAD's sets and their DAREA entries.
    pub terms: Vec<LoadTerm>,
    /// The time functions, one per TLOAD.
    pub functions: Vec<TimeFunction>,
    /// Where the load comes from (`DLOAD 4 at deck.bdf:12:1`), for messages.
    pub source: String,
}

impl Excitation {
    /// Writes P(t) into `out` (over the solved DOFs), every other entry zero.
    pub fn load_at(&self, t: f64, out: &mut [f64]) {
        out.fill(0.0);
        for term in &self.terms {
            out[term.dof] += term.scale * self.functions[term.function].value(t - term.delay);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// NASTRAN-95 BULK.TXT, TLOAD2: P(t) = A t̃^B e^(C t̃) cos(2πF t̃ + P) for
    /// T1 ≤ t − τ ≤ T2 and 0 otherwise, t̃ = t − T1 − τ; with B = 0 the power is 1 at
    /// t̃ = 0 (a cosine pulse starts at its full value).
    #[test]
    fn tload2_is_zero_outside_its_window_and_the_formula_inside() {
        let f = TimeFunction::Formula(Formula {
            t1: 1.0,
            t2: 3.0,
            f: 0.25,
            p: 90.0,
            c: -0.5,
            b: 1.0,
        });
        assert_eq!(f.value(0.99), 0.0);
        assert_eq!(f.value(3.01), 0.0);
        let s: f64 = 1.5;
        let expected =
            s * (-0.5 * s).exp() * (2.0 * std::f64::consts::PI * 0.25 * s + std::f64::consts::FRAC_PI_2).cos();
        assert!((f.value(2.5) - expected).abs() <= 1e-15);
        let step = TimeFunction::Formula(Formula {
            t1: 0.0,
            t2: 1.0,
            f: 0.0,
            p: 0.0,
            c: 0.0,
            b: 0.0,
        });
        assert_eq!(step.value(0.0), 1.0);
        let ex = Excitation {
            terms: vec![
                LoadTerm {
                    dof: 1,
                    scale: 2.0,
                    delay: 0.5,
                    function: 0,
                },
                LoadTerm {
                    dof: 1,
                    scale: -1.0,
                    delay: 0.0,
                    function: 0,
                },
            ],
            functions: vec![step],
            source: String::new(),
        };
        let mut p = [9.0; 3];
        ex.load_at(0.25, &mut p);
        assert_eq!(p, [0.0, -1.0, 0.0]);
        ex.load_at(0.75, &mut p);
        assert_eq!(p, [0.0, 1.0, 0.0]);
    }
}
