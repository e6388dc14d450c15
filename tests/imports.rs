//! The modules of `src/` do not import each other in a circle: for every pair of modules
//! that are not parent and child, the `crate::…` and `super::…` paths of their files (and the
//! items a parent re-exports from a child) give a graph with no cycle. A parent's `mod` and
//! `pub use` of its children, and a child's use of its parent's own items, are not edges.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

type Module = Vec<String>;

fn modules(dir: &Path, prefix: &Module, out: &mut BTreeMap<Module, String>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        let name = p.file_stem().unwrap().to_string_lossy().to_string();
        if p.is_dir() {
            let mut m = prefix.clone();
            m.push(p.file_name().unwrap().to_string_lossy().to_string());
            modules(&p, &m, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let m = match name.as_str() {
                "mod" | "lib" => prefix.clone(),
                "main" => continue,
                _ => {
                    let mut m = prefix.clone();
                    m.push(name);
                    m
                }
            };
            out.insert(m, std::fs::read_to_string(&p).unwrap());
        }
    }
}

/// The paths a text names after `crate::` or `super::`, as identifiers.
fn paths(text: &str, root: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(root) {
        let before = rest[..at].chars().last();
        rest = &rest[at + root.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let mut path = Vec::new();
        let mut s = rest;
        loop {
            let n = s
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(s.len());
            if n == 0 {
                break;
            }
            path.push(s[..n].to_string());
            s = &s[n..];
            if let Some(t) = s.strip_prefix("::") {
                s = t;
            } else {
                break;
            }
        }
        if !path.is_empty() {
            out.push(path.clone());
        }
        // `super::{a, b::c}`: each item of the group.
        if let Some(group) = s.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let item = item.trim();
                let first: String = item
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !first.is_empty() {
                    let mut p = path.clone();
                    p.push(first);
                    out.push(p);
                }
            }
        }
    }
    out
}

/// Items a module re-exports from one of its children (`pub use child::{A, B}`).
fn reexports(module: &Module, text: &str) -> BTreeMap<String, Module> {
    let mut out = BTreeMap::new();
    for stmt in text.split(';') {
        let stmt = stmt.trim();
        let Some(rest) = stmt.strip_prefix("pub use ") else {
            continue;
        };
        let Some((child, items)) = rest.split_once("::") else {
            continue;
        };
        if child == "crate" || child == "super" || child == "self" {
            continue;
        }
        let mut m = module.clone();
        m.push(child.trim().to_string());
        let items = items.trim().trim_start_matches('{').trim_end_matches('}');
        for item in items.split(',') {
            let name = item.split_whitespace().last().unwrap_or("").trim();
            if !name.is_empty() {
                out.insert(name.to_string(), m.clone());
            }
        }
    }
    out
}

fn is_prefix(a: &Module, b: &Module) -> bool {
    a.len() <= b.len() && b[..a.len()] == a[..]
}

#[test]
fn no_module_of_src_imports_another_in_a_circle() {
    let mut files = BTreeMap::new();
    modules(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &Vec::new(),
        &mut files,
    );
    let re: BTreeMap<Module, BTreeMap<String, Module>> = files
        .iter()
        .map(|(m, t)| (m.clone(), reexports(m, t)))
        .collect();
    // The module a path lands in: its longest prefix that is a module, or the child its
    // first item beyond that was re-exported from.
    let resolve = |path: &[String]| -> Option<Module> {
        let mut best: Option<Module> = None;
        for k in (0..=path.len()).rev() {
            let m: Module = path[..k].to_vec();
            if files.contains_key(&m) {
                best = Some(m);
                break;
            }
        }
        let m = best?;
        if let Some(item) = path.get(m.len()) {
            if let Some(child) = re.get(&m).and_then(|r| r.get(item)) {
                return Some(child.clone());
            }
        }
        Some(m)
    };
    let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (m, text) in &files {
        let is_mod_rs = files
            .keys()
            .any(|k| k.len() == m.len() + 1 && is_prefix(m, k))
            || m.is_empty();
        let parent: Module = if is_mod_rs || m.is_empty() {
            m.iter().take(m.len().saturating_sub(1)).cloned().collect()
        } else {
            m[..m.len() - 1].to_vec()
        };
        let mut targets = Vec::new();
        for p in paths(text, "crate::") {
            targets.push(p);
        }
        for p in paths(text, "super::") {
            let mut full = parent.clone();
            full.extend(p);
            targets.push(full);
        }
        for t in targets {
            if let Some(n) = resolve(&t) {
                if &n != m && !is_prefix(&n, m) && !is_prefix(m, &n) {
                    edges.entry(m.clone()).or_default().insert(n);
                }
            }
        }
    }
    // A cycle: a module that reaches itself.
    let mut circles = Vec::new();
    for start in files.keys() {
        let mut seen = BTreeSet::new();
        let mut stack: Vec<Module> = edges.get(start).into_iter().flatten().cloned().collect();
        while let Some(n) = stack.pop() {
            if &n == start {
                circles.push(start.join("::"));
                break;
            }
            if seen.insert(n.clone()) {
                stack.extend(edges.get(&n).into_iter().flatten().cloned());
            }
        }
    }
    assert!(
        circles.is_empty(),
        "modules on an import circle: {circles:?}"
    );
}
