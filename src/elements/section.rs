//! Beam cross-sections given by their dimensions (PBARL, PBEAML): area, moments of
//! inertia, torsional constant and stress recovery points.
//!
//! Axes are NASTRAN's for these sections: y up the figure (the plane-1 direction), z
//! across it; I1 = ∫y² dA, I2 = ∫z² dA, I12 = ∫yz dA about the centroid. The
//! dimensions are read as NASTRAN's PBARL figures draw them (and as pyNastran reads
//! them):
//!
//! | TYPE | DIM1 … |
//! |---|---|
//! | BAR | width (z), height (y) |
//! | BOX | width, height, top and bottom wall thickness, side wall thickness |
//! | ROD | radius |
//! | TUBE | outer radius, inner radius |
//! | I | height, bottom flange width, top flange width, web, bottom flange and top flange thickness |
//! | T | flange width, height, flange thickness (the flange on top), web thickness |
//! | L | width, height, horizontal leg thickness (at the bottom), vertical leg thickness (at the left) |
//! | CHAN | flange width (with the web), height, web thickness, flange thickness |
//! | HAT | height, thickness, crown width (top), brim width (each, beyond the web) |
//! | Z | flange width (each, beyond the web), web thickness, flange thickness, height |
//!
//! A, I1, I2 and I12 are exact for these shapes: each is a union of rectangles
//! (or a disc and an annulus) and its moments are summed about the centroid. J is the
//! Saint-Venant torsion constant: exact for ROD and TUBE (π/2 (r₀⁴ − rᵢ⁴)); for BAR
//! the exact series of a solid rectangle (Timoshenko & Goodier, §109),
//! (1/3) a³ b (1 − (192/π⁵)(a/b) Σ_{n odd} tanh(nπb/2a)/n⁵), a ≤ b; for BOX Bredt's
//! thin-walled closed cell on the wall mid-lines, 4 Aₘ² / ∮ ds/t; for the open sections
//! (I, T, L, CHAN, HAT, Z) the thin-walled sum Σ b t³/3 over the rectangles, each with
//! its longer side b.
//!
//! The recovery points C, D, E, F are the corners of the section's bounding box about
//! the centroid: C (+y, +z), D (−y, +z), E (−y, −z), F (+y, −z); for ROD and TUBE
//! the points of the outer circle on the axes, C (+r, 0), D (0, +r), E (−r, 0), F (0, −r).

use std::f64::consts::PI;

/// A cross-section type of PBARL and PBEAML.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// Solid rectangle.
    Bar,
    /// Rectangular tube.
    Box,
    /// Solid circle.
    Rod,
    /// Circular tube.
    Tube,
    /// I-section with unequal flanges.
    I,
    /// T-section.
    T,
    /// Angle.
    L,
    /// Channel.
    Chan,
    /// Hat (open top-hat stringer).
    Hat,
    /// Z-section.
    Z,
}

impl Shape {
    /// Every shape, with its TYPE name and number of dimensions.
    pub const ALL: [(Shape, &'static str, usize); 10] = [
        (Shape::Bar, "BAR", 2),
        (Shape::Box, "BOX", 4),
        (Shape::Rod, "ROD", 1),
        (Shape::Tube, "TUBE", 2),
        (Shape::I, "I", 6),
        (Shape::T, "T", 4),
        (Shape::L, "L", 4),
        (Shape::Chan, "CHAN", 4),
        (Shape::Hat, "HAT", 4),
        (Shape::Z, "Z", 4),
    ];

    /// The shape of a TYPE name.
    pub fn named(name: &str) -> Option<Shape> {
        Shape::ALL
            .iter()
            .find(|(_, n, _)| n.eq_ignore_ascii_case(name))
            .map(|s| s.0)
    }

    /// Its TYPE name.
    pub fn name(self) -> &'static str {
        Shape::ALL.iter().find(|s| s.0 == self).map_or("", |s| s.1)
    }

