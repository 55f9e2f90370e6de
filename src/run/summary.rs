//! The typed summary of a run (`summary.json`, schema version 3).
//!
//! Values are in the deck's units, never converted: `units` says what they are.
//! No key names a unit, except the wall-clock costs under `run` (`wall_s`,
//! `factor_s`, `solve_s`, `assembly_s`), which are real seconds whatever the deck's
//! units. A value that does not exist for a run (no contact, no ledger, no rebound) is
//! `null`, never zero or NaN.

use crate::deck::Units;
use crate::integrate::Scheme;
use serde::{Deserialize, Serialize};

/// The `schema_version` this build writes.
pub const SCHEMA_VERSION: u32 = 3;

/// The JSON Schema (draft 2020-12) of `summary.json`, from the typed summary: its
/// keys, their types, which may be `null` or left out, and each one's doc comment as
/// its description.
pub fn json_schema() -> serde_json::Value {
    schemars::schema_for!(Summary).to_value()
}

/// `summary.json`'s keys as a Markdown table, from [`json_schema`]: each key's path
/// (an array's elements under `[]`), its JSON type (`or null` where a run may have no
/// value, "optional" where the key is left out when it has none) and its description.
pub fn schema_markdown() -> String {
    use serde_json::Value;
    let schema = json_schema();
    let defs = &schema["$defs"];
    // A schema with its `$ref` resolved.
    let resolve = |s: &Value| -> Value {
        match s.get("$ref").and_then(Value::as_str) {
            Some(r) => defs[r.trim_start_matches("#/$defs/")].clone(),
            None => s.clone(),
        }
    };
    // A schema's type in words, and the object schema its keys are listed from (an
    // object, or an array's element object).
    fn describe(s: &Value, resolve: &dyn Fn(&Value) -> Value) -> (String, Option<(Value, bool)>) {
        let s = resolve(s);
        if let Some(alternatives) = s.get("anyOf").or_else(|| s.get("oneOf")).and_then(Value::as_array) {
            let mut words = Vec::new();
            let mut inner = None;
            for a in alternatives {
                // An enum's variant with data is an object of one key, its name.
                let r = resolve(a);
                let variant = r
                    .get("properties")
                    .and_then(Value::as_object)
                    .filter(|p| p.len() == 1 && r.get("additionalProperties") == Some(&Value::Bool(false)));
                let (w, i) = match (a.get("const"), variant) {
                    (Some(c), _) => (format!("`{c}`"), None),
                    (None, Some(p)) => {
                        let (k, v) = p.iter().next().expect("one key");
                        (format!("`{{\"{k}\": …}}` ({})", describe(v, resolve).0), None)
                    }
                    (None, None) => describe(a, resolve),
                };
                words.push(w);
                inner = inner.or(i);
            }
            return (words.join(" or "), inner);
        }
        if let Some(values) = s.get("enum").and_then(Value::as_array) {
            let words: Vec<String> = values.iter().map(|v| format!("`{v}`")).collect();
            return (words.join(" or "), None);
        }
        let types: Vec<&str> = match &s["type"] {
            Value::String(t) => vec![t.as_str()],
            Value::Array(ts) => ts.iter().filter_map(Value::as_str).collect(),
            _ => vec!["any"],
        };
        let mut inner = None;
        let words: Vec<String> = types
            .iter()
            .map(|&t| match t {
                "array" => {
                    let (w, i) = describe(&s["items"], resolve);
                    inner = i.map(|(v, _)| (v, true));
                    format!("array of {w}")
                }
                "object" if s.get("properties").is_some() => {
                    inner = Some((s.clone(), false));
                    "object".to_string()
                }
                t => t.to_string(),
            })
            .collect();
        (words.join(" or "), inner)
    }
    fn rows(object: &Value, path: &str, resolve: &dyn Fn(&Value) -> Value, out: &mut String) {
        let required: Vec<&str> = object["required"]
            .as_array()
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        let Some(properties) = object["properties"].as_object() else {
            return;
        };
        for (name, p) in properties {
            let key = if path.is_empty() {
                name.clone()
            } else {
                format!("{path}.{name}")
            };
            let (ty, inner) = describe(p, resolve);
            // The field's own doc comment, else its type's.
            let text = p
                .get("description")
                .and_then(Value::as_str)
                .map(str::to_string)
                .or_else(|| {
                    resolve(p)
                        .get("description")
                        .and_then(Value::as_str)
                        .map(str::to_string)
                })
                .unwrap_or_default();
            let optional = if required.contains(&name.as_str()) {
                ""
            } else {
                "; optional"
            };
            // One line; a rustdoc link ([`Type::field`]) as its code alone.
            let text = text
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ")
                .replace("[`", "`")
                .replace("`]", "`")
                .replace('|', "\\|");
            let _ = writeln!(out, "| `{key}` | {ty}{optional} | {text} |");
            if let Some((object, array)) = inner {
                let key = if array { format!("{key}[]") } else { key };
                rows(&object, &key, resolve, out);
            }
        }
    }
    use std::fmt::Write;
    let mut out = format!(
        "# The `summary.json` schema\n\nEvery key of `summary.json` (schema version {SCHEMA_VERSION}), generated from \
         the typed summary (`impactlab::run::Summary`) and its documentation: `impactlab reference summary` prints this \
         page and `impactlab reference summary-schema` the JSON Schema, \
         [`summary.schema.json`](summary.schema.json), which `tests/book.rs` holds to them. A key marked optional \
         may be absent (some are written only when a run has them); `null` is a value a run does not have.\n\n\
         | key | type | what it is |\n|---|---|---|\n"
    );
    rows(&schema, "", &resolve, &mut out);
    out
}

