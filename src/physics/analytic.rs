//! Independent references for the verification layer. Nothing here uses the solver
//! core (model, assembly, integrators, ledger): each reference is a closed form or a
//! small ODE integrated by its own classical Runge–Kutta, from plain numbers.
//!
//! - [`HertzDashpot`]: a rigid impactor of mass m on a Hertz spring F = K α^A whose
//!   target face moves at F/c (a dashpot of impedance c). With c = ρCA it is the ball
//!   on a semi-infinite rod, exact for the rod's continuum limit until the reflection
//!   from the far end returns (t = 2L/C). With c = 8√(ρh D*) it is the Zener/Olsson
//!   infinite plate, valid before the flexural waves come back from the edges.
//! - [`dalembert_strain`]: the strain at distance x from the struck end of a rod,
//!   ε(x, t) = −F(t − x/C)/(EA), valid until the far-end reflection arrives.
//! - [`rigid_target`]: m on a rigid half-space (or two rigid bodies with the reduced
//!   mass): α_max = (5 m v0² / 4K)^(2/5) and a contact duration 2.9432 α_max / v0.
//! - [`NavierPlate`]: a simply supported, specially orthotropic Kirchhoff plate under
//!   point loads F(t): its fibre strains by the Navier double sine series, each mode
//!   integrated exactly (Duhamel) for a piecewise-linear F.
//! - [`cylinder_lowest_frequency`]: the lowest natural frequency of a simply supported
//!   closed cylindrical shell by Sanders' or Donnell-Mushtari's thin-shell theory.

/// Ball + Hertz spring + dashpot. State y = (x, v, w): impactor displacement and
/// velocity, target face displacement; α = x − w.
#[derive(Debug, Clone, Copy)]
pub struct HertzDashpot {
    /// Impactor mass m.
    pub mass: f64,
    /// Impact velocity.
    pub v0: f64,
    /// Hertz stiffness K.
    pub stiffness: f64,
    /// Hertz exponent (1.5).
    pub exponent: f64,
    /// Dashpot impedance c (force per velocity); the face moves at F/c.
    pub impedance: f64,
}

/// A sampled solution of [`HertzDashpot`].
#[derive(Debug, Clone, Default)]
pub struct Trace {
    /// Sample times.
    pub time: Vec<f64>,
    /// Contact force K α^A.
    pub force: Vec<f64>,
    /// Indentation α.
    pub alpha: Vec<f64>,
    /// Impactor velocity.
    pub velocity: Vec<f64>,
}

/// Events of a [`Trace`]: the first contact interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Events {
    /// End of the first contact.
    pub contact_end: f64,
    /// First time the impactor's velocity is zero.
    pub velocity_zero: f64,
    /// Largest contact force.
    pub peak_force: f64,
    /// Its time.
    pub peak_time: f64,
    /// Impactor velocity when contact ends.
    pub rebound_velocity: f64,
}

impl HertzDashpot {
    fn force(&self, alpha: f64) -> f64 {
        if alpha > 0.0 {
            self.stiffness * alpha.powf(self.exponent)
        } else {
            0.0
        }
    }

    fn rhs(&self, y: [f64; 3]) -> [f64; 3] {
        let f = self.force(y[0] - y[2]);
        [y[1], -f / self.mass, f / self.impedance]
    }