    /// How many dimensions it takes.
    pub fn dims(self) -> usize {
        Shape::ALL.iter().find(|s| s.0 == self).map_or(0, |s| s.2)
    }
}

/// A section's constants, about its centroid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constants {
    /// Area A.
    pub area: f64,
    /// I1 = ∫y² dA.
    pub i1: f64,
    /// I2 = ∫z² dA.
    pub i2: f64,
    /// I12 = ∫yz dA.
    pub i12: f64,
    /// Torsion constant J.
    pub j: f64,
    /// Recovery points C, D, E, F as (y, z) from the centroid.
    pub points: [[f64; 2]; 4],
}

/// An axis-aligned rectangle: y from `y.0` to `y.1`, z from `z.0` to `z.1`.
#[derive(Debug, Clone, Copy)]
struct Rect {
    y: (f64, f64),
    z: (f64, f64),
}

impl Rect {
    fn new(y0: f64, y1: f64, z0: f64, z1: f64) -> Self {
        Rect {
            y: (y0, y1),
            z: (z0, z1),
        }
    }
    fn h(&self) -> f64 {
        self.y.1 - self.y.0
    }
    fn w(&self) -> f64 {
        self.z.1 - self.z.0
    }
    fn area(&self) -> f64 {
        self.h() * self.w()
    }
    fn centre(&self) -> (f64, f64) {
        (0.5 * (self.y.0 + self.y.1), 0.5 * (self.z.0 + self.z.1))
    }
    /// Σ b t³/3 of a thin wall, b its longer side.
    fn thin_torsion(&self) -> f64 {
        let (a, b) = (self.h().min(self.w()), self.h().max(self.w()));
        b * a.powi(3) / 3.0
    }
}

/// Why a section's dimensions make no section: the rest of the sentence after
/// `PBARL <pid> <TYPE>`.
#[derive(Debug, Clone, PartialEq)]
pub struct BadSection(pub String);

