//! Geometry: coordinate systems, where each grid is in the basic system and which
//! frame its displacements are written in. The one place where frames are turned:
//! elements receive their own frame (see [`crate::elements::Placement`]) and never
//! read a coordinate system card.
//!
//! NASTRAN's definitions (MSC Nastran Quick Reference Guide, CORD1R … CORD2S, GRID):
//! - A system is an origin A and unit axes: z along A→B, y along z × (C − A), x = y × z.
//!   CORD2x gives A, B, C in the coordinates of system RID; CORD1x gives them as three
//!   grids' positions.
//! - A location (X1, X2, X3) in system CP is x, y, z (rectangular); R, θ, z
//!   (cylindrical, θ in degrees about z from x); R, θ, φ (spherical, θ in degrees
//!   from z, φ in degrees about z from x).
//! - A displacement frame CD at a grid is the system's local triad there: x, y, z;
//!   e_R, e_θ, e_z; e_R, e_θ, e_φ. It is undefined on a cylindrical system's axis and
//!   on a spherical system's axis, where such a CD is an error.
//!
//! Systems are resolved in dependency order, since a CORD2x may be written in a
//! system defined later in the deck and a CORD1x's grids may be located in other
//! systems: a system is built once its RID system (CORD2x) or the CP systems of its
//! three grids (CORD1x) are. What is left unbuilt is on a cycle of dependencies or
//! depends on a system that does not exist; both are errors naming the field.

use crate::deck::cards::{Bulk, CoordKind, Cord, CordDef, Grid};
use crate::deck::Diagnostic;
use nalgebra::{Matrix3, Vector3};
use rustc_hash::FxHashMap;
use std::collections::BTreeMap;

/// Relative tolerance below which A, B and C are taken as on one line (the cross
/// product of A→B and A→C against the product of their lengths), and a grid as on a
/// cylindrical or spherical system's axis (its distance from the axis against its
/// distance from the origin, or 1 length unit when at the origin).
pub const COLLINEAR: f64 = 1e-10;

/// True when `a > b`; false when either is NaN (coordinates that overflowed), so
/// that such a geometry is refused rather than built.
fn exceeds(a: f64, b: f64) -> bool {
    a > b
}

/// A coordinate system resolved to the basic one.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordSys {
    /// Rectangular, cylindrical or spherical.
    pub kind: CoordKind,
    /// Its origin in basic coordinates.
    pub origin: Vector3<f64>,
    /// Its unit axes x, y, z in basic components, as columns.
    pub axes: Matrix3<f64>,
}

impl CoordSys {
    /// The basic system.
    pub fn basic() -> Self {
        CoordSys {
            kind: CoordKind::Rectangular,
            origin: Vector3::zeros(),
            axes: Matrix3::identity(),
        }
    }

    /// A system from its origin A, a point B on its z axis and a point C in its
    /// xz-plane, all in basic coordinates; `None` when A = B or C is on the line AB.
    pub fn from_points(kind: CoordKind, a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>) -> Option<Self> {
        let (ab, ac) = (b - a, c - a);
        let y = ab.cross(&ac);
        if ab.norm() == 0.0 || !exceeds(y.norm(), COLLINEAR * ab.norm() * ac.norm()) {
            return None;
        }
        let z = ab.normalize();
        let y = y.normalize();
        let x = y.cross(&z);
        Some(CoordSys {
            kind,
            origin: a,
            axes: Matrix3::from_columns(&[x, y, z]),
        })
    }

    /// The local rectangular components (along its own x, y, z) of a location given
    /// in its coordinates.
    fn local(&self, x: [f64; 3]) -> Vector3<f64> {
        match self.kind {
            CoordKind::Rectangular => Vector3::from(x),
            CoordKind::Cylindrical => {
                let t = x[1].to_radians();
                Vector3::new(x[0] * t.cos(), x[0] * t.sin(), x[2])
            }
            CoordKind::Spherical => {
                let (t, p) = (x[1].to_radians(), x[2].to_radians());
                Vector3::new(x[0] * t.sin() * p.cos(), x[0] * t.sin() * p.sin(), x[0] * t.cos())
            }
        }
    }

