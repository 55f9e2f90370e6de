//! The mutation campaign's page (`reports/mutants/`): whether the gate catches the
//! faults `cargo mutants` injects into the solver core.
//!
//! Each run of `cargo mutants` leaves `mutants.out/outcomes.json`; [`outcomes_from_json`]
//! turns it into one CSV row per mutant (name, file, outcome, build and test seconds),
//! committed as `reports/mutants/RUN.csv`. The page is made from those CSVs and
//! `campaign.toml` alone ([`readme`]), which names each run (its command, commit and
//! purpose) and says what was done about every mutant that survived: `killed` by a
//! named test or check (then a later run of the campaign must have caught it) or
//! `equivalent` (it cannot change a result, and why). A survivor without a verdict, or a
//! verdict for no survivor, is an error: the page cannot go stale silently.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Why the campaign's page cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum MutantsError {
    /// `outcomes.json` could not be read.
    #[error("cargo-mutants outcomes: {0}")]
    Json(#[from] serde_json::Error),
    /// A run's CSV could not be read.
    #[error("{run}.csv: {source}")]
    Csv {
        /// The run.
        run: String,
        /// What failed.
        #[source]
        source: csv::Error,
    },
    /// `campaign.toml` could not be read.
    #[error("campaign.toml: {0}")]
    Campaign(#[from] toml::de::Error),
    /// A surviving mutant has no verdict, or a verdict does not hold.
    #[error("campaign.toml: {0}")]
    Verdict(String),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What failed.
        #[source]
        source: std::io::Error,
    },
}

fn read(path: &Path) -> Result<Vec<u8>, MutantsError> {
    std::fs::read(path).map_err(|source| MutantsError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// The page of the campaign in `dir` (`campaign.toml` and each run's CSV), as
/// [`readme`] makes it.
pub fn page(dir: &Path) -> Result<String, MutantsError> {
    let text = read(&dir.join("campaign.toml"))?;
    let campaign: Campaign = toml::from_str(&String::from_utf8_lossy(&text))?;
    let runs = campaign
        .run
        .iter()
        .map(|r| read_csv(&r.name, &read(&dir.join(format!("{}.csv", r.name)))?))
        .collect::<Result<Vec<_>, _>>()?;
    readme(&campaign, &runs)
}

/// Records a cargo-mutants output directory (`mutants.out`) as run `name` of the
/// campaign in `dir` (`dir/name.csv`), when given, then writes the page
/// (`dir/README.md`); returns the page.
pub fn write(dir: &Path, from: Option<(&Path, &str)>) -> Result<String, MutantsError> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| MutantsError::Io { path, source }
    };
    if let Some((out, name)) = from {
        let outcomes = outcomes_from_json(&read(&out.join("outcomes.json"))?)?;
        let path = dir.join(format!("{name}.csv"));
        crate::output::write_file_atomically(&path, &csv(&outcomes)).map_err(io(&path))?;
    }
    let p = page(dir)?;
    let path = dir.join("README.md");
    crate::output::write_file_atomically(&path, p.as_bytes()).map_err(io(&path))?;
    Ok(p)
}

/// What became of a mutant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// A test failed: the gate saw it.
    Caught,
    /// Every test passed: the gate did not see it.
    Missed,
    /// The tests ran past the time limit (counted as caught by cargo-mutants).
    Timeout,
    /// It did not compile.
    Unviable,
}

/// One mutant of a run, a row of `RUN.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// cargo-mutants' name: `file:line:col: replace … with …`.
    pub mutant: String,
    /// The source file.
    pub file: String,
    /// What became of it.
    pub outcome: Kind,
    /// Build time, s.
    pub build_s: f64,
    /// Test time, s (0 when it did not build).
    pub test_s: f64,
}

#[derive(Deserialize)]
struct OutcomesJson {
    outcomes: Vec<OutcomeJson>,
}

#[derive(Deserialize)]
struct OutcomeJson {
    scenario: serde_json::Value,
    summary: String,
    phase_results: Vec<PhaseJson>,
}

#[derive(Deserialize)]
struct PhaseJson {
    phase: String,
    duration: f64,
}

