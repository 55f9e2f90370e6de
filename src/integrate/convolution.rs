//! The convolution engine of the trapezoidal schemes (`newmark`, `energy`).
//!
//! With a fixed Δt the trapezoidal rule's linear part is linear and time-invariant,
//! and the target starts at rest. The contact is the only nonlinearity and enters a
//! step through one scalar, p_n: the target's load over step n averages g_T·p_n/2,
//! with p_n = φ(α(n−1)) + φ(α(n)) for `newmark` and twice the discrete gradient for
//! `energy`. So every linear output y of the target is the discrete convolution
//!
//!   y(n) = Σ_{j=1..n} h_y(n−j+1) p_j,
//!
//! h_y being the response of the same scheme, Δt and model to p = (1, 0, 0, …) from
//! rest: one linear pass, [`unit_response`]. The impactor, a free point mass, keeps
//! its own trapezoidal recursion, and the contact is solved by the same scalar
//! equation as the direct stepper ([`super::newmark`]), its α* coming from a history
//! sum instead of a sparse solve ([`contact_history`]). In exact arithmetic this is
//! the direct run; in floating point it agrees to round-off (the sums run in another
//! order).
//!
//! The target's energy needs no field: the trapezoidal rule satisfies the discrete
//! work identity E_T(n) − E_T(n−1) = (w(n) − w(n−1))·p_n/2 exactly, w = g_T·u_T.
//! A damped target (its C in the kernel pass's effective matrix, as in the direct
//! step) satisfies it with E_T + D_T on the left: the identity gives their sum, not
//! each. A mass-proportional damping (ALPHA1) damps the impactor too: its recursion
//! carries its share a₁m, and its dissipation ΔxᵀcΔx/Δt is booked step by step. A
//! damping element on the impactor is refused.
//!
//! Cost: the kernel pass is one solve and two sparse products per step, as a direct
//! step. The contact history is causal (α at step n needs p before n), so its sum is
//! taken step by step: N²/2 multiply-adds over the steps in contact, in eight
//! independent partial sums. Everything else is linear in the finished load history
//! and is computed afterwards as full convolutions by FFT ([`Convolver`]): every
//! output column and the ledger's w, work and momentum, O(N log N) each.
//!
//! Not for `nastran` (its three-point linear part is a different recursion, and its
//! lagged contact would need its own kernel pass: not built) nor `central` (explicit).

use super::law::History;
use super::linear::Factor;
use super::newmark::{complete, contact_load, effective_matrix, predictor, ContactForm};
use super::{contact_vectors, ContactEnergy, SolveError, StepCosts};
use crate::assembly::System;
use crate::model::{apply, Model};
use crate::numerics::dot;

/// Why a model cannot run on the convolution engine.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the convolution engine cannot run this model: {0}")]
pub struct NotConvolvable(pub String);

/// The response of the trapezoidal target to a unit contact load at step 1, from
/// rest: the kernels of α and of the target's energy.
#[derive(Debug, Clone)]
pub struct UnitResponse {
    /// Time step.
    pub dt: f64,
    /// c_T·u_T(k) for k = 1..=N (index k − 1): the target's share of α.
    pub alpha: Vec<f64>,
    /// g_T·u_T(k): the load-weighted displacement whose increments times p/2 are the
    /// work done on the target.
    pub work: Vec<f64>,
    /// What the pass cost.
    pub costs: StepCosts,
}

impl UnitResponse {
    /// The response to the contact loads scaled by `s` (a Hertz K scaled by `s` scales
    /// every NOLIN3 load): α's kernel scales by s, the work's by s².
    pub fn scaled(&self, s: f64) -> Self {
        UnitResponse {
            dt: self.dt,
            alpha: self.alpha.iter().map(|a| a * s).collect(),
            work: self.work.iter().map(|w| w * s * s).collect(),
            costs: self.costs,
        }
    }
}

/// The impactor as the convolution engine sees it: a free point mass.
#[derive(Debug, Clone, Copy)]
struct Ball {
    dof: usize,
    mass: f64,
    /// Its NOLIN3 scale (the load is g·p/2 over a step).
    g: f64,
    /// Its coefficient in α.
    c: f64,
    /// Its viscous damping: the mass-proportional share a₁m (ALPHA1), which damps it
    /// as it damps every mass.
    damping: f64,
}