    /// Classical fourth-order Runge–Kutta (RK4; explicit, here far inside its
    /// stability limit) with fixed step h from t = 0 to `t_end`, sampled every step.
    /// The force grows as t^(3/2) from the first touch (α^(3/2) with α ≈ v0 t), so the
    /// right-hand side is not smooth at t = 0 and the first step's error, O(h^(5/2)),
    /// sets the observed global order: 2.5, not 4 (tested). At the steps used here
    /// (L/C/2e5) successive halvings agree to better than 1e-9 relative.
    /// [`HertzDashpot::events`] locates events by interpolation between samples.
    pub fn integrate(&self, t_end: f64, h: f64) -> Trace {
        let steps = (t_end / h).ceil() as usize;
        let mut y = [0.0, self.v0, 0.0];
        let mut tr = Trace::default();
        let push = |t: f64, y: [f64; 3], tr: &mut Trace| {
            tr.time.push(t);
            tr.alpha.push(y[0] - y[2]);
            tr.force.push(self.force(y[0] - y[2]));
            tr.velocity.push(y[1]);
        };
        push(0.0, y, &mut tr);
        let add = |a: [f64; 3], b: [f64; 3], s: f64| [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]];
        for k in 1..=steps {
            let k1 = self.rhs(y);
            let k2 = self.rhs(add(y, k1, h / 2.0));
            let k3 = self.rhs(add(y, k2, h / 2.0));
            let k4 = self.rhs(add(y, k3, h));
            for i in 0..3 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
            push(k as f64 * h, y, &mut tr);
        }
        tr
    }

    /// Contact end (α crosses zero), impactor at rest (v crosses zero), the peak force
    /// and the rebound velocity; `None` if contact has not ended by the trace's end.
    pub fn events(tr: &Trace) -> Option<Events> {
        let cross = |y: &[f64], k: usize| {
            let (y0, y1) = (y[k - 1], y[k]);
            tr.time[k - 1] + (tr.time[k] - tr.time[k - 1]) * y0 / (y0 - y1)
        };
        let end = (1..tr.alpha.len()).find(|&k| tr.alpha[k - 1] > 0.0 && tr.alpha[k] <= 0.0)?;
        let vz = (1..tr.velocity.len()).find(|&k| tr.velocity[k - 1] > 0.0 && tr.velocity[k] <= 0.0)?;
        let (kp, fp) = tr
            .force
            .iter()
            .enumerate()
            .fold((0, 0.0f64), |a, (k, &f)| if f > a.1 { (k, f) } else { a });
        Some(Events {
            contact_end: cross(&tr.alpha, end),
            velocity_zero: cross(&tr.velocity, vz),
            peak_force: fp,
            peak_time: tr.time[kp],
            rebound_velocity: tr.velocity[end],
        })
    }
}

/// Linear interpolation of a trace's force at time t (zero outside the trace).
pub fn force_at(tr: &Trace, t: f64) -> f64 {
    crate::numerics::interp(&tr.time, &tr.force, t)
}

/// d'Alembert: strain at distance x from the struck end of a rod (wave speed C,
/// axial stiffness EA) under the end force F(t): ε = −F(t − x/C)/EA.
pub fn dalembert_strain(tr: &Trace, x: f64, wave_speed: f64, ea: f64, t: f64) -> f64 {
    -force_at(tr, t - x / wave_speed) / ea
}

/// Zener/Olsson impedance of an infinite orthotropic plate struck transversely:
/// 8√(ρh D*), D* = √(D11 D22 (A + 1)/2), A = (D12 + 2 D66)/√(D11 D22).
pub fn plate_impedance(mass_per_area: f64, d11: f64, d22: f64, d12: f64, d66: f64) -> f64 {
    let a = (d12 + 2.0 * d66) / (d11 * d22).sqrt();
    let d_star = (d11 * d22 * (a + 1.0) / 2.0).sqrt();
    8.0 * (mass_per_area * d_star).sqrt()
}

/// The lowest `count` natural frequencies (rad/time) of a simply supported a × a
/// specially orthotropic Kirchhoff plate (Navier): ω_mn² = π⁴/(ρh)·[D11 (m/a)⁴ +
/// 2(D12 + 2D66)(m/a)²(n/a)² + D22 (n/a)⁴], over m, n = 1…8, ascending.
pub fn navier_frequencies(side: f64, mass_per_area: f64, d: [f64; 4], count: usize) -> Vec<f64> {
    lowest(count, |m, n| {
        let [d11, d22, d12, d66] = d;
        let (p, q) = (m / side, n / side);
        std::f64::consts::PI.powi(2)
            * ((d11 * p.powi(4) + 2.0 * (d12 + 2.0 * d66) * p * p * q * q + d22 * q.powi(4)) / mass_per_area).sqrt()
    })
}