/// Everything `summary.json` holds.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Summary {
    /// Version of this schema ([`SCHEMA_VERSION`]).
    pub schema_version: u32,
    /// The impactlab version that wrote it.
    pub impactlab_version: String,
    /// The deck's name (its file stem).
    pub deck: String,
    /// SHA-256 of the deck's bytes followed by those of each INCLUDEd file in the
    /// order read: for a deck without INCLUDE, what `sha256sum DECK` prints.
    pub deck_sha256: String,
    /// The deck's TITLE.
    pub title: String,
    /// The units every number is in.
    pub units: UnitSystem,
    /// Sizes and contact law of the model.
    pub model: ModelSummary,
    /// Contact intervals and peak force.
    pub contact: ContactSummary,
    /// Impactor mass, velocities and their times.
    pub impactor: ImpactorSummary,
    /// Energy balance.
    pub energy: EnergySummary,
    /// Momentum balance.
    pub momentum: MomentumSummary,
    /// Settings and costs of the run.
    pub run: RunSummary,
    /// Times in units of the rod's transit time L/C, for a uniform rod target.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod: Option<RodSummary>,
    /// The plate's delamination threshold against the peak force, when the run was
    /// given the interface's toughness G_IIc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub delamination: Option<DelaminationSummary>,
    /// The plies' failure indices, when a written laminate element's PCOMP names a
    /// failure theory (FT).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<FailureSummary>,
    /// For a scene: which effects were simulated and which were not, and why.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub effects: Option<crate::scene::EffectReport>,
    /// For a scene: where the Hertz K came from (given, Eq. 5 or Eq. 18).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_stiffness_source: Option<String>,
}

/// The delamination threshold ([`crate::damage`]) of the struck plate and how near the
/// run's peak force came to it.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct DelaminationSummary {
    /// G_IIc, D*, F_crit and the formula.
    #[serde(flatten)]
    pub onset: crate::damage::DelaminationOnset,
    /// Peak contact force / F_crit: at least 1 when the threshold is reached.
    pub peak_over_critical: f64,
}

/// The plies' failure indices ([`crate::damage`]) over the written laminate elements
/// (the STRESS/STRAIN set), every ply's bottom and top, every history row.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct FailureSummary {
    /// The index of the theory each ply's PCOMP names (FT).
    pub theory: PlyIndex,
    /// The maximum-stress index, where the allowables are stresses.
    pub max_stress: Option<PlyIndex>,
    /// The bond index max(|τ1z|, |τ2z|)/SB at the ply interfaces, where the PCOMP
    /// gives SB and the plate is flexible in transverse shear (`ply`: the ply below
    /// the bond, `face`: its `top`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bond: Option<PlyIndex>,
}

/// Where a failure index was largest, and when it first reached 1.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct PlyIndex {
    /// The theory (FT's word, or MAXSTRESS); several joined by `+` when the
    /// laminates name different ones.
    pub name: String,
    /// The largest index.
    pub largest: f64,
    /// When it was largest.
    pub time: f64,
    /// In which element.
    pub element: i64,
    /// In which ply, from 1 at the bottom.
    pub ply: u16,
    /// On the ply's `bottom` or `top` surface.
    pub face: String,
    /// The first time any ply's index reached 1; null when none did.
    pub first_reaches_one: Option<f64>,
}