/// The rectangles of a thin-walled or solid rectangular shape, in its figure's axes.
fn rectangles(shape: Shape, d: &[f64]) -> Result<Vec<Rect>, BadSection> {
    let need = |ok: bool, what: &str| if ok { Ok(()) } else { Err(BadSection(what.to_string())) };
    Ok(match shape {
        Shape::Bar => vec![Rect::new(-0.5 * d[1], 0.5 * d[1], -0.5 * d[0], 0.5 * d[0])],
        Shape::Box => {
            let (b, h, t1, t2) = (d[0], d[1], d[2], d[3]);
            need(h > 2.0 * t1, "needs DIM2 > 2·DIM3 (the walls meet inside)")?;
            need(b > 2.0 * t2, "needs DIM1 > 2·DIM4 (the walls meet inside)")?;
            let (y, z) = (0.5 * h, 0.5 * b);
            vec![
                Rect::new(y - t1, y, -z, z),
                Rect::new(-y, -y + t1, -z, z),
                Rect::new(-y + t1, y - t1, -z, -z + t2),
                Rect::new(-y + t1, y - t1, z - t2, z),
            ]
        }
        Shape::I => {
            let (h, a, b, tw, ta, tb) = (d[0], d[1], d[2], d[3], d[4], d[5]);
            need(h > ta + tb, "needs DIM1 > DIM5 + DIM6 (a web between the flanges)")?;
            need(
                a >= tw && b >= tw,
                "needs flanges at least as wide as the web (DIM2, DIM3 ≥ DIM4)",
            )?;
            vec![
                Rect::new(0.0, ta, -0.5 * a, 0.5 * a),
                Rect::new(ta, h - tb, -0.5 * tw, 0.5 * tw),
                Rect::new(h - tb, h, -0.5 * b, 0.5 * b),
            ]
        }
        Shape::T => {
            let (b, h, tf, tw) = (d[0], d[1], d[2], d[3]);
            need(h > tf, "needs DIM2 > DIM3 (a web below the flange)")?;
            need(b >= tw, "needs DIM1 ≥ DIM4 (the flange at least as wide as the web)")?;
            vec![
                Rect::new(h - tf, h, -0.5 * b, 0.5 * b),
                Rect::new(0.0, h - tf, -0.5 * tw, 0.5 * tw),
            ]
        }
        Shape::L => {
            let (b, h, t1, t2) = (d[0], d[1], d[2], d[3]);
            need(h > t1 && b >= t2, "needs DIM2 > DIM3 and DIM1 ≥ DIM4")?;
            vec![Rect::new(0.0, t1, 0.0, b), Rect::new(t1, h, 0.0, t2)]
        }
        Shape::Chan => {
            let (b, h, tw, tf) = (d[0], d[1], d[2], d[3]);
            need(h > 2.0 * tf && b > tw, "needs DIM2 > 2·DIM4 and DIM1 > DIM3")?;
            vec![
                Rect::new(0.0, h, 0.0, tw),
                Rect::new(0.0, tf, tw, b),
                Rect::new(h - tf, h, tw, b),
            ]
        }
        Shape::Hat => {
            let (h, t, crown, brim) = (d[0], d[1], d[2], d[3]);
            need(h > 2.0 * t && crown > 2.0 * t, "needs DIM1 > 2·DIM2 and DIM3 > 2·DIM2")?;
            let c = 0.5 * crown;
            vec![
                Rect::new(h - t, h, -c, c),
                Rect::new(t, h - t, -c, -c + t),
                Rect::new(t, h - t, c - t, c),
                Rect::new(0.0, t, -c - brim, -c + t),
                Rect::new(0.0, t, c - t, c + brim),
            ]
        }
        Shape::Z => {
            let (b, tw, tf, h) = (d[0], d[1], d[2], d[3]);
            need(h > 2.0 * tf, "needs DIM4 > 2·DIM3 (a web between the flanges)")?;
            let (y, z) = (0.5 * h, 0.5 * tw);
            vec![
                Rect::new(-y, y, -z, z),
                Rect::new(y - tf, y, z, z + b),
                Rect::new(-y, -y + tf, -z - b, -z),
            ]
        }
        Shape::Rod | Shape::Tube => unreachable!("circular shapes have no rectangles"),
    })
}

/// The exact torsion constant of a solid a × b rectangle (Saint-Venant's series,
/// summed until its terms fall below round-off).
fn rectangle_torsion(h: f64, w: f64) -> f64 {
    let (a, b) = (h.min(w), h.max(w));
    let mut sum = 0.0;
    let mut n = 1.0;
    loop {
        let term = (n * PI * b / (2.0 * a)).tanh() / n.powi(5);
        sum += term;
        if term < 1e-17 * sum {
            break;
        }
        n += 2.0;
    }
    a.powi(3) * b / 3.0 * (1.0 - 192.0 / PI.powi(5) * (a / b) * sum)
}