/// The `count` lowest of a frequency over the modes (m, n) = 1..8 each.
fn lowest(count: usize, omega: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    let mut w: Vec<f64> = Vec::new();
    for m in 1..=8 {
        for n in 1..=8 {
            w.push(omega(m as f64, n as f64));
        }
    }
    w.sort_by(f64::total_cmp);
    w.truncate(count);
    w
}

/// The `count` lowest natural frequencies (rad/s) of a simply supported square
/// plate with transverse shear deformation (first-order shear deformation theory,
/// Reissner-Mindlin), "hard" supports (w = 0 and the rotation along each edge held:
/// Navier's solution, Reddy, Mechanics of Laminated Composite Plates and Shells,
/// 2nd ed., §6.2), specially orthotropic D (D11, D22, D12, D66), transverse shear
/// stiffness (K55 in xz, K44 in yz, shear correction included) and no rotary
/// inertia (the element's lumped mass has none): for each mode (m, n), α = mπ/a,
/// β = nπ/a, the rotations condensed out of the 3 × 3 Navier system,
///   ω² ρt = s11 − [s12 s13] [s22 s23; s23 s33]⁻¹ [s12 s13]ᵀ,
/// s11 = K55 α² + K44 β², s12 = K55 α, s13 = K44 β, s22 = D11 α² + D66 β² + K55,
/// s23 = (D12 + D66) α β, s33 = D66 α² + D22 β² + K44. As K → ∞ this is
/// [`navier_frequencies`]; for an isotropic plate ω² = ω_K²/(1 + D k²/K).
pub fn mindlin_navier_frequencies(
    side: f64,
    mass_per_area: f64,
    d: [f64; 4],
    shear: [f64; 2],
    count: usize,
) -> Vec<f64> {
    let [d11, d22, d12, d66] = d;
    let [k55, k44] = shear;
    lowest(count, |m, n| {
        let (a, b) = (m * std::f64::consts::PI / side, n * std::f64::consts::PI / side);
        let (s11, s12, s13) = (k55 * a * a + k44 * b * b, k55 * a, k44 * b);
        let (s22, s23, s33) = (
            d11 * a * a + d66 * b * b + k55,
            (d12 + d66) * a * b,
            d66 * a * a + d22 * b * b + k44,
        );
        let det = s22 * s33 - s23 * s23;
        let condensed = s11 - (s12 * (s33 * s12 - s23 * s13) + s13 * (s22 * s13 - s23 * s12)) / det;
        (condensed / mass_per_area).sqrt()
    })
}

/// A simply supported a × a plate, specially orthotropic, thin (Kirchhoff): bending
/// stiffnesses D11, D22, D12, D66 and mass per area ρh (no rotary inertia), the
/// Navier plate of Timoshenko & Woinowsky-Krieger (*Theory of Plates and Shells*,
/// §28 and the dynamic analogue of §30): w = Σ q_mn(t) sin(mπx/a) sin(nπy/a),
/// ρh a²/4 · q̈_mn + K_mn q_mn = f_mn(t), K_mn = a²/4 · π⁴ [D11 (m/a)⁴ +
/// 2(D12 + 2D66)(m/a)²(n/a)² + D22 (n/a)⁴], from the origin at a corner.
#[derive(Debug, Clone, Copy)]
pub struct NavierPlate {
    /// Side a.
    pub side: f64,
    /// Mass per area ρh.
    pub mass_per_area: f64,
    /// D11, D22, D12, D66.
    pub d: [f64; 4],
}

