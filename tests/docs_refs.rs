//! Every section reference in the repository resolves to a heading of `docs/`.
//!
//! The conventions are those of docs/README.md ("How to read a reference"):
//! - explicit: `<name>.md §N[.M]` (or `<name>.md section N`): `docs/<name>.md` must exist and
//!   have a heading numbered N (N.M);
//! - `P§N`: can-protocol.md (the conformance plan's notation); `§N of the plan`:
//!   conformance-tests.md;
//! - a `§` that continues a list or range (`, `, `/`, `and`, `–`) takes the document of the
//!   reference before it on the same line; `§3.3–3.6` checks both ends;
//! - bare: the file must name at least one docs file (its default documents) and one of them
//!   must have the section; inside `docs/` a bare reference means the same document;
//! - a section sign must be followed by a number; text in backticks is not read;
//! - no file names a path outside the repository.
//!
//! Scanned: every `.rs`, `.md` and `.toml` file, except under `target/`, `.git/`,
//! `verilog-out/` and `constraints/`. Std only. The section sign is written `\u{a7}` in this
//! file so that the scanner does not read its own patterns.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

const SECTION: char = '\u{a7}';
const SKIP_DIRS: [&str; 4] = ["target", ".git", "verilog-out", "constraints"];
const EXTENSIONS: [&str; 3] = ["rs", "md", "toml"];

/// Section numbers ("2", "2.1") of every docs file, by file name.
type Headings = BTreeMap<String, BTreeSet<String>>;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The number at the start of a heading's text: "1. Bus model" -> "1", "2.1 Time" -> "2.1".
fn heading_number(text: &str) -> Option<String> {
    let num: String = text
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    let num = num.trim_end_matches('.');
    if num.is_empty() || !num.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    let rest = &text[num.len()..];
    // "1. Bus" / "2.1 Time": the number must end at a dot, a space or the end.
    if !(rest.is_empty() || rest.starts_with('.') || rest.starts_with(' ')) {
        return None;
    }
    Some(num.to_string())
}

/// Numbered headings of a markdown text, outside fenced code blocks.
fn headings_of(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced || !line.starts_with('#') {
            continue;
        }
        let body = line.trim_start_matches('#');
        if !body.starts_with(' ') {
            continue;
        }
        if let Some(n) = heading_number(body.trim_start()) {
            out.insert(n);
        }
    }
    out
}

fn load_headings(docs: &Path) -> Headings {
    let mut h = Headings::new();
    for entry in fs::read_dir(docs).expect("docs/ exists") {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) == Some("md") {
            let name = path.file_name().unwrap().to_str().unwrap().to_string();
            h.insert(name, headings_of(&fs::read_to_string(&path).unwrap()));
        }
    }
    h
}

fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '-' || c == '_'
}

/// Docs files a text names (`hub.md`, `docs/hub.md`, `/elsewhere/hub.md`), as whole names.
fn mentioned_docs(text: &str, headings: &Headings) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for name in headings.keys() {
        for (i, _) in text.match_indices(name.as_str()) {
            let before = text[..i].chars().next_back();
            let after = text[i + name.len()..].chars().next();
            if !before.is_some_and(is_name_char) && !after.is_some_and(is_name_char) {
                out.insert(name.clone());
                break;
            }
        }
    }
    out
}

/// Blank out inline code spans (between backticks) so that examples are not read.
fn without_code_spans(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut inside = false;
    for c in line.chars() {
        if c == '`' {
            inside = !inside;
            out.push(c);
        } else if inside {
            out.push(' ');
        } else {
            out.push(c);
        }
    }
    out
}

/// The markdown file name `before` ends with (ignoring spaces, `)`, `]`, `*`, `` ` ``), if any.
fn trailing_md_name(before: &str) -> Option<String> {
    let t = before.trim_end().trim_end_matches([')', ']', '*', '`', ' ']);
    let stem = t.strip_suffix(".md")?;
    let start = stem.rfind(|c: char| !is_name_char(c)).map_or(0, |i| i + 1);
    let name = &stem[start..];
    (!name.is_empty()).then(|| format!("{name}.md"))
}

