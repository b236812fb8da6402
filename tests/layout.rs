//! The layout rules the repository keeps (README "Layout"):
//!
//! - dependencies between the files of a crate point one way: no cycle among the
//!   modules through `crate::` paths (comments and `#[cfg(test)] mod tests` blocks are
//!   not counted);
//! - no source file is included twice through `#[path]`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if p.is_dir() {
            if name != "target" && !name.starts_with('.') {
                rust_files(&p, out);
            }
        } else if name.ends_with(".rs") {
            out.push(p);
        }
    }
}

/// The crates of the workspace: directories with a Cargo.toml and a src/.
fn crate_srcs() -> Vec<PathBuf> {
    let r = root();
    let mut v = vec![r.join("src")];
    for e in std::fs::read_dir(&r).unwrap().flatten() {
        let p = e.path();
        if p.join("Cargo.toml").is_file() && p.join("src").is_dir() {
            v.push(p.join("src"));
        }
    }
    v
}

/// Module path of a source file relative to its crate's `src/`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    if matches!(parts.last().map(|s| s.as_str()), Some("lib" | "main" | "mod")) {
        parts.pop();
    }
    parts
}

/// The code of a file without comment lines and without its unit-test module.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    text.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n")
}

/// `crate::a::b::c` paths in `code`, as segment lists.
fn crate_paths(code: &str) -> Vec<Vec<String>> {
    let mut v = vec![];
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().last();
        rest = &rest[i + 7..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let path: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':').collect();
        v.push(path.split("::").filter(|s| !s.is_empty()).map(str::to_string).collect());
    }
    v
}

/// Strongly connected components with more than one module (Tarjan).
fn cycles(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    struct T<'a> {
        e: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        idx: BTreeMap<&'a Vec<String>, usize>,
        low: BTreeMap<&'a Vec<String>, usize>,
        stack: Vec<&'a Vec<String>>,
        on: BTreeSet<&'a Vec<String>>,
        n: usize,
        out: Vec<Vec<Vec<String>>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a Vec<String>) {
        t.idx.insert(v, t.n);
        t.low.insert(v, t.n);
        t.n += 1;
        t.stack.push(v);
        t.on.insert(v);
        for w in t.e.get(v).into_iter().flatten() {
            let Some((w, _)) = t.e.get_key_value(w) else { continue };
            if !t.idx.contains_key(w) {
                visit(t, w);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.idx[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.idx[v] {
            let mut comp = vec![];
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                comp.push(w.clone());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                t.out.push(comp);
            }
        }
    }
    let mut t = T { e: edges, idx: BTreeMap::new(), low: BTreeMap::new(), stack: vec![], on: BTreeSet::new(), n: 0, out: vec![] };
    for v in edges.keys() {
        if !t.idx.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.out
}

fn module_graph(src: &Path) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let mut files = vec![];
    rust_files(src, &mut files);
    let mods: BTreeMap<Vec<String>, PathBuf> = files.iter().map(|f| (module_of(src, f), f.clone())).collect();
    let mut edges = BTreeMap::new();
    for (m, f) in &mods {
        let text = std::fs::read_to_string(f).unwrap();
        let mut deps = BTreeSet::new();
        for p in crate_paths(&code(&text)) {
            // the longest prefix that is a module (file) of this crate
            if let Some(k) = (1..=p.len()).rev().find(|&k| mods.contains_key(&p[..k])) {
                if p[..k] != m[..] {
                    deps.insert(p[..k].to_vec());
                }
            }
        }
        edges.insert(m.clone(), deps);
    }
    edges
}

#[test]
fn no_import_cycle_between_files() {
    let mut bad = vec![];
    for src in crate_srcs() {
        for comp in cycles(&module_graph(&src)) {
            let names: Vec<String> = comp.iter().map(|m| if m.is_empty() { "lib".into() } else { m.join("::") }).collect();
            bad.push(format!("{}: {}", src.display(), names.join(" <-> ")));
        }
    }
    assert!(bad.is_empty(), "import cycles:\n{}", bad.join("\n"));
}

#[test]
fn the_cycle_finder_finds_a_cycle() {
    let m = |s: &str| s.split("::").map(str::to_string).collect::<Vec<_>>();
    let mut e = BTreeMap::new();
    e.insert(m("a"), BTreeSet::from([m("b")]));
    e.insert(m("b"), BTreeSet::from([m("c")]));
    e.insert(m("c"), BTreeSet::from([m("a")]));
    e.insert(m("d"), BTreeSet::from([m("a")]));
    let c = cycles(&e);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].len(), 3);
    assert_eq!(crate_paths("use crate::kernel::Sim; x = my_crate::y; crate::vcd"), vec![m("kernel::Sim"), m("vcd")]);
}

#[test]
fn no_path_includes() {
    let mut files = vec![];
    rust_files(&root(), &mut files);
    let me = Path::new(file!()).file_name().unwrap().to_owned();
    let bad: Vec<String> = files
        .iter()
        .filter(|f| f.file_name() != Some(&me))
        .filter(|f| std::fs::read_to_string(f).unwrap().lines().any(|l| l.trim_start().starts_with("#[path")))
        .map(|f| f.display().to_string())
        .collect();
    assert!(bad.is_empty(), "#[path] includes in {bad:?}");
}