/// The deck's unit system, as its `$ Units:` line declares it, or "unspecified".
/// Mass and energy are the consistent units that follow (force·time²/length and
/// force·length): labels, not conversions.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct UnitSystem {
    /// Length unit.
    pub length: String,
    /// Force unit.
    pub force: String,
    /// Time unit.
    pub time: String,
    /// Mass unit (force·time²/length).
    pub mass: String,
    /// Energy unit (force·length).
    pub energy: String,
}

impl UnitSystem {
    /// The summary's units from the deck's.
    pub fn of(u: &Units) -> Self {
        let declared = u.declared();
        let derived = |s: String| if declared { s } else { Units::UNSPECIFIED.to_string() };
        UnitSystem {
            length: u.length.clone(),
            force: u.force.clone(),
            time: u.time.clone(),
            mass: derived(format!("{}*{}^2/{}", u.force, u.time, u.length)),
            energy: derived(format!("{}*{}", u.force, u.length)),
        }
    }
}

/// Sizes and contact law of the model.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ModelSummary {
    /// Active DOFs as NASTRAN counts them (solved, inert and TF-defined points).
    pub active_dofs: usize,
    /// DOFs solved for.
    pub solved_dofs: usize,
    /// DOFs dropped as identically zero.
    pub inert_dofs_skipped: usize,
    /// Elements, CONM2 masses included.
    pub elements: usize,
    /// Hertz stiffness K.
    pub contact_stiffness: Option<f64>,
    /// Contact exponent A.
    pub contact_exponent: Option<f64>,
    /// True when the NOLIN3 loads derive from the Hertz potential.
    pub contact_conservative: Option<bool>,
    /// Shell elements with transverse shear flexibility (the MITC4 plate: a PSHELL
    /// with MID3, or a PCOMP whose plies give G1Z and G2Z); absent when none has it
    /// (every shell thin, Kirchhoff).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transverse_shear_elements: Option<usize>,
    /// Output requests of the deck's case control that impactlab does not write
    /// (SPCFORCES, OLOAD, ACCEL, …); absent when there are none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_written: Vec<String>,
}

/// When the impactor touched the target and how hard.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ContactSummary {
    /// [start, end] of every interval with α > 0, interpolated between steps.
    pub intervals: Vec<[f64; 2]>,
    /// True when the last interval is still open at the end of the run.
    pub open_at_end: bool,
    /// Length of the first interval.
    pub duration: Option<f64>,
    /// Largest contact force.
    pub peak_force: f64,
    /// Its time.
    pub peak_force_time: Option<f64>,
}

impl ContactSummary {
    /// The relative differences |x / x_ref − 1| of the contact duration (`None` when
    /// either contact has none) and of the peak force from `reference`'s.
    pub fn relative_difference(&self, reference: &ContactSummary) -> (Option<f64>, f64) {
        let duration = self.duration.zip(reference.duration).map(|(a, b)| (a / b - 1.0).abs());
        (duration, (self.peak_force / reference.peak_force - 1.0).abs())
    }
}

/// The impactor's mass and motion.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ImpactorSummary {
    /// Mass.
    pub mass: Option<f64>,
    /// Velocity at t = 0.
    pub initial_velocity: f64,
    /// First time the impactor's velocity crosses zero.
    pub velocity_zero_time: Option<f64>,
    /// Velocity at the end of the run, once contact has ended.
    pub rebound_velocity: Option<f64>,
}

/// The energy balance of the ledger.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct EnergySummary {
    /// Energy at t = 0, U_0.
    pub initial: Option<f64>,
    /// Total energy at the last step.
    pub final_total: Option<f64>,
    /// External work over the run.
    pub external_work: Option<f64>,
    /// For a damped structure only: the energy its damping dissipated over the run
    /// (null on the convolution engine: see [`ImpactorLoss::damping`]), and the
    /// damping it was given (not written for an undamped one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSummary>,
    /// For a contact that unloads along another curve than it loads on only: what its
    /// hysteresis dissipated, and its law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactDissipation>,
    /// Where the energy the impactor lost went, at the last step; written only when
    /// some of it was dissipated (damping or a contact's hysteresis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impactor_loss: Option<ImpactorLoss>,
    /// 1 − (v_rebound/v0)²: the fraction of the impactor's energy left in the target.
    pub transferred_fraction: Option<f64>,
    /// Largest |relative energy error| over the run.
    pub max_relative_error: Option<f64>,
    /// Relative energy error at the last step.
    pub final_relative_error: Option<f64>,
}

