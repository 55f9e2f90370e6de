//! The user guide (`docs/`, an mdBook) against the program and against itself: its
//! generated reference is what the program generates, every card the reader takes is
//! in its card reference, every page is in its table of contents, every link it and
//! the README make resolves, everything the README said before the guide has a
//! home in it, and every tutorial runs as shown. (`.ci/run` builds it with mdBook.)

use crate::common::{impactlab, root};
use pulldown_cmark::{Event, HeadingLevel, Parser, Tag, TagEnd};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The guide's pages: `docs/src/**/*.md`, relative to `docs/src`.
fn pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, base: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, base, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p.strip_prefix(base).unwrap().to_path_buf());
            }
        }
    }
    let src = root().join("docs/src");
    let mut out = Vec::new();
    walk(&src, &src, &mut out);
    out.sort();
    out
}

/// A heading's anchor as mdBook (and GitHub) makes it: lower case, letters, digits,
/// `-` and `_` kept, spaces turned to `-`, anything else dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// A page's headings (their text) and the destinations of its links, code blocks
/// left out.
fn parse(text: &str) -> (Vec<(HeadingLevel, String)>, Vec<String>) {
    let mut headings = Vec::new();
    let mut links = Vec::new();
    let mut heading: Option<(HeadingLevel, String)> = None;
    for event in Parser::new(text) {
        match event {
            Event::Start(Tag::Heading { level, .. }) => heading = Some((level, String::new())),
            Event::End(TagEnd::Heading(_)) => headings.extend(heading.take()),
            Event::Text(t) | Event::Code(t) => {
                if let Some((_, h)) = &mut heading {
                    h.push_str(&t);
                }
            }
            Event::Start(Tag::Link { dest_url, .. }) | Event::Start(Tag::Image { dest_url, .. }) => {
                links.push(dest_url.to_string())
            }
            _ => {}
        }
    }
    (headings, links)
}

/// The generated page `file` of `docs/src/reference/`, which `impactlab reference
/// PAGE` must print byte for byte.
fn generated(page: &str, file: &str) -> String {
    let o = impactlab(&["reference", page]);
    assert!(o.status.success());
    let committed = std::fs::read_to_string(root().join("docs/src/reference").join(file)).unwrap();
    assert!(
        String::from_utf8_lossy(&o.stdout) == committed,
        "docs/src/reference/{file} is stale: `impactlab reference {page} > docs/src/reference/{file}`"
    );
    committed
}

/// Goal: the command-line reference is the program's own: `impactlab reference cli`
/// (every command's and subcommand's `--help`) prints `docs/src/reference/cli.md`
/// byte for byte, so a flag added, renamed or re-documented without the page fails.
#[test]
fn the_cli_reference_is_what_the_program_prints() {
    let page = generated("cli", "cli.md");
    for command in ["run", "sweep", "verify", "check", "compare", "audit"] {
        assert!(page.contains(&format!("### `impactlab {command}`")), "{command}");
    }
}

/// Goal: the `summary.json` reference is the typed summary's: its page and its JSON
/// Schema are what the program generates from the types and their documentation, and
/// they name the keys a run writes (here the rod's summary, key by key, nested objects
/// and arrays included).
#[test]
fn the_summary_reference_is_the_typed_summarys() {
    let page = generated("summary", "summary-schema.md");
    let schema: serde_json::Value = serde_json::from_str(&generated("summary-schema", "summary.schema.json")).unwrap();
    assert_eq!(schema["properties"]["schema_version"]["type"], "integer");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rod");
    let deck = root().join("reference-data/decks/rod.bdf");
    let o = impactlab(&["run", deck.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success());
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    fn keys(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    let key = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    keys(x, &key, out);
                    out.push(key);
                }
            }
            serde_json::Value::Array(a) => {
                for x in a.iter().filter(|x| x.is_object()) {
                    keys(x, &format!("{path}[]"), out);
                }
            }
            _ => {}
        }
    }
    let mut written = Vec::new();
    keys(&summary, "", &mut written);
    let missing: Vec<&String> = written
        .iter()
        .filter(|k| !page.contains(&format!("| `{k}` |")))
        .collect();
    assert!(
        written.len() > 40 && missing.is_empty(),
        "not in summary-schema.md: {missing:?}"
    );
}