/// Modes kept in each direction for the quasi-static part of
/// [`NavierPlate::fibre_strains`] (a series summed once): at 1-2 in from a point load
/// on the paper's plate the sum changes by 1e-5 of itself from 1000 to 2000 modes.
const STATIC_MODES: usize = 2000;
/// Modes kept in each direction for the dynamic remainder (q − q_static falls like
/// ω⁻² faster than q): 100 and 200 agree to 2e-5 of the peak strain on the paper's plate.
const DYNAMIC_MODES: usize = 100;

impl NavierPlate {
    /// K_mn per unit modal amplitude, with p = mπ/a, q = nπ/a.
    fn modal_stiffness(&self, p: f64, q: f64) -> f64 {
        let [d11, d22, d12, d66] = self.d;
        (d11 * p.powi(4) + 2.0 * (d12 + 2.0 * d66) * p * p * q * q + d22 * q.powi(4)) * self.side * self.side / 4.0
    }

    /// Wave numbers mπ/a, m = 1..=count.
    fn wave_numbers(&self, count: usize) -> Vec<f64> {
        (1..=count)
            .map(|m| std::f64::consts::PI * m as f64 / self.side)
            .collect()
    }

    /// The mode shapes sin(p x) sin(q y) at `point` over count² modes (m major).
    fn shapes(&self, count: usize, point: [f64; 2]) -> Vec<f64> {
        let k = self.wave_numbers(count);
        let (sx, sy): (Vec<f64>, Vec<f64>) = k.iter().map(|p| ((p * point[0]).sin(), (p * point[1]).sin())).unzip();
        sx.iter().flat_map(|a| sy.iter().map(move |b| a * b)).collect()
    }

    /// The modal loads of count² modes when the `loads` share a unit force.
    fn modal_load(&self, count: usize, loads: &[[f64; 2]]) -> Vec<f64> {
        let mut l = vec![0.0; count * count];
        for &x in loads {
            for (li, s) in l.iter_mut().zip(self.shapes(count, x)) {
                *li += s / loads.len() as f64;
            }
        }
        l
    }

    /// Curvature factors (p², q²) of count² modes, m major.
    fn curvatures(&self, count: usize) -> Vec<[f64; 2]> {
        let k = self.wave_numbers(count);
        k.iter().flat_map(|p| k.iter().map(move |q| [p * p, q * q])).collect()
    }

    /// Fibre strains (ε_xx, ε_yy) at height `z` from the mid-plane at each gauge point
    /// and each time k·Δt, when the force `force[k]` (linear between samples, zero
    /// before t = 0, the plate at rest) is shared equally by the `loads` points; points
    /// in plate coordinates from a corner. ε = −z ∂²w/∂x², −z ∂²w/∂y².
    ///
    /// Mode-acceleration summation: the quasi-static response F(t)·S (S the static
    /// strain per unit force, a slowly converging series summed once over
    /// `STATIC_MODES`²) plus the dynamic remainder Σ (q_mn − F f_mn/K_mn), which
    /// converges fast (`DYNAMIC_MODES`²). Each mode's step is the exact solution of
    /// q̈ + ω²q = f(t)/M for f linear over the step, so the result is exact in time
    /// for a piecewise-linear force and converges in the mode counts only.
    pub fn fibre_strains(
        &self,
        loads: &[[f64; 2]],
        force: &[f64],
        dt: f64,
        gauges: &[[f64; 2]],
        z: f64,
    ) -> Vec<Vec<[f64; 2]>> {
        self.fibre_strains_with([STATIC_MODES, DYNAMIC_MODES], loads, force, dt, gauges, z)
    }