/// The impactor of a model, if the convolution engine can treat it as a free mass.
fn ball(model: &Model) -> Result<Ball, NotConvolvable> {
    let no = |why: &str| NotConvolvable(why.to_string());
    let ct = model.contact.as_ref().ok_or_else(|| no("it has no contact"))?;
    let dof = ct.impactor.dof;
    let imp = &ct.impactor.dofs;
    let target = model.target_mask();
    if (0..model.n()).any(|i| target[i] && (model.u0[i] != 0.0 || model.v0[i] != 0.0)) {
        return Err(no("the target does not start at rest"));
    }
    if imp
        .iter()
        .any(|&i| i != dof && (model.u0[i] != 0.0 || model.v0[i] != 0.0))
    {
        return Err(no("the impactor moves in more than the impact direction"));
    }
    let (g, c) = contact_vectors(model);
    if c.iter().any(|&(j, _)| imp.contains(&j) && j != dof) || imp.iter().any(|&i| i != dof && g[i] != 0.0) {
        return Err(no("the contact acts on more than the impactor's impact direction"));
    }
    if model
        .elements
        .iter()
        .any(|e| e.damps() && e.dofs.iter().flatten().flatten().any(|d| imp.contains(d)))
    {
        return Err(no("a damping element acts on the impactor"));
    }
    Ok(Ball {
        dof,
        mass: ct.impactor.mass,
        g: g[dof],
        c: c.iter().filter(|&&(j, _)| j == dof).map(|&(_, w)| w).sum(),
        damping: model.damping.as_ref().map_or(0.0, |d| d.mass) * ct.impactor.mass,
    })
}

/// The kernel pass: the trapezoidal rule on the target alone, from rest, with the
/// contact load g_T·p and p = (1, 0, 0, …), for `steps` steps of `dt`. `record` sees
/// the target's state (u, v over all solved DOFs, the impactor's at zero) after
/// every step, so that the caller keeps the kernels of its own outputs. The target's
/// mass may be coupled (a modal reduction's M_r is dense); the impactor's may not.
pub fn unit_response(
    model: &Model,
    sys: &System,
    dt: f64,
    steps: usize,
    record: &mut dyn FnMut(&[f64], &[f64]),
) -> Result<UnitResponse, RunFailure> {
    let b = ball(model)?;
    let no = |why: &str| RunFailure::Model(NotConvolvable(why.to_string()));
    let kd = sys.k_diag();
    let imp = &model
        .contact
        .as_ref()
        .expect("ball() checked the contact")
        .impactor
        .dofs;
    if imp.iter().any(|&i| kd[i] != 0.0) {
        return Err(no("the impactor is attached to an element"));
    }
    if sys
        .m
        .iter()
        .any(|t| t.row != t.col && t.val != 0.0 && (imp.contains(&t.row) || imp.contains(&t.col)))
    {
        return Err(no("the impactor's mass is coupled to the target's"));
    }
    let (mut g, c) = contact_vectors(model);
    for &i in imp {
        g[i] = 0.0;
    }
    let c_t: Vec<(usize, f64)> = c.into_iter().filter(|&(j, _)| j != b.dof).collect();
    let (mut alpha, mut work) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    let costs = linear_response(model, sys, dt, steps, &g, &mut |u, v| {
        alpha.push(apply(&c_t, u));
        work.push(g.iter().zip(u).map(|(g, u)| g * u).sum());
        record(u, v);
    })?;
    Ok(UnitResponse { dt, alpha, work, costs })
}

