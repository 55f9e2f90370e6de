//! Properties and materials: the sections of rods, bars, shear panels and shells
//! (PSHELL, PCOMP) from their cards, each resolved once per property.

use super::*;

/// The property and material cards, resolved once per property (a laminate once per
/// property and material axis).
pub(super) struct Properties<'d> {
    pub(super) bulk: &'d crate::deck::cards::Bulk,
    pub(super) mat1: HashMap<i64, &'d crate::deck::cards::Mat1>,
    pub(super) prod: HashMap<i64, &'d crate::deck::cards::Prod>,
    pub(super) pshear: HashMap<i64, &'d crate::deck::cards::Pshear>,
    pub(super) bars: HashMap<i64, &'d crate::deck::cards::BarProperty>,
    pub(super) pshell: HashMap<i64, &'d crate::deck::cards::Pshell>,
    pub(super) pcomp: HashMap<i64, &'d crate::deck::cards::Pcomp>,
    /// COSMIC's plate properties by (card, id).
    pub(super) cosmic: HashMap<(&'static str, i64), &'d crate::deck::cards::Pshell>,
    pub(super) shells: HashMap<i64, Option<ShellSection>>,
    pub(super) cosmic_shells: HashMap<(&'static str, i64), Option<ShellSection>>,
    pub(super) laminates: HashMap<(i64, u64), Option<(ShellSection, PlyStack)>>,
}

impl<'d> Properties<'d> {
    pub(super) fn new(cx: &mut Ctx, b: &'d crate::deck::cards::Bulk) -> Self {
        let pshell: HashMap<i64, &crate::deck::cards::Pshell> = b.pshells.iter().map(|p| (p.pid, p)).collect();
        for p in b.pcomps.iter().filter(|p| pshell.contains_key(&p.pid)) {
            cx.err(p.at.error(format!("property {} is both a PSHELL and a PCOMP", p.pid)));
        }
        Properties {
            bulk: b,
            mat1: b.mat1s.iter().map(|m| (m.mid, m)).collect(),
            prod: b.prods.iter().map(|p| (p.pid, p)).collect(),
            pshear: b.pshears.iter().map(|p| (p.pid, p)).collect(),
            bars: b.bar_properties.iter().map(|p| (p.pid, p)).collect(),
            pshell,
            pcomp: b.pcomps.iter().map(|p| (p.pid, p)).collect(),
            cosmic: b.cosmic_plates.iter().map(|(card, p)| ((*card, p.pid), p)).collect(),
            shells: HashMap::new(),
            cosmic_shells: HashMap::new(),
            laminates: HashMap::new(),
        }
    }

    /// The MAT1 `mid` property `pid` (its card `at`) references; an error if none.
    pub(super) fn mat1_of(
        &self,
        cx: &mut Ctx,
        at: &CardRef,
        pid: i64,
        mid: i64,
    ) -> Option<&'d crate::deck::cards::Mat1> {
        let m = self.mat1.get(&mid).copied();
        if m.is_none() {
            cx.err(at.error(format!("{} {pid} references MAT1 {mid}, which does not exist", at.name)));
        }
        m
    }

    /// The element's structural damping coefficient GE and the card that gives it:
    /// its MAT1's for a rod, bar or shear panel; a PSHELL's MID1 material's (MAT1 or
    /// MAT2: "structural damping, when needed, is obtained from the MID1 material",
    /// NASTRAN-95 User's Manual, PSHELL remark 5); a PCOMP's own GE field, its plies'
    /// materials' being ignored (MSC Quick Reference Guide, PCOMP). `None` when its
    /// property or material does not resolve (its error is reported where its section
    /// is).
    pub(super) fn structural_damping(&self, c: &'d Connection) -> Option<(f64, &'d CardRef)> {
        let b = self.bulk;
        let material = |mid: i64| -> Option<(f64, &'d CardRef)> {
            match self.mat1.get(&mid) {
                Some(m) => Some((m.ge, &m.at)),
                None => b.mat2s.iter().find(|m| m.mid == mid).map(|m| (m.ge, &m.at)),
            }
        };
        match c.kind.build {
            Build::Rod(_) => material(c.rod.as_deref().or_else(|| self.prod.get(&c.pid).copied())?.mid),
            Build::Panel(_) => material(self.pshear.get(&c.pid)?.mid),
            Build::Bar(_) => material(self.bars.get(&c.pid)?.mid),
            Build::Shell(_) => {
                let shell = match c.property_card {
                    Some(card) => self.cosmic.get(&(card, c.pid)),
                    None => self.pshell.get(&c.pid),
                };
                match (shell, self.pcomp.get(&c.pid)) {
                    (Some(p), _) => material(p.mid1?),
                    (None, Some(p)) => Some((p.ge, &p.at)),
                    (None, None) => None,
                }
            }
        }
    }

    /// A rod's PROD and MAT1.
    pub(super) fn rod(&self, cx: &mut Ctx, c: &'d Connection) -> Option<RodSection> {
        let property = if c.kind.card == "CTUBE" { "PTUBE" } else { "PROD" };
        let Some(p) = c.rod.as_deref().or_else(|| self.prod.get(&c.pid).copied()) else {
            cx.err(c.at.error(format!(
                "{} {} references {property} {}, which does not exist",
                c.kind.card, c.eid, c.pid
            )));
            return None;
        };
        let m = self.mat1_of(cx, &p.at, p.pid, p.mid)?;
        Some(RodSection {
            e: m.e,
            g: m.g,
            area: p.a,
            torsion: p.j,
            rho: m.rho,
            nsm: p.nsm,
            coupled_mass: self
                .bulk
                .coupled_mass(if c.kind.card == "CTUBE" { "CPTUBE" } else { "CPROD" })
                .is_some(),
        })
    }

    /// A shear panel's PSHEAR and MAT1.
    pub(super) fn panel(&self, cx: &mut Ctx, c: &Connection) -> Option<crate::elements::shear::PanelSection> {
        let Some(p) = self.pshear.get(&c.pid) else {
            cx.err(c.at.error(format!(
                "{} {} references PSHEAR {}, which does not exist",
                c.kind.card, c.eid, c.pid
            )));
            return None;
        };
        let m = self.mat1_of(cx, &p.at, p.pid, p.mid)?;
        if m.g <= 0.0 {
            cx.err(p.at.error(format!(
                "PSHEAR {}: its MAT1 {} gives no shear modulus (G = {:e}): a shear panel has no other stiffness",
                p.pid, p.mid, m.g
            )));
            return None;
        }
        Some(crate::elements::shear::PanelSection {
            g: m.g,
            nu: m.nu,
            t: p.t,
            rho: m.rho,
            nsm: p.nsm,
        })
    }

    /// A bar's property (a CBAR's PBAR or PBARL, a CBEAM's PBEAM or PBEAML) and MAT1:
    /// its section's constants, given or computed from its dimensions.
    pub(super) fn bar(&self, cx: &mut Ctx, c: &Connection) -> Option<crate::elements::bar::BarSection> {
        let (names, beam) = match c.kind.card {
            "CBEAM" => ("PBEAM or PBEAML", true),
            _ => ("PBAR or PBARL", false),
        };
        let p = match self.bars.get(&c.pid) {
            Some(p) if p.at.name.starts_with("PBEAM") == beam => p,
            other => {
                let but = match other {
                    Some(p) => format!(
                        ": property {} is a {}, which a {} takes",
                        c.pid,
                        p.at.name,
                        if beam { "CBAR" } else { "CBEAM" }
                    ),
                    None => String::new(),
                };
                cx.err(c.at.error(format!(
                    "{} {} references {names} {}, which does not exist{but}",
                    c.kind.card, c.eid, c.pid
                )));
                return None;
            }
        };
        let Some(m) = self.mat1.get(&p.mid) else {
            cx.err(p.at.error(format!(
                "{} {} references MAT1 {}, which does not exist",
                p.at.name, p.pid, p.mid
            )));
            return None;
        };
        let k = match &p.dims {
            crate::deck::cards::BarDims::Constants(k) => *k,
            crate::deck::cards::BarDims::Shape(shape, dims) => {
                crate::elements::section::constants(*shape, dims).expect("the reader checked the section's dimensions")
            }
        };
        Some(crate::elements::bar::BarSection {
            e: m.e,
            g: m.g,
            area: k.area,
            i1: k.i1,
            i2: k.i2,
            i12: k.i12,
            j: k.j,
            rho: m.rho,
            nsm: p.nsm,
            points: k.points,
            torsional_inertia: if beam { m.rho * (k.i1 + k.i2) } else { 0.0 },
            alpha: m.alpha,
            tref: m.tref,
        })
    }

    /// A shell's PSHELL or PCOMP with its materials, and a laminate's plies; `axes`
    /// the material x axis (degrees from the element kernel's x axis), `None` when the
    /// element's grids are not all known (a laminate is then not resolved).
    pub(super) fn shell(
        &mut self,
        cx: &mut Ctx,
        c: &Connection,
        axes: Option<f64>,
    ) -> Option<(ShellSection, Option<PlyStack>)> {
        let b = self.bulk;
        if let Some(card) = c.property_card {
            let key = (card, c.pid);
            if !self.cosmic_shells.contains_key(&key) {
                let s = match self.cosmic.get(&key) {
                    Some(p) => shell_section(cx, p, &self.mat1, &b.mat2s),
                    None => {
                        cx.err(c.at.error(format!(
                            "{} {} references {card} {}, which does not exist",
                            c.at.name, c.eid, c.pid
                        )));
                        None
                    }
                };
                self.cosmic_shells.insert(key, s);
            }
            let s = self.cosmic_shells[&key].clone();
            return self.oriented(s, self.cosmic.get(&key).copied(), axes);
        }
        match (self.shells.get(&c.pid), self.pcomp.get(&c.pid)) {
            (_, Some(p)) if !self.pshell.contains_key(&c.pid) => {
                let axes = axes?;
                let lam = self
                    .laminates
                    .entry((c.pid, axes.to_bits()))
                    .or_insert_with(|| laminate_section(cx, p, &b.mat1s, &b.mat8s, axes))
                    .clone();
                lam.map(|(section, layers)| (section, Some(layers)))
            }
            (cached, _) => {
                let s = match cached {
                    Some(s) => s.clone(),
                    None => {
                        let s = match self.pshell.get(&c.pid) {
                            Some(p) => shell_section(cx, p, &self.mat1, &b.mat2s),
                            None => {
                                cx.err(c.at.error(format!(
                                    "{} {} references property {} (PSHELL or PCOMP), which does not exist",
                                    c.kind.card, c.eid, c.pid
                                )));
                                None
                            }
                        };
                        self.shells.insert(c.pid, s.clone());
                        s
                    }
                };
                self.oriented(s, self.pshell.get(&c.pid).copied(), axes)
            }
        }
    }

    /// A PSHELL's section in the element's axes: turned to the material axis when
    /// one of its materials is a MAT2 (anisotropic).
    pub(super) fn oriented(
        &self,
        s: Option<ShellSection>,
        p: Option<&crate::deck::cards::Pshell>,
        axes: Option<f64>,
    ) -> Option<(ShellSection, Option<PlyStack>)> {
        let anisotropic = p.is_some_and(|p| {
            [p.mid1, p.mid2, p.mid3, p.mid4]
                .iter()
                .flatten()
                .any(|mid| self.bulk.mat2s.iter().any(|m| m.mid == *mid))
        });
        match (s, axes) {
            (Some(s), Some(angle)) if anisotropic => Some((turned_section(&s, angle), None)),
            (s, _) => s.map(|s| (s, None)),
        }
    }
}