    /// The basic position of a location given in this system's coordinates.
    pub fn to_basic(&self, x: [f64; 3]) -> Vector3<f64> {
        self.origin + self.axes * self.local(x)
    }

    /// The displacement frame at basic point `p`: its unit axes (x, y, z; e_R, e_θ,
    /// e_z; e_R, e_θ, e_φ) in basic components, as columns. `None` on a cylindrical or
    /// spherical system's axis, where e_R and e_θ (or e_φ) are undefined.
    pub fn frame_at(&self, p: &Vector3<f64>) -> Option<Matrix3<f64>> {
        let l = self.axes.transpose() * (p - self.origin);
        let scale = l.norm().max(1.0);
        let local = match self.kind {
            CoordKind::Rectangular => return Some(self.axes),
            CoordKind::Cylindrical => {
                let r = l.x.hypot(l.y);
                if r <= COLLINEAR * scale {
                    return None;
                }
                let (c, s) = (l.x / r, l.y / r);
                Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
            }
            CoordKind::Spherical => {
                let rho = l.x.hypot(l.y);
                if rho <= COLLINEAR * scale {
                    return None;
                }
                let r = l.norm();
                let (st, ct) = (rho / r, l.z / r);
                let (cp, sp) = (l.x / rho, l.y / rho);
                // Columns e_R, e_θ, e_φ.
                Matrix3::new(st * cp, ct * cp, -sp, st * sp, ct * sp, cp, ct, -st, 0.0)
            }
        };
        Some(self.axes * local)
    }
}

/// Every grid's basic position and displacement frame, and the systems they use.
#[derive(Debug, Clone, Default)]
pub struct Geometry {
    /// Basic position of each grid.
    pub positions: FxHashMap<i64, [f64; 3]>,
    /// The displacement frame of each grid whose CD is not the basic system: its
    /// axes in basic components, as columns.
    pub frames: FxHashMap<i64, Matrix3<f64>>,
    /// The resolved systems by id (0, the basic system, included).
    pub systems: BTreeMap<i64, CoordSys>,
}

impl Geometry {
    /// The displacement frame of grid `g` (the identity for the basic system).
    pub fn frame(&self, g: i64) -> Matrix3<f64> {
        self.frames.get(&g).copied().unwrap_or_else(Matrix3::identity)
    }
}

/// A grid's CP and CD with GRDSET's defaults for blank fields.
pub fn grid_systems(g: &Grid, b: &Bulk) -> (i64, i64) {
    (g.cp.unwrap_or(b.grdset.cp), g.cd.unwrap_or(b.grdset.cd))
}