/// The trapezoidal rule's response from rest to the load `load`·p with p = (1, 0, 0,
/// …): u(k), v(k) after each step k = 1..=`steps`, shown to `record`. The same
/// arithmetic as the direct step ([`super::newmark`]), in increments.
pub fn linear_response(
    model: &Model,
    sys: &System,
    dt: f64,
    steps: usize,
    load: &[f64],
    record: &mut dyn FnMut(&[f64], &[f64]),
) -> Result<StepCosts, SolveError> {
    let n = model.n();
    let mut factor = Factor::effective(sys, effective_matrix(dt), &model.dofs)?;
    let (mut u, mut v, mut f) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut du, mut kdu, mut mv) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for k in 1..=steps {
        // The direct step's own arithmetic (newmark.rs), the load at step 1 only.
        predictor(
            sys,
            &mut factor,
            dt,
            (&v, &f, &mut mv, &mut du),
            (k == 1).then_some((load, 1.0)),
            None,
        );
        complete(sys, dt, &du, &mut kdu, (&mut u, &mut f, &mut v));
        record(&u, &v);
    }
    Ok(StepCosts {
        factorizations: 1,
        solves: factor.solves,
        contact_iterations: 0,
        factor_time: factor.factor_time,
        solve_time: factor.solve_time,
    })
}

