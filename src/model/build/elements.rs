//! The elements: each card's kernel with its property and frames, point masses,
//! scalar and general elements, attached through the rigid elements' ties, and the
//! drilling supports a run adds.

use super::*;

/// The elements, and the grids they touch.
pub(super) struct Elements<'a, 's> {
    pub(super) list: Vec<Element>,
    /// The grids an element is connected to (not kept by a survey).
    pub(super) on_element: FxHashSet<i64>,
    /// The plies of each laminate (PCOMP) element, by its index in `list`.
    pub(super) plies: HashMap<usize, PlyStack>,
    /// The rigid elements, whose ties each element is attached through.
    pub(super) rigid: &'a crate::model::rigid::Rigid,
    /// For a survey of the structure: each element is handed to it as it is built,
    /// with the grids' geometry, instead of kept in `list`.
    pub(super) survey: Option<&'s mut Surveyor<'s>>,
    /// The grids' positions and frames.
    pub(super) geo: &'a Geometry,
    /// PARAM W4 when set (not zero): the frequency at which the elements' structural
    /// damping GE is turned viscous.
    pub(super) w4: Option<f64>,
    /// The elements given a structural damping GE, and the card of the first: turned
    /// viscous at W4, or left out without it.
    pub(super) structurally_damped: (usize, Option<CardRef>),
}

impl Elements<'_, '_> {
    /// `e` with its structural damping coefficient `ge` (given on the card `from`,
    /// its material or property) turned viscous at PARAM W4:
    /// [`Element::stiffness_damping`] = GE/W4. Without W4 it is left out, as NASTRAN's
    /// transient solutions leave it out, and [`build_model`] says so once.
    pub(super) fn with_structural_damping(&mut self, mut e: Element, ge: f64, from: &CardRef) -> Element {
        if ge != 0.0 {
            let (n, first) = &mut self.structurally_damped;
            *n += 1;
            first.get_or_insert_with(|| from.clone());
            if let Some(w4) = self.w4 {
                e.stiffness_damping = ge / w4;
            }
        }
        e
    }

    /// An element built, on grids whose DOFs are `dofs(g)`: attached through the ties
    /// of the rigid elements (an independent grid that a grid follows whole carries
    /// that grid's elements), then kept or surveyed.
    pub(super) fn push(&mut self, e: Element, dofs: impl Fn(i64) -> [Option<usize>; 6]) {
        let e = if self.rigid.ties.is_empty() {
            e
        } else {
            if !matches!(e.kernel.family(), Family::Point { .. }) && self.survey.is_none() {
                for (gn, _) in e.grids.iter().filter_map(|g| self.rigid.ties.get(g)?.whole()) {
                    self.on_element.insert(gn);
                }
            }
            self.rigid.attach(e, dofs)
        };
        match &mut self.survey {
            Some(survey) => survey(&e, self.geo),
            None => self.list.push(e),
        }
    }
}

/// The element cards, CONM1s and CONM2s with their materials and sections resolved, then
/// the drilling supports their grids need.
pub(super) fn build_elements<'a, 's>(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &'a Geometry,
    rigid: &'a crate::model::rigid::Rigid,
    survey: Option<&'s mut Surveyor<'s>>,
) -> Elements<'a, 's> {
    let mut out = Elements {
        list: Vec::new(),
        on_element: FxHashSet::default(),
        plies: HashMap::new(),
        rigid,
        survey,
        geo,
        w4: element_damping_frequency(deck).map(|s| s.value),
        structurally_damped: (0, None),
    };
    connected(cx, deck, num, geo, &mut out);
    point_masses(cx, deck, num, geo, &mut out);
    mass_matrices(cx, deck, num, geo, &mut out);
    bushings(cx, deck, num, geo, &mut out);
    scalar_elements(cx, deck, num, geo, rigid, &mut out);
    viscous_dampers(cx, deck, num, geo, &mut out);
    general_elements(cx, deck, num, geo, rigid, &mut out);
    if out.survey.is_none() {
        drilling_supports(num, geo, &mut out);
    }
    out
}

/// A placement for an element whose kernel works in the basic axes (a rod, a mass, a
/// shell in the basic XY plane), needed only when one of its grids is displaced in
/// another frame.
pub(super) fn frames_only(grids: &[i64], geo: &Geometry, points: &[[f64; 3]]) -> Option<Placement> {
    offset_in_basic(grids, geo, points, [0.0; 3])
}