/// The document of a postfix form: "... of can-protocol.md" right after the section number.
fn suffix_md_name(after: &str) -> Option<String> {
    let rest = after.strip_prefix(" of ")?;
    let len = rest
        .find(|c: char| !(is_name_char(c) || c == '.'))
        .unwrap_or(rest.len());
    let word = rest[..len].trim_end_matches('.');
    (word.ends_with(".md") && word.len() > 3).then(|| word.to_string())
}

/// Text between two references that makes the second continue the first.
fn is_list_separator(between: &str) -> bool {
    let mut rest = between.trim();
    loop {
        let before = rest;
        rest = rest.trim_start_matches([',', '/', '–', '-', '&', ' ']);
        for word in ["and ", "or "] {
            if let Some(r) = rest.strip_prefix(word) {
                rest = r;
            }
        }
        if rest == before {
            break;
        }
    }
    rest.is_empty()
}

/// A parsed section number and how far it reaches in the line (byte offset).
fn number_at(s: &str) -> Option<(String, usize)> {
    let mut end = 0;
    let bytes = s.as_bytes();
    let digits = |from: usize| bytes[from..].iter().take_while(|b| b.is_ascii_digit()).count();
    let n = digits(0);
    if n == 0 {
        return None;
    }
    end += n;
    while end + 1 < bytes.len() && bytes[end] == b'.' && bytes[end + 1].is_ascii_digit() {
        end += 1 + digits(end + 1);
    }
    Some((s[..end].to_string(), end))
}

/// Which document a reference points to.
#[derive(Clone, Debug, PartialEq)]
enum Target {
    /// A named document (explicit, prefixed, `of the plan`, or inherited from a list).
    Doc(String),
    /// The file's default documents.
    Bare,
}

/// One reference found in a line.
#[derive(Debug, PartialEq)]
struct Ref {
    /// The text as written, for the report.
    text: String,
    target: Target,
    /// Section numbers to check (two for a range).
    sections: Vec<String>,
}

/// Problems that are not a missing section: a section sign without a number, an unknown prefix.
#[derive(Debug, PartialEq)]
struct Malformed {
    text: String,
    why: &'static str,
}