/// Why a convolution run failed.
#[derive(Debug, Clone, thiserror::Error)]
pub enum RunFailure {
    /// The model does not fit the engine.
    #[error(transparent)]
    Model(#[from] NotConvolvable),
    /// The numerics failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
}

/// One step of a convolution run, as [`contact_history`] reports it.
#[derive(Debug, Clone, Copy)]
pub struct ConvStep {
    /// Step, from 0.
    pub step: usize,
    /// Time.
    pub time: f64,
    /// Indentation α.
    pub alpha: f64,
    /// The impactor's displacement along the impact direction.
    pub x: f64,
    /// Its velocity.
    pub xv: f64,
    /// The step's load p_n (0 at step 0).
    pub p: f64,
    /// φ(α): every NOLIN3 load is S·φ.
    pub load_factor: f64,
    /// The mean load factor over the step, p/2.
    pub work_factor: f64,
    /// The target's share of α, c_T·u_T.
    pub alpha_target: f64,
    /// The contact solve's iterations in this step.
    pub iterations: usize,
    /// The contact's energies.
    pub contact: ContactEnergy,
    /// What the impactor's own damping (its share of ALPHA1) has dissipated so far.
    pub impactor_dissipated: f64,
}

/// The contact history of a trapezoidal run from its kernel: for each step the
/// scalar contact equation of the direct stepper, α* = (impactor predictor) +
/// Σ_{j<n} h_α(n−j+1) p_j. `observe` sees every step from 0 and may stop the run
/// (returns false). Returns the loads p_1..p_n of the steps done and the contact
/// solve's iterations.
///
/// The history sum runs over the loads from the first nonzero one on (a zero load adds
/// nothing), in eight partial sums ([`dot`]): the order of the additions, and so the
/// round-off, is not the direct stepper's.
pub fn contact_history(
    model: &Model,
    form: ContactForm,
    kernel: &UnitResponse,
    steps: usize,
    observe: &mut dyn FnMut(&ConvStep) -> Result<bool, SolveError>,
) -> Result<(Vec<f64>, usize), RunFailure> {
    let b = ball(model)?;
    let ct = model.contact.as_ref().expect("ball() checked the contact");
    let dt = kernel.dt;
    let steps = steps.min(kernel.alpha.len());
    let h_a = &kernel.alpha;
    // α's kernel reversed: the history sum at step n is a dot product of two runs
    // that both go forward in memory.
    let reversed: Vec<f64> = h_a.iter().rev().copied().collect();
    let last = reversed.len();
    // The impactor's trapezoidal step with its damping c: m(v1 − v0) = Δt/2 (g p −
    // c(v0 + v1)), so Δx = Δt v0 m/m' + Δt² g p/(4m'), m' = m + cΔt/2 (m itself, and
    // the factor 1, when undamped). Condensed compliance: the impactor's Δt²/(4m')
    // and the target's first response.
    let damped_mass = b.mass + 0.5 * b.damping * dt;
    let keep = b.mass / damped_mass;
    let s = b.c * b.g * dt * dt / (4.0 * damped_mass) + h_a[0];
    let (mut x, mut xv) = (model.u0[b.dof], model.v0[b.dof]);
    let mut alpha = b.c * x;
    let mut history = History::new(ct, alpha);
    let mut phi = history.load_factor();
    let mut p: Vec<f64> = Vec::with_capacity(steps);
    let mut iterations = 0;
    let mut go = observe(&ConvStep {
        step: 0,
        time: 0.0,
        alpha,
        x,
        xv,
        p: 0.0,
        load_factor: phi,
        work_factor: phi,
        alpha_target: 0.0,
        iterations: 0,
        contact: history.energy(),
        impactor_dissipated: 0.0,
    })?;
    let mut dissipated = 0.0;
    let mut n = 0;
    // The first nonzero load: those before it add nothing to any sum.
    let mut first: Option<usize> = None;
    while go && n < steps {
        n += 1;
        let time = n as f64 * dt;
        // History of the loads before this step, seen by α at step n: Σ_j h_α[n−1−j]·p_j
        // for j < n − 1, h_α[k] being reversed[last − 1 − k].
        let hist_a = first.map_or(0.0, |f| dot(&p[f..], &reversed[last - n + f..last - 1]));
        let x_pred = x + xv * dt * keep;
        let base = b.c * x_pred + hist_a;
        let alpha_star = match form {
            ContactForm::Endpoint => base + s * phi,
            ContactForm::DiscreteGradient => base,
        };
        let (psi, its) = contact_load(form, &history.step_law(), alpha_star, s, alpha)
            .ok_or(SolveError::ContactSolve { step: n, time })?;
        iterations += its;
        let pn = match form {
            ContactForm::Endpoint => phi + psi,
            ContactForm::DiscreteGradient => psi,
        };
        p.push(pn);
        if first.is_none() && pn != 0.0 {
            first = Some(n - 1);
        }
        let dx = xv * dt * keep + b.g * pn * dt * dt / (4.0 * damped_mass);
        // ΔxᵀcΔx/Δt: the trapezoidal rule's damping term.
        dissipated += b.damping * dx * dx / dt;
        xv = 2.0 * dx / dt - xv;
        x += dx;
        let alpha_target = hist_a + h_a[0] * pn;
        alpha = b.c * x + alpha_target;
        phi = history.commit(alpha);
        go = observe(&ConvStep {
            step: n,
            time,
            alpha,
            x,
            xv,
            p: pn,
            load_factor: phi,
            work_factor: 0.5 * pn,
            impactor_dissipated: dissipated,
            alpha_target,
            iterations: its,
            contact: history.energy(),
        })?;
    }
    Ok((p, iterations))
}

/// Full linear convolutions of sequences of up to `n` terms, truncated to their first
/// `n` terms, by FFT (realfft's real-to-complex transforms over rustfft):
///
///   c(m) = Σ_{i=0..m} h(m−i)·p(i),  m = 0..n−1,
///
/// computed as the circular convolution of length L ≥ 2n − 1 (the smallest 2^a·3^b,
/// so no term wraps round) of the zero-padded sequences: c = IFFT(FFT(h)·FFT(p))/L.
/// Cost O(L log L) against n²/2 for the sums. Exact in exact arithmetic; in floating
/// point each term is within a few ε·log₂L·‖h‖₂‖p‖₂ of the sum (the transforms'
/// round-off), which the `superposition` check measures against the direct engine.
/// A kernel's spectrum is computed once ([`Convolver::spectrum`]) and serves every
/// load history.
pub struct Convolver {
    n: usize,
    forward: std::sync::Arc<dyn realfft::RealToComplex<f64>>,
    inverse: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
}

/// A spectrum of [`Convolver`]'s length.
pub type Spectrum = Vec<realfft::num_complex::Complex<f64>>;

impl Convolver {
    /// A convolver for sequences of up to `n` terms.
    pub fn new(n: usize) -> Self {
        let need = (2 * n).saturating_sub(1).max(2);
        let mut len = usize::MAX;
        let mut two = 1usize;
        while two < 2 * need {
            let mut l = two;
            while l < need {
                l *= 3;
            }
            len = len.min(l);
            two *= 2;
        }
        let mut planner = realfft::RealFftPlanner::<f64>::new();
        Convolver {
            n,
            forward: planner.plan_fft_forward(len),
            inverse: planner.plan_fft_inverse(len),
        }
    }