/// Resolves the deck's coordinate systems and its grids' positions and displacement
/// frames, with every problem as an error diagnostic naming the card and field (a
/// grid whose position cannot be resolved is left out of `positions`).
pub fn resolve(b: &Bulk) -> (Geometry, Vec<Diagnostic>) {
    let mut errors = Vec::new();
    let mut defs: BTreeMap<i64, &Cord> = BTreeMap::new();
    for c in &b.cords {
        if c.cid == 0 {
            errors.push(c.at.error("coordinate system 0 is the basic system and cannot be redefined"));
        } else if let Some(first) = defs.insert(c.cid, c) {
            errors.push(c.at.error(format!(
                "coordinate system {} is defined twice (first at {})",
                c.cid, first.at.pos
            )));
        }
    }
    let grids: BTreeMap<i64, &Grid> = b.grids.iter().map(|g| (g.id, g)).collect();
    let mut geo = Geometry::default();
    geo.systems.insert(0, CoordSys::basic());
    // Grids located in the basic system need nothing; the others wait for their CP.
    let mut waiting: Vec<&Grid> = Vec::new();
    for g in &b.grids {
        let (cp, _) = grid_systems(g, b);
        if cp == 0 {
            geo.positions.insert(g.id, g.x);
        } else {
            waiting.push(g);
        }
    }
    let mut pending: Vec<&Cord> = defs.values().copied().collect();
    // Each pass builds what its dependencies allow; a pass that builds nothing ends it.
    loop {
        let mut progress = false;
        pending.retain(|c| {
            let points = match &c.def {
                CordDef::Points { rid, abc, .. } => geo.systems.get(rid).map(|s| abc.map(|p| s.to_basic(p))),
                CordDef::Grids { g, .. } => {
                    let p: Vec<_> = g.iter().filter_map(|id| geo.positions.get(id)).collect();
                    (p.len() == 3).then(|| std::array::from_fn(|i| Vector3::from(*p[i])))
                }
            };
            let Some([a, bp, cp]) = points else { return true };
            progress = true;
            match CoordSys::from_points(c.kind, a, bp, cp) {
                Some(s) => {
                    geo.systems.insert(c.cid, s);
                }
                None => errors.push(c.at.field_error(
                    &c.third_at,
                    format!(
                        "coordinate system {}: A, B and C (its origin, a point on its z axis and one in its \
                         xz-plane) lie on one line, so its axes are undefined",
                        c.cid
                    ),
                )),
            }
            false
        });
        waiting.retain(|g| {
            let (cp, _) = grid_systems(g, b);
            match geo.systems.get(&cp) {
                Some(s) => {
                    let p = s.to_basic(g.x);
                    geo.positions.insert(g.id, [p.x, p.y, p.z]);
                    progress = true;
                    false
                }
                None => true,
            }
        });
        if !progress {
            break;
        }
    }
    for c in &pending {
        errors.push(unresolved_system(c, &defs, &grids, b));
    }
    for g in &waiting {
        let (cp, _) = grid_systems(g, b);
        if !defs.contains_key(&cp) {
            errors.push(undefined(g, cp, "CP", b));
        }
        // A grid waiting on a defined system: that system's own error says why.
    }
    for g in &b.grids {
        let (_, cd) = grid_systems(g, b);
        if cd == 0 {
            continue;
        }
        let Some(s) = geo.systems.get(&cd) else {
            if !defs.contains_key(&cd) {
                errors.push(undefined(g, cd, "CD", b));
            }
            continue;
        };
        let Some(p) = geo.positions.get(&g.id) else { continue };
        match s.frame_at(&Vector3::from(*p)) {
            Some(f) => {
                geo.frames.insert(g.id, f);
            }
            None => errors.push(on_axis(g, cd, s.kind, b)),
        }
    }
    (geo, errors)
}

/// Grid `g` names system `cid` (in its CP or CD, or through GRDSET) that no card defines.
fn undefined(g: &Grid, cid: i64, field: &str, b: &Bulk) -> Diagnostic {
    let (blank, at) = if field == "CP" {
        (g.cp.is_none(), &g.cp_at)
    } else {
        (g.cd.is_none(), &g.cd_at)
    };
    let msg = format!(
        "GRID {}: {field} = {cid} names a coordinate system that no CORD card defines",
        g.id
    );
    match (&b.grdset.at, blank) {
        (Some(gs), true) => gs.error(format!("{msg} (the GRID leaves {field} blank: GRDSET's applies)")),
        _ => g.at.field_error(at, msg),
    }
}

/// A grid on the axis of the cylindrical or spherical system it takes as CD.
fn on_axis(g: &Grid, cd: i64, kind: CoordKind, b: &Bulk) -> Diagnostic {
    let what = match kind {
        CoordKind::Cylindrical => "cylindrical",
        _ => "spherical",
    };
    let msg = format!(
        "GRID {} lies on the axis of {what} system {cd}, its CD, where the radial and circumferential \
         directions are undefined: give it a rectangular CD",
        g.id
    );
    match (&b.grdset.at, g.cd.is_none()) {
        (Some(gs), true) => gs.error(format!("{msg} (the GRID leaves CD blank: GRDSET's applies)")),
        _ => g.at.field_error(&g.cd_at, msg),
    }
}