/// [`frames_only`] with the kernel's corners at the grids moved by `offset` (basic),
/// tied to them rigidly: needed when a grid is displaced in another frame or the
/// offset is not zero.
pub(super) fn offset_in_basic(
    grids: &[i64],
    geo: &Geometry,
    points: &[[f64; 3]],
    offset: [f64; 3],
) -> Option<Placement> {
    (offset != [0.0; 3] || grids.iter().any(|g| geo.frames.contains_key(g))).then(|| Placement {
        turn: grids
            .iter()
            .map(|&g| Placement::turn_of(&Matrix3::identity(), &geo.frame(g), offset))
            .collect(),
        points: points.to_vec(),
    })
}

/// True when a shell's corners lie in one plane z = const of the basic system (within
/// 1e-9 relative) and run counter-clockwise about +z: its kernel then works in the
/// basic axes themselves, as it always has for the paper's plate.
pub(super) fn in_basic_xy(points: &[[f64; 3]]) -> bool {
    let z = points[0][2];
    if points.iter().any(|p| (p[2] - z).abs() > 1e-9 * (1.0 + z.abs())) {
        return false;
    }
    let n = points.len();
    let twice_area: f64 = (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    twice_area > 0.0
}

/// Every grid that a shell out of the basic XY plane touches, whose rotations some
/// direction of no shell stiffens, gets a [`Drill`] spring along that direction.
pub(super) fn drilling_supports(num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let mut placed: std::collections::BTreeSet<i64> = std::collections::BTreeSet::new();
    for e in out
        .list
        .iter()
        .filter(|e| e.kernel.family().shell().is_some() && e.placement.is_some())
    {
        placed.extend(e.grids.iter().copied());
    }
    if placed.is_empty() {
        return;
    }
    let mut blocks: BTreeMap<i64, Matrix3<f64>> = placed.iter().map(|&g| (g, Matrix3::zeros())).collect();
    for e in out.list.iter().filter(|e| e.kernel.family().shell().is_some()) {
        if !e.grids.iter().any(|g| placed.contains(g)) {
            continue;
        }
        for l in e.stiffness() {
            for (a, &(ga, ca)) in l.at.iter().enumerate() {
                for (b, &(gb, cb)) in l.at.iter().enumerate() {
                    if ga == gb && ca >= 3 && cb >= 3 {
                        if let Some(k) = blocks.get_mut(&e.grids[ga]) {
                            k[(ca - 3, cb - 3)] += l.values[(a, b)];
                        }
                    }
                }
            }
        }
    }
    for (g, k) in blocks {
        let x = geo.positions.get(&g).copied().unwrap_or_default();
        if let Some(d) = Drill::for_rotations(x, &k) {
            out.list.push(Element::new(0, vec![g], vec![num.grid_dofs(g)], d));
        }
    }
}

/// What the deck's coupled-mass parameters do not do here, as warnings on their
/// cards: a per-element parameter without COUPMASS = 0 is inactive (NASTRAN-95 reads
/// it only then), and the coupled mass of a CBEAM (MSC's, which NASTRAN-95 has no
/// element for) or of COSMIC's QUAD1, QUAD2, TRIA1 and TRIA2 is not built: those keep
/// their lumped mass, where NASTRAN would couple it. A rod's and a CBAR's are built
/// ([`crate::elements::rod`], [`crate::elements::bar`]).
fn coupled_mass_notes(cx: &mut Ctx, b: &crate::deck::cards::Bulk) {
    if b.mass_params.is_empty() {
        return;
    }
    let coupmass = b.mass_param("COUPMASS").map(|(v, _)| v);
    for (name, _, at) in b
        .mass_params
        .iter()
        .filter(|(n, _, _)| n != "COUPMASS" && coupmass != Some(0))
    {
        cx.warn(at.error(format!(
            "PARAM {name} is read only when PARAM COUPMASS is 0 ({}): ignored",
            coupmass.map_or("the deck sets none".to_string(), |v| format!("the deck's is {v}"))
        )));
    }
    // The parameter governing each such element, and the card it was written as (a
    // COSMIC plate is read as a CQUAD4 or CTRIA3).
    let lumped_here = |c: &Connection| match (c.kind.build, c.property_card) {
        (Build::Bar(_), _) if c.kind.card == "CBEAM" => Some(("CPBAR", "CBEAM")),
        (_, Some("PQUAD1")) => Some(("CPQUAD1", "CQUAD1")),
        (_, Some("PQUAD2")) => Some(("CPQUAD2", "CQUAD2")),
        (_, Some("PTRIA1")) => Some(("CPTRIA1", "CTRIA1")),
        (_, Some("PTRIA2")) => Some(("CPTRIA2", "CTRIA2")),
        _ => None,
    };
    for c in &b.elements {
        let Some((param, card)) = lumped_here(c) else { continue };
        if let Some(at) = b.coupled_mass(param) {
            cx.warn(at.error(format!(
                "coupled mass is asked for, and impactlab builds it for CROD, CONROD, CTUBE and CBAR only: this deck's \
                 {card} elements keep their lumped mass (NASTRAN would couple it)"
            )));
        }
    }
}

/// The element cards of [`crate::elements::KINDS`], kind by kind in the table's
/// order and each in deck order, with their properties and materials resolved and
/// their frames (see [`Placement`]).
pub(super) fn connected(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let b = &deck.bulk;
    coupled_mass_notes(cx, b);
    let mut props = Properties::new(cx, b);
    for kind in &crate::elements::KINDS {
        for c in b.elements.iter().filter(|c| c.kind.card == kind.card) {
            let mut ok = true;
            let mut xyz = Vec::with_capacity(c.g.len());
            for g in &c.g {
                match geo.positions.get(g) {
                    Some(x) => xyz.push(*x),
                    // A grid whose position did not resolve: its error is reported.
                    None if num.grids.contains_key(g) => ok = false,
                    None => {
                        cx.err(c.at.error(format!(
                            "{} {} references grid {g}, which does not exist",
                            kind.card, c.eid
                        )));
                        ok = false;
                    }
                }
            }
            let mut plies = None;
            let (kernel, placement) = match kind.build {
                Build::Rod(build) => {
                    let Some(section) = props.rod(cx, c) else { continue };
                    if !ok {
                        continue;
                    }
                    (build(&xyz, section), frames_only(&c.g, geo, &xyz))
                }
                Build::Panel(build) => {
                    let Some(section) = props.panel(cx, c) else { continue };
                    if !ok {
                        continue;
                    }
                    (build(&xyz, section), frames_only(&c.g, geo, &xyz))
                }
                Build::Bar(build) => {
                    let section = props.bar(cx, c);
                    let Some(placed) = ok.then(|| place_bar(cx, c, &xyz, geo)).flatten() else {
                        continue;
                    };
                    let Some(section) = section else { continue };
                    let card = c.bar.as_ref().expect("a bar's card keeps its bar fields");
                    let spec = crate::elements::bar::BarSpec {
                        card: kind.card,
                        section,
                        released: card.released.map(|r| r.0),
                        coupled_mass: kind.card == "CBAR" && b.coupled_mass("CPBAR").is_some(),
                    };
                    (build(&placed.0, spec), Some(placed.1))
                }
                Build::Shell(build) => {
                    let Some(placed) = ok.then(|| place_shell(cx, c, &xyz, geo)).flatten() else {
                        // The section is still resolved, so that its errors are reported.
                        props.shell(cx, c, None);
                        continue;
                    };
                    let Some((section, layers)) = props.shell(cx, c, Some(placed.material_angle)) else {
                        continue;
                    };
                    plies = layers;
                    (build(&placed.corners, section), placed.placement)
                }
            };
            let kernel = match kernel {
                Ok(k) => k,
                Err(BadShape(why)) => {
                    cx.err(c.at.error(format!("{} {} {why}", kind.card, c.eid)));
                    continue;
                }
            };
            if out.survey.is_none() {
                out.on_element.extend(&c.g);
            }
            let dofs = c.g.iter().map(|&g| num.grid_dofs(g)).collect();
            // A survey keeps no element, so no plies either.
            if let (Some(layers), None) = (plies, &out.survey) {
                out.plies.insert(out.list.len(), layers);
            }
            let e = Element::boxed(c.eid, c.g.clone(), dofs, kernel);
            let e = match props.structural_damping(c) {
                Some((ge, from)) => out.with_structural_damping(e, ge, from),
                None => e,
            };
            out.push(
                match placement {
                    Some(p) => e.placed(p),
                    None => e,
                },
                |g| num.grid_dofs(g),
            );
        }
    }
}

/// A bar's ends in its own axes (A at the origin, B along x) and its placement: its
/// ends are its grids moved by their offsets WA, WB (in the grids' displacement frames
/// or the basic system, as OFFT says); x runs from end A to end B, y is the part of
/// the orientation vector v normal to x (v in GA's displacement frame or the basic
/// system, or from GA to G0), z = x × y.
pub(super) fn place_bar(
    cx: &mut Ctx,
    c: &Connection,
    xyz: &[[f64; 3]],
    geo: &Geometry,
) -> Option<(Vec<[f64; 3]>, Placement)> {
    let card = c.bar.as_ref().expect("a bar's card keeps its bar fields");
    let frames = [geo.frame(c.g[0]), geo.frame(c.g[1])];
    let offset = |k: usize| {
        let w = Vector3::from(card.offsets[k]);
        if card.offsets_basic[k] {
            w
        } else {
            frames[k] * w
        }
    };
    let (wa, wb) = (offset(0), offset(1));
    let (a, b) = (Vector3::from(xyz[0]) + wa, Vector3::from(xyz[1]) + wb);
    let l = (b - a).norm();
    let size = (Vector3::from(xyz[0]).norm() + Vector3::from(xyz[1]).norm()).max(1e-300);
    if l.is_nan() || l <= 1e-12 * size {
        cx.err(c.at.error(format!(
            "{} {} has zero length: its ends (its grids moved by WA and WB) coincide",
            c.kind.card, c.eid
        )));
        return None;
    }
    let x = (b - a) / l;
    let v = match card.orientation {
        BarOrientation::Vector(v) if card.orientation_basic => Vector3::from(v),
        BarOrientation::Vector(v) => frames[0] * Vector3::from(v),
        BarOrientation::Grid(g0) => {
            let Some(p) = geo.positions.get(&g0) else {
                cx.err(c.at.field_error(
                    &card.orientation_at,
                    format!("{} {}: G0 = {g0} is not a grid of the deck", c.kind.card, c.eid),
                ));
                return None;
            };
            Vector3::from(*p) - Vector3::from(xyz[0])
        }
    };
    let y = v - x * v.dot(&x);
    if y.norm().is_nan() || y.norm() <= 1e-9 * v.norm() {
        cx.err(c.at.field_error(
            &card.orientation_at,
            format!(
                "{} {}: the orientation vector lies along the bar's axis, so it gives no plane 1",
                c.kind.card, c.eid
            ),
        ));
        return None;
    }
    let y = y.normalize();
    let axes = Matrix3::from_columns(&[x, y, x.cross(&y)]);
    let turn = vec![
        Placement::turn_of(&axes, &frames[0], wa.into()),
        Placement::turn_of(&axes, &frames[1], wb.into()),
    ];
    Some((
        vec![[0.0; 3], [l, 0.0, 0.0]],
        Placement {
            turn,
            points: xyz.to_vec(),
        },
    ))
}

/// Where a shell's kernel works and how its material axes lie.
pub(super) struct PlacedShell {
    /// The corners as its kernel takes them.
    pub(super) corners: Vec<[f64; 3]>,
    /// How its kernel's DOFs come from its grids' (`None`: they are the same).
    pub(super) placement: Option<Placement>,
    /// The material x axis, degrees counter-clockwise from the kernel's x axis.
    pub(super) material_angle: f64,
}

/// A shell's frame and material axis: in the basic XY plane (counter-clockwise about
/// +z) its kernel works in the basic axes, as for the paper's plate; anywhere else in
/// its own frame ([`crate::geometry::shell_frame`]). The material x axis is the G1→G2
/// side turned by THETA, or the x axis of system MCID projected onto the element.
pub(super) fn place_shell(cx: &mut Ctx, c: &Connection, xyz: &[[f64; 3]], geo: &Geometry) -> Option<PlacedShell> {
    let (frame, corners, placement) = if in_basic_xy(xyz) {
        // The reference plane ZOFFS along +z.
        let placement = offset_in_basic(&c.g, geo, xyz, [0.0, 0.0, c.zoffs]);
        (Matrix3::identity(), xyz.to_vec(), placement)
    } else {
        let f = match crate::geometry::shell_frame(xyz) {
            Ok(f) => f,
            Err(FrameError::Degenerate) => {
                cx.err(c.at.error(format!(
                    "{} {} is degenerate: its corners lie on one line or coincide",
                    c.kind.card, c.eid
                )));
                return None;
            }
            Err(FrameError::Warped(w)) => {
                cx.err(c.at.error(format!(
                    "{} {} is warped: its corners stand {w:.3} of its half mean diagonal off its mean plane, \
                     beyond the {} a flat element projected onto that plane is taken to stand for",
                    c.kind.card,
                    c.eid,
                    crate::geometry::MAX_WARP
                )));
                return None;
            }
        };
        let turn =
            c.g.iter()
                .zip(&f.offsets)
                .map(|(&g, &d)| {
                    let d = Vector3::from(d) + f.axes.column(2) * c.zoffs;
                    Placement::turn_of(&f.axes, &geo.frame(g), d.into())
                })
                .collect();
        let placement = Placement {
            turn,
            points: xyz.to_vec(),
        };
        (f.axes, f.local, Some(placement))
    };
    let side = Vector3::from(corners[1]) - Vector3::from(corners[0]);
    let g1g2 = if frame == Matrix3::identity() {
        side.y.atan2(side.x).to_degrees()
    } else {
        0.0
    };
    let material_angle = match c.orientation {
        Orientation::Theta(theta) => g1g2 + theta,
        Orientation::Mcid(mcid) => {
            let at = c
                .orientation_at
                .as_ref()
                .expect("a shell's card keeps its THETA/MCID field");
            let Some(sys) = geo.systems.get(&mcid) else {
                cx.err(c.at.field_error(
                    at,
                    format!(
                        "{} {}: MCID = {mcid} names a coordinate system that no CORD card defines",
                        c.kind.card, c.eid
                    ),
                ));
                return None;
            };
            let centroid = xyz.iter().map(|&p| Vector3::from(p)).sum::<Vector3<f64>>() / xyz.len() as f64;
            let x_axis = sys.frame_at(&centroid).map(|f| f.column(0).into_owned());
            match x_axis.and_then(|x| crate::geometry::angle_in_plane(&frame, &x)) {
                Some(a) => a,
                None => {
                    cx.err(c.at.field_error(
                        at,
                        format!(
                            "{} {}: the x axis of system {mcid} at the element is along its normal (or undefined \
                             there), so its projection gives no material axis",
                            c.kind.card, c.eid
                        ),
                    ));
                    return None;
                }
            }
        }
    };
    Some(PlacedShell {
        corners,
        placement,
        material_angle,
    })
}

/// CONM2s: the mass at its grid moved by its offset (X1, X2, X3 in system CID's axes
/// at the grid; CID = −1: X1-X3 are the mass's basic location), its inertia in CID's
/// axes (basic for CID 0 and −1), tied rigidly to its grid and turned to the grid's
/// displacement frame.
pub(super) fn point_masses(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    let b = &deck.bulk;
    for m in &b.conm2s {
        if !num.grids.contains_key(&m.g) {
            cx.err(m.at.error(format!("CONM2 {} references grid {}, which does not exist", m.eid, m.g)));
            continue;
        }
        let Some(&x) = geo.positions.get(&m.g) else { continue };
        let Some(axes) = mass_axes(cx, &m.at, m.eid, m.cid, x, geo) else {
            continue;
        };
        let offset = match m.cid {
            -1 => Vector3::from(m.offset) - Vector3::from(x),
            _ => axes * Vector3::from(m.offset),
        };
        let at = Vector3::from(x) + offset;
        let point = PointMass {
            x: at.into(),
            mass: m.mass,
            inertia: m.inertia,
        };
        let e = Element::new(m.eid, vec![m.g], vec![num.grid_dofs(m.g)], point);
        let placed = if m.cid <= 0 {
            offset_in_basic(&[m.g], geo, &[x], offset.into())
        } else {
            Some(Placement {
                turn: vec![Placement::turn_of(&axes, &geo.frame(m.g), offset.into())],
                points: vec![x],
            })
        };
        out.push(
            match placed {
                Some(p) => e.placed(p),
                None => e,
            },
            |g| num.grid_dofs(g),
        );
    }
}

/// The CVISC dampers along the lines of their grids (their PVISC's C1 and C2), in
/// the basic axes, placed where a grid is displaced in another frame.
pub(super) fn viscous_dampers(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    use crate::elements::damper::Viscous;
    let b = &deck.bulk;
    let pvisc: HashMap<i64, (f64, f64)> = b.pviscs.iter().map(|p| (p.pid, (p.extension, p.rotation))).collect();
    for c in &b.cviscs {
        let Some(&(extension, rotation)) = pvisc.get(&c.pid) else {
            cx.err(c.at.error(format!(
                "CVISC {} references PVISC {}, which does not exist",
                c.eid, c.pid
            )));
            continue;
        };
        if let Some(g) = c.grids.iter().find(|g| !num.grids.contains_key(g)) {
            cx.err(c.at.error(format!("CVISC {} references grid {g}, which does not exist", c.eid)));
            continue;
        }
        let (Some(&xa), Some(&xb)) = (geo.positions.get(&c.grids[0]), geo.positions.get(&c.grids[1])) else {
            continue;
        };
        if xa == xb {
            cx.err(c.at.error(format!(
                "CVISC {} has zero length (its grids coincide): it has no line to damp along",
                c.eid
            )));
            continue;
        }
        let grids = c.grids.to_vec();
        let dofs = grids.iter().map(|&g| num.grid_dofs(g)).collect();
        let e = Element::new(
            c.eid,
            grids.clone(),
            dofs,
            Viscous {
                x: [xa, xb],
                extension,
                rotation,
            },
        );
        out.push(
            match frames_only(&grids, geo, &[xa, xb]) {
                Some(p) => e.placed(p),
                None => e,
            },
            |g| num.grid_dofs(g),
        );
    }
}

/// CONM1s: the card's matrix at its grid, turned from system CID's axes at the grid
/// (basic for CID 0) to the grid's displacement frame.
pub(super) fn mass_matrices(cx: &mut Ctx, deck: &Deck, num: &Numbering, geo: &Geometry, out: &mut Elements) {
    use crate::elements::mass::MassMatrix;
    for m in &deck.bulk.conm1s {
        if !num.grids.contains_key(&m.g) {
            cx.err(m.at.error(format!("CONM1 {} references grid {}, which does not exist", m.eid, m.g)));
            continue;
        }
        let Some(&x) = geo.positions.get(&m.g) else { continue };
        let e = Element::new(
            m.eid,
            vec![m.g],
            vec![num.grid_dofs(m.g)],
            MassMatrix::from_lower(x, &m.lower),
        );
        let Some(axes) = mass_axes(cx, &m.at, m.eid, m.cid, x, geo) else {
            continue;
        };
        let placed = match m.cid {
            0 => frames_only(&[m.g], geo, &[x]),
            _ => Some(Placement {
                turn: vec![Placement::turn_of(&axes, &geo.frame(m.g), [0.0; 3])],
                points: vec![x],
            }),
        };
        out.push(
            match placed {
                Some(p) => e.placed(p),
                None => e,
            },
            |g| num.grid_dofs(g),
        );
    }
}

/// The axes of a concentrated mass's system CID at its grid `x` (basic for CID 0 and
/// −1); an error naming its card when no CORD card defines it there.
fn mass_axes(cx: &mut Ctx, at: &CardRef, eid: i64, cid: i64, x: [f64; 3], geo: &Geometry) -> Option<Matrix3<f64>> {
    if cid <= 0 {
        return Some(Matrix3::identity());
    }
    let axes = geo.systems.get(&cid).and_then(|s| s.frame_at(&Vector3::from(x)));
    if axes.is_none() {
        cx.err(at.error(format!(
            "{} {eid}: CID = {cid} names a coordinate system that no CORD card defines (or one undefined at its grid)",
            at.name
        )));
    }
    axes
}

/// The scalar springs, masses and dampers (CELAS1-4, CMASS1-4, CDAMP1-4) between
/// their terminals: a grid's component in its displacement frame, or a scalar point;
/// ground left out.
pub(super) fn scalar_elements(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &Geometry,
    rigid: &crate::model::rigid::Rigid,
    out: &mut Elements,
) {
    use crate::deck::cards::{ScalarRole, ScalarValue};
    use crate::elements::scalar::{Scalar, ScalarKind};
    let b = &deck.bulk;
    use crate::deck::cards::ScalarProperty;
    fn by_pid(props: &[ScalarProperty]) -> HashMap<i64, &ScalarProperty> {
        props.iter().map(|p| (p.pid, p)).collect()
    }
    let (pelas, pmass, pdamp) = (by_pid(&b.pelas), by_pid(&b.pmass), by_pid(&b.pdamps));
    for c in &b.scalars {
        let card = c.at.name.as_str();
        // The element's value and structural damping GE, with the card that gives GE:
        // a CELAS2's own, a CELAS1's or CELAS3's its PELAS's (0 for masses and dampers).
        let value = match c.value {
            ScalarValue::Value(v) => Some((v, c.ge, &c.at)),
            ScalarValue::Property(pid) => {
                let props = match c.role {
                    ScalarRole::Spring => &pelas,
                    ScalarRole::Mass => &pmass,
                    ScalarRole::Damper => &pdamp,
                };
                let name = c.role.property();
                let v = props.get(&pid).map(|p| (p.value, p.ge, &p.at));
                if v.is_none() {
                    cx.err(c.at.error(format!(
                        "{card} {} references {name} {pid}, which does not exist",
                        c.eid
                    )));
                }
                v
            }
        };
        let mut grids = Vec::new();
        let mut dofs = Vec::new();
        let mut slots = Vec::new();
        let mut points = Vec::new();
        let mut ok = true;
        for &(g, comp) in c.terminals.iter().filter(|(g, _)| *g != 0) {
            let (d, slot, x) = if num.grids.contains_key(&g) {
                if comp == 0 {
                    cx.err(c.at.field_error(
                        &c.first_at,
                        format!(
                            "{card} {}: grid {g} needs a component 1-6 (0 or blank is a scalar point's)",
                            c.eid
                        ),
                    ));
                    ok = false;
                    continue;
                }
                if rigid.ties.contains_key(&g) {
                    cx.err(c.at.error(format!(
                        "{card} {} is on grid {g}, which a rigid element makes dependent: connect it to an independent grid",
                        c.eid
                    )));
                    ok = false;
                    continue;
                }
                (num.grid_dofs(g), comp - 1, geo.positions.get(&g).copied())
            } else if num.scalar.contains_key(&g) {
                if comp != 0 {
                    cx.err(c.at.field_error(
                        &c.first_at,
                        format!(
                            "{card} {}: point {g} is a scalar point: its component is 0 or blank",
                            c.eid
                        ),
                    ));
                    ok = false;
                    continue;
                }
                let i = num.index(&DofLabel { point: g, comp: 0 });
                let mut d = [None; 6];
                d[0] = i;
                (d, 0, None)
            } else {
                cx.err(c.at.error(format!("{card} {} references point {g}, which does not exist", c.eid)));
                ok = false;
                continue;
            };
            slots.push((grids.len(), slot));
            grids.push(g);
            dofs.push(d);
            points.push(x);
        }
        let Some((v, ge, ge_from)) = value.filter(|_| ok) else {
            continue;
        };
        let kind = match c.role {
            ScalarRole::Spring => ScalarKind::Spring(v),
            ScalarRole::Mass => ScalarKind::Mass(v),
            ScalarRole::Damper => ScalarKind::Damper(v),
        };
        let kernel = Scalar {
            card: crate::elements::scalar::card_name(card),
            kind,
            slots,
            points,
        };
        let e = out.with_structural_damping(Element::new(c.eid, grids, dofs, kernel), ge, ge_from);
        out.push(e, |g| num.grid_dofs(g));
    }
}

/// The GENELs: each a [`crate::elements::general::General`] over its {uᵢ} and {u_d}
/// (grid components in their displacement frames, scalar points), K given or Z
/// inverted, [S] given or computed from the grids' positions.
pub(super) fn general_elements(
    cx: &mut Ctx,
    deck: &Deck,
    num: &Numbering,
    geo: &Geometry,
    rigid: &crate::model::rigid::Rigid,
    out: &mut Elements,
) {
    use crate::elements::general::{from_lower, rigid_row, rigid_s, General};
    for c in &deck.bulk.genels {
        let mut points: Vec<i64> = Vec::new();
        let mut dofs = Vec::new();
        let mut xs = Vec::new();
        let mut slots = Vec::new();
        let mut ok = true;
        for &(p, comp) in c.ui.iter().chain(&c.ud) {
            let at = match points.iter().position(|&q| q == p) {
                Some(i) => i,
                None => {
                    let (d, x) = if num.grids.contains_key(&p) {
                        if rigid.ties.contains_key(&p) {
                            cx.err(c.at.error(format!(
                                "GENEL {} is on grid {p}, which a rigid element makes dependent: connect it to an \
                                 independent grid",
                                c.eid
                            )));
                            ok = false;
                            continue;
                        }
                        (num.grid_dofs(p), geo.positions.get(&p).copied())
                    } else if num.scalar.contains_key(&p) {
                        let mut d = [None; 6];
                        d[0] = num.index(&DofLabel { point: p, comp: 0 });
                        (d, None)
                    } else {
                        cx.err(c.at.error(format!("GENEL {} references point {p}, which does not exist", c.eid)));
                        ok = false;
                        continue;
                    };
                    points.push(p);
                    dofs.push(d);
                    xs.push(x);
                    points.len() - 1
                }
            };
            let scalar = xs[at].is_none() && num.scalar.contains_key(&p);
            if scalar != (comp == 0) {
                cx.err(c.at.error(format!(
                    "GENEL {}: point {p} component {comp}: a grid takes a component 1-6, a scalar point 0",
                    c.eid
                )));
                ok = false;
                continue;
            }
            slots.push((at, comp.saturating_sub(1)));
        }
        if !ok {
            continue;
        }
        if points.len() > crate::elements::MAX_GRIDS {
            cx.err(c.at.error(format!(
                "GENEL {} connects {} points: a GENEL of more than {} is not supported",
                c.eid,
                points.len(),
                crate::elements::MAX_GRIDS
            )));
            continue;
        }
        let m = c.ui.len();
        let given = from_lower(m, &c.lower);
        let k = if c.flexibility {
            match General::stiffness_of_flexibility(given) {
                Ok(k) => k,
                Err(e) => {
                    cx.err(c.at.error(format!("GENEL {} {e}", c.eid)));
                    continue;
                }
            }
        } else {
            given
        };
        let n = c.ud.len();
        let s = match (&c.s, n) {
            (_, 0) => None,
            (Some(v), _) => Some(nalgebra::DMatrix::from_row_slice(m, n, v)),
            (None, _) => {
                let at_dof = |&(p, comp): &(i64, usize)| {
                    let i = points.iter().position(|&q| q == p).expect("resolved above");
                    xs[i].map(|x| (x, geo.frame(p), comp))
                };
                // The rigid motions about the first dependent grid, read at each DOF;
                // none where a DOF is a scalar point's (it has no position).
                let rows = |list: &[(i64, usize)], x0: [f64; 3]| -> Option<nalgebra::DMatrix<f64>> {
                    let r: Option<Vec<[f64; 6]>> = list
                        .iter()
                        .map(|d| at_dof(d).map(|(x, t, comp)| rigid_row(x, &t, comp, x0)))
                        .collect();
                    r.map(|r| nalgebra::DMatrix::from_row_iterator(r.len(), 6, r.into_iter().flatten()))
                };
                let computed = at_dof(&c.ud[0]).and_then(|(x0, _, _)| Some((rows(&c.ui, x0)?, rows(&c.ud, x0)?)));
                let Some((ri, rd)) = computed else {
                    cx.err(c.at.error(format!(
                        "GENEL {}: [S] is not given and a scalar point has no position to compute it from: give [S]",
                        c.eid
                    )));
                    continue;
                };
                match rigid_s(&ri, &rd) {
                    Ok(s) => Some(s),
                    Err(e) => {
                        cx.err(c.at.error(format!("GENEL {} {e}", c.eid)));
                        continue;
                    }
                }
            }
        };
        let kernel = General::new(slots, k, s, xs);
        out.push(Element::new(c.eid, points, dofs, kernel), |g| num.grid_dofs(g));
    }
}