    /// The spectrum of `x` (at most n terms), zero-padded to the transform's length.
    pub fn spectrum(&self, x: &[f64]) -> Spectrum {
        assert!(x.len() <= self.n, "a sequence longer than the convolver's");
        let mut buf = self.forward.make_input_vec();
        buf[..x.len()].copy_from_slice(x);
        let mut out = self.forward.make_output_vec();
        self.forward
            .process(&mut buf, &mut out)
            .expect("buffers of the plan's sizes");
        out
    }

    /// The first n terms of the convolution whose factors have the spectra `h` and
    /// `p`, each times `scale`.
    pub fn convolve(&self, h: &Spectrum, p: &Spectrum, scale: f64) -> Vec<f64> {
        let len = self.forward.len();
        let mut prod: Spectrum = h.iter().zip(p).map(|(a, b)| a * b).collect();
        // The product of two real signals' spectra is a real signal's: the imaginary
        // parts of its first and (for even L) last bins are round-off; clear them.
        prod[0].im = 0.0;
        if len % 2 == 0 {
            let last = prod.len() - 1;
            prod[last].im = 0.0;
        }
        let mut out = self.inverse.make_output_vec();
        self.inverse
            .process(&mut prod, &mut out)
            .expect("buffers of the plan's sizes");
        let f = scale / len as f64;
        out.truncate(self.n);
        out.iter_mut().for_each(|x| *x *= f);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: a Hertz K scaled by s scales every NOLIN3 load, so the unit response of
    /// the scaled model is `scaled(s)` of the original's: α's kernel by s, the work's
    /// by s² (what a sweep over k relies on). Model: the paper's rod, K × 2.5, 400
    /// steps; both kernels within 1e-12 of their peaks.
    #[test]
    fn unit_response_of_a_scaled_contact_is_the_scaled_response() {
        let rod = crate::model_from_text("rod", include_str!("../../reference-data/decks/rod.bdf")).unwrap();
        let stiffer = crate::model::Modify {
            contact_stiffness_scale: Some(2.5),
            ..Default::default()
        }
        .apply(&rod)
        .unwrap();
        let response = |m: &Model| {
            let sys = crate::assembly::assemble(m);
            unit_response(m, &sys, 2e-7, 400, &mut |_, _| {}).unwrap()
        };
        let (scaled, direct) = (response(&rod).scaled(2.5), response(&stiffer));
        for (a, b) in [(&scaled.alpha, &direct.alpha), (&scaled.work, &direct.work)] {
            let peak = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let d = a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            assert!(peak > 0.0 && d <= 1e-12 * peak, "{d:e} of {peak:e}");
        }
    }

    /// Goal: the FFT convolution is the direct sum to round-off, on sequences of every
    /// length class (even and odd transforms, a single term), and `dot` is the sum.
    #[test]
    fn fft_convolution_is_the_direct_sum() {
        for n in [1usize, 2, 7, 100, 1001, 3000] {
            let h: Vec<f64> = (0..n)
                .map(|k| ((k as f64) * 0.37).sin() * (-(k as f64) / 400.0).exp())
                .collect();
            let p: Vec<f64> = (0..n)
                .map(|k| if k < n / 2 { ((k as f64) * 0.01).sin() } else { 0.0 })
                .collect();
            let c = Convolver::new(n);
            let y = c.convolve(&c.spectrum(&h), &c.spectrum(&p), 2.0);
            let peak = (0..n)
                .map(|m| (0..=m).map(|i| h[m - i] * p[i]).sum::<f64>().abs())
                .fold(0.0, f64::max)
                .max(f64::MIN_POSITIVE);
            for m in 0..n {
                let exact: f64 = 2.0 * (0..=m).map(|i| h[m - i] * p[i]).sum::<f64>();
                assert!(
                    (y[m] - exact).abs() <= 1e-13 * 2.0 * peak,
                    "n {n}, m {m}: {} vs {exact}",
                    y[m]
                );
            }
            let d: f64 = h.iter().zip(&p).map(|(a, b)| a * b).sum();
            assert!((dot(&h, &p) - d).abs() <= 1e-14 * h.iter().zip(&p).map(|(a, b)| (a * b).abs()).sum::<f64>());
        }
    }
}