    /// [`Self::fibre_strains`] with the mode counts (static, dynamic) given.
    fn fibre_strains_with(
        &self,
        [static_modes, dynamic_modes]: [usize; 2],
        loads: &[[f64; 2]],
        force: &[f64],
        dt: f64,
        gauges: &[[f64; 2]],
        z: f64,
    ) -> Vec<Vec<[f64; 2]>> {
        let per_unit_force = |count: usize| {
            let (l, c) = (self.modal_load(count, loads), self.curvatures(count));
            let k: Vec<f64> = c
                .iter()
                .map(|c| self.modal_stiffness(c[0].sqrt(), c[1].sqrt()))
                .collect();
            (l, c, k)
        };
        let (l, c, k) = per_unit_force(static_modes);
        let stat: Vec<[f64; 2]> = gauges
            .iter()
            .map(|&g| {
                let shape = self.shapes(static_modes, g);
                (0..l.len()).fold([0.0, 0.0], |acc, i| {
                    let s = l[i] / k[i] * shape[i];
                    [acc[0] + s * c[i][0], acc[1] + s * c[i][1]]
                })
            })
            .collect();
        let (l, c, k) = per_unit_force(dynamic_modes);
        let shapes: Vec<Vec<f64>> = gauges.iter().map(|&g| self.shapes(dynamic_modes, g)).collect();
        let mass = self.mass_per_area * self.side * self.side / 4.0;
        let w: Vec<f64> = k.iter().map(|k| (k / mass).sqrt()).collect();
        let (cos, sin): (Vec<f64>, Vec<f64>) = w.iter().map(|w| ((w * dt).cos(), (w * dt).sin())).unzip();
        let (mut q, mut v) = (vec![0.0; l.len()], vec![0.0; l.len()]);
        let mut out = Vec::with_capacity(force.len());
        for (step, &f) in force.iter().enumerate() {
            if step > 0 {
                let f0 = force[step - 1];
                for i in 0..l.len() {
                    // The particular solution a + b·s of the linear load, then the free
                    // oscillation of what remains.
                    let a = f0 * l[i] / k[i];
                    let b = (f - f0) * l[i] / (k[i] * dt);
                    let (qh, vh) = (q[i] - a, v[i] - b);
                    q[i] = qh * cos[i] + vh / w[i] * sin[i] + a + b * dt;
                    v[i] = -qh * w[i] * sin[i] + vh * cos[i] + b;
                }
            }
            out.push(
                shapes
                    .iter()
                    .zip(&stat)
                    .map(|(shape, s)| {
                        let r = (0..l.len()).fold([0.0, 0.0], |acc, i| {
                            let d = (q[i] - f * l[i] / k[i]) * shape[i];
                            [acc[0] + d * c[i][0], acc[1] + d * c[i][1]]
                        });
                        [z * (f * s[0] + r[0]), z * (f * s[1] + r[1])]
                    })
                    .collect(),
            );
        }
        out
    }
}

/// The rigid-target Hertz impact (A = 3/2): m on a rigid half-space at v0, or two
/// rigid bodies with the reduced mass m. Returns (α_max, peak force, duration).
///
/// Energy: ½ m v0² = 2/5 K α_max^(5/2). Duration: 2 ∫₀^αmax dα / v(α) with
/// v = v0 √(1 − (α/α_max)^(5/2)), i.e. (α_max/v0)·2∫₀¹ ds/√(1 − s^(5/2)) = 2.94328 α_max/v0.
pub fn rigid_target(mass: f64, v0: f64, stiffness: f64) -> (f64, f64, f64) {
    let a_max = (5.0 * mass * v0 * v0 / (4.0 * stiffness)).powf(0.4);
    (
        a_max,
        stiffness * a_max.powf(1.5),
        RIGID_DURATION_FACTOR * a_max / v0.abs(),
    )
}

/// 2∫₀¹ ds/√(1 − s^(5/2)) = 2 Γ(2/5) Γ(1/2) / (5/2 · Γ(9/10)) = 2.9432752…
pub const RIGID_DURATION_FACTOR: f64 = 2.943_275_184_324_705;

/// A thin-shell theory of the closed cylinder (Leissa, Vibration of Shells, NASA
/// SP-288, 1973, ch. 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellTheory {
    /// Sanders' (the curvature changes and twist with their in-plane terms).
    Sanders,
    /// Donnell-Mushtari's (the curvatures of w alone; too stiff at low n).
    Donnell,
}