/// What a damped structure's damping did.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct DampingSummary {
    /// The energy dissipated over the run.
    pub dissipated: f64,
    /// The structure's proportional damping a₁ of M (ALPHA1), 0 when none.
    pub mass_coefficient: f64,
    /// a₂ of K (ALPHA2 + G/W3), 0 when none.
    pub stiffness_coefficient: f64,
    /// The elements that damp: CDAMP1-4, CVISC, CBUSH with B, and those whose
    /// structural damping GE PARAM W4 turns viscous.
    pub elements: usize,
    /// The cards the proportional damping comes from, and PARAM W4 with the elements
    /// whose GE it turns viscous.
    pub from: Vec<String>,
}

/// What a hysteretic contact dissipated, and its law.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ContactDissipation {
    /// The energy dissipated over the run (the ledger's `dissipated_contact`).
    pub dissipated: f64,
    /// The law (`yang-sun`).
    pub law: String,
    /// Its critical indentation α_cr.
    pub critical_indentation: f64,
    /// Its unloading exponent q.
    pub unloading_exponent: f64,
    /// The largest indentation of the run, α_m.
    pub max_indentation: f64,
    /// The permanent indentation α0 it leaves: α_m [1 − (α_cr/α_m)^(2/5)] above α_cr,
    /// 0 below.
    pub permanent_indentation: f64,
}

/// Where the energy the impactor lost went, from the start to the last step:
/// `lost` = `target` + `contact_holds` + `damping` + `contact` − `external_work`
/// + `residual`, the residual being the ledger's balance (−error·U_0).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ImpactorLoss {
    /// The impactor's kinetic energy at the start less at the end.
    pub lost: f64,
    /// What the target gained (its kinetic and strain energy).
    pub target: f64,
    /// What the contact gained (SE_i).
    pub contact_holds: f64,
    /// What the structure's damping dissipated (null on the convolution engine, which
    /// cannot split it from the target's energy: `target` then holds it).
    pub damping: f64,
    /// What the contact's hysteresis dissipated.
    pub contact: f64,
    /// The work of the loads that derive from no potential.
    pub external_work: f64,
    /// What the ledger does not account for.
    pub residual: f64,
}

/// Momentum along the impact direction.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct MomentumSummary {
    /// At t = 0.
    pub initial: Option<f64>,
    /// Largest |change| over the run (no external force: round-off).
    pub max_abs_change: Option<f64>,
}

/// Settings and costs of the run.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RunSummary {
    /// The scheme.
    pub scheme: Scheme,
    /// The engine, written only when it is not the direct one.
    #[serde(default, skip_serializing_if = "super::Engine::is_direct")]
    pub engine: super::Engine,
    /// Where the convolution engine's kernels came from (not written when off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kernel_cache: Option<super::convolution::CacheUse>,
    /// What the modal engine's reduction kept (not written for the other engines).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modal: Option<super::modal::Truncation>,
    /// Time step.
    pub dt: f64,
    /// Steps planned.
    pub steps: usize,
    /// Steps done.
    pub steps_done: usize,
    /// Factorisations.
    pub factorizations: usize,
    /// Triangular solve pairs.
    pub solves: usize,
    /// Iterations of the scalar contact solve, over all steps.
    pub contact_iterations: usize,
    /// Seconds factorising (wall clock, as all the times below).
    pub factor_s: f64,
    /// Seconds in solves.
    pub solve_s: f64,
    /// Seconds assembling.
    pub assembly_s: f64,
    /// Seconds for the whole run.
    pub wall_s: f64,
    /// False when the run stopped before its last step for a failure (the energy
    /// guard); a scene's planned stop after separation is complete.
    pub complete: bool,
    /// Why an incomplete run stopped.
    pub stopped_by: Option<String>,
}