/// Why a system could not be built: what it depends on is undefined or depends on it.
fn unresolved_system(c: &Cord, defs: &BTreeMap<i64, &Cord>, grids: &BTreeMap<i64, &Grid>, b: &Bulk) -> Diagnostic {
    match &c.def {
        CordDef::Points { rid, rid_at, .. } => {
            if defs.contains_key(rid) {
                c.at.field_error(
                    rid_at,
                    format!(
                        "coordinate system {} is defined in system {rid}, which depends on it in turn: a cycle \
                         of coordinate systems ({})",
                        c.cid,
                        cycle(c.cid, defs, grids, b)
                    ),
                )
            } else {
                c.at.field_error(
                    rid_at,
                    format!(
                        "coordinate system {} is defined in system {rid}, which no CORD card defines",
                        c.cid
                    ),
                )
            }
        }
        CordDef::Grids { g, g_at } => {
            for (id, at) in g.iter().zip(g_at) {
                match grids.get(id) {
                    None => {
                        return c.at.field_error(
                            at,
                            format!(
                                "coordinate system {} is defined by grid {id}, which does not exist",
                                c.cid
                            ),
                        )
                    }
                    Some(gr) => {
                        let (cp, _) = grid_systems(gr, b);
                        if cp != 0 && !defs.contains_key(&cp) {
                            return c.at.field_error(
                                at,
                                format!(
                                    "coordinate system {} is defined by grid {id}, located in system {cp}, which \
                                     no CORD card defines",
                                    c.cid
                                ),
                            );
                        }
                    }
                }
            }
            c.at.field_error(
                &g_at[0],
                format!(
                    "coordinate system {} is defined by grids located in systems that depend on it in turn: a \
                     cycle of coordinate systems ({})",
                    c.cid,
                    cycle(c.cid, defs, grids, b)
                ),
            )
        }
    }
}

/// The systems a system depends on directly.
fn depends_on(c: &Cord, grids: &BTreeMap<i64, &Grid>, b: &Bulk) -> Vec<i64> {
    match &c.def {
        CordDef::Points { rid, .. } => vec![*rid],
        CordDef::Grids { g, .. } => g
            .iter()
            .filter_map(|id| grids.get(id))
            .map(|gr| grid_systems(gr, b).0)
            .collect(),
    }
}

/// The chain of dependencies from `start`, as "3 → 4 → 3", up to where it repeats.
fn cycle(start: i64, defs: &BTreeMap<i64, &Cord>, grids: &BTreeMap<i64, &Grid>, b: &Bulk) -> String {
    let mut chain = vec![start];
    let mut at = start;
    while let Some(next) = defs.get(&at).and_then(|c| {
        depends_on(c, grids, b)
            .into_iter()
            .find(|d| *d != 0 && defs.contains_key(d))
    }) {
        let repeat = chain.contains(&next);
        chain.push(next);
        if repeat || chain.len() > defs.len() + 1 {
            break;
        }
        at = next;
    }
    chain.iter().map(|c| c.to_string()).collect::<Vec<_>>().join(" → ")
}

/// A quadrilateral whose corners stand off its mean plane by more than this fraction
/// of half its mean diagonal is refused. NASTRAN's geometry check (MSC GEOMCHECK
/// Q4_WARP) takes 0.05 as its default limit on the warping of a QUAD4; the measure
/// here is ours, h/(¼(d₁₃ + d₂₄)), h the corners' distance from the mean plane.
pub const MAX_WARP: f64 = 0.05;

/// A quadrilateral whose corners stand off its mean plane by no more than this
/// fraction of half its mean diagonal is flat: the distance is round-off of its
/// coordinates (about 1e-16 of their size).
pub const FLAT: f64 = 1e-12;