/// All references of one line (code spans already blanked).
fn refs_in_line(line: &str) -> (Vec<Ref>, Vec<Malformed>) {
    let mut refs = Vec::new();
    let mut bad = Vec::new();
    let mut prev: Option<(usize, Target)> = None; // end of the previous reference, its target
    for (i, _) in line.match_indices(SECTION) {
        let before = &line[..i];
        let after = &line[i + SECTION.len_utf8()..];
        let snippet_start = before.char_indices().rev().take(24).last().map_or(0, |(k, _)| k);
        let Some((num, len)) = number_at(after) else {
            let tail: String = after.chars().take(12).collect();
            bad.push(Malformed {
                text: format!("{}{SECTION}{tail}", &line[snippet_start..i]),
                why: "section sign without a section number (cite other documents in words)",
            });
            continue;
        };
        let mut end = i + SECTION.len_utf8() + len;
        let mut sections = vec![num];
        // Range without a second sign: "3.3–3.6", "4-6".
        let rest = &line[end..];
        for dash in ["–", "-"] {
            if let Some(r) = rest.strip_prefix(dash) {
                if let Some((n2, l2)) = number_at(r) {
                    sections.push(n2);
                    end += dash.len() + l2;
                }
                break;
            }
        }
        let prev_char = before.chars().next_back();
        let target = if prev_char == Some('P') {
            let pp = before[..before.len() - 1].chars().next_back();
            if pp.is_some_and(|c| c.is_ascii_alphanumeric()) {
                None
            } else {
                Some(Target::Doc("can-protocol.md".into()))
            }
        } else if prev_char.is_some_and(|c| c.is_alphanumeric()) {
            None
        } else if let Some(name) = trailing_md_name(before) {
            Some(Target::Doc(name))
        } else if line[end..].starts_with(" of the plan") {
            Some(Target::Doc("conformance-tests.md".into()))
        } else if let Some(name) = suffix_md_name(&line[end..]) {
            Some(Target::Doc(name))
        } else {
            match &prev {
                Some((pend, t)) if is_list_separator(&line[*pend..i]) => Some(t.clone()),
                _ => Some(Target::Bare),
            }
        };
        // Report the reference as written: with its document name, its P prefix or "of the plan".
        let mut text_start = if prev_char == Some('P') { i - 1 } else { i };
        if let Some(Target::Doc(name)) = &target {
            if let Some(k) = before.rfind(name.as_str()) {
                if before[k..]
                    .trim_end()
                    .trim_end_matches([')', ']', '*', '`'])
                    .len()
                    <= name.len() + 2
                {
                    text_start = k;
                }
            }
        }
        let report_end = if line[end..].starts_with(" of the plan") {
            end + " of the plan".len()
        } else if let Some(name) = suffix_md_name(&line[end..]) {
            end + " of ".len() + name.len()
        } else {
            end
        };
        let Some(target) = target else {
            bad.push(Malformed {
                text: line[snippet_start..end].to_string(),
                why: "unknown prefix before the section sign (only P is defined)",
            });
            continue;
        };
        refs.push(Ref {
            text: line[text_start..report_end].to_string(),
            target: target.clone(),
            sections,
        });
        prev = Some((end, target));
    }
    // "<name>.md section N" in words
    for (i, _) in line.match_indices(".md section ") {
        let before = &line[..i + 3];
        if let (Some(name), Some((num, len))) = (trailing_md_name(before), number_at(&line[i + 12..])) {
            let start = i + 3 - name.len();
            refs.push(Ref {
                text: line[start..i + 12 + len].to_string(),
                target: Target::Doc(name),
                sections: vec![num],
            });
        }
    }
    (refs, bad)
}

/// Path fragments that point outside the repository (built at run time so that this file does
/// not contain them).
fn outside_paths() -> Vec<String> {
    vec![
        ["/", "work/"].concat(),
        ["shared", "/spec"].concat(),
        ["shared", " spec"].concat(),
    ]
}

/// Check one file's text; `rel` is its path relative to the root (for reports and for the
/// docs rule). Returns one line per problem: `path:line: text: cause`.
fn check_text(rel: &str, text: &str, headings: &Headings) -> Vec<String> {
    let mut problems = Vec::new();
    let in_docs = rel.starts_with("docs/");
    let own_name = Path::new(rel).file_name().unwrap().to_str().unwrap().to_string();
    let defaults: BTreeSet<String> = if in_docs {
        [own_name].into_iter().collect()
    } else {
        mentioned_docs(text, headings)
    };
    let outside = outside_paths();
    for (n, raw) in text.lines().enumerate() {
        let lineno = n + 1;
        let lower = raw.to_lowercase();
        if outside.iter().any(|p| lower.contains(p.as_str())) {
            problems.push(format!(
                "{rel}:{lineno}: `{}`: names a path outside the repository",
                raw.trim()
            ));
        }
        if !raw.contains(SECTION) && !raw.contains(".md section ") {
            continue;
        }
        let (refs, bad) = refs_in_line(&without_code_spans(raw));
        for b in bad {
            problems.push(format!("{rel}:{lineno}: `{}`: {}", b.text.trim(), b.why));
        }
        for r in refs {
            for s in &r.sections {
                let cause = match &r.target {
                    Target::Doc(d) => match headings.get(d) {
                        None => Some(format!("{d} is not a file of docs/")),
                        Some(h) if !h.contains(s) => Some(format!("{d} has no section {s}")),
                        Some(_) => None,
                    },
                    Target::Bare if defaults.is_empty() => {
                        Some("bare reference in a file that names no docs file".to_string())
                    }
                    Target::Bare => {
                        let found = defaults
                            .iter()
                            .any(|d| headings.get(d).is_some_and(|h| h.contains(s)));
                        (!found).then(|| {
                            let names: Vec<&str> = defaults.iter().map(|d| d.as_str()).collect();
                            format!(
                                "no section {s} in the documents the file names ({})",
                                names.join(", ")
                            )
                        })
                    }
                };
                if let Some(c) = cause {
                    problems.push(format!("{rel}:{lineno}: `{}`: {c}", r.text.trim()));
                }
            }
        }
    }
    problems
}

