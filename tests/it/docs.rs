//! The documents a newcomer reads (issue 33): README.md and ARCHITECTURE.md short (the two
//! commands on README's first screen), and every relative link in README.md, ARCHITECTURE.md, BENCHMARKS.md and docs/ resolving
//! to a file and, where it names one, to a heading of that file.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use needlesim_tests::repo_root;

/// The Markdown documents whose links are checked: the top-level ones and every .md under docs/.
fn documents() -> Vec<PathBuf> {
    let root = repo_root();
    let mut docs: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "BENCHMARKS.md"].iter().map(|f| root.join(f)).collect();
    let mut dirs = vec![root.join("docs")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                docs.push(path);
            }
        }
    }
    docs.sort();
    docs
}

/// The text outside fenced code blocks and inline code spans, line by line.
fn prose_lines(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop inline code: the parts between backticks.
        let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        out.push((i + 1, prose));
    }
    out
}

/// The link targets `[text](target)` and `![alt](target)` of a line.
fn link_targets(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        match after.find(')') {
            Some(end) => {
                out.push(after[..end].split_whitespace().next().unwrap_or("").to_owned());
                rest = &after[end..];
            }
            None => break,
        }
    }
    out
}

/// GitHub's anchor of a heading: lower case, punctuation other than `-` and `_` dropped,
/// spaces to `-`.
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

/// The anchors of a Markdown file's headings (outside code blocks).
fn anchors(path: &Path) -> BTreeSet<String> {
    let text = std::fs::read_to_string(path).unwrap();
    prose_lines(&text.replace('`', ""))
        .into_iter()
        .filter_map(|(_, l)| l.strip_prefix('#').map(|h| anchor(h.trim_start_matches('#'))))
        .collect()
}

/// Issue 33: every relative link of the documents names a file that exists and, with a
/// `#fragment`, a heading of that file; links to the web and mail are not followed.
#[test]
fn issue_33_every_relative_link_in_the_documents_resolves() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        for (line_no, line) in prose_lines(&text) {
            for target in link_targets(&line) {
                if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                checked += 1;
                let (file, fragment) = target.split_once('#').unwrap_or((&target, ""));
                let path = if file.is_empty() { doc.clone() } else { doc.parent().unwrap().join(file) };
                let shown = format!("{}:{line_no}: ({target})", doc.strip_prefix(repo_root()).unwrap().display());
                if !path.exists() {
                    broken.push(format!("{shown}: no file {}", path.display()));
                } else if !fragment.is_empty() && path.extension().is_some_and(|e| e == "md") && !anchors(&path).contains(fragment) {
                    broken.push(format!("{shown}: no heading #{fragment} in {}", path.display()));
                }
            }
        }
    }
    assert!(checked >= 30, "the documents link to each other ({checked} relative links)");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// Issue 33: README.md is at most 300 lines, and its first 60 hold both commands (the main job
/// and `tests/run`); the guide's pages are linked from it.
#[test]
fn issue_33_readme_is_short_with_both_commands_on_its_first_screen() {
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    let lines: Vec<&str> = readme.lines().collect();
    assert!(lines.len() <= 300, "README.md has {} lines", lines.len());
    let first = lines[..lines.len().min(60)].join("\n");
    assert!(first.contains("cargo run --release -p needlesim-server"), "the main job in README's first 60 lines");
    assert!(first.contains("\ntests/run"), "tests/run in README's first 60 lines");
    for page in std::fs::read_dir(repo_root().join("docs/guide")).unwrap() {
        let name = page.unwrap().file_name().into_string().unwrap();
        if name.ends_with(".md") && name != "README.md" {
            assert!(readme.contains(&format!("(docs/guide/{name})")), "README links the guide's page {name}");
        }
    }
}

/// Issue 33: ARCHITECTURE.md is the short map (at most 300 lines, its boundaries stated as
/// "Architecture invariant:" lines); the long one is docs/internals.md, linked from it.
#[test]
fn issue_33_architecture_is_short_and_states_its_invariants() {
    let text = std::fs::read_to_string(repo_root().join("ARCHITECTURE.md")).unwrap();
    let lines = text.lines().count();
    assert!(lines <= 300, "ARCHITECTURE.md has {lines} lines");
    let invariants = text.matches("Architecture invariant:").count();
    assert!(invariants >= 10, "ARCHITECTURE.md states {invariants} invariants");
    assert!(text.contains("(docs/internals.md)"), "ARCHITECTURE.md links the long map");
}

#[test]
fn anchors_follow_githubs_rules() {
    assert_eq!(anchor(" Measurement: marker tracking and identification"), "measurement-marker-tracking-and-identification");
    assert_eq!(anchor("3D Fig. 3"), "3d-fig-3");
    assert_eq!(anchor("The needlesim CLI"), "the-needlesim-cli");
    assert_eq!(link_targets("see [a](b.md#c) and ![x](y.png)"), vec!["b.md#c", "y.png"]);
}