/// The constants of a section of `shape` with dimensions `dims` (as many as
/// [`Shape::dims`], each > 0).
pub fn constants(shape: Shape, dims: &[f64]) -> Result<Constants, BadSection> {
    if dims.len() != shape.dims() {
        return Err(BadSection(format!(
            "takes {} dimensions, {} given",
            shape.dims(),
            dims.len()
        )));
    }
    if let Some(k) = dims.iter().position(|&x| !(x > 0.0 && x.is_finite())) {
        return Err(BadSection(format!("DIM{} must be a positive number", k + 1)));
    }
    let circle = |ro: f64, ri: f64| {
        let i = PI / 4.0 * (ro.powi(4) - ri.powi(4));
        Constants {
            area: PI * (ro * ro - ri * ri),
            i1: i,
            i2: i,
            i12: 0.0,
            j: 2.0 * i,
            points: [[ro, 0.0], [0.0, ro], [-ro, 0.0], [0.0, -ro]],
        }
    };
    match shape {
        Shape::Rod => return Ok(circle(dims[0], 0.0)),
        Shape::Tube => {
            if dims[1] >= dims[0] {
                return Err(BadSection("needs DIM1 > DIM2 (outer radius above inner)".into()));
            }
            return Ok(circle(dims[0], dims[1]));
        }
        _ => {}
    }
    let rects = rectangles(shape, dims)?;
    let area: f64 = rects.iter().map(Rect::area).sum();
    let (yc, zc) = rects.iter().fold((0.0, 0.0), |(y, z), r| {
        let (cy, cz) = r.centre();
        (y + r.area() * cy, z + r.area() * cz)
    });
    let (yc, zc) = (yc / area, zc / area);
    let (mut i1, mut i2, mut i12) = (0.0, 0.0, 0.0);
    for r in &rects {
        let (cy, cz) = r.centre();
        let (dy, dz) = (cy - yc, cz - zc);
        i1 += r.w() * r.h().powi(3) / 12.0 + r.area() * dy * dy;
        i2 += r.h() * r.w().powi(3) / 12.0 + r.area() * dz * dz;
        i12 += r.area() * dy * dz;
    }
    let j = match shape {
        Shape::Bar => rectangle_torsion(dims[1], dims[0]),
        Shape::Box => {
            let (b, h, t1, t2) = (dims[0], dims[1], dims[2], dims[3]);
            let (bm, hm) = (b - t2, h - t1);
            4.0 * (bm * hm).powi(2) / (2.0 * bm / t1 + 2.0 * hm / t2)
        }
        _ => rects.iter().map(Rect::thin_torsion).sum(),
    };
    let lo = |f: fn(&Rect) -> (f64, f64)| rects.iter().map(|r| f(r).0).fold(f64::INFINITY, f64::min);
    let hi = |f: fn(&Rect) -> (f64, f64)| rects.iter().map(|r| f(r).1).fold(f64::NEG_INFINITY, f64::max);
    let (y0, y1) = (lo(|r| r.y) - yc, hi(|r| r.y) - yc);
    let (z0, z1) = (lo(|r| r.z) - zc, hi(|r| r.z) - zc);
    Ok(Constants {
        area,
        i1,
        i2,
        i12,
        j,
        points: [[y1, z1], [y0, z1], [y0, z0], [y1, z0]],
    })
}