/// Times in units of a rod's transit time L/C.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RodSummary {
    /// Bar wave speed C.
    pub wave_speed: f64,
    /// Length L.
    pub length: f64,
    /// L/C.
    pub transit_time: f64,
    /// Contact intervals, in tC/L.
    pub contact_intervals_tcl: Vec<[f64; 2]>,
    /// End of the first contact, in tC/L.
    pub contact_end_tcl: Option<f64>,
    /// Time of the peak force, in tC/L.
    pub peak_force_time_tcl: Option<f64>,
    /// First time the impactor is at rest, in tC/L.
    pub velocity_zero_time_tcl: Option<f64>,
}

/// A dotted key (`contact.peak_force`) that names no number of the summary.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{key}` is not a number of the summary (numbers: {known})")]
pub struct UnknownKey {
    /// The key asked for.
    pub key: String,
    /// The keys there are, comma-separated.
    pub known: String,
}

impl Summary {
    /// A summary with every optional part present, to list what keys exist.
    fn template() -> Summary {
        Summary {
            rod: Some(RodSummary::default()),
            delamination: Some(DelaminationSummary::default()),
            failure: Some(FailureSummary {
                max_stress: Some(PlyIndex::default()),
                bond: Some(PlyIndex::default()),
                ..Default::default()
            }),
            ..Default::default()
        }
    }

    /// The numeric keys of the summary, dotted (`contact.peak_force`).
    pub fn numeric_keys() -> Vec<String> {
        fn walk(prefix: &str, v: &serde_json::Value, out: &mut Vec<String>) {
            if let serde_json::Value::Object(m) = v {
                for (k, x) in m {
                    let key = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    match x {
                        serde_json::Value::Object(_) => walk(&key, x, out),
                        serde_json::Value::Number(_) | serde_json::Value::Null => out.push(key),
                        _ => {}
                    }
                }
            }
        }
        let mut out = Vec::new();
        let v = serde_json::to_value(Summary::template()).expect("a summary is plain data");
        walk("", &v, &mut out);
        out.retain(|k| !matches!(k.as_str(), "effects" | "contact_stiffness_source" | "run.stopped_by"));
        out
    }

    /// Checks that `key` names a number of the summary.
    pub fn check_key(key: &str) -> Result<(), UnknownKey> {
        let keys = Summary::numeric_keys();
        if keys.iter().any(|k| k == key) {
            Ok(())
        } else {
            Err(UnknownKey {
                key: key.to_string(),
                known: keys.join(", "),
            })
        }
    }

    /// The number under a dotted key: `Ok(None)` where the run has no such value
    /// (null), an error where the key names no number of the summary.
    pub fn number(&self, key: &str) -> Result<Option<f64>, UnknownKey> {
        Summary::check_key(key)?;
        let v = serde_json::to_value(self).expect("a summary is plain data");
        Ok(key.split('.').fold(&v, |v, k| &v[k]).as_f64())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Goal: every key the schema documents is numeric and found; a misspelt one is an
    /// error that lists the valid ones; a missing optional value reads as None.
    #[test]
    fn dotted_keys_are_checked_against_the_schema() {
        let keys = Summary::numeric_keys();
        for k in [
            "contact.peak_force",
            "contact.duration",
            "impactor.velocity_zero_time",
            "run.dt",
            "run.wall_s",
            "rod.contact_end_tcl",
            "energy.transferred_fraction",
        ] {
            assert!(keys.iter().any(|x| x == k), "{k} in {keys:?}");
        }
        let e = Summary::check_key("contact.peak_force_time_s").unwrap_err();
        assert!(e.to_string().contains("contact.peak_force_time,"), "{e}");
        assert!(Summary::check_key("run.scheme").is_err());
        let s = Summary {
            contact: ContactSummary {
                peak_force: 3.0,
                ..Default::default()
            },
            ..Default::default()
        };
        assert_eq!(s.number("contact.peak_force").unwrap(), Some(3.0));
        assert_eq!(s.number("contact.duration").unwrap(), None);
        assert_eq!(s.number("rod.contact_end_tcl").unwrap(), None);
    }

    /// Goal: the mass and energy units follow from a declared system and are
    /// "unspecified" when the deck declares none.
    #[test]
    fn derived_units_follow_the_declared_ones() {
        let u = UnitSystem::of(&Units {
            length: "in".into(),
            force: "lbf".into(),
            time: "s".into(),
        });
        assert_eq!((u.mass.as_str(), u.energy.as_str()), ("lbf*s^2/in", "lbf*in"));
        let u = UnitSystem::of(&Units::default());
        assert_eq!(u.time, "unspecified");
        assert_eq!(u.mass, "unspecified");
    }
}
