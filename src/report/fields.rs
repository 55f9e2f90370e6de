//! Fields for ParaView: one VTU (VTK XML unstructured grid, written by vtkio) per
//! snapshot with the nodal displacement and, for shells, the fibre strains per
//! element, plus a `.pvd` collection giving each file its time, so the wave can be
//! animated.

use crate::elements::{Cell, Element, Fibre, Recovered};
use crate::model::{DofLabel, Model};
use crate::run::RunResult;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, ElementType, IOBuffer, Piece, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};

/// Field files that cannot be written or read back.
#[derive(Debug, thiserror::Error)]
pub enum FieldsError {
    #[error("{path}: {source}")]
    Vtk {
        path: String,
        #[source]
        source: vtkio::Error,
    },
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {what}")]
    Content { path: String, what: &'static str },
}

/// Writes `DIR/fields-NNNN.vtu` for each snapshot of `run` and `DIR/fields.pvd`, all
/// at once (staged, then swapped in like the run's outputs).
pub fn write_fields(model: &Model, run: &RunResult, dir: &Path) -> Result<Vec<PathBuf>, FieldsError> {
    let mesh = Mesh::of(model);
    let full: HashMap<DofLabel, usize> = model.dofs.iter().enumerate().map(|(i, l)| (*l, i)).collect();
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    let mut written = Vec::new();
    let mut pvd = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (k, (t, u_run)) in run.snapshots.iter().enumerate() {
        // The run may have solved a reduced set of DOFs: spread them back.
        let mut u = vec![0.0; model.n()];
        for (l, v) in run.dofs.iter().zip(u_run) {
            if let Some(&i) = full.get(l) {
                u[i] = *v;
            }
        }
        let name = format!("fields-{k:04}.vtu");
        let mut bytes = Vec::new();
        mesh.snapshot(model, &full, &u, *t)
            .write_xml(&mut bytes)
            .map_err(|source| FieldsError::Vtk {
                path: dir.join(&name).display().to_string(),
                source,
            })?;
        let _ = writeln!(pvd, "    <DataSet timestep=\"{t:e}\" part=\"0\" file=\"{name}\"/>");
        written.push(dir.join(&name));
        files.push((name, bytes));
    }
    pvd += "  </Collection>\n</VTKFile>\n";
    files.push(("fields.pvd".into(), pvd.into_bytes()));
    written.push(dir.join("fields.pvd"));
    let refs: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    crate::output::write_dir_atomically(dir, &refs).map_err(|source| FieldsError::Io {
        path: dir.display().to_string(),
        source,
    })?;
    Ok(written)
}

/// The drawn part of a model: every grid an element touches, and the cells.
struct Mesh<'m> {
    /// Point index of each grid.
    index: HashMap<i64, usize>,
    points: Vec<f64>,
    conn: Vec<u64>,
    offsets: Vec<u64>,
    types: Vec<CellType>,
    cells: Vec<&'m Element>,
    /// The strain arrays written per cell (see [`strain_layout`]).
    layout: Vec<(String, Vec<usize>)>,
}

impl<'m> Mesh<'m> {
    fn of(model: &'m Model) -> Self {
        let mut m = Mesh {
            index: HashMap::new(),
            points: Vec::new(),
            conn: Vec::new(),
            offsets: Vec::new(),
            types: Vec::new(),
            cells: Vec::new(),
            layout: Vec::new(),
        };
        for e in &model.elements {
            let Some(cell) = e.kernel.cell() else { continue };
            for (g, x) in e.grids.iter().zip(e.kernel.points()) {
                let points = &mut m.points;
                let p = *m.index.entry(*g).or_insert_with(|| {
                    points.extend_from_slice(&x);
                    points.len() / 3 - 1
                });
                m.conn.push(p as u64);
            }
            m.types.push(match cell {
                Cell::Line => CellType::Line,
                Cell::Quad => CellType::Quad,
            });
            m.offsets.push(m.conn.len() as u64);
            m.cells.push(e);
        }
        m.layout = strain_layout(&m.cells);
        m
    }