/// A PSHELL's section, its MAT2 materials given in the material axes, in the
/// element's axes when the material x axis is `angle` degrees from the element's x:
/// G = Tᵀ G_material T with T [`crate::laminate::strain_rotation`], and the transverse
/// shear's 2×2 turned as a tensor. A half turn leaves a plane material as it is, so
/// an angle of a whole number of half turns returns the section unchanged (exactly,
/// as the paper's plate has it on every element).
pub(super) fn turned_section(s: &ShellSection, angle: f64) -> ShellSection {
    if angle.rem_euclid(180.0) == 0.0 {
        return s.clone();
    }
    let turn = |g: Option<Matrix3<f64>>| g.map(|g| crate::laminate::rotated(&g, angle));
    let (sn, cs) = angle.to_radians().sin_cos();
    // (γxz, γyz) in material axes = R (γxz, γyz) in element axes.
    let r = Matrix2::new(cs, sn, -sn, cs);
    ShellSection {
        g_membrane: turn(s.g_membrane),
        g_bending: turn(s.g_bending),
        g_coupling: turn(s.g_coupling),
        shear: s.shear.map(|h| r.transpose() * h * r),
        ..s.clone()
    }
}

/// The material matrix of a MAT1 (plane stress) or MAT2 id, checked positive definite.
pub(super) fn material_matrix(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<(Matrix3<f64>, f64)> {
    material(cx, mid, used_by, mat1, mat2s, true)
}

/// PSHELL MID3's transverse shear material, the 2×2 G relating (Qx, Qy)/(TS·T) to
/// (γxz, γyz): a MAT1's G on the diagonal, or a MAT2's [G11 G12; G12 G22], whose
/// G13, G23 and G33 must then be blank (Altair OptiStruct Reference Guide, MAT2,
/// comment 3: a MAT2 referenced by PSHELL MID3 uses G11, G12, G22), positive definite.
pub(super) fn transverse_shear_material(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<nalgebra::Matrix2<f64>> {
    if let Some(m) = mat2s.iter().find(|m| m.mid == mid) {
        if m.g[0][2] != 0.0 || m.g[1][2] != 0.0 || m.g[2][2] != 0.0 {
            cx.err(m.at.error(format!(
                "MAT2 {mid} is a transverse shear material (PSHELL MID3): G11, G12 and G22 form its 2×2 matrix, \
                 and G13, G23, G33 must be blank"
            )));
            return None;
        }
        let g = nalgebra::Matrix2::new(m.g[0][0], m.g[0][1], m.g[0][1], m.g[1][1]);
        if g.cholesky().is_none() {
            cx.err(m.at.error(format!(
                "MAT2 {mid} (PSHELL MID3) is not positive definite: [G11 G12; G12 G22] gives no shear energy for \
                 some shear strain"
            )));
            return None;
        }
        return Some(g);
    }
    if let Some(m) = mat1.get(&mid) {
        if m.g <= 0.0 {
            cx.err(m.at.error(format!("MAT1 {mid} (PSHELL MID3) has no shear modulus G")));
            return None;
        }
        return Some(nalgebra::Matrix2::identity() * m.g);
    }
    cx.err(used_by.error(format!("material {mid} (MAT1 or MAT2), PSHELL MID3, does not exist")));
    None
}

/// A MAT2's or MAT1's plane-stress matrix and density; a MAT2 must be positive
/// definite when `definite` (a coupling material, MID4, need not be).
pub(super) fn material(
    cx: &mut Ctx,
    mid: i64,
    used_by: &CardRef,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
    definite: bool,
) -> Option<(Matrix3<f64>, f64)> {
    if let Some(m) = mat2s.iter().find(|m| m.mid == mid) {
        let g = Matrix3::from_fn(|i, j| m.g[i][j]);
        if definite && g.cholesky().is_none() {
            cx.err(m.at.error(format!(
                "MAT2 {mid} is not positive definite: no strain energy for some strain state (check G11..G33)"
            )));
            return None;
        }
        return Some((g, m.rho));
    }
    if let Some(m) = mat1.get(&mid) {
        let q = m.e / (1.0 - m.nu * m.nu);
        let g = Matrix3::new(q, q * m.nu, 0.0, q * m.nu, q, 0.0, 0.0, 0.0, m.g);
        return Some((g, m.rho));
    }
    cx.err(used_by.error(format!("material {mid} (MAT1 or MAT2) does not exist")));
    None
}

pub(super) fn shell_section(
    cx: &mut Ctx,
    p: &crate::deck::cards::Pshell,
    mat1: &HashMap<i64, &crate::deck::cards::Mat1>,
    mat2s: &[crate::deck::cards::Mat2],
) -> Option<ShellSection> {
    let mem = match p.mid1 {
        Some(mid) => Some(material_matrix(cx, mid, &p.at, mat1, mat2s)?),
        None => None,
    };
    let bend = match p.mid2 {
        Some(mid) => Some(material_matrix(cx, mid, &p.at, mat1, mat2s)?),
        None => None,
    };
    if mem.is_none() && bend.is_none() {
        cx.err(p.at.error("PSHELL has neither MID1 nor MID2: the shell has no stiffness"));
        return None;
    }
    let coupling = match p.mid4 {
        Some(_) if mem.is_none() || bend.is_none() => {
            cx.err(p.at.error("PSHELL MID4 (membrane-bending coupling) needs both MID1 and MID2"));
            return None;
        }
        Some(mid) => Some(material(cx, mid, &p.at, mat1, mat2s, false)?.0),
        None => None,
    };
    let shear = match p.mid3 {
        Some(mid) => Some(transverse_shear_material(cx, mid, &p.at, mat1, mat2s)? * (p.ts_t * p.t)),
        None => None,
    };
    // NASTRAN takes the shell's density from MID1 (else MID2).
    let rho = mem.or(bend).map(|(_, r)| r).unwrap_or(0.0);
    let section = ShellSection {
        thickness: p.t,
        g_membrane: mem.map(|(g, _)| g),
        g_bending: bend.map(|(g, _)| g * p.bend_ratio),
        g_coupling: coupling,
        shear,
        mass_per_area: rho * p.t + p.nsm,
    };
    if !section_is_definite(&section) {
        cx.err(p.at.error(if section.g_coupling.is_some() {
            "the membrane, bending and coupling stiffnesses [A B; B D] are not positive definite (MID4 too \
             large against MID1 and MID2)"
                .to_string()
        } else {
            format!(
                "the membrane and bending stiffnesses A = G1·T and D = G2·T³/12 are not positive definite in \
                 double precision: T = {:e} is too small or too large for them",
                p.t
            )
        }));
        return None;
    }
    Some(section)
}

/// True when a section's stiffness, [A B; B D] (B zero when uncoupled; A or D alone
/// when the other is absent), is finite and positive definite in double precision.
/// Its materials are checked where they are read; what this adds is the coupling
/// (MID4 against MID1 and MID2) and the scaling by the thickness, which can overflow
/// or underflow (a bending stiffness G·T³/12 of 0 for T = 1e-110).
pub(super) fn section_is_definite(s: &ShellSection) -> bool {
    fn definite<const N: usize>(k: nalgebra::SMatrix<f64, N, N>) -> bool {
        k.iter().all(|v| v.is_finite()) && k.cholesky().is_some()
    }
    match (s.a(), s.d()) {
        (Some(a), Some(d)) => {
            let b = s.b().unwrap_or_else(Matrix3::zeros);
            let mut k = nalgebra::Matrix6::zeros();
            k.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
            k.fixed_view_mut::<3, 3>(0, 3).copy_from(&b);
            k.fixed_view_mut::<3, 3>(3, 0).copy_from(&b.transpose());
            k.fixed_view_mut::<3, 3>(3, 3).copy_from(&d);
            definite(k)
        }
        (Some(m), None) | (None, Some(m)) => definite(m),
        (None, None) => true,
    }
}

/// The section of a PCOMP for an element whose material x axis is `axes` degrees
/// counter-clockwise from basic x (its plies' fibres at θ + `axes` in basic axes): its
/// plies (MAT8 or MAT1) through the lamination stage, the laminate's A/t, 12D/t³ and,
/// for an unsymmetric laminate, B/t² as the plate's membrane, bending and coupling
/// materials (NASTRAN's MID1, MID2 and MID4 equivalents). A, B and D are taken about
/// the reference plane (the grids' plane), Z0 from it to the bottom surface: a Z0
/// other than −T/2 (an offset laminate) couples membrane and bending through B, as
/// NASTRAN's equivalent PSHELL does with its MID4.
pub(super) fn laminate_section(
    cx: &mut Ctx,
    p: &crate::deck::cards::Pcomp,
    mat1s: &[crate::deck::cards::Mat1],
    mat8s: &[crate::deck::cards::Mat8],
    axes: f64,
) -> Option<(ShellSection, PlyStack)> {
    use crate::laminate::{plies_of, ply_layers, Laminate};
    let plies = match plies_of(p, mat1s, mat8s) {
        Ok(plies) => plies,
        Err(e) => {
            cx.err(p.at.error(format!("PCOMP {}: {e}", p.pid)));
            return None;
        }
    };
    let lam = match Laminate::new(&plies, p.z0, axes) {
        Ok(l) => l,
        Err(e) => {
            cx.err(p.at.error(format!("PCOMP {}: {e}", p.pid)));
            return None;
        }
    };
    // Transverse shear: the plies' integral with the shear correction factor 5/6
    // (first-order shear deformation theory's), reordered from (yz, xz) to (xz, yz).
    let shear = lam
        .shear
        .map(|h| Matrix2::new(h[(1, 1)], h[(0, 1)], h[(1, 0)], h[(0, 0)]) * (5.0 / 6.0));
    if shear.is_none() {
        cx.warn(p.at.error(format!(
            "PCOMP {}: not every ply's MAT8 gives G1Z and G2Z: the laminate is taken as rigid in transverse shear \
             (a thin plate)",
            p.pid
        )));
    }
    let blank_f12 = p
        .stack()
        .iter()
        .any(|ply| mat8s.iter().any(|m| m.mid == ply.mid && m.f12.is_none()));
    if p.ft.as_deref() == Some("TSAI") && blank_f12 {
        cx.warn(p.at.error(format!(
            "PCOMP {}: FT = TSAI with a ply whose MAT8 leaves F12 blank: F12 = 0 there, as NASTRAN takes it",
            p.pid
        )));
    }
    let section = ShellSection {
        thickness: lam.thickness,
        g_membrane: Some(lam.membrane_material()),
        g_bending: Some(lam.bending_material()),
        g_coupling: (!lam.is_uncoupled()).then(|| lam.coupling_material()),
        shear,
        mass_per_area: lam.mass_per_area + p.nsm,
    };
    // Plies of positive thickness and positive definite Q make a positive definite
    // [A B; B D] in exact arithmetic; in double precision, plies thin or soft enough
    // (or stiff enough) underflow or overflow it.
    if !section_is_definite(&section) {
        cx.err(p.at.error(format!(
            "PCOMP {}: the laminate's stiffness [A B; B D] is not positive definite in double precision \
             (A11 = {:e}, D11 = {:e}): its plies are too thin, too soft or too stiff for it to be represented",
            p.pid,
            lam.a[(0, 0)],
            lam.d[(0, 0)],
        )));
        return None;
    }
    Some((
        section,
        std::sync::Arc::new(ply_layers(&plies, p.z0, axes, p.sb.filter(|_| p.ft.is_some()))),
    ))
}