/// A flat shell's own frame: the plane its kernel works in.
///
/// - Normal n: (G3 − G1) × (G4 − G2) for a quadrilateral (the mean plane of its
///   corners, through their centroid: the four corners stand at ±h from it), and
///   (G2 − G1) × (G3 − G1) for a triangle; the corners are then counter-clockwise
///   about n.
/// - Local x: the G1→G2 side projected onto the plane (NASTRAN's reference for
///   THETA); y = n × x.
/// - A warped quadrilateral is projected onto its mean plane, each corner tied to its
///   grid by a rigid offset (MacNeal's treatment of the warped QUAD4: the flat
///   element's corner moves with the grid's translation and rotation), and refused
///   beyond [`MAX_WARP`].
#[derive(Debug, Clone, PartialEq)]
pub struct ShellFrame {
    /// Local x, y and the normal in basic components, as columns.
    pub axes: Matrix3<f64>,
    /// The corners in the local frame (x, y, 0).
    pub local: Vec<[f64; 3]>,
    /// From each grid to its corner on the mean plane, in basic components (zero
    /// for a triangle and a flat quadrilateral).
    pub offsets: Vec<[f64; 3]>,
}

/// Why a shell's frame cannot be built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FrameError {
    /// Its corners are on one line or coincide.
    Degenerate,
    /// A quadrilateral warped beyond [`MAX_WARP`]: the warp found.
    Warped(f64),
}

/// The frame of a flat shell on `points` (basic coordinates, 3 or 4 corners).
pub fn shell_frame(points: &[[f64; 3]]) -> Result<ShellFrame, FrameError> {
    let p: Vec<Vector3<f64>> = points.iter().map(|&x| Vector3::from(x)).collect();
    let n = match p.len() {
        4 => (p[2] - p[0]).cross(&(p[3] - p[1])),
        _ => (p[1] - p[0]).cross(&(p[2] - p[0])),
    };
    let size = (1..p.len()).map(|i| (p[i] - p[0]).norm()).fold(0.0, f64::max);
    if !exceeds(n.norm(), COLLINEAR * size * size) {
        return Err(FrameError::Degenerate);
    }
    let n = n.normalize();
    let centroid = p.iter().sum::<Vector3<f64>>() / p.len() as f64;
    let side = p[1] - p[0];
    let x = side - n * side.dot(&n);
    if !exceeds(x.norm(), COLLINEAR * size) {
        return Err(FrameError::Degenerate);
    }
    let x = x.normalize();
    let y = n.cross(&x);
    let mut heights: Vec<f64> = p.iter().map(|q| (q - centroid).dot(&n)).collect();
    if p.len() == 4 {
        let half_diagonal = 0.25 * ((p[2] - p[0]).norm() + (p[3] - p[1]).norm());
        let warp = heights.iter().fold(0.0f64, |m, h| m.max(h.abs())) / half_diagonal;
        if warp > MAX_WARP {
            return Err(FrameError::Warped(warp));
        }
        // Heights at the round-off of the coordinates are no warp: a flat element
        // keeps its corners where its grids are (no offsets).
        if warp <= FLAT {
            heights.iter_mut().for_each(|h| *h = 0.0);
        }
    } else {
        heights.iter_mut().for_each(|h| *h = 0.0);
    }
    Ok(ShellFrame {
        axes: Matrix3::from_columns(&[x, y, n]),
        local: p
            .iter()
            .map(|q| {
                let r = q - centroid;
                [r.dot(&x), r.dot(&y), 0.0]
            })
            .collect(),
        offsets: heights
            .iter()
            .map(|&h| if h == 0.0 { [0.0; 3] } else { (-(n * h)).into() })
            .collect(),
    })
}

/// The angle in degrees, counter-clockwise about the normal of `frame`, from its
/// local x axis to the projection of `dir` onto its plane; `None` when `dir` is
/// (nearly) along the normal, where the projection has no direction.
pub fn angle_in_plane(frame: &Matrix3<f64>, dir: &Vector3<f64>) -> Option<f64> {
    let (x, y) = (dir.dot(&frame.column(0)), dir.dot(&frame.column(1)));
    (x.hypot(y) > 1e-6 * dir.norm()).then(|| y.atan2(x).to_degrees())
}