    /// One snapshot: nodal displacement and the cells' strains at `u` (all DOFs).
    fn snapshot(&self, model: &Model, full: &HashMap<DofLabel, usize>, u: &[f64], t: f64) -> Vtk {
        let mut disp = vec![0.0; self.points.len()];
        for (l, &i) in full {
            if (1..=3).contains(&l.comp) {
                if let Some(&p) = self.index.get(&l.point) {
                    disp[3 * p + l.comp as usize - 1] = u[i];
                }
            }
        }
        let mut cell_data = Vec::new();
        let strains: Vec<Vec<f64>> = self.cells.iter().map(|e| e.recover(u, false)).collect();
        for (name, columns) in &self.layout {
            let v: Vec<f64> = strains.iter().flat_map(|r| columns.iter().map(|&j| r[j])).collect();
            cell_data.push(if columns.len() == 1 {
                Attribute::scalars(name.as_str(), 1).with_data(v)
            } else {
                Attribute::DataArray(vtkio::model::DataArray {
                    name: name.clone(),
                    elem: ElementType::Vectors,
                    data: IOBuffer::F64(v),
                })
            });
        }
        Vtk {
            version: Version::new_xml(1, 0),
            title: format!("{} t = {t:e}", model.name),
            byte_order: ByteOrder::LittleEndian,
            file_path: None,
            data: DataSet::inline(UnstructuredGridPiece {
                points: IOBuffer::F64(self.points.clone()),
                cells: Cells {
                    cell_verts: VertexNumbers::XML {
                        connectivity: self.conn.clone(),
                        offsets: self.offsets.clone(),
                    },
                    types: self.types.clone(),
                },
                data: Attributes {
                    point: vec![Attribute::DataArray(vtkio::model::DataArray {
                        name: format!("displacement [{}]", model.units.length),
                        elem: ElementType::Vectors,
                        data: IOBuffer::F64(disp),
                    })],
                    cell: cell_data,
                },
            }),
        }
    }
}

/// The strain arrays of the cells: a name and which recovered values it holds. Empty
/// where the cells recover different values (a model mixing element kinds).
fn strain_layout(cells: &[&Element]) -> Vec<(String, Vec<usize>)> {
    let Some(first) = cells.first() else { return Vec::new() };
    let rec: Vec<Recovered> = first.kernel.recovered(false);
    if cells.iter().any(|e| e.kernel.recovered(false) != rec) {
        return Vec::new();
    }
    let mut out: Vec<(String, Vec<usize>)> = Vec::new();
    for (j, r) in rec.iter().enumerate() {
        let name = match r.at {
            None => "axial_strain".to_string(),
            Some((Fibre::Z1, _)) => "strain_bottom_z1 (xx, yy, xy)".to_string(),
            Some((Fibre::Z2, _)) => "strain_top_z2 (xx, yy, xy)".to_string(),
        };
        match out.iter_mut().find(|(n, _)| *n == name) {
            Some((_, cols)) => cols.push(j),
            None => out.push((name, vec![j])),
        }
    }
    out
}

/// Snapshot times for `n` fields evenly spread over a run of `steps` steps of `dt`.
pub fn field_times(dt: f64, steps: usize, n: usize) -> Vec<f64> {
    let n = n.max(1);
    (0..=n).map(|k| (k * steps / n) as f64 * dt).collect()
}

/// Reads a VTU back (for tests and users' checks): number of points and cells.
pub fn read_back(path: &Path) -> Result<(usize, usize), FieldsError> {
    let file = || path.display().to_string();
    let vtk = Vtk::import(path).map_err(|source| FieldsError::Vtk { path: file(), source })?;
    match vtk.data {
        DataSet::UnstructuredGrid { pieces, .. } => match pieces.into_iter().next() {
            Some(Piece::Inline(p)) => Ok((p.num_points(), p.cells.types.len())),
            _ => Err(FieldsError::Content {
                path: file(),
                what: "no inline piece",
            }),
        },
        _ => Err(FieldsError::Content {
            path: file(),
            what: "not an unstructured grid",
        }),
    }
}
