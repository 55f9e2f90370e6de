//! Fields for ParaView: one VTU (VTK XML unstructured grid, inline binary) per snapshot and a
//! `.pvd` collection giving each file its time, both written with quick-xml.
//!
//! Every value traces back to the deck. Point data: `grid_id` (the NASTRAN grid),
//! `displacement` and `velocity` (translations, in the basic system: a grid displaced
//! in another frame, its CD, is turned to basic). Cell data: `element_id` and the
//! strains the element recovers (`axial_strain` for rods; `strain_z1`, `strain_z2`
//! with components xx, yy, xy for shells), NaN where an element recovers no such
//! value; when a laminate's PCOMP names a failure theory, `failure_index`: each
//! element's largest index of that theory over its plies' bottoms and tops (NaN for
//! elements without one). Every element is drawn: CONM2 masses, the impactor among them, as vertices
//! at their grid. Array names carry no units; the field data does: `TimeValue`,
//! `time_unit`, `displacement_unit`, `velocity_unit`, with the model's name and the
//! deck's SHA-256.

use crate::elements::{At, Element, Fibre, Plane, Recovered};
use crate::model::{DofLabel, Model};
use crate::run::{Column, RunResult, Snapshot, UnitSystem};
use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Field files that cannot be written.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {source}")]
pub struct FieldsError {
    /// The directory being written.
    pub path: String,
    /// What failed.
    #[source]
    pub source: std::io::Error,
}

/// Writes `DIR/fields-NNNN.vtu` for each snapshot of `run` and `DIR/fields.pvd`, all
/// at once (staged, then swapped in like the run's outputs).
pub fn write_fields(model: &Model, run: &RunResult, dir: &Path) -> Result<Vec<PathBuf>, FieldsError> {
    let mesh = Mesh::of(model);
    let full: HashMap<DofLabel, usize> = model.dofs.iter().enumerate().map(|(i, l)| (*l, i)).collect();
    let units = UnitSystem::of(&model.units);
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    for (k, snap) in run.snapshots.iter().enumerate() {
        // The run may have solved a reduced set of DOFs: spread them back.
        let spread = |x: &[f64]| {
            let mut all = vec![0.0; model.n()];
            for (l, v) in run.dofs.iter().zip(x) {
                if let Some(&i) = full.get(l) {
                    all[i] = *v;
                }
            }
            all
        };
        let state = Snapshot {
            time: snap.time,
            u: spread(&snap.u),
            v: spread(&snap.v),
        };
        files.push((format!("fields-{k:04}.vtu"), mesh.vtu(model, &units, &full, &state)));
    }
    let pvd = collection(
        files
            .iter()
            .zip(&run.snapshots)
            .map(|((name, _), s)| (s.time, name.as_str())),
    );
    files.push(("fields.pvd".into(), pvd));
    let refs: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    crate::output::write_dir_atomically(dir, &refs).map_err(|source| FieldsError {
        path: dir.display().to_string(),
        source,
    })?;
    Ok(files.iter().map(|(n, _)| dir.join(n)).collect())
}

/// The `.pvd` collection: each file with its time.
fn collection<'a>(files: impl Iterator<Item = (f64, &'a str)>) -> Vec<u8> {
    vtk_file(
        &[
            ("type", "Collection"),
            ("version", "0.1"),
            ("byte_order", "LittleEndian"),
        ],
        |w| {
            w.create_element("Collection").write_inner_content(|w| {
                for (t, name) in files {
                    let t = t.to_string();
                    w.create_element("DataSet")
                        .with_attributes([("timestep", t.as_str()), ("part", "0"), ("file", name)])
                        .write_empty()?;
                }
                Ok(())
            })?;
            Ok(())
        },
    )
}

/// A VTK XML file: the declaration and a `VTKFile` element with these attributes and
/// the content `body` writes, indented, ending with a newline.
fn vtk_file(attributes: &[(&str, &str)], body: impl FnOnce(&mut Writer<Vec<u8>>) -> std::io::Result<()>) -> Vec<u8> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", None, None)))
        .and_then(|_| {
            w.create_element("VTKFile")
                .with_attributes(attributes.iter().copied())
                .write_inner_content(body)
                .map(|_| ())
        })
        .expect("writing XML into memory cannot fail");
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    bytes
}