/// Where a point lies on a flat shell: the shape functions of its corners there, its
/// distance from the shell's plane, and how far outside the element it is.
#[derive(Debug, Clone, PartialEq)]
pub struct OnShell {
    /// The corners' shape functions at the point's projection (bilinear for a
    /// quadrilateral, linear for a triangle): they sum to 1.
    pub weights: Vec<f64>,
    /// The point's distance from the element's (mean) plane.
    pub height: f64,
    /// How far the projection is outside the element, in its parametric
    /// coordinates: 0 inside, else the largest amount a shape function falls below
    /// 0 (a quadrilateral's ξ or η beyond ±1 by that much, half of it).
    pub outside: f64,
    /// The element's normal (basic), as [`shell_frame`] gives it.
    pub normal: [f64; 3],
    /// The element's size: its longest side.
    pub size: f64,
}

/// Where point `p` (basic) lies on the flat shell with corners `points`: projected
/// onto the element's plane, its parametric coordinates found (a triangle's by the
/// linear map; a quadrilateral's by Newton's method on the bilinear map, converged to
/// 1e-14), and the shape functions there. `None` for a degenerate element or a
/// projection Newton's method does not resolve (far outside a distorted quadrilateral).
pub fn on_shell(points: &[[f64; 3]], p: [f64; 3]) -> Option<OnShell> {
    let f = shell_frame(points).ok()?;
    let centroid = points.iter().map(|&q| Vector3::from(q)).sum::<Vector3<f64>>() / points.len() as f64;
    let r = Vector3::from(p) - centroid;
    let (x, y, height) = (
        r.dot(&f.axes.column(0)),
        r.dot(&f.axes.column(1)),
        r.dot(&f.axes.column(2)),
    );
    let xy: Vec<[f64; 2]> = f.local.iter().map(|q| [q[0], q[1]]).collect();
    let size = (0..points.len())
        .map(|i| (Vector3::from(points[(i + 1) % points.len()]) - Vector3::from(points[i])).norm())
        .fold(0.0, f64::max);
    let weights = if xy.len() == 3 {
        let (a, b, c) = (xy[0], xy[1], xy[2]);
        let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        let l1 = ((b[0] - x) * (c[1] - y) - (c[0] - x) * (b[1] - y)) / det;
        let l2 = ((c[0] - x) * (a[1] - y) - (a[0] - x) * (c[1] - y)) / det;
        vec![l1, l2, 1.0 - l1 - l2]
    } else {
        let corner = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let (mut xi, mut eta) = (0.0f64, 0.0f64);
        let mut converged = false;
        for _ in 0..50 {
            let (mut fx, mut fy) = (-x, -y);
            let mut j = [[0.0; 2]; 2];
            for (k, &(a, b)) in corner.iter().enumerate() {
                let n = 0.25 * (1.0 + a * xi) * (1.0 + b * eta);
                fx += n * xy[k][0];
                fy += n * xy[k][1];
                let (dxi, deta) = (0.25 * a * (1.0 + b * eta), 0.25 * b * (1.0 + a * xi));
                j[0][0] += dxi * xy[k][0];
                j[0][1] += deta * xy[k][0];
                j[1][0] += dxi * xy[k][1];
                j[1][1] += deta * xy[k][1];
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if det.abs() <= f64::MIN_POSITIVE {
                return None;
            }
            let dxi = (j[1][1] * fx - j[0][1] * fy) / det;
            let deta = (-j[1][0] * fx + j[0][0] * fy) / det;
            xi -= dxi;
            eta -= deta;
            if dxi.abs().max(deta.abs()) < 1e-14 {
                converged = true;
                break;
            }
        }
        if !converged || !xi.is_finite() || !eta.is_finite() {
            return None;
        }
        corner
            .iter()
            .map(|&(a, b)| 0.25 * (1.0 + a * xi) * (1.0 + b * eta))
            .collect()
    };
    let outside = weights.iter().fold(0.0f64, |m, &w| m.max(-w));
    let n = f.axes.column(2);
    Some(OnShell {
        weights,
        height: height.abs(),
        outside,
        normal: [n.x, n.y, n.z],
        size,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
        Vector3::new(x, y, z)
    }

    /// Goal: CORD2R's construction. Reference: A = (1, 2, 3), B = A + 2 ŷ, C = A + x̂
    /// make z = ŷ, y = z × (C − A)/|…| = −ẑ, x = y × z = x̂; the local point (1, 2, 3)
    /// is then A + 1 x̂ + 2 (−ẑ) + 3 ŷ. Tolerance: round-off.
    #[test]
    fn cord2r_axes_follow_a_b_c() {
        let s = CoordSys::from_points(
            CoordKind::Rectangular,
            v(1.0, 2.0, 3.0),
            v(1.0, 4.0, 3.0),
            v(2.0, 2.0, 3.0),
        )
        .unwrap();
        assert_relative_eq!(s.axes.column(0).into_owned(), v(1.0, 0.0, 0.0), epsilon = 1e-15);
        assert_relative_eq!(s.axes.column(1).into_owned(), v(0.0, 0.0, -1.0), epsilon = 1e-15);
        assert_relative_eq!(s.axes.column(2).into_owned(), v(0.0, 1.0, 0.0), epsilon = 1e-15);
        assert_relative_eq!(s.to_basic([1.0, 2.0, 3.0]), v(2.0, 5.0, 1.0), epsilon = 1e-15);
        assert!(CoordSys::from_points(
            CoordKind::Rectangular,
            v(0.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(0.0, 0.0, 3.0)
        )
        .is_none());
    }

    /// Goal: a shell's frame in space. Reference: a unit square turned by a rotation
    /// R and moved has the turned z as its normal, the turned G1→G2 as its x and its
    /// corners at (±½, ±½) about the centroid; a warped quadrilateral's corners are
    /// projected by ∓h n onto the mean plane. Tolerance: round-off.
    #[test]
    fn a_turned_square_has_its_own_axes_and_a_warped_one_its_mean_plane() {
        let r = nalgebra::Rotation3::from_euler_angles(0.4, -1.2, 2.5).into_inner();
        let shift = v(3.0, -1.0, 7.0);
        let sq = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let turned: Vec<[f64; 3]> = sq.iter().map(|&q| (r * Vector3::from(q) + shift).into()).collect();
        let f = shell_frame(&turned).unwrap();
        assert_relative_eq!(f.axes, r, epsilon = 1e-14);
        for (l, q) in f.local.iter().zip(&sq) {
            assert_relative_eq!(v(l[0], l[1], l[2]), v(q[0] - 0.5, q[1] - 0.5, 0.0), epsilon = 1e-14);
        }
        assert!(f.offsets.iter().all(|d| d.iter().all(|c| c.abs() < 1e-14)));
        let h = 0.01;
        let warped = [[0.0, 0.0, h], [1.0, 0.0, -h], [1.0, 1.0, h], [0.0, 1.0, -h]];
        let f = shell_frame(&warped).unwrap();
        assert_relative_eq!(f.axes.column(2).into_owned(), v(0.0, 0.0, 1.0), epsilon = 1e-15);
        assert_relative_eq!(v(f.offsets[0][0], f.offsets[0][1], f.offsets[0][2]), v(0.0, 0.0, -h));
        assert_relative_eq!(v(f.offsets[1][0], f.offsets[1][1], f.offsets[1][2]), v(0.0, 0.0, h));
        let too = [[0.0, 0.0, 0.1], [1.0, 0.0, -0.1], [1.0, 1.0, 0.1], [0.0, 1.0, -0.1]];
        assert!(matches!(shell_frame(&too), Err(FrameError::Warped(w)) if w > MAX_WARP));
    }

    /// Goal: a point's shape functions on a shell. Reference: the centre of a turned
    /// square has ¼ at each corner; the point (0.25, 0.75) of the unit square has the
    /// bilinear weights (0.1875, 0.0625, 0.1875, 0.5625); a triangle's centroid ⅓ each;
    /// a point off the plane by h reports h, one beyond an edge how far. Tolerance:
    /// round-off.
    #[test]
    fn a_point_on_a_shell_has_its_shape_functions() {
        let r = nalgebra::Rotation3::from_euler_angles(0.4, -1.2, 2.5).into_inner();
        let sq = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let turned: Vec<[f64; 3]> = sq.iter().map(|&q| (r * Vector3::from(q)).into()).collect();
        let at = |x: f64, y: f64, z: f64| -> [f64; 3] { (r * v(x, y, z)).into() };
        let o = on_shell(&turned, at(0.5, 0.5, 0.3)).unwrap();
        assert!(o.weights.iter().all(|w| (w - 0.25).abs() < 1e-14), "{:?}", o.weights);
        assert!((o.height - 0.3).abs() < 1e-14 && o.outside == 0.0);
        let o = on_shell(&turned, at(0.25, 0.75, 0.0)).unwrap();
        for (w, e) in o.weights.iter().zip([0.1875, 0.0625, 0.1875, 0.5625]) {
            assert!((w - e).abs() < 1e-14, "{:?}", o.weights);
        }
        let o = on_shell(&turned, at(1.5, 0.5, 0.0)).unwrap();
        assert!((o.outside - 0.25).abs() < 1e-14, "{}", o.outside);
        let tri = [[0.0, 0.0, 1.0], [3.0, 0.0, 1.0], [0.0, 3.0, 1.0]];
        let o = on_shell(&tri, [1.0, 1.0, 1.0]).unwrap();
        assert!(
            o.weights.iter().all(|w| (w - 1.0 / 3.0).abs() < 1e-14),
            "{:?}",
            o.weights
        );
    }

    /// Goal: cylindrical and spherical locations and frames. Reference: the basic
    /// system read as cylindrical, (R, θ, z) = (2, 30°, 5) is (2 cos 30°, 2 sin 30°, 5),
    /// with e_R = (cos 30°, sin 30°, 0), e_θ = (−sin 30°, cos 30°, 0); read as
    /// spherical, (R, θ, φ) = (2, 60°, 30°) is 2 (sin 60° cos 30°, sin 60° sin 30°,
    /// cos 60°), e_θ = ∂p/∂θ / R, e_φ = ẑ × e_R normalised; every frame orthonormal
    /// and right-handed. Tolerance: round-off.
    #[test]
    fn cylindrical_and_spherical_frames_are_the_local_triads() {
        let mut s = CoordSys::basic();
        s.kind = CoordKind::Cylindrical;
        let (c, sn) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let p = s.to_basic([2.0, 30.0, 5.0]);
        assert_relative_eq!(p, v(2.0 * c, 2.0 * sn, 5.0), epsilon = 1e-14);
        let f = s.frame_at(&p).unwrap();
        assert_relative_eq!(f.column(0).into_owned(), v(c, sn, 0.0), epsilon = 1e-15);
        assert_relative_eq!(f.column(1).into_owned(), v(-sn, c, 0.0), epsilon = 1e-15);
        assert!(s.frame_at(&v(0.0, 0.0, 3.0)).is_none());
        s.kind = CoordKind::Spherical;
        let (t, ph) = (60f64.to_radians(), 30f64.to_radians());
        let p = s.to_basic([2.0, 60.0, 30.0]);
        assert_relative_eq!(
            p,
            2.0 * v(t.sin() * ph.cos(), t.sin() * ph.sin(), t.cos()),
            epsilon = 1e-14
        );
        let f = s.frame_at(&p).unwrap();
        assert_relative_eq!(f.column(0).into_owned(), p / 2.0, epsilon = 1e-15);
        let dtheta = v(t.cos() * ph.cos(), t.cos() * ph.sin(), -t.sin());
        assert_relative_eq!(f.column(1).into_owned(), dtheta, epsilon = 1e-15);
        assert_relative_eq!(f.column(2).into_owned(), v(-ph.sin(), ph.cos(), 0.0), epsilon = 1e-15);
        assert_relative_eq!(f.transpose() * f, Matrix3::identity(), epsilon = 1e-15);
        assert_relative_eq!(f.determinant(), 1.0, epsilon = 1e-15);
        assert!(s.frame_at(&v(0.0, 0.0, -3.0)).is_none());
    }
}
