//! The paper's two decks (restored from its appendix, `reference-data/decks/`),
//! embedded so that an installed binary runs them from any directory.

use std::path::Path;

/// The steel ball on the free-free aluminium rod (144 CRODs).
pub const ROD_DECK: &str = include_str!("../reference-data/decks/rod.bdf");
/// The steel rod on the clamped glass/epoxy plate (49×49 CQUAD4); its mesh is in
/// [`PLATE_MESH`], which it INCLUDEs.
pub const PLATE_DECK: &str = include_str!("../reference-data/decks/plate.bdf");
/// The plate's mesh, `plate-mesh-49x49.bdf`.
pub const PLATE_MESH: &str = include_str!("../reference-data/decks/plate-mesh-49x49.bdf");

/// The plate as the cross-ply [0₅/90₅/0₅] of MAT8 plies with transverse shear moduli
/// (PCOMP, G1Z and G2Z: the shear-deformable plate), on [`PLATE_MESH`].
pub const PLATE_SHEAR_DECK: &str = include_str!("../reference-data/decks/plate-pcomp-shear.bdf");

/// The model of the paper's rod deck.
pub fn rod_model() -> Result<crate::model::Model, crate::model::LoadError> {
    read(&[("rod.bdf", ROD_DECK)])
}

/// The model of the paper's plate deck.
pub fn plate_model() -> Result<crate::model::Model, crate::model::LoadError> {
    read(&[("plate.bdf", PLATE_DECK), ("plate-mesh-49x49.bdf", PLATE_MESH)])
}

/// The model of [`PLATE_SHEAR_DECK`].
pub fn plate_shear_model() -> Result<crate::model::Model, crate::model::LoadError> {
    read(&[
        ("plate-pcomp-shear.bdf", PLATE_SHEAR_DECK),
        ("plate-mesh-49x49.bdf", PLATE_MESH),
    ])
}

/// Writes the files into a temporary directory and reads the first as a deck, so that
/// INCLUDEs, positions and the deck's SHA-256 are those of the files themselves.
fn read(files: &[(&str, &str)]) -> Result<crate::model::Model, crate::model::LoadError> {
    let dir = tempfile::tempdir().map_err(|source| crate::model::LoadError::Io {
        path: "a temporary directory".into(),
        source,
    })?;
    for (name, text) in files {
        let p = dir.path().join(name);
        std::fs::write(&p, text).map_err(|source| crate::model::LoadError::Io {
            path: p.display().to_string(),
            source,
        })?;
    }
    let deck = dir.path().join(files[0].0);
    Ok(crate::load_deck(Path::new(&deck), Default::default())?.0)
}