/// One VTK data array: name, component names (one entry per component) and values.
struct Array<'a> {
    name: &'a str,
    components: &'a [&'a str],
    values: Values,
    /// A field-data array (its tuple count stated, as VTK's reader needs).
    field: bool,
}

enum Values {
    F64(Vec<f64>),
    I64(Vec<i64>),
    U8(Vec<u8>),
    /// One string, one tuple.
    Text(String),
}

impl Array<'_> {
    fn write(&self, w: &mut Writer<Vec<u8>>) -> std::io::Result<()> {
        use base64::Engine as _;
        // Numbers in VTK's inline binary: base64 of a UInt64 byte count followed by
        // the little-endian values (exact, NaN included). Strings in ASCII: character
        // codes, each string ended by a 0.
        fn binary<const N: usize, T: Copy>(v: &[T], bytes: impl Fn(T) -> [u8; N]) -> String {
            let mut raw = ((v.len() * N) as u64).to_le_bytes().to_vec();
            raw.extend(v.iter().flat_map(|x| bytes(*x)));
            base64::engine::general_purpose::STANDARD.encode(raw)
        }
        let (ty, format, text) = match &self.values {
            Values::F64(v) => ("Float64", "binary", binary(v, f64::to_le_bytes)),
            Values::I64(v) => ("Int64", "binary", binary(v, i64::to_le_bytes)),
            Values::U8(v) => ("UInt8", "binary", binary(v, |x: u8| [x])),
            Values::Text(s) => {
                let codes: Vec<String> = s.bytes().chain([0]).map(|c| c.to_string()).collect();
                ("String", "ascii", codes.join(" "))
            }
        };
        let n = self.components.len().max(1).to_string();
        let mut e = w
            .create_element("DataArray")
            .with_attributes([("type", ty), ("Name", self.name)]);
        if self.components.len() > 1 {
            e = e.with_attribute(("NumberOfComponents", n.as_str()));
            for (i, c) in self.components.iter().enumerate() {
                e = e.with_attribute((format!("ComponentName{i}").as_str(), *c));
            }
        }
        if self.field {
            e = e.with_attribute(("NumberOfTuples", "1"));
        }
        e.with_attribute(("format", format))
            .write_text_content(BytesText::new(&text))?;
        Ok(())
    }
}

const XYZ: [&str; 3] = ["x", "y", "z"];

/// The field data of a snapshot: its time, the units of time, displacement and
/// velocity, the model and its deck's SHA-256.
fn field_arrays(model: &Model, units: &UnitSystem, s: &Snapshot) -> [Array<'static>; 6] {
    [
        Array {
            name: "TimeValue",
            components: &[],
            values: Values::F64(vec![s.time]),
            field: true,
        },
        text("time_unit", Column::Time.unit(units)),
        text("displacement_unit", Column::ImpactorDisp.unit(units)),
        text("velocity_unit", Column::ImpactorVelo.unit(units)),
        text("model", model.name.clone()),
        text("deck_sha256", model.deck_sha256.clone()),
    ]
}

/// The drawn model: every grid an element touches, and one cell per element.
struct Mesh<'m> {
    /// Point index of each grid.
    index: HashMap<i64, usize>,
    grids: Vec<i64>,
    points: Vec<f64>,
    conn: Vec<i64>,
    offsets: Vec<i64>,
    types: Vec<u8>,
    cells: Vec<&'m Element>,
    /// The displacement frames of grids not displaced in the basic system.
    frames: &'m std::collections::BTreeMap<i64, crate::model::GridFrame>,
    /// The strain arrays written per cell (see [`strain_layout`]).
    layout: Vec<StrainArray>,
}

