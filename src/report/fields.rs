//! Fields for ParaView: one VTU (VTK XML unstructured grid, written by vtkio) per
//! snapshot with the nodal displacement and, for shells, the fibre strains per
//! element, plus a `.pvd` collection giving each file its time, so the wave can be
//! animated.

use crate::model::{DofLabel, Element, Model};
use crate::run::{recovery, Run};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, ElementType, IOBuffer, Piece, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};

/// Writes `DIR/fields-NNNN.vtu` for each snapshot of `run` and `DIR/fields.pvd`, all
/// at once (staged, then swapped in like the run's outputs).
pub fn write_fields(model: &Model, run: &Run, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    // Points: every grid an element touches, with its coordinates.
    let mut index: HashMap<i64, usize> = HashMap::new();
    let mut points: Vec<f64> = Vec::new();
    let mut conn: Vec<u64> = Vec::new();
    let mut offsets: Vec<u64> = Vec::new();
    let mut types = Vec::new();
    let mut cells: Vec<&Element> = Vec::new();
    let mut add = |g: i64, x: [f64; 3], points: &mut Vec<f64>| -> u64 {
        *index.entry(g).or_insert_with(|| {
            points.extend_from_slice(&x);
            points.len() / 3 - 1
        }) as u64
    };
    for e in &model.elements {
        match e {
            Element::Rod { grids, x, .. } => {
                for k in 0..2 {
                    let p = add(grids[k], x[k], &mut points);
                    conn.push(p);
                }
                types.push(CellType::Line);
            }
            Element::Quad4 { grids, xy, .. } => {
                for k in 0..4 {
                    let p = add(grids[k], [xy[k][0], xy[k][1], 0.0], &mut points);
                    conn.push(p);
                }
                types.push(CellType::Quad);
            }
            Element::Mass { .. } => continue,
        }
        offsets.push(conn.len() as u64);
        cells.push(e);
    }
    let full: HashMap<DofLabel, usize> = model.dofs.iter().enumerate().map(|(i, l)| (*l, i)).collect();
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
        let mut disp = vec![0.0; points.len()];
        for (l, &i) in &full {
            if (1..=3).contains(&l.comp) {
                if let Some(&p) = index.get(&l.point) {
                    disp[3 * p + l.comp as usize - 1] = u[i];
                }
            }
        }
        let mut cell_data = Vec::new();
        let shells = cells.iter().all(|e| matches!(e, Element::Quad4 { .. }));
        if shells {
            for (name, off) in [("strain_bottom_z1", 0), ("strain_top_z2", 3)] {
                let v: Vec<f64> = cells
                    .iter()
                    .flat_map(|e| {
                        let r = recovery(e, &u, false);
                        [r[off], r[off + 1], r[off + 2]]
                    })
                    .collect();
                cell_data.push(Attribute::DataArray(vtkio::model::DataArray {
                    name: format!("{name} (xx, yy, xy)"),
                    elem: ElementType::Vectors,
                    data: IOBuffer::F64(v),
                }));
            }
        } else {
            let v: Vec<f64> = cells.iter().map(|e| recovery(e, &u, false)[0]).collect();
            cell_data.push(Attribute::scalars("axial_strain", 1).with_data(v));
        }
        let vtk = Vtk {
            version: Version::new((1, 0)),
            title: format!("{} t = {t:e}", model.name),
            byte_order: ByteOrder::LittleEndian,
            file_path: None,
            data: DataSet::inline(UnstructuredGridPiece {
                points: IOBuffer::F64(points.clone()),
                cells: Cells {
                    cell_verts: VertexNumbers::XML {
                        connectivity: conn.clone(),
                        offsets: offsets.clone(),
                    },
                    types: types.clone(),
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
        };
        let name = format!("fields-{k:04}.vtu");
        let mut bytes = Vec::new();
        vtk.write_xml(&mut bytes).map_err(|e| format!("{name}: {e}"))?;
        let _ = writeln!(pvd, "    <DataSet timestep=\"{t:e}\" part=\"0\" file=\"{name}\"/>");
        written.push(dir.join(&name));
        files.push((name, bytes));
    }
    pvd += "  </Collection>\n</VTKFile>\n";
    files.push(("fields.pvd".into(), pvd.into_bytes()));
    written.push(dir.join("fields.pvd"));
    let refs: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    crate::output::write_dir_atomically(dir, &refs).map_err(|e| format!("{}: {e}", dir.display()))?;
    Ok(written)
}

/// Snapshot times for `n` fields evenly spread over a run of `steps` steps of `dt`.
pub fn field_times(dt: f64, steps: usize, n: usize) -> Vec<f64> {
    let n = n.max(1);
    (0..=n).map(|k| (k * steps / n) as f64 * dt).collect()
}

/// Reads a VTU back (for tests and users' checks): number of points and cells.
pub fn read_back(path: &Path) -> Result<(usize, usize), String> {
    let vtk = Vtk::import(path).map_err(|e| format!("{}: {e}", path.display()))?;
    match vtk.data {
        DataSet::UnstructuredGrid { pieces, .. } => match pieces.into_iter().next() {
            Some(Piece::Inline(p)) => Ok((p.num_points(), p.cells.types.len())),
            _ => Err("no inline piece".into()),
        },
        _ => Err("not an unstructured grid".into()),
    }
}