/// The mutants of a cargo-mutants `outcomes.json` (the baseline left out), in its order.
pub fn outcomes_from_json(bytes: &[u8]) -> Result<Vec<Outcome>, MutantsError> {
    let json: OutcomesJson = serde_json::from_slice(bytes)?;
    Ok(json
        .outcomes
        .iter()
        .filter_map(|o| {
            let m = o.scenario.get("Mutant")?;
            let outcome = match o.summary.as_str() {
                "CaughtMutant" => Kind::Caught,
                "MissedMutant" => Kind::Missed,
                "Timeout" => Kind::Timeout,
                _ => Kind::Unviable,
            };
            let time = |phase: &str| {
                o.phase_results
                    .iter()
                    .filter(|p| p.phase == phase)
                    .map(|p| p.duration)
                    .sum::<f64>()
                    + 0.0 // an empty sum is −0.0
            };
            Some(Outcome {
                mutant: m.get("name")?.as_str()?.to_string(),
                file: m.get("file")?.as_str()?.to_string(),
                outcome,
                build_s: (time("Build") * 10.0).round() / 10.0,
                test_s: (time("Test") * 10.0).round() / 10.0,
            })
        })
        .collect())
}

/// A run's CSV.
pub fn csv(outcomes: &[Outcome]) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for o in outcomes {
        w.serialize(o).expect("rows of plain values serialize");
    }
    w.into_inner().expect("writing to memory")
}

/// Reads a run's CSV.
pub fn read_csv(run: &str, bytes: &[u8]) -> Result<Vec<Outcome>, MutantsError> {
    csv::Reader::from_reader(bytes)
        .deserialize()
        .collect::<Result<_, _>>()
        .map_err(|source| MutantsError::Csv {
            run: run.to_string(),
            source,
        })
}

/// `campaign.toml`: the runs, in order, and the verdict on every survivor.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Campaign {
    /// The machine the runs ran on.
    pub machine: String,
    /// The runs; each has `NAME.csv` beside the page.
    pub run: Vec<Run>,
    /// What was done about each mutant a run missed.
    #[serde(default)]
    pub survivor: Vec<Survivor>,
}

/// One `cargo mutants` run.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Run {
    /// Its name (the CSV's stem).
    pub name: String,
    /// When it ran.
    pub date: String,
    /// The commit it mutated.
    pub commit: String,
    /// The command, as run.
    pub command: String,
    /// Why it ran.
    pub purpose: String,
}

/// The verdict on a surviving mutant.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Survivor {
    /// cargo-mutants' name of the mutant.
    pub mutant: String,
    /// `killed` or `equivalent`.
    pub verdict: Verdict,
    /// What kills it (for `killed`).
    #[serde(default)]
    pub by: Option<String>,
    /// Its name in the later run that caught it, when its line moved in between.
    #[serde(default)]
    pub caught_as: Option<String>,
    /// Why it survived, and why the verdict holds.
    pub why: String,
}

/// What a survivor turned out to be.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// A new test or check fails on it; a later run caught it.
    Killed,
    /// It cannot change any result.
    Equivalent,
}

/// Counts of one run: caught, missed, timeout, unviable.
fn counts(outcomes: &[Outcome]) -> BTreeMap<Kind, usize> {
    let mut c = BTreeMap::new();
    for o in outcomes {
        *c.entry(o.outcome).or_insert(0) += 1;
    }
    c
}

