//! The columns of `history.csv`: typed, turned into header text only when written.

use super::UnitSystem;
use crate::elements::{At, Fibre, Measure, Plane, Recovered};
use crate::model::DofLabel;

/// One column of a run's history.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Column {
    /// Time.
    Time,
    /// Contact force magnitude K φ(α) (the force on the impactor).
    ContactForce,
    /// The indentation α.
    Indentation,
    /// The impactor's displacement along the impact direction.
    ImpactorDisp,
    /// The impactor's velocity along the impact direction.
    ImpactorVelo,
    /// Displacement of a DOF (DISP request), in its grid's displacement frame (the
    /// CD, 0 for the basic system and for a scalar point).
    Disp(DofLabel, i64),
    /// Velocity of a DOF (VELO request), in its grid's displacement frame.
    Velo(DofLabel, i64),
    /// A NOLIN3 load on a DOF (NLLOAD request), in its grid's displacement frame.
    NlLoad(DofLabel, i64),
    /// A recovered stress or strain of an element (STRESS/STRAIN requests).
    Element {
        /// Element id.
        eid: i64,
        /// Which value.
        value: Recovered,
    },
    /// A strain or stress of a laminate element's ply, in the ply's axes (its
    /// element's STRESS/STRAIN request).
    Ply {
        /// Element id.
        eid: i64,
        /// The ply, from 1 at the bottom.
        ply: u16,
        /// Its bottom or top surface.
        face: Face,
        /// Stress or strain.
        measure: Measure,
        /// The component in the ply's axes.
        axis: PlyAxis,
    },
}

/// A ply's bottom or top surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Face {
    /// The surface nearer z = −T/2.
    Bottom,
    /// The surface nearer z = +T/2.
    Top,
}

impl Face {
    /// Its name in the summary: `bottom` or `top`.
    pub fn name(self) -> &'static str {
        match self {
            Face::Bottom => "bottom",
            Face::Top => "top",
        }
    }
}

/// A component in a ply's axes: 1 along the fibres, 2 across, 12 the engineering
/// shear.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PlyAxis {
    /// Along the fibres.
    P11,
    /// Across the fibres.
    P22,
    /// In-plane shear.
    P12,
    /// Interlaminar shear in the 1-z plane (at a ply's top, the bond with the ply
    /// above).
    P1z,
    /// Interlaminar shear in the 2-z plane.
    P2z,
}

impl Column {
    /// The columns of a laminate element's plies, in the order they are computed: ply
    /// by ply from the bottom, bottom then top surface, strains (11, 22, 12) then
    /// stresses.
    pub fn plies(eid: i64, count: usize) -> Vec<Column> {
        let mut out = Vec::with_capacity(12 * count);
        for ply in 1..=count as u16 {
            for face in [Face::Bottom, Face::Top] {
                for measure in [Measure::Strain, Measure::Stress] {
                    for axis in [PlyAxis::P11, PlyAxis::P22, PlyAxis::P12] {
                        out.push(Column::Ply {
                            eid,
                            ply,
                            face,
                            measure,
                            axis,
                        });
                    }
                }
            }
        }
        out
    }

    /// The interlaminar shear stress columns of a laminate element: at the top of each
    /// ply that has an [`crate::laminate::Interface`] (the bond with the ply above),
    /// τ1z then τ2z in that ply's axes, from the bottom.
    pub fn interlaminar(eid: i64, plies: &[crate::laminate::PlyLayer]) -> Vec<Column> {
        (1..=plies.len() as u16)
            .zip(plies)
            .filter(|(_, p)| p.interface.is_some())
            .flat_map(|(ply, _)| {
                [PlyAxis::P1z, PlyAxis::P2z].map(|axis| Column::Ply {
                    eid,
                    ply,
                    face: Face::Top,
                    measure: Measure::Stress,
                    axis,
                })
            })
            .collect()
    }
}

impl Column {
    /// Axial strain of rod `eid`.
    pub fn rod_strain(eid: i64) -> Self {
        Column::Element {
            eid,
            value: Recovered {
                measure: Measure::Strain,
                at: None,
            },
        }
    }

    /// Strain of shell `eid` at a fibre, in-plane component.
    pub fn shell_strain(eid: i64, fibre: Fibre, component: Plane) -> Self {
        Column::Element {
            eid,
            value: Recovered {
                measure: Measure::Strain,
                at: Some(At::Fibre(fibre, component)),
            },
        }
    }