impl<'m> Mesh<'m> {
    fn of(model: &'m Model) -> Self {
        let mut m = Mesh {
            index: HashMap::new(),
            grids: Vec::new(),
            points: Vec::new(),
            conn: Vec::new(),
            offsets: Vec::new(),
            types: Vec::new(),
            cells: Vec::new(),
            frames: &model.frames,
            layout: Vec::new(),
        };
        for e in model.elements.iter() {
            let Some(cell) = e.kernel.cell() else { continue };
            for (g, x) in e.grids.iter().zip(e.points()) {
                let p = *m.index.entry(*g).or_insert_with(|| {
                    m.points.extend_from_slice(&x);
                    m.grids.push(*g);
                    m.grids.len() - 1
                });
                m.conn.push(p as i64);
            }
            m.types.push(cell.vtk_type());
            m.offsets.push(m.conn.len() as i64);
            m.cells.push(e);
        }
        m.layout = strain_layout(&m.cells);
        m
    }

    /// One snapshot's VTU, from the state over all of the model's DOFs.
    /// The VTU file of one snapshot: field data (time, units, model), point data
    /// (grid ids, displacement, velocity), cell data (element ids, failure index,
    /// recovered strains), the points and the cells.
    fn vtu(&self, model: &Model, units: &UnitSystem, full: &HashMap<DofLabel, usize>, s: &Snapshot) -> Vec<u8> {
        let field = field_arrays(model, units, s);
        let point = self.point_arrays(full, s);
        let cell = self.cell_arrays(model, s);
        let geometry = Array {
            name: "Points",
            components: &XYZ,
            values: Values::F64(self.points.clone()),
            field: false,
        };
        let topology = [
            Array {
                name: "connectivity",
                components: &[],
                values: Values::I64(self.conn.clone()),
                field: false,
            },
            Array {
                name: "offsets",
                components: &[],
                values: Values::I64(self.offsets.clone()),
                field: false,
            },
            Array {
                name: "types",
                components: &[],
                values: Values::U8(self.types.clone()),
                field: false,
            },
        ];
        let (np, nc) = (self.grids.len().to_string(), self.cells.len().to_string());
        let all = |w: &mut Writer<Vec<u8>>, arrays: &[Array]| arrays.iter().try_for_each(|a| a.write(w));
        let attributes = [
            ("type", "UnstructuredGrid"),
            ("version", "1.0"),
            ("byte_order", "LittleEndian"),
            ("header_type", "UInt64"),
        ];
        vtk_file(&attributes, |w| {
            w.create_element("UnstructuredGrid").write_inner_content(|w| {
                w.create_element("FieldData").write_inner_content(|w| all(w, &field))?;
                w.create_element("Piece")
                    .with_attributes([("NumberOfPoints", np.as_str()), ("NumberOfCells", nc.as_str())])
                    .write_inner_content(|w| {
                        w.create_element("PointData")
                            .with_attributes([("Scalars", "grid_id"), ("Vectors", "displacement")])
                            .write_inner_content(|w| all(w, &point))?;
                        w.create_element("CellData")
                            .with_attribute(("Scalars", "element_id"))
                            .write_inner_content(|w| all(w, &cell))?;
                        w.create_element("Points").write_inner_content(|w| geometry.write(w))?;
                        w.create_element("Cells").write_inner_content(|w| all(w, &topology))?;
                        Ok(())
                    })?;
                Ok(())
            })?;
            Ok(())
        })
    }

    /// Grid ids, displacement and velocity (translations) at each point.
    fn point_arrays(&self, full: &HashMap<DofLabel, usize>, s: &Snapshot) -> [Array<'static>; 3] {
        let mut disp = vec![0.0; self.points.len()];
        let mut velo = vec![0.0; self.points.len()];
        for (l, &i) in full {
            if (1..=3).contains(&l.comp) {
                if let Some(&p) = self.index.get(&l.point) {
                    disp[3 * p + l.comp as usize - 1] = s.u[i];
                    velo[3 * p + l.comp as usize - 1] = s.v[i];
                }
            }
        }
        for (g, f) in self.frames.iter() {
            if let Some(&p) = self.index.get(g) {
                for a in [&mut disp, &mut velo] {
                    let basic = f.axes * nalgebra::Vector3::from_column_slice(&a[3 * p..3 * p + 3]);
                    a[3 * p..3 * p + 3].copy_from_slice(basic.as_slice());
                }
            }
        }
        [
            Array {
                name: "grid_id",
                components: &[],
                values: Values::I64(self.grids.clone()),
                field: false,
            },
            Array {
                name: "displacement",
                components: &XYZ,
                values: Values::F64(disp),
                field: false,
            },
            Array {
                name: "velocity",
                components: &XYZ,
                values: Values::F64(velo),
                field: false,
            },
        ]
    }