/// The page: the runs and their counts, the first run per file, and every survivor
/// with its verdict. `runs` are the campaign's runs' outcomes, in its order.
pub fn readme(campaign: &Campaign, runs: &[Vec<Outcome>]) -> Result<String, MutantsError> {
    let verdict = |m: &str| campaign.survivor.iter().find(|s| s.mutant == m);
    let missed: Vec<(&Run, &Outcome)> = campaign
        .run
        .iter()
        .zip(runs)
        .flat_map(|(r, os)| os.iter().filter(|o| o.outcome == Kind::Missed).map(move |o| (r, o)))
        .collect();
    for (run, o) in &missed {
        match verdict(&o.mutant) {
            None => {
                return Err(MutantsError::Verdict(format!(
                    "run {}: survivor {} has no verdict",
                    run.name, o.mutant
                )))
            }
            Some(s) if s.verdict == Verdict::Killed => {
                let later = campaign
                    .run
                    .iter()
                    .zip(runs)
                    .skip_while(|(r, _)| r.name != run.name)
                    .skip(1)
                    .any(|(_, os)| {
                        let name = s.caught_as.as_deref().unwrap_or(&o.mutant);
                        os.iter().any(|x| x.mutant == name && x.outcome == Kind::Caught)
                    });
                if !later || s.by.is_none() {
                    return Err(MutantsError::Verdict(format!(
                        "{} is called killed, but no later run caught it or `by` is missing",
                        o.mutant
                    )));
                }
            }
            Some(_) => {}
        }
    }
    if let Some(s) = campaign
        .survivor
        .iter()
        .find(|s| !missed.iter().any(|(_, o)| o.mutant == s.mutant))
    {
        return Err(MutantsError::Verdict(format!("{} is no run's survivor", s.mutant)));
    }

    let mut p = String::new();
    let w = &mut p;
    let _ = writeln!(w, "# Does the gate catch real faults? (cargo-mutants)\n");
    let _ = writeln!(
        w,
        "Made by `impactlab study mutants` from `campaign.toml` and each run's CSV (from its \
         `mutants.out/outcomes.json`). Machine: {}.\n",
        campaign.machine
    );
    let _ = writeln!(
        w,
        "| run | date | commit | mutants | caught | missed | timeout | unviable | build + test time |"
    );
    let _ = writeln!(w, "|---|---|---|---|---|---|---|---|---|");
    for (r, os) in campaign.run.iter().zip(runs) {
        let c = counts(os);
        let n = |k| c.get(&k).copied().unwrap_or(0);
        let secs: f64 = os.iter().map(|o| o.build_s + o.test_s).sum();
        let _ = writeln!(
            w,
            "| {} | {} | `{}` | {} | {} | {} | {} | {} | {:.0} min |",
            r.name,
            r.date,
            r.commit,
            os.len(),
            n(Kind::Caught),
            n(Kind::Missed),
            n(Kind::Timeout),
            n(Kind::Unviable),
            secs / 60.0
        );
    }
    let _ = writeln!(w);
    for r in &campaign.run {
        let _ = writeln!(w, "- **{}**: {}\n\n      {}\n", r.name, r.purpose, r.command);
    }
    if let (Some(first), Some(os)) = (campaign.run.first(), runs.first()) {
        let c = counts(os);
        let n = |k| c.get(&k).copied().unwrap_or(0);
        let viable = os.len() - n(Kind::Unviable);
        let seen = n(Kind::Caught) + n(Kind::Timeout);
        let killed = missed
            .iter()
            .filter(|(r, o)| r.name == first.name && verdict(&o.mutant).is_some_and(|s| s.verdict == Verdict::Killed))
            .count();
        let equivalent = n(Kind::Missed) - killed;
        let pct = |k: usize, of: usize| if of == 0 { 0.0 } else { 100.0 * k as f64 / of as f64 };
        let _ = writeln!(w, "## Run {}\n", first.name);
        let _ = writeln!(
            w,
            "Of {viable} viable mutants the gate caught {seen} ({:.1} %) as it stood. Of the {} \
             survivors, {killed} are now killed by a new test or check (a later run caught each) and \
             {equivalent} cannot change a result (equivalent): {} of the {} that can are caught ({:.1} %).\n",
            pct(seen, viable),
            n(Kind::Missed),
            seen + killed,
            viable - equivalent,
            pct(seen + killed, viable - equivalent)
        );
        let mut files: BTreeMap<&str, BTreeMap<Kind, usize>> = BTreeMap::new();
        for o in os {
            *files.entry(&o.file).or_default().entry(o.outcome).or_insert(0) += 1;
        }
        let _ = writeln!(w, "| file | mutants | caught | missed | timeout | unviable |");
        let _ = writeln!(w, "|---|---|---|---|---|---|");
        for (f, c) in &files {
            let n = |k| c.get(&k).copied().unwrap_or(0);
            let _ = writeln!(
                w,
                "| `{f}` | {} | {} | {} | {} | {} |",
                c.values().sum::<usize>(),
                n(Kind::Caught),
                n(Kind::Missed),
                n(Kind::Timeout),
                n(Kind::Unviable)
            );
        }
        let _ = writeln!(w);
    }
    let _ = writeln!(w, "## Survivors\n");
    if missed.is_empty() {
        let _ = writeln!(w, "None.");
    }
    for (run, o) in &missed {
        let s = verdict(&o.mutant).expect("checked above");
        let what = match (s.verdict, &s.by) {
            (Verdict::Killed, Some(by)) => format!("killed by {by}"),
            _ => "equivalent".to_string(),
        };
        let _ = writeln!(w, "- `{}` (run {}): **{what}**. {}", o.mutant, run.name, s.why);
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(mutant: &str, outcome: Kind) -> Outcome {
        Outcome {
            mutant: mutant.into(),
            file: "src/a.rs".into(),
            outcome,
            build_s: 1.0,
            test_s: 2.0,
        }
    }

    fn campaign(survivors: &str) -> Campaign {
        toml::from_str(&format!(
            "machine = \"m\"\n[[run]]\nname = \"sample\"\ndate = \"d\"\ncommit = \"c\"\ncommand = \"x\"\npurpose = \"p\"\n\
             [[run]]\nname = \"rerun\"\ndate = \"d\"\ncommit = \"c\"\ncommand = \"x\"\npurpose = \"p\"\n{survivors}"
        ))
        .unwrap()
    }

    /// Goal: the page cannot hide a survivor: one without a verdict, a `killed` one no
    /// later run caught, and a verdict naming no survivor are each refused; with every
    /// verdict backed, the rate counts killed survivors as caught and equivalent ones
    /// out of the viable.
    #[test]
    fn every_survivor_needs_a_verdict_that_holds() {
        let sample = vec![
            outcome("a", Kind::Caught),
            outcome("b", Kind::Missed),
            outcome("c", Kind::Missed),
            outcome("d", Kind::Unviable),
        ];
        let killed_b = "[[survivor]]\nmutant = \"b\"\nverdict = \"killed\"\nby = \"t\"\nwhy = \"w\"\n";
        let equivalent_c = "[[survivor]]\nmutant = \"c\"\nverdict = \"equivalent\"\nwhy = \"w\"\n";
        let caught_b = vec![outcome("b", Kind::Caught)];
        let missed_b = vec![outcome("b", Kind::Missed)];
        let e = readme(&campaign(killed_b), &[sample.clone(), caught_b.clone()]).unwrap_err();
        assert!(e.to_string().contains("c has no verdict"), "{e}");
        let both = format!("{killed_b}{equivalent_c}");
        let e = readme(&campaign(&both), &[sample.clone(), vec![]]).unwrap_err();
        assert!(e.to_string().contains("b is called killed"), "{e}");
        let e = readme(&campaign(&both), &[sample.clone(), missed_b]).unwrap_err();
        assert!(
            e.to_string().contains("no verdict") || e.to_string().contains("called killed"),
            "{e}"
        );
        let stray = format!("{both}[[survivor]]\nmutant = \"z\"\nverdict = \"equivalent\"\nwhy = \"w\"\n");
        let e = readme(&campaign(&stray), &[sample.clone(), caught_b.clone()]).unwrap_err();
        assert!(e.to_string().contains("z is no run's survivor"), "{e}");
        // A survivor whose line moved before the later run names what that run caught.
        let moved = format!("{}caught_as = \"b2\"\n{equivalent_c}", killed_b);
        let caught_b2 = vec![outcome("b2", Kind::Caught)];
        assert!(readme(&campaign(&moved), &[sample.clone(), caught_b2.clone()]).is_ok());
        assert!(readme(&campaign(&both), &[sample.clone(), caught_b2]).is_err());
        let page = readme(&campaign(&both), &[sample, caught_b]).unwrap();
        assert!(
            page.contains("Of 3 viable mutants the gate caught 1 (33.3 %)"),
            "{page}"
        );
        assert!(page.contains("2 of the 2 that can are caught (100.0 %)"), "{page}");
    }

    /// Goal: a run's outcomes read back from its CSV as written, and cargo-mutants'
    /// JSON gives one row per mutant with its phases' times, the baseline left out.
    #[test]
    fn outcomes_round_trip_through_the_csv() {
        let json = br#"{"outcomes": [
            {"scenario": "Baseline", "summary": "Success", "phase_results": []},
            {"scenario": {"Mutant": {"name": "src/a.rs:1:2: replace x with y", "file": "src/a.rs"}},
             "summary": "MissedMutant",
             "phase_results": [{"phase": "Build", "duration": 12.34}, {"phase": "Test", "duration": 5.0}]}]}"#;
        let o = outcomes_from_json(json).unwrap();
        assert_eq!(
            o,
            vec![Outcome {
                mutant: "src/a.rs:1:2: replace x with y".into(),
                file: "src/a.rs".into(),
                outcome: Kind::Missed,
                build_s: 12.3,
                test_s: 5.0,
            }]
        );
        assert_eq!(read_csv("r", &csv(&o)).unwrap(), o);
    }
}