    /// The column's name (the header without its unit): `disp_73_T1`, `strain_72`;
    /// a grid's component in a displacement frame other than the basic system names
    /// it: `disp_73_T1_cd5` is T1 along the x axis (or e_R) of system 5 at grid 73.
    pub fn name(&self) -> String {
        let tag = |d: &DofLabel, cd: &i64| {
            const C: [&str; 7] = ["", "T1", "T2", "T3", "R1", "R2", "R3"];
            match (d.comp, cd) {
                (0, _) => format!("{}", d.point),
                (c, 0) => format!("{}_{}", d.point, C[c as usize]),
                (c, cd) => format!("{}_{}_cd{cd}", d.point, C[c as usize]),
            }
        };
        match self {
            Column::Time => "time".into(),
            Column::ContactForce => "contact_force".into(),
            Column::Indentation => "indentation".into(),
            Column::ImpactorDisp => "impactor_disp".into(),
            Column::ImpactorVelo => "impactor_velo".into(),
            Column::Disp(d, cd) => format!("disp_{}", tag(d, cd)),
            Column::Velo(d, cd) => format!("velo_{}", tag(d, cd)),
            Column::NlLoad(d, cd) => format!("nlload_{}", tag(d, cd)),
            Column::Element { eid, value } => value.name(*eid),
            Column::Ply {
                eid,
                ply,
                face,
                measure,
                axis,
            } => format!(
                "ply_{}_{eid}_p{ply}_{}_{}",
                match measure {
                    Measure::Stress => "stress",
                    Measure::Strain => "strain",
                    Measure::ShearForce(_) => "shear_force",
                    Measure::Force(_) => "force",
                },
                match face {
                    Face::Bottom => "bot",
                    Face::Top => "top",
                },
                match axis {
                    PlyAxis::P11 => "11",
                    PlyAxis::P22 => "22",
                    PlyAxis::P12 => "12",
                    PlyAxis::P1z => "1z",
                    PlyAxis::P2z => "2z",
                }
            ),
        }
    }

    /// The column's unit in the deck's unit system.
    pub fn unit(&self, u: &UnitSystem) -> String {
        let (l, f, t) = (&u.length, &u.force, &u.time);
        let dof = |d: &DofLabel| {
            if (4..=6).contains(&d.comp) {
                "rad".to_string()
            } else {
                l.clone()
            }
        };
        match self {
            Column::Time => t.clone(),
            Column::ContactForce | Column::NlLoad(..) => f.clone(),
            Column::Indentation | Column::ImpactorDisp => l.clone(),
            Column::ImpactorVelo => format!("{l}/{t}"),
            Column::Disp(d, _) => dof(d),
            Column::Velo(d, _) => format!("{}/{t}", dof(d)),
            Column::Element {
                value: Recovered { measure, .. },
                ..
            }
            | Column::Ply { measure, .. } => match measure {
                Measure::Stress => format!("{f}/{l}^2"),
                Measure::Strain => "-".into(),
                Measure::ShearForce(_) => format!("{f}/{l}"),
                Measure::Force(r) => r.unit(f, l),
            },
        }
    }

    /// The header text: `name [unit]`.
    pub fn header(&self, u: &UnitSystem) -> String {
        format!("{} [{}]", self.name(), self.unit(u))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::Units;

    /// Goal: headers carry the deck's units, rotations in rad, strains dimensionless,
    /// and a grid's displacement frame when it is not the basic system.
    #[test]
    fn headers_carry_the_decks_units() {
        let u = UnitSystem::of(&Units {
            length: "mm".into(),
            force: "kN".into(),
            time: "ms".into(),
        });
        let d = |point, comp| DofLabel { point, comp };
        assert_eq!(Column::Time.header(&u), "time [ms]");
        assert_eq!(Column::Velo(d(73, 5), 0).header(&u), "velo_73_R2 [rad/ms]");
        assert_eq!(Column::Disp(d(1001, 0), 0).header(&u), "disp_1001 [mm]");
        assert_eq!(Column::NlLoad(d(999, 1), 0).header(&u), "nlload_999_T1 [kN]");
        assert_eq!(Column::Disp(d(73, 3), 5).header(&u), "disp_73_T3_cd5 [mm]");
        assert_eq!(Column::rod_strain(72).header(&u), "strain_72 [-]");
        let stress = Column::Element {
            eid: 3,
            value: Recovered {
                measure: Measure::Stress,
                at: Some(At::Fibre(Fibre::Z2, Plane::Xx)),
            },
        };
        assert_eq!(stress.header(&u), "stress_3_z2_xx [kN/mm^2]");
        let plies = Column::plies(2525, 2);
        assert_eq!(plies.len(), 24);
        assert_eq!(plies[0].header(&u), "ply_strain_2525_p1_bot_11 [-]");
        assert_eq!(plies[5].header(&u), "ply_stress_2525_p1_bot_12 [kN/mm^2]");
        assert_eq!(plies[23].header(&u), "ply_stress_2525_p2_top_12 [kN/mm^2]");
    }
}
