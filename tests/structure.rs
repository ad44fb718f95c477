//! The workspace's structure: no two files import each other, directly or around a circle.
//!
//! Every crate's files are read as text: each path through `crate::`, `super::` or `self::`
//! (in a `use` or in code, tests left out) is resolved to the file that defines the name,
//! following a module's `pub use` re-exports to their source. A module's own declarations and
//! re-exports of its submodules are its facade, not an import. The graph of files must have no
//! cycle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A crate's files by module path (`[]` the root, `["studies"]` for `studies/mod.rs`).
struct Crate {
    files: BTreeMap<Vec<String>, String>,
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The code of a file without comments and without its test module.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

impl Crate {
    fn read(src: &Path) -> Crate {
        let mut paths = Vec::new();
        rust_files(src, &mut paths);
        let files = paths
            .into_iter()
            .map(|p| {
                let rel = p.strip_prefix(src).unwrap().with_extension("");
                let mut module: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                if matches!(
                    module.last().map(String::as_str),
                    Some("lib" | "main" | "mod")
                ) {
                    module.pop();
                }
                (module, code(&std::fs::read_to_string(&p).unwrap()))
            })
            .collect();
        Crate { files }
    }

    /// The module a path of `segments` names, starting from `module`, and the item after it.
    fn resolve(&self, module: &[String], segments: &[String]) -> (Vec<String>, Option<String>) {
        let mut at = module.to_vec();
        for (k, s) in segments.iter().enumerate() {
            let mut next = at.clone();
            next.push(s.clone());
            if !self.files.contains_key(&next) {
                return (at, Some(segments[k].clone()));
            }
            at = next;
        }
        (at, None)
    }

    /// The file that defines `item` of `module`: the module itself, or the source of its
    /// `pub use` of that name.
    fn defining(&self, module: Vec<String>, item: Option<String>, depth: usize) -> Vec<String> {
        let (Some(item), Some(text)) = (item, self.files.get(&module)) else {
            return module;
        };
        if depth > 8 {
            return module;
        }
        for (start, segments) in paths(text, &module) {
            let is_reexport = text[..start].trim_end().ends_with("pub use");
            if is_reexport && segments.last() == Some(&item) {
                let (m, i) = self.resolve(&[], &segments);
                return self.defining(m, i, depth + 1);
            }
        }
        module
    }

    /// Every file's imports of other files, by module path.
    fn imports(&self) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
        let mut graph = BTreeMap::new();
        for (module, text) in &self.files {
            let mut to = BTreeSet::new();
            for (_, segments) in paths(text, module) {
                let (m, item) = self.resolve(&[], &segments);
                let target = self.defining(m, item, 0);
                // Itself, or its own submodules (its facade).
                if !target.starts_with(module) {
                    to.insert(target);
                }
            }
            graph.insert(module.clone(), to);
        }
        graph
    }
}

/// Every path through `crate::`, `super::` or `self::` in `text` (the code of `module`), as
/// absolute segments from the crate root, with the offset where it starts; a braced group
/// `a::{b, c::d}` gives one path per member.
fn paths(text: &str, module: &[String]) -> Vec<(usize, Vec<String>)> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    for root in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(i) = text[from..].find(root).map(|i| i + from) {
            from = i + root.len();
            if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_') {
                continue;
            }
            let mut base: Vec<String> = match root {
                "crate::" => Vec::new(),
                "super::" => module[..module.len().saturating_sub(1)].to_vec(),
                _ => module.to_vec(),
            };
            let rest = &text[from..];
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(rest.len());
            let head = &rest[..end];
            let mut parts: Vec<String> = head
                .split("::")
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect();
            while parts.first().is_some_and(|p| p == "super") {
                parts.remove(0);
                base.pop();
            }
            base.extend(parts);
            if rest[end..].starts_with('{') {
                let close = rest[end..].find('}').map_or(rest.len(), |c| end + c);
                for member in rest[end + 1..close].split(',') {
                    let member = member.split(" as ").next().unwrap_or("").trim();
                    if member.is_empty() || member == "self" || member == "*" {
                        continue;
                    }
                    let mut p = base.clone();
                    p.extend(member.split("::").map(str::to_string));
                    out.push((i, p));
                }
            } else {
                out.push((i, base));
            }
        }
    }
    out
}

/// A cycle of `graph`, if it has one.
fn cycle(graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Option<Vec<Vec<String>>> {
    fn visit(
        node: &Vec<String>,
        graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        state: &mut BTreeMap<Vec<String>, u8>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        state.insert(node.clone(), 1);
        stack.push(node.clone());
        for next in graph.get(node).into_iter().flatten() {
            match state.get(next) {
                Some(1) => {
                    let at = stack.iter().position(|n| n == next).unwrap();
                    return Some(stack[at..].to_vec());
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(next, graph, state, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        state.insert(node.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for node in graph.keys() {
        if !state.contains_key(node) {
            if let Some(c) = visit(node, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn crate_roots() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut roots = vec![root.join("src"), root.join("python/src")];
    for entry in std::fs::read_dir(root.join("crates")).unwrap() {
        roots.push(entry.unwrap().path().join("src"));
    }
    roots.sort();
    roots
}

#[test]
fn no_file_imports_another_that_imports_it_back() {
    for src in crate_roots() {
        let c = Crate::read(&src);
        let graph = c.imports();
        if let Some(circle) = cycle(&graph) {
            let names: Vec<String> = circle.iter().map(|m| m.join("/")).collect();
            panic!("{}: import cycle {}", src.display(), names.join(" -> "));
        }
    }
}

#[test]
fn the_check_finds_a_cycle_where_there_is_one() {
    // Two files that take a name each from the other, and a module that re-exports a name of
    // its child, which a sibling imports: a cycle a <-> b, none through the facade.
    let files = [
        (
            vec!["a".to_string()],
            "use crate::b::B;\npub struct A;".to_string(),
        ),
        (
            vec!["b".to_string()],
            "use crate::a::A;\npub struct B;".to_string(),
        ),
        (
            vec!["m".to_string()],
            "mod c;\npub use self::c::C;\npub fn f() {}".to_string(),
        ),
        (
            vec!["m".to_string(), "c".to_string()],
            "use super::f;\npub struct C;".to_string(),
        ),
        (vec!["d".to_string()], "use crate::m::C;".to_string()),
    ];
    let c = Crate {
        files: files.into_iter().collect(),
    };
    let graph = c.imports();
    let to = |m: &str| graph[&vec![m.to_string()]].clone();
    assert_eq!(
        to("d"),
        BTreeSet::from([vec!["m".to_string(), "c".to_string()]])
    );
    assert!(to("m").is_empty(), "{:?}", to("m"));
    let circle = cycle(&graph).expect("a <-> b");
    assert_eq!(circle, [vec!["a".to_string()], vec!["b".to_string()]]);
}