/// Goal: the card reference names every card the reader takes, so that a card added
/// to the reader without its documentation fails: each of `deck::cards::supported()`
/// appears, as a word, in the first column of a table of `docs/src/reference/decks.md`.
#[test]
fn the_card_reference_names_every_card_the_reader_takes() {
    let page = std::fs::read_to_string(root().join("docs/src/reference/decks.md")).unwrap();
    let named: BTreeSet<String> = page
        .lines()
        .filter_map(|l| l.strip_prefix("| "))
        .map(|l| l.split(" |").next().unwrap_or(""))
        .flat_map(|c| {
            c.split(|ch: char| !(ch.is_ascii_alphanumeric()))
                .map(str::to_string)
                .collect::<Vec<_>>()
        })
        .collect();
    // A range in the table ("CELAS1-4") names each card of it.
    let covered = |card: &str| {
        named.contains(card)
            || card.strip_suffix(|c: char| c.is_ascii_digit()).is_some_and(|stem| {
                page.lines().filter(|l| l.starts_with("| ")).any(|l| {
                    let first = l.split(" |").next().unwrap_or("");
                    first.contains(&format!("{stem}1-")) || first.contains(&format!("{stem}1/"))
                })
            })
    };
    let missing: Vec<&str> = impactlab::deck::cards::supported()
        .into_iter()
        .filter(|c| !["ENDDATA", "INCLUDE", "PARAM"].contains(c) && !covered(c))
        .collect();
    assert!(missing.is_empty(), "not in docs/src/reference/decks.md: {missing:?}");
}

/// Goal: the card fields reference is the reader's: `impactlab reference cards`
/// prints `docs/src/reference/card-fields.md` byte for byte, it has a section for
/// every card the reader takes, and it puts fields where NASTRAN's manuals put them
/// (MSC's Quick Reference Guide and NASTRAN-95's BULK.TXT): a reader that moved a
/// field, renamed it or changed its default would move a row.
#[test]
fn the_card_fields_reference_is_the_readers() {
    let page = generated("cards", "card-fields.md");
    let sections: BTreeSet<&str> = page.lines().filter_map(|l| l.strip_prefix("## ")).collect();
    let supported: BTreeSet<&str> = impactlab::deck::cards::supported().into_iter().collect();
    assert_eq!(sections, supported);
    let rows = |card: &str| -> Vec<String> {
        let at = page.find(&format!("## {card}\n")).unwrap();
        page[at..]
            .lines()
            .skip(1)
            .take_while(|l| !l.starts_with("## "))
            .filter(|l| l.starts_with("| ") && !l.starts_with("| field"))
            .map(str::to_string)
            .collect()
    };
    for (card, row) in [
        // MAT1 MID E G NU RHO A TREF GE
        ("MAT1", "| 1.9 | GE | real | `0.0` |"),
        ("MAT1", "| 1.2 | MID | id (> 0) | required |"),
        // PSHELL PID MID1 T MID2 12I/T**3 MID3 TS/T NSM: 12I/T**3 1.0, TS/T 0.833333
        ("PSHELL", "| 1.6 | 12I/T**3 | real | `1.0` |"),
        ("PSHELL", "| 1.8 | TS/T | real | `0.833333` |"),
        // CONM2 EID G CID M X1 X2 X3, then I11 I21 I22 I31 I32 I33
        ("CONM2", "| 1.5 | M | real | required |"),
        ("CONM2", "| 2.7 | I33 | real | `0.0` |"),
        // CQUAD4 EID PID G1 G2 G3 G4 THETA/MCID ZOFFS; PID blank: EID
        ("CQUAD4", "| 1.3 | PID | integer | EID's |"),
        ("CQUAD4", "| 1.9 | ZOFFS | real | `0.0` |"),
        // PLOAD4 SID EID P1 P2 P3 P4: P2-P4 blank, P1
        ("PLOAD4", "| 1.6 | P3 | real | P1's |"),
        // SPC1 SID C G1 G2 ... (THRU)
        ("SPC1", "| 1.4 | G | ids to the card's end (THRU) | — |"),
        // LOAD SID S S1 L1 S2 L2 ...
        ("LOAD", "| 1.6 … | Si, Li | repeated | |"),
    ] {
        assert!(
            rows(card).iter().any(|r| r == row),
            "{card}: no `{row}` in {:#?}",
            rows(card)
        );
    }
}

