//! The paper's two decks (restored from its appendix, `reference-data/decks/`),
//! embedded so that an installed binary runs them from any directory.

/// The steel ball on the free-free aluminium rod (144 CRODs).
pub const ROD_DECK: &str = include_str!("../reference-data/decks/rod.bdf");
/// The steel rod on the clamped glass/epoxy plate (49×49 CQUAD4).
pub const PLATE_DECK: &str = include_str!("../reference-data/decks/plate.bdf");

/// The model of the paper's rod deck.
pub fn rod_model() -> Result<crate::model::Model, crate::Error> {
    crate::model_from_text("rod", ROD_DECK)
}

/// The model of the paper's plate deck.
pub fn plate_model() -> Result<crate::model::Model, crate::Error> {
    crate::model_from_text("plate", PLATE_DECK)
}