fn collect_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_str().unwrap_or("");
        if path.is_dir() {
            if !SKIP_DIRS.contains(&name) {
                collect_files(&path, out);
            }
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| EXTENSIONS.contains(&e))
        {
            out.push(path);
        }
    }
}

/// Check every scanned file under `dir` (relative to the root); print and return the problems.
fn check_tree(dir: &Path) -> (usize, usize, Vec<String>) {
    let root = root();
    let headings = load_headings(&root.join("docs"));
    let mut files = Vec::new();
    collect_files(dir, &mut files);
    let mut problems = Vec::new();
    let mut n_refs = 0;
    for f in &files {
        let text = fs::read_to_string(f).unwrap_or_default();
        n_refs += text.matches(SECTION).count();
        let rel = f
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        problems.extend(check_text(&rel, &text, &headings));
    }
    for p in &problems {
        println!("{p}");
    }
    println!(
        "{} files, {} section signs, {} problems",
        files.len(),
        n_refs,
        problems.len()
    );
    (files.len(), n_refs, problems)
}

/// The whole repository: every reference resolves.
#[test]
fn every_reference_in_the_repository_resolves() {
    let (files, _, problems) = check_tree(&root());
    assert!(files > 50, "the scan found only {files} files");
    assert!(
        problems.is_empty(),
        "{} unresolved references (listed above)",
        problems.len()
    );
}

/// docs/ itself: every heading the code relies on exists and the documents' own references
/// resolve.
#[test]
fn docs_references_resolve() {
    let root = root();
    let (files, refs, problems) = check_tree(&root.join("docs"));
    assert!(files >= 6, "docs/ has {files} markdown files");
    assert!(refs > 100, "docs/ has only {refs} section signs");
    assert!(
        problems.is_empty(),
        "{} unresolved references in docs/ (listed above)",
        problems.len()
    );
    let h = load_headings(&root.join("docs"));
    let want: [(&str, &[&str]); 5] = [
        (
            "can-protocol.md",
            &[
                "1", "1.2", "1.5", "2.3", "2.5", "3.6", "4.5", "13.4", "16", "17", "18", "19.3", "19.9",
            ],
        ),
        ("conformance-tests.md", &["0", "1", "3", "6", "13"]),
        ("hub.md", &["1", "2", "3", "4", "5", "5.1", "5.7", "6"]),
        ("recancentrate.md", &["1", "2", "3", "4", "5", "6"]),
        ("boards.md", &[]),
    ];
    for (doc, secs) in want {
        let have = h.get(doc).unwrap_or_else(|| panic!("docs/{doc} missing"));
        for s in secs {
            assert!(have.contains(*s), "docs/{doc} has no section {s}");
        }
    }
}