/// Goal: the table of contents holds every page and names no missing one, so no page
/// is left out of the built book.
#[test]
fn every_page_is_in_the_table_of_contents() {
    let summary = std::fs::read_to_string(root().join("docs/src/SUMMARY.md")).unwrap();
    let listed: BTreeSet<PathBuf> = parse(&summary).1.into_iter().map(PathBuf::from).collect();
    let pages: BTreeSet<PathBuf> = pages().into_iter().filter(|p| p != Path::new("SUMMARY.md")).collect();
    assert_eq!(listed, pages, "docs/src/SUMMARY.md against docs/src/**/*.md");
}

/// Goal: every link of the guide and of the README resolves: a relative path to a file
/// or directory of the repository, and an anchor to a heading of the page it names
/// (or of its own page). Web addresses are not fetched.
#[test]
fn every_link_of_the_guide_and_the_readme_resolves() {
    let src = root().join("docs/src");
    let mut anchors: BTreeMap<PathBuf, BTreeSet<String>> = BTreeMap::new();
    let mut texts = Vec::new();
    for p in pages() {
        let file = src.join(&p);
        let text = std::fs::read_to_string(&file).unwrap();
        anchors.insert(file.clone(), parse(&text).0.iter().map(|(_, h)| anchor(h)).collect());
        texts.push((file, text));
    }
    let readme = root().join("README.md");
    texts.push((readme.clone(), std::fs::read_to_string(&readme).unwrap()));
    let mut broken = Vec::new();
    for (file, text) in &texts {
        for link in parse(text).1 {
            if link.contains("://") || link.starts_with("mailto:") {
                continue;
            }
            let (path, fragment) = match link.split_once('#') {
                Some((p, f)) => (p, Some(f)),
                None => (link.as_str(), None),
            };
            let target = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            if !target.exists() {
                broken.push(format!("{}: {link} (no such file)", file.display()));
                continue;
            }
            if let Some(f) = fragment {
                let target = target.canonicalize().unwrap();
                let known = anchors
                    .iter()
                    .find(|(p, _)| p.canonicalize().unwrap() == target)
                    .is_some_and(|(_, a)| a.contains(f));
                if !known {
                    broken.push(format!("{}: {link} (no such heading)", file.display()));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Goal: nothing the README said before the guide is lost: each of its headings (kept
/// in `docs/readme-headings.txt`) is a heading of a page of the guide.
#[test]
fn every_heading_of_the_old_readme_has_a_home_in_the_guide() {
    let src = root().join("docs/src");
    let headings: BTreeSet<String> = pages()
        .iter()
        .flat_map(|p| parse(&std::fs::read_to_string(src.join(p)).unwrap()).0)
        .map(|(_, h)| h)
        .collect();
    let old = std::fs::read_to_string(root().join("docs/readme-headings.txt")).unwrap();
    let homeless: Vec<&str> = old
        .lines()
        .skip_while(|l| l.starts_with("//"))
        // The parser gives a heading's code without its backticks.
        .filter(|h| !headings.contains(&h.replace('`', "")))
        .collect();
    assert!(homeless.is_empty(), "without a home in docs/src: {homeless:?}");
}

/// The commands a page of the guide shows: the lines of its indented code blocks of
/// commands (blocks whose first line is one; a block of printed output is not) that
/// start with `impactlab` or `cargo run --release --`, without a trailing
/// `# comment`, as the arguments after `impactlab`.
fn shown_commands(text: &str) -> Vec<Vec<String>> {
    let command = |l: &str| {
        l.strip_prefix("impactlab ")
            .or_else(|| l.strip_prefix("cargo run --release -- "))
            .map(|l| {
                let l = l.split("  #").next().unwrap_or("");
                l.split_whitespace().map(str::to_string).collect::<Vec<String>>()
            })
    };
    let mut out = Vec::new();
    let mut commands_block = false;
    let mut previous_blank = true;
    for line in text.lines() {
        match line.strip_prefix("    ") {
            Some(l) => {
                if previous_blank {
                    commands_block = command(l).is_some();
                }
                if commands_block {
                    out.extend(command(l));
                }
            }
            None => commands_block = false,
        }
        previous_blank = line.trim().is_empty();
    }
    out
}

/// Goal: every command the tutorials and how-to guides show is one the program has,
/// on files the repository has: its subcommand is in the command-line reference and
/// every deck, scene or case it reads (a path with a directory) exists.
#[test]
fn every_command_the_guide_shows_names_a_command_and_files_that_exist() {
    let src = root().join("docs/src");
    let cli = std::fs::read_to_string(src.join("reference/cli.md")).unwrap();
    let mut seen = 0;
    for p in pages()
        .iter()
        .filter(|p| p.starts_with("tutorials") || p.starts_with("how-to"))
    {
        for args in shown_commands(&std::fs::read_to_string(src.join(p)).unwrap()) {
            seen += 1;
            let command = match args[0].as_str() {
                "mesh" | "study" => format!("`impactlab {} {}`", args[0], args[1]),
                c => format!("`impactlab {c}`"),
            };
            assert!(cli.contains(&command), "{}: {command} is no command", p.display());
            let mut output = false;
            for a in &args[1..] {
                let reads = a.contains('/') && [".bdf", ".toml"].iter().any(|x| a.ends_with(x)) && !output;
                if reads {
                    assert!(root().join(a).exists(), "{}: {a} does not exist", p.display());
                }
                output = ["--out", "--fields", "--to-deck"].contains(&a.as_str());
            }
        }
    }
    assert!(seen >= 15, "{seen} commands");
}

/// A fresh directory holding the repository's decks and cases (linked), where the
/// guide's commands run as a reader would run them from a checkout.
fn checkout_like() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for d in ["reference-data", "verification"] {
        std::os::unix::fs::symlink(root().join(d), dir.path().join(d)).unwrap();
    }
    dir
}

/// `impactlab args` run in `dir`, the kernels' cache kept inside it.
fn impactlab_in(dir: &Path, args: &[String]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_impactlab"))
        .args(args)
        .current_dir(dir)
        .env("XDG_CACHE_HOME", dir.join("cache"))
        .output()
        .unwrap()
}

/// Goal: the CI tutorial's comparison is what the program does: its three commands,
/// run as shown (in a directory holding the repository's decks), print the audit the
/// page describes ("6 of 85 quantities moved") and exit 1.
#[test]
fn the_ci_tutorials_audit_runs_as_shown() {
    let page = std::fs::read_to_string(root().join("docs/src/tutorials/ci-gate.md")).unwrap();
    let dir = checkout_like();
    let commands: Vec<Vec<String>> = shown_commands(&page)
        .into_iter()
        .filter(|a| a[0] == "run" || a[0] == "audit")
        .collect();
    assert_eq!(commands.len(), 3);
    // Each in turn: the audit reads what the runs before it wrote.
    let mut outputs: Vec<_> = commands.iter().map(|args| impactlab_in(dir.path(), args)).collect();
    let o = outputs.pop().unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{stdout}");
    assert!(page.contains("Here 6 of 85 quantities move"));
    assert!(stdout.contains("MOVED: 6 of 85 quantities moved"), "{stdout}");
}

/// Goal: what a tutorial shows a command printing is what it prints: the rod's report
/// (`tutorials/rod.md`) and the plate's run (`tutorials/plate.md`), run as shown in a
/// directory holding the repository's decks and cases, print the lines of the page's
/// `text` block after that command, but for the wall time on the first.
#[test]
fn the_tutorials_printed_output_is_what_the_commands_print() {
    let dir = checkout_like();
    for (page, command) in [("tutorials/rod.md", "report"), ("tutorials/plate.md", "run")] {
        let text = std::fs::read_to_string(root().join("docs/src").join(page)).unwrap();
        let args = shown_commands(&text)
            .into_iter()
            .find(|a| a[0] == command)
            .unwrap_or_else(|| panic!("{page}: no `{command}`"));
        let shown_at = text.find(&args.join(" ")).unwrap();
        let block = &text[shown_at..];
        let block = &block[block.find("```text\n").expect("its output") + 8..];
        let shown: Vec<&str> = block[..block.find("```").unwrap()].lines().collect();
        let mut args = args.clone();
        if command == "run" {
            // Into the temporary directory, not the page's out/.
            args.truncate(args.iter().position(|a| a == "--out").unwrap_or(args.len()));
        }
        let o = impactlab_in(dir.path(), &args);
        assert!(o.status.success(), "{page}: {}", String::from_utf8_lossy(&o.stderr));
        let printed = String::from_utf8_lossy(&o.stdout).into_owned();
        let printed: Vec<&str> = printed.lines().collect();
        let wall = |l: &str| l.rsplit_once(", ").map_or(l.to_string(), |(head, _)| head.to_string());
        assert_eq!(wall(shown[0]), wall(printed[0]), "{page}");
        assert_eq!(shown[1..], printed[1..shown.len()], "{page}");
    }
}

/// A tutorial's commands, run as shown in a [`checkout_like`] directory (`files`
/// written there first) by [`impactlab_in`]: each must succeed. Returns the directory and each command's standard output.
fn run_tutorial(page: &str, files: &[(&str, &str)]) -> (tempfile::TempDir, Vec<String>) {
    let text = std::fs::read_to_string(root().join("docs/src").join(page)).unwrap();
    let dir = checkout_like();
    for (name, content) in files {
        std::fs::write(dir.path().join(name), content).unwrap();
    }
    let commands = shown_commands(&text);
    assert!(!commands.is_empty(), "{page}: no command");
    let printed = commands
        .iter()
        .map(|args| {
            let o = impactlab_in(dir.path(), args);
            let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
            assert!(
                o.status.success(),
                "{page}: `impactlab {}`: {stdout}{}",
                args.join(" "),
                String::from_utf8_lossy(&o.stderr)
            );
            stdout
        })
        .collect();
    (dir, printed)
}

/// The directory a command printed as its `outputs:` (the first word after it).
fn outputs(dir: &Path, printed: &str) -> PathBuf {
    let line = printed
        .lines()
        .find_map(|l| l.trim().strip_prefix("outputs:"))
        .unwrap_or_else(|| panic!("no outputs line: {printed}"));
    dir.join(line.split_whitespace().next().unwrap())
}

/// The number printed after `label` on a line of `printed` (`F_crit 3.7439e2`).
fn printed_number(printed: &str, label: &str) -> f64 {
    let at = printed.find(label).unwrap_or_else(|| panic!("no `{label}`: {printed}")) + label.len();
    let word = printed[at..].split_whitespace().next().unwrap();
    word.trim_end_matches([',', ':'])
        .parse()
        .unwrap_or_else(|_| panic!("`{label}` {word}"))
}

/// A number as a page writes it agrees with the program's when the program's, rounded
/// to the page's last digit, is the page's.
fn as_written(page_value: &str, printed: f64) -> bool {
    let decimals = page_value.split_once('.').map_or(0, |(_, d)| d.len());
    format!("{printed:.decimals$}") == page_value
}

/// Goal: the panel tutorial (`tutorials/your-panel.md`) runs as shown: the page's scene
/// as `strike.toml`, the panel meshed, struck and written out as the deck the scene
/// stands for, which holds the cards the page says the scene writes.
#[test]
fn the_panel_tutorial_runs_as_shown() {
    let page = "tutorials/your-panel.md";
    let text = std::fs::read_to_string(root().join("docs/src").join(page)).unwrap();
    let scene = text.split("```toml\n").nth(1).unwrap().split("```").next().unwrap();
    assert!(text.contains("A scene, `strike.toml`:"));
    let (dir, printed) = run_tutorial(page, &[("strike.toml", scene)]);
    assert_eq!(printed.len(), 3);
    assert!(printed[1].contains("peak force"), "{}", printed[1]);
    let deck = std::fs::read_to_string(dir.path().join("strike.bdf")).unwrap();
    for card in ["EPOINT", "TF", "NOLIN3", "CONM2", "TIC"] {
        assert!(text.contains(card), "{card}");
        assert!(
            deck.lines().any(|l| l.split([',', ' ']).next() == Some(card)),
            "strike.bdf has no {card}"
        );
    }
}

/// Goal: the sweeps tutorial (`tutorials/sweeps.md`) runs as shown: each sweep writes a
/// row a point (the product of its `--vary` lists), the columns the page names, and,
/// for the grid of two parameters, the maps.
#[test]
fn the_sweeps_tutorial_runs_as_shown() {
    let page = "tutorials/sweeps.md";
    let text = std::fs::read_to_string(root().join("docs/src").join(page)).unwrap();
    let (dir, printed) = run_tutorial(page, &[]);
    let commands = shown_commands(&text);
    assert_eq!(printed.len(), 3);
    for (args, printed) in commands.iter().zip(&printed) {
        let counts: Vec<usize> = args
            .windows(2)
            .filter(|w| w[0] == "--vary")
            .map(|w| {
                let values = w[1].split_once('=').unwrap().1;
                match values.split(':').collect::<Vec<_>>()[..] {
                    [_, _, n] => n.parse::<usize>().unwrap(),
                    _ => values.split(',').count(),
                }
            })
            .collect();
        let points: usize = counts.iter().product();
        let out = outputs(dir.path(), printed);
        let mut csv = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
        let header: Vec<String> = csv.headers().unwrap().iter().map(str::to_string).collect();
        let fixed = impactlab::study::sweep::RESULT_COLUMNS;
        for column in ["point", "direct_check"].iter().chain(&fixed) {
            assert!(text.contains(&format!("`{column}`")), "{column}");
            assert!(header.contains(&column.to_string()), "{}: no {column}", args.join(" "));
        }
        assert_eq!(csv.records().count(), points, "{}", args.join(" "));
        // "for a grid of two parameters of three values or more, maps"
        if counts.len() == 2 && counts.iter().all(|&n| n >= 3) {
            assert!(text.contains("`peak-force-map`"));
            assert!(out.join("peak-force-map.png").exists(), "{}", args.join(" "));
        }
    }
}

/// Goal: the layup tutorial (`tutorials/layup-threshold.md`) runs as shown and prints
/// the numbers the page quotes: F_crit and the peak force of the run, the threshold
/// speed and its impact energy (in the deck's units and in joules) of the search.
#[test]
fn the_layup_tutorial_runs_as_shown() {
    let page = "tutorials/layup-threshold.md";
    let text = std::fs::read_to_string(root().join("docs/src").join(page)).unwrap();
    let (_dir, printed) = run_tutorial(page, &[]);
    assert_eq!(printed.len(), 2);
    let quoted = [
        ("F_crit\n374.4 lbf", printed_number(&printed[0], "F_crit")),
        ("a peak of 1398 lbf", printed_number(&printed[0], "peak force")),
        ("start at 423.7 in/s", printed_number(&printed[1], "threshold speed")),
        ("7.27 lbf·in", printed_number(&printed[1], "½mv² =")),
        ("= 0.821 J", printed_number(&printed[1], "lbf*in =")),
    ];
    for (phrase, value) in quoted {
        assert!(text.contains(phrase), "{page} no longer says `{phrase}`");
        let number = phrase.split_whitespace().find(|w| w.parse::<f64>().is_ok()).unwrap();
        assert!(as_written(number, value), "{page}: `{phrase}`, printed {value}");
    }
}