/// The section's outline as closed polygons (each counter-clockwise in (z, y), the
/// figure's axes, holes clockwise), for an independent computation of its constants
/// by Green's theorem: a BOX is its outer and inner rectangles, a circle a polygon of
/// `n` sides (`n` is read for ROD and TUBE only).
pub fn outline(shape: Shape, d: &[f64], n: usize) -> Vec<Vec<[f64; 2]>> {
    let rect = |y0: f64, y1: f64, z0: f64, z1: f64| vec![[z0, y0], [z1, y0], [z1, y1], [z0, y1]];
    let circle = |r: f64, sign: f64| {
        (0..n)
            .map(|k| {
                let a = sign * 2.0 * PI * k as f64 / n as f64;
                [r * a.cos(), r * a.sin()]
            })
            .collect::<Vec<_>>()
    };
    match shape {
        Shape::Bar => vec![rect(-0.5 * d[1], 0.5 * d[1], -0.5 * d[0], 0.5 * d[0])],
        Shape::Box => {
            let (b, h, t1, t2) = (d[0], d[1], d[2], d[3]);
            let mut inner = rect(-0.5 * h + t1, 0.5 * h - t1, -0.5 * b + t2, 0.5 * b - t2);
            inner.reverse();
            vec![rect(-0.5 * h, 0.5 * h, -0.5 * b, 0.5 * b), inner]
        }
        Shape::Rod => vec![circle(d[0], 1.0)],
        Shape::Tube => vec![circle(d[0], 1.0), circle(d[1], -1.0)],
        Shape::I => {
            let (h, a, b, tw, ta, tb) = (d[0], d[1], d[2], d[3], d[4], d[5]);
            vec![vec![
                [-0.5 * a, 0.0],
                [0.5 * a, 0.0],
                [0.5 * a, ta],
                [0.5 * tw, ta],
                [0.5 * tw, h - tb],
                [0.5 * b, h - tb],
                [0.5 * b, h],
                [-0.5 * b, h],
                [-0.5 * b, h - tb],
                [-0.5 * tw, h - tb],
                [-0.5 * tw, ta],
                [-0.5 * a, ta],
            ]]
        }
        Shape::T => {
            let (b, h, tf, tw) = (d[0], d[1], d[2], d[3]);
            vec![vec![
                [-0.5 * tw, 0.0],
                [0.5 * tw, 0.0],
                [0.5 * tw, h - tf],
                [0.5 * b, h - tf],
                [0.5 * b, h],
                [-0.5 * b, h],
                [-0.5 * b, h - tf],
                [-0.5 * tw, h - tf],
            ]]
        }
        Shape::L => {
            let (b, h, t1, t2) = (d[0], d[1], d[2], d[3]);
            vec![vec![[0.0, 0.0], [b, 0.0], [b, t1], [t2, t1], [t2, h], [0.0, h]]]
        }
        Shape::Chan => {
            let (b, h, tw, tf) = (d[0], d[1], d[2], d[3]);
            vec![vec![
                [0.0, 0.0],
                [b, 0.0],
                [b, tf],
                [tw, tf],
                [tw, h - tf],
                [b, h - tf],
                [b, h],
                [0.0, h],
            ]]
        }
        Shape::Hat => {
            let (h, t, crown, brim) = (d[0], d[1], d[2], d[3]);
            let c = 0.5 * crown;
            vec![vec![
                [-c - brim, 0.0],
                [-c + t, 0.0],
                [-c + t, h - t],
                [c - t, h - t],
                [c - t, 0.0],
                [c + brim, 0.0],
                [c + brim, t],
                [c, t],
                [c, h],
                [-c, h],
                [-c, t],
                [-c - brim, t],
            ]]
        }
        Shape::Z => {
            let (b, tw, tf, h) = (d[0], d[1], d[2], d[3]);
            let (y, z) = (0.5 * h, 0.5 * tw);
            vec![vec![
                [-z - b, -y],
                [z, -y],
                [z, y - tf],
                [z + b, y - tf],
                [z + b, y],
                [-z, y],
                [-z, -y + tf],
                [-z - b, -y + tf],
            ]]
        }
    }
}