/// Ω² of mode (m, n) of a simply supported closed cylinder (R, L, t, ν): the lowest
/// eigenvalue of the 3×3 stiffness of u = A cos λs cos nθ, v = B sin λs sin nθ,
/// w = C sin λs cos nθ (s = x/R, λ = mπR/L, the diaphragms' v = w = 0 and free u),
/// with unit mass on A, B, C; Ω² = ρ(1 − ν²)R²ω²/E. Membrane strains ε_x = u_s,
/// ε_θ = v_θ + w, γ = u_θ + v_s; Sanders' changes of curvature κ_x = −w_ss,
/// κ_θ = v_θ − w_θθ, twist τ = −w_sθ + ¾v_s − ¼u_θ (all over R, R²); energy
/// ε_x² + ε_θ² + 2νε_xε_θ + (1−ν)/2 γ² + k(κ_x² + κ_θ² + 2νκ_xκ_θ + 2(1−ν)τ²),
/// k = t²/12R². Donnell-Mushtari's theory keeps only the w terms of the curvatures.
pub fn cylinder_omega2(r: f64, l: f64, t: f64, nu: f64, (m, n): (usize, usize), theory: ShellTheory) -> f64 {
    use nalgebra::{Matrix3, Vector3};
    let (lam, n) = (m as f64 * std::f64::consts::PI * r / l, n as f64);
    let k = t * t / (12.0 * r * r);
    let mut s = Matrix3::new(
        lam * lam + 0.5 * (1.0 - nu) * n * n,
        -0.5 * (1.0 + nu) * lam * n,
        -nu * lam,
        -0.5 * (1.0 + nu) * lam * n,
        n * n + 0.5 * (1.0 - nu) * lam * lam,
        n,
        -nu * lam,
        n,
        1.0,
    );
    // Curvatures and twist as linear forms in (A, B, C).
    let (kx, kt, tw) = match theory {
        ShellTheory::Donnell => (
            Vector3::new(0.0, 0.0, lam * lam),
            Vector3::new(0.0, 0.0, n * n),
            Vector3::new(0.0, 0.0, lam * n),
        ),
        ShellTheory::Sanders => (
            Vector3::new(0.0, 0.0, lam * lam),
            Vector3::new(0.0, n, n * n),
            Vector3::new(0.25 * n, 0.75 * lam, lam * n),
        ),
    };
    s += (kx * kx.transpose()
        + kt * kt.transpose()
        + (kx * kt.transpose() + kt * kx.transpose()) * nu
        + tw * tw.transpose() * (2.0 * (1.0 - nu)))
        * k;
    crate::numerics::symmetric_eigenvalues(s).min()
}