    /// Element ids, each laminate element's largest failure index (when asked) and
    /// the recovered strain arrays of [`strain_layout`], per cell.
    fn cell_arrays(&self, model: &Model, s: &Snapshot) -> Vec<Array<'_>> {
        let recovered: Vec<Vec<f64>> = self
            .cells
            .iter()
            .map(|e| e.recover(&s.u, crate::elements::Output::Strain))
            .collect();
        let mut cell = vec![Array {
            name: "element_id",
            components: &[],
            values: Values::I64(self.cells.iter().map(|e| e.eid).collect()),
            field: false,
        }];
        if !model.outputs.failure_fields.is_empty() {
            let stacks: HashMap<i64, &crate::model::PlyStack> = model
                .outputs
                .failure_fields
                .iter()
                .map(|(e, p)| (model.elements[*e].eid, p))
                .collect();
            let v = self
                .cells
                .iter()
                .map(|e| {
                    stacks
                        .get(&e.eid)
                        .map_or(f64::NAN, |p| crate::run::largest_failure_index(e, p, &s.u))
                })
                .collect();
            cell.push(Array {
                name: "failure_index",
                components: &[],
                values: Values::F64(v),
                field: false,
            });
        }
        for a in &self.layout {
            let v = a
                .columns
                .iter()
                .zip(&recovered)
                .flat_map(|(cols, r)| {
                    (0..a.components.len().max(1)).map(move |c| cols.as_ref().map_or(f64::NAN, |j| r[j[c]]))
                })
                .collect();
            cell.push(Array {
                name: &a.name,
                components: a.components,
                values: Values::F64(v),
                field: false,
            });
        }
        cell
    }
}

/// A one-string field-data array.
fn text(name: &'static str, value: String) -> Array<'static> {
    Array {
        name,
        components: &[],
        values: Values::Text(value),
        field: true,
    }
}

/// A strain array of the cells: its name, component names, and per cell where its
/// components are among the cell's recovered values (`None`: the cell has none).
struct StrainArray {
    name: String,
    components: &'static [&'static str],
    columns: Vec<Option<Vec<usize>>>,
}

/// The strain arrays over all cells, in the order the elements recover them.
fn strain_layout(cells: &[&Element]) -> Vec<StrainArray> {
    const PLANE: [&str; 3] = ["xx", "yy", "xy"];
    const BAR: [&str; 8] = ["a_c", "a_d", "a_e", "a_f", "b_c", "b_d", "b_e", "b_f"];
    let mut out: Vec<StrainArray> = Vec::new();
    for (k, e) in cells.iter().enumerate() {
        let rec: Vec<Recovered> = e.kernel.recovered(crate::elements::Output::Strain);
        for (j, r) in rec.iter().enumerate() {
            let (name, components, c): (&str, &'static [&'static str], usize) = match r.at {
                None | Some(At::End(_)) => ("axial_strain", &[], 0),
                Some(At::Point(end, p)) => ("bar_strain", &BAR, 4 * end as usize + p as usize),
                Some(At::Fibre(f, p)) => (
                    match f {
                        Fibre::Z1 => "strain_z1",
                        Fibre::Z2 => "strain_z2",
                    },
                    &PLANE,
                    match p {
                        Plane::Xx => 0,
                        Plane::Yy => 1,
                        Plane::Xy => 2,
                    },
                ),
            };
            let i = match out.iter().position(|a| a.name == name) {
                Some(i) => i,
                None => {
                    out.push(StrainArray {
                        name: name.to_string(),
                        components,
                        columns: vec![None; cells.len()],
                    });
                    out.len() - 1
                }
            };
            let width = components.len().max(1);
            out[i].columns[k].get_or_insert_with(|| vec![usize::MAX; width])[c] = j;
        }
    }
    out
}

/// Snapshot times for `n` fields evenly spread over a run of `steps` steps of `dt`.
pub fn field_times(dt: f64, steps: usize, n: usize) -> Vec<f64> {
    let n = n.max(1);
    (0..=n).map(|k| (k * steps / n) as f64 * dt).collect()
}