/// A, I1, I2, I12 of closed polygons (z, y vertices) by Green's theorem: the moments
/// of the region as boundary integrals, then moved to the centroid.
pub fn polygon_moments(polygons: &[Vec<[f64; 2]>]) -> [f64; 4] {
    let (mut a, mut sz, mut sy, mut iyy, mut izz, mut iyz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in polygons {
        for k in 0..p.len() {
            let ([z0, y0], [z1, y1]) = (p[k], p[(k + 1) % p.len()]);
            let c = z0 * y1 - z1 * y0;
            a += 0.5 * c;
            sz += (z0 + z1) * c / 6.0;
            sy += (y0 + y1) * c / 6.0;
            iyy += (y0 * y0 + y0 * y1 + y1 * y1) * c / 12.0;
            izz += (z0 * z0 + z0 * z1 + z1 * z1) * c / 12.0;
            iyz += (z0 * y1 + 2.0 * z0 * y0 + 2.0 * z1 * y1 + z1 * y0) * c / 24.0;
        }
    }
    let (zc, yc) = (sz / a, sy / a);
    [a, iyy - a * yc * yc, izz - a * zc * zc, iyz - a * yc * zc]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dimensions of each shape used by the tests: unequal, so that a dimension read
    /// in the wrong place changes the constants.
    fn sample(shape: Shape) -> Vec<f64> {
        match shape {
            Shape::Bar => vec![2.0, 3.0],
            Shape::Box => vec![4.0, 3.0, 0.2, 0.3],
            Shape::Rod => vec![1.5],
            Shape::Tube => vec![2.0, 1.5],
            Shape::I => vec![6.0, 3.0, 4.0, 0.2, 0.3, 0.4],
            Shape::T => vec![3.0, 4.0, 0.3, 0.2],
            Shape::L => vec![3.0, 4.0, 0.3, 0.2],
            Shape::Chan => vec![3.0, 4.0, 0.3, 0.2],
            Shape::Hat => vec![4.0, 0.2, 2.0, 1.0],
            Shape::Z => vec![3.0, 0.2, 0.3, 4.0],
        }
    }

    /// Goal: every shape's A, I1, I2, I12 (summed over its rectangles) equal the same
    /// moments of its outline by Green's theorem, an independent computation; circles
    /// converge to the polygon's limit at second order in the number of sides.
    /// Tolerance: 1e-12 relative for the rectangles' shapes (round-off).
    #[test]
    fn section_constants_equal_their_outlines_moments() {
        for (shape, name, _) in Shape::ALL {
            let d = sample(shape);
            let c = constants(shape, &d).unwrap();
            if matches!(shape, Shape::Rod | Shape::Tube) {
                let err = |n| {
                    let m = polygon_moments(&outline(shape, &d, n));
                    (m[1] / c.i1 - 1.0).abs()
                };
                let order = (err(200) / err(400)).log2();
                assert!((order - 2.0).abs() < 0.01, "{name}: order {order}");
                continue;
            }
            let m = polygon_moments(&outline(shape, &d, 0));
            let scale = c.i1.max(c.i2);
            assert!((m[0] / c.area - 1.0).abs() < 1e-12, "{name} A: {} vs {}", m[0], c.area);
            assert!((m[1] - c.i1).abs() < 1e-12 * scale, "{name} I1: {} vs {}", m[1], c.i1);
            assert!((m[2] - c.i2).abs() < 1e-12 * scale, "{name} I2: {} vs {}", m[2], c.i2);
            assert!(
                (m[3] - c.i12).abs() < 1e-12 * scale,
                "{name} I12: {} vs {}",
                m[3],
                c.i12
            );
        }
    }

    /// Goal: the torsion constants' closed forms. A square's J is 0.1406 a⁴
    /// (Timoshenko & Goodier's table, β = 0.141 to three figures: 0.140577); a long
    /// thin strip's tends to b t³/3; a thin box's Bredt constant of a square tube
    /// b = h, t: 4 (b−t)⁴ / (4 (b−t)/t) = (b−t)³ t.
    #[test]
    fn torsion_constants_of_textbook_sections() {
        let sq = constants(Shape::Bar, &[1.0, 1.0]).unwrap().j;
        assert!((sq - 0.140577).abs() < 1e-6, "{sq}");
        let strip = constants(Shape::Bar, &[100.0, 1.0]).unwrap().j;
        assert!((strip / (100.0 / 3.0) - 1.0).abs() < 0.007, "{strip}");
        let bx = constants(Shape::Box, &[2.0, 2.0, 0.1, 0.1]).unwrap().j;
        assert!((bx - 1.9f64.powi(3) * 0.1).abs() < 1e-12, "{bx}");
    }

    /// Goal: dimensions that make no section are refused, with what is wrong.
    #[test]
    fn impossible_dimensions_are_refused() {
        assert!(constants(Shape::Box, &[4.0, 3.0, 2.0, 0.3]).is_err());
        assert!(constants(Shape::Tube, &[1.0, 1.5]).is_err());
        assert!(constants(Shape::Bar, &[1.0, -1.0]).is_err());
        assert!(constants(Shape::I, &[1.0, 1.0]).is_err());
    }
}