/// The lowest Ω = √(ρ(1 − ν²)/E)·Rω of a simply supported closed cylinder by
/// `theory`, and its mode (m, n), over m = 1..=3 axial half-waves and n = 1..=24
/// circumferential waves (the lowest of a thin cylinder of L/R ~ 2 lies at m = 1,
/// n of 3 to 8).
pub fn cylinder_lowest_frequency(r: f64, l: f64, t: f64, nu: f64, theory: ShellTheory) -> (f64, (usize, usize)) {
    (1..=3)
        .flat_map(|m| (1..=24).map(move |n| (m, n)))
        .map(|mode| (cylinder_omega2(r, l, t, nu, mode, theory).sqrt(), mode))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("modes searched")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: the RK4 solution converges at the order the t^(3/2) onset allows, 2.5:
    /// the force at 20 µs changes 2^2.5 ≈ 5.7× less when h is halved, and at h = 1 ns
    /// the change is below 1e-9 of the force. Model: the paper's ball on a
    /// semi-infinite aluminium rod.
    #[test]
    fn semi_infinite_rod_rk4_order_four() {
        let p = HertzDashpot {
            mass: 9.587e-5,
            v0: 62.1,
            stiffness: 6.24e6,
            exponent: 1.5,
            impedance: 2.5e-4 * 2.0e5 * 0.196,
        };
        let peak_at = |h: f64| {
            // F at a fixed time before the peak, where the solution is smooth.
            force_at(&p.integrate(20e-6, h), 20e-6)
        };
        let (a, b, c) = (peak_at(4e-8), peak_at(2e-8), peak_at(1e-8));
        let order = ((a - b) / (b - c)).abs().log2();
        assert!((order - 2.5).abs() < 0.1, "order {order}");
        assert!((peak_at(1e-9) - peak_at(5e-10)).abs() < 1e-9 * c, "converged at 1 ns");
    }

    /// Goal: the semi-infinite rod reproduces the independent scipy DOP853 solution
    /// recorded in reference-data/rod-published.toml (contact end 74.41 µs = 0.41340
    /// L/C, at rest 0.22352 L/C, rebound −28.3805 in/s) to 1e-4.
    #[test]
    fn semi_infinite_rod_matches_recorded_solution() {
        let p = HertzDashpot {
            mass: 9.587e-5,
            v0: 62.1,
            stiffness: 6.24e6,
            exponent: 1.5,
            impedance: 2.5e-4 * 2.0e5 * 0.196,
        };
        let e = HertzDashpot::events(&p.integrate(100e-6, 1e-9)).unwrap();
        let lc = 36.0 / 2.0e5;
        assert!(
            (e.contact_end / lc / 0.41340 - 1.0).abs() < 1e-4,
            "{}",
            e.contact_end / lc
        );
        assert!((e.velocity_zero / lc / 0.22352 - 1.0).abs() < 1e-4);
        assert!((e.rebound_velocity / -28.3805 - 1.0).abs() < 1e-4);
    }

    /// The paper's plate (MAT2 201 bending, 0.15 in, ρ 1.8e-4) as a Navier plate, loaded
    /// at the four corners of its 49×49 mesh's centre element, gauges 1 and 2 in from
    /// the centre.
    fn paper_navier_plate() -> (NavierPlate, [[f64; 2]; 4], [[f64; 2]; 2]) {
        let t: f64 = 0.15;
        let d = |g: f64| g * t.powi(3) / 12.0;
        let plate = NavierPlate {
            side: 6.0,
            mass_per_area: 1.8e-4 * t,
            d: [d(5.7e6), d(1.4e6), d(2.9e5), d(5.7e5)],
        };
        let h = 6.0 / 49.0 / 2.0;
        let loads = [
            [3.0 - h, 3.0 - h],
            [3.0 + h, 3.0 - h],
            [3.0 - h, 3.0 + h],
            [3.0 + h, 3.0 + h],
        ];
        (plate, loads, [[3.0, 4.0], [3.0, 5.0]])
    }

    /// Goal: each mode's step is exact for a load linear in time. A force switched on
    /// at t = 0 and one ramped from 0 at rate r make each mode follow
    /// F f/K (1 − cos ωt) and r f/K (t − sin(ωt)/ω); the strains summed from those
    /// closed forms over the same 10 × 10 modes agree to 1e-10 of their peak after
    /// 10 000 steps (the recurrence's error would grow with the step count).
    #[test]
    fn navier_modes_follow_their_closed_forms_under_step_and_ramp_loads() {
        let (plate, loads, gauges) = paper_navier_plate();
        let (dt, steps, z) = (1e-7, 10_000, 0.075);
        let count = 10;
        let (l, c) = (plate.modal_load(count, &loads), plate.curvatures(count));
        let shape = plate.shapes(count, gauges[0]);
        let mass = plate.mass_per_area * 36.0 / 4.0;
        let exact = |t: f64, mode: &dyn Fn(f64, f64) -> f64| {
            (0..l.len()).fold([0.0, 0.0], |acc, i| {
                let k = plate.modal_stiffness(c[i][0].sqrt(), c[i][1].sqrt());
                let q = l[i] / k * mode(t, (k / mass).sqrt());
                [acc[0] + z * q * shape[i] * c[i][0], acc[1] + z * q * shape[i] * c[i][1]]
            })
        };
        let step: Vec<f64> = vec![1000.0; steps + 1];
        let ramp: Vec<f64> = (0..=steps).map(|k| 1e9 * k as f64 * dt).collect();
        let step_mode = |t: f64, w: f64| 1000.0 * (1.0 - (w * t).cos());
        let ramp_mode = |t: f64, w: f64| 1e9 * (t - (w * t).sin() / w);
        for (force, mode) in [(&step, &step_mode as &dyn Fn(f64, f64) -> f64), (&ramp, &ramp_mode)] {
            let got = plate.fibre_strains_with([count, count], &loads, force, dt, &gauges[..1], z);
            let want: Vec<[f64; 2]> = (0..=steps).map(|k| exact(k as f64 * dt, mode)).collect();
            let peak = want.iter().fold(0.0f64, |a, e| a.max(e[0].abs()).max(e[1].abs()));
            let worst = got.iter().zip(&want).fold(0.0f64, |a, (g, w)| {
                a.max((g[0][0] - w[0]).abs()).max((g[0][1] - w[1]).abs())
            });
            assert!(worst < 1e-10 * peak, "{worst:e} of {peak:e}");
        }
    }

    /// Goal: the strains converge in both mode counts as the constants' docs say. A
    /// 200 µs half-sine of 1400 lbf (the paper's contact) on the paper's plate: doubling
    /// the static modes (1000 → 2000) and the dynamic ones (100 → 200) each moves the
    /// gauges' strains by less than 1e-4 of their peak.
    #[test]
    fn navier_strains_converge_in_their_mode_counts() {
        let (plate, loads, gauges) = paper_navier_plate();
        let dt = 1e-7;
        let force: Vec<f64> = (0..=1500)
            .map(|k| 1400.0 * (std::f64::consts::PI * k as f64 * dt / 200e-6).sin())
            .collect();
        let run = |counts| plate.fibre_strains_with(counts, &loads, &force, dt, &gauges, 0.075);
        let base = run([STATIC_MODES, DYNAMIC_MODES]);
        let peak = base
            .iter()
            .flatten()
            .fold(0.0f64, |a, e| a.max(e[0].abs()).max(e[1].abs()));
        for counts in [[STATIC_MODES / 2, DYNAMIC_MODES], [STATIC_MODES, 2 * DYNAMIC_MODES]] {
            let other = run(counts);
            let worst = base
                .iter()
                .flatten()
                .zip(other.iter().flatten())
                .fold(0.0f64, |a, (x, y)| a.max((x[0] - y[0]).abs()).max((x[1] - y[1]).abs()));
            assert!(worst < 1e-4 * peak, "{counts:?}: {:e} of the peak", worst / peak);
        }
    }

    /// Goal: with an almost rigid target (impedance 1e6× the rod's) the dashpot model
    /// tends to the closed form: duration 2.94328 α_max/v0 and peak K α_max^1.5.
    #[test]
    fn rigid_target_closed_form_is_the_stiff_limit() {
        let p = HertzDashpot {
            mass: 9.587e-5,
            v0: 62.1,
            stiffness: 6.24e6,
            exponent: 1.5,
            impedance: 1e7,
        };
        let (_, fmax, dur) = rigid_target(p.mass, p.v0, p.stiffness);
        let e = HertzDashpot::events(&p.integrate(2.0 * dur, dur / 1e5)).unwrap();
        assert!((e.contact_end / dur - 1.0).abs() < 1e-4, "{} vs {dur}", e.contact_end);
        assert!((e.peak_force / fmax - 1.0).abs() < 1e-4);
    }
}