/// The scanner itself, on lines written in each accepted form and in wrong ones.
#[test]
fn scanner_reads_every_reference_form() {
    let s = SECTION;
    let secs = |v: &[&str]| -> BTreeSet<String> { v.iter().map(|x| x.to_string()).collect() };
    let mut h = Headings::new();
    h.insert(
        "can-protocol.md".into(),
        secs(&["2", "2.3", "3.3", "3.4", "3.5", "3.6", "18", "19", "19.6"]),
    );
    h.insert("conformance-tests.md".into(), secs(&["0", "9"]));
    h.insert("hub.md".into(), secs(&["1", "5.7"]));

    // explicit, P-prefixed, "of the plan", list inheritance, ranges, markdown links
    let good = format!(
        "//! can-protocol.md {s}2.3; P{s}19.6 and P{s}3.4/{s}3.5; idle ({s}9 of the plan);\n\
         //! hub.md {s}1, {s}5.7; can-protocol.md {s}3.3–3.6; [hub.md](hub.md) {s}5.7;\n\
         //! recancentrate is not named; conformance-tests.md {s}0; `placeholder {s}N`\n\
         # conformance-tests.md section 9; {s}2.3–3.6 of can-protocol.md.\n"
    );
    assert_eq!(check_text("x/a.rs", &good, &h), Vec::<String>::new());

    // a bare reference resolves against the documents the file names
    let bare = format!("//! (can-protocol.md)\n// {s}18 and {s}19.6\n");
    assert!(check_text("x/b.rs", &bare, &h).is_empty());
    let bare_unnamed = format!("// see {s}18\n");
    let p = check_text("x/c.rs", &bare_unnamed, &h);
    assert_eq!(p.len(), 1);
    assert!(
        p[0].starts_with("x/c.rs:1: `") && p[0].contains("names no docs file"),
        "{p:?}"
    );

    // missing sections, unknown documents, prefixes, signs without numbers, outside paths
    let wrong = format!(
        "//! can-protocol.md {s}2.9\n//! P{s}0 of WAIT_FOR\n//! foo.md {s}1\n//! X{s}2\n\
         //! data sheet {s}TXERR\n//! hub.md {s}1, {s}2\n//! see {s}3.3–3.7\n//! {s}9 of the plan? {s}1 of the plan\n\
         //! after {}/hub.md\n//! {s}5 of hub.md\n",
        ["/", "work"].concat()
    );
    let p = check_text("x/d.rs", &wrong, &h);
    let causes: Vec<&str> = p.iter().map(|l| l.as_str()).collect();
    let expect = [
        "x/d.rs:1: `can-protocol.md \u{a7}2.9`: can-protocol.md has no section 2.9",
        "x/d.rs:2: `P\u{a7}0`: can-protocol.md has no section 0",
        "x/d.rs:3: `foo.md \u{a7}1`: foo.md is not a file of docs/",
        "x/d.rs:4: `//! X\u{a7}2`: unknown prefix before the section sign (only P is defined)",
        "x/d.rs:5: `//! data sheet \u{a7}TXERR`: section sign without a section number (cite other documents in words)",
        "x/d.rs:6: `\u{a7}2`: hub.md has no section 2",
        "x/d.rs:7: `\u{a7}3.3–3.7`: no section 3.7 in the documents the file names (can-protocol.md, hub.md)",
        "x/d.rs:8: `\u{a7}1 of the plan`: conformance-tests.md has no section 1",
        "x/d.rs:10: `\u{a7}5 of hub.md`: hub.md has no section 5",
    ];
    for e in expect {
        assert!(causes.contains(&e), "missing {e:?} in {causes:#?}");
    }
    let outside = format!(
        "x/d.rs:9: `//! after {}/hub.md`: names a path outside the repository",
        ["/", "work"].concat()
    );
    assert!(
        causes.contains(&outside.as_str()),
        "missing {outside:?} in {causes:#?}"
    );
    assert_eq!(p.len(), expect.len() + 1, "{causes:#?}");

    // inside docs/ a bare reference means the same document only
    let in_docs = format!("See hub.md. Rule {s}2.3 here.\n");
    let p = check_text("docs/can-protocol.md", &in_docs, &h);
    assert!(p.is_empty(), "{p:?}");
    let p = check_text("docs/hub.md", &in_docs, &h);
    assert_eq!(p.len(), 1, "{p:?}");

    // headings: numbers, not inside code fences
    let md = "# Title\n## 1. One\n### 1.2 Sub\n```\n# 7 not a heading\n```\n## Notes 3\n#### 19.9 Verdict\n";
    assert_eq!(headings_of(md), secs(&["1", "1.2", "19.9"]));
}
