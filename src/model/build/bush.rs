//! The bushings (CBUSH with its PBUSH): the element's axes, the spring's point on the
//! line GA-GB, and each grid's motion carried to that point.

use super::*;
use crate::deck::cards::{BushAxes, Cbush};
use crate::elements::bush::Bush;

/// MSC's distance below which GA and GB coincide and CID must give the axes ("If the
/// distance between GA and GB is less than .0001, or if GB is blank, then CID must
/// be specified", Quick Reference Guide, CBUSH).
const COINCIDENT: f64 = 1e-4;

/// Every CBUSH: its kernel at the spring's point, placed on its grids.
pub(super) fn bushings(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let b = &deck.bulk;
    let pbush: HashMap<i64, &crate::deck::cards::Pbush> = b.pbushes.iter().map(|p| (p.pid, p)).collect();
    for c in &b.cbushes {
        let Some(&p) = pbush.get(&c.pid) else {
            cx.err(c.at.error(format!(
                "CBUSH {} references PBUSH {}, which does not exist",
                c.eid, c.pid
            )));
            continue;
        };
        let grids: Vec<i64> = std::iter::once(c.ga).chain(c.gb).collect();
        if let Some(g) = grids.iter().find(|g| !num.grids.contains_key(g)) {
            cx.err(c.at.error(format!("CBUSH {} references grid {g}, which does not exist", c.eid)));
            continue;
        }
        let Some(points) = grids
            .iter()
            .map(|g| geo.positions.get(g).copied())
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let Some(axes) = axes(cx, c, &points, geo) else {
            continue;
        };
        let (a, b_end) = (Vector3::from(points[0]), points.get(1).map(|&p| Vector3::from(p)));
        let spring = match b_end {
            Some(bp) => a + (bp - a) * c.s,
            None => a,
        };
        let turn = grids
            .iter()
            .zip(&points)
            .map(|(&g, &x)| Placement::turn_of(&axes, &geo.frame(g), (spring - Vector3::from(x)).into()))
            .collect();
        let dofs = grids.iter().map(|&g| num.grid_dofs(g)).collect();
        let e = Element::new(
            c.eid,
            grids,
            dofs,
            Bush {
                k: p.k,
                b: p.b,
                points: points.clone(),
            },
        );
        let e = out.with_structural_damping(e, p.ge, &p.at);
        out.push(e.placed(Placement { turn, points }), |g| num.grid_dofs(g));
    }
}

/// The element's axes (columns, basic): system CID's at GA, or x from GA to GB with
/// the xy plane through the orientation vector (GA's displacement frame) or GO.
fn axes(cx: &mut Ctx, c: &Cbush, points: &[[f64; 3]], geo: &Geometry) -> Option<Matrix3<f64>> {
    let a = Vector3::from(points[0]);
    let orientation = match c.axes {
        BushAxes::System(0) => return Some(Matrix3::identity()),
        BushAxes::System(cid) => {
            let frame = geo.systems.get(&cid).and_then(|s| s.frame_at(&a));
            if frame.is_none() {
                cx.err(c.at.error(format!(
                    "CBUSH {}: CID = {cid} names a coordinate system that no CORD card defines (or one undefined \
                     at GA)",
                    c.eid
                )));
            }
            return frame;
        }
        BushAxes::Oriented(o) => Some(o),
        BushAxes::Missing => None,
    };
    let along = points.get(1).map(|&p| Vector3::from(p) - a);
    let Some(along) = along.filter(|d| d.norm() >= COINCIDENT) else {
        cx.err(c.at.error(format!(
            "CBUSH {}: {}, so its axes must come from CID (MSC: \"If the distance between GA and GB is less than \
             .0001, or if GB is blank, then CID must be specified\")",
            c.eid,
            if c.gb.is_some() {
                "GA and GB coincide"
            } else {
                "GB is blank"
            }
        )));
        return None;
    };
    let Some(orientation) = orientation else {
        cx.err(c.at.error(format!(
            "CBUSH {} gives neither CID nor an orientation (GO or X1-X3): its y and z axes are undefined",
            c.eid
        )));
        return None;
    };
    let v = match orientation {
        BarOrientation::Vector(v) => geo.frame(c.ga) * Vector3::from(v),
        BarOrientation::Grid(g0) => match geo.positions.get(&g0) {
            Some(&p) => Vector3::from(p) - a,
            None => {
                cx.err(c.at.field_error(
                    &c.orientation_at,
                    format!("CBUSH {}: GO = {g0} is not a grid of the deck", c.eid),
                ));
                return None;
            }
        },
    };
    let x = along.normalize();
    let y = v - x * v.dot(&x);
    if y.norm().is_nan() || y.norm() <= 1e-9 * v.norm() {
        cx.err(c.at.field_error(
            &c.orientation_at,
            format!(
                "CBUSH {}: the orientation vector lies along GA-GB, so it gives no xy plane",
                c.eid
            ),
        ));
        return None;
    }
    let y = y.normalize();
    Some(Matrix3::from_columns(&[x, y, x.cross(&y)]))
}
