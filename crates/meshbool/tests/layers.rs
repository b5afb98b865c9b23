//! The library's layers. Each top-level module of `src/` uses only modules below it in
//! [`LAYERS`], so dependencies point down only and the modules form no cycle; within a
//! module directory, the files beside `mod.rs` form no cycle either. Uses are `crate::`
//! paths, `super::` paths, the items `lib.rs` and a directory's `mod.rs` re-export, and
//! the macros `lib.rs` defines; test code (`#[cfg(test)]` items, files named `tests.rs`
//! or `*_tests.rs`) and comments are left out. A failure lists every offending use with
//! its file and line.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The top-level modules of `src/`, bottom to top: each may use only those before it.
const LAYERS: &[&str] = &[
    // Plain values, errors, threads.
    "vec3",
    "format",
    "error",
    "par",
    // The exact kernel and the data model.
    "kernel",
    "welder",
    "mesh",
    "mesh_edit",
    // What every stage may need: extreme scales, stages and cancellation, edges.
    "scale",
    "stage",
    "edges",
    // Trees, the broad phase, measures, shapes.
    "bvh",
    "broad",
    "kept",
    "measure",
    "transform",
    "shapes",
    // The pipeline, in its order, with repair below the booleans that use it.
    "intersect",
    "arrange",
    "classify",
    "repair",
    "boolean",
    // Around the pipeline.
    "io",
    "query",
    // The front door, used by front ends only.
    "ops",
    // CSG documents, on the front door's booleans.
    "csg",
];

/// One use of a module by another.
#[derive(Debug)]
struct Use {
    from: String,
    to: String,
    file: PathBuf,
    line: usize,
}

impl Use {
    /// `file:line: from uses to`, the file relative to `src`.
    fn show(&self, src: &Path) -> String {
        let file = self.file.strip_prefix(src).unwrap_or(&self.file);
        format!(
            "{}:{}: {} uses {}",
            file.display(),
            self.line,
            self.from,
            self.to
        )
    }
}

/// A library file: its path, its module path (`["boolean", "nary"]`) and its code,
/// blanked ([`blank`]).
struct Source {
    file: PathBuf,
    module: Vec<String>,
    code: String,
}

#[test]
fn modules_use_only_modules_below_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let layer = |m: &str| LAYERS.iter().position(|&l| l == m);

    let tops = top_modules(&src);
    let unlisted: Vec<&String> = tops.iter().filter(|m| layer(m).is_none()).collect();
    let gone: Vec<&&str> = LAYERS
        .iter()
        .filter(|l| !tops.iter().any(|m| m == *l))
        .collect();
    assert!(unlisted.is_empty(), "modules not in LAYERS: {unlisted:?}");
    assert!(gone.is_empty(), "LAYERS names modules src/ lacks: {gone:?}");

    let mut up: Vec<String> = top_uses(&src)
        .iter()
        .filter(|u| layer(&u.to) >= layer(&u.from))
        .map(|u| u.show(&src))
        .collect();
    // One line for the several names of one `use`.
    up.dedup();
    assert!(
        up.is_empty(),
        "{} uses of a module not below the user (LAYERS, bottom to top: {}):\n{}",
        up.len(),
        LAYERS.join(", "),
        up.join("\n")
    );
}

#[test]
fn files_of_a_module_form_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let uses = sibling_uses(&src);
    let mut edges: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for u in &uses {
        edges.entry(&u.from).or_default().insert(&u.to);
    }
    // The uses whose two files reach each other.
    let reaches = |from: &str, to: &str| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from];
        while let Some(m) = stack.pop() {
            if m == to {
                return true;
            }
            if seen.insert(m) {
                stack.extend(edges.get(m).into_iter().flatten());
            }
        }
        false
    };
    let mut cyclic: Vec<String> = uses
        .iter()
        .filter(|u| reaches(&u.to, &u.from))
        .map(|u| u.show(&src))
        .collect();
    cyclic.dedup();
    assert!(
        cyclic.is_empty(),
        "{} uses on a cycle between files of one module:\n{}",
        cyclic.len(),
        cyclic.join("\n")
    );
}

/// The checker itself: `crate::` paths, groups, `super::` out of a module, `lib.rs`'s
/// re-exports and macros are seen; comments, strings and test items are not.
#[test]
fn checker_sees_every_kind_of_use() {
    let exports = BTreeMap::from([
        ("Mesh".to_string(), "mesh".to_string()),
        ("by_name".to_string(), "error".to_string()),
    ]);
    let text = r#"
use crate::{kernel::Point, bvh, Mesh};
// crate::ops in a comment
/// [`crate::ops::Cancel`]
fn f() -> crate::measure::Stats { let s = "crate::io"; let c = '"'; super::super::par::join() }
by_name!(Format, "format");
#[cfg(test)]
mod tests {
    use crate::ops;
}
#[cfg(test)]
use crate::query;
fn g<'a>(x: &'a str) -> crate::shapes::Shape { super::sides::f(); todo!() }
"#;
    let module = ["boolean".to_string(), "nary".to_string()];
    let code = blank(text);
    let found: Vec<(String, usize)> = paths_in(&code, &module, &exports)
        .into_iter()
        .map(|(path, line)| (path.join("::"), line))
        .collect();
    let want = [
        ("kernel::Point", 2),
        ("bvh", 2),
        ("Mesh", 2),
        ("measure::Stats", 5),
        ("par::join", 5),
        ("by_name", 6),
        ("shapes::Shape", 13),
        ("boolean::sides::f", 13),
    ];
    let want: Vec<(String, usize)> = want.iter().map(|&(m, l)| (m.to_string(), l)).collect();
    assert_eq!(found, want);
}

/// The top-level modules: the files and directories of `src/` other than `lib.rs` and
/// test files.
fn top_modules(src: &Path) -> BTreeSet<String> {
    sources(src)
        .into_iter()
        .map(|s| s.module[0].clone())
        .collect()
}

/// Whether a file (or directory) of this stem holds tests only.
fn is_test_file(stem: &str) -> bool {
    stem == "tests" || stem.ends_with("_tests") || stem == "test_util"
}

/// The library's files other than `lib.rs` and test files, blanked ([`blank`]), by path.
fn sources(src: &Path) -> Vec<Source> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files.sort();
    let mut out = Vec::new();
    for file in files {
        let rel = file.strip_prefix(src).expect("under src/");
        let mut module: Vec<String> = rel
            .iter()
            .map(|p| p.to_str().expect("UTF-8 path").to_string())
            .collect();
        let last = module.pop().expect("a file name");
        let stem = last.trim_end_matches(".rs");
        let is_lib = module.is_empty() && stem == "lib";
        if is_lib || is_test_file(stem) || module.iter().any(|m| is_test_file(m)) {
            continue;
        }
        if stem != "mod" {
            module.push(stem.to_string());
        }
        let code = blank(&fs::read_to_string(&file).expect("source is readable"));
        out.push(Source { file, module, code });
    }
    out
}

/// Every use of one top-level module by another, in file order.
fn top_uses(src: &Path) -> Vec<Use> {
    let lib = blank(&fs::read_to_string(src.join("lib.rs")).expect("lib.rs is readable"));
    let exports = exports(&lib);
    let sources = sources(src);
    let tops: BTreeSet<&String> = sources.iter().map(|s| &s.module[0]).collect();
    let mut out = Vec::new();
    for s in &sources {
        let from = &s.module[0];
        for (path, line) in paths_in(&s.code, &s.module, &exports) {
            // Other names are `lib.rs`'s own items.
            let to = exports.get(&path[0]).unwrap_or(&path[0]);
            if to != from && tops.contains(to) {
                out.push(Use {
                    from: from.clone(),
                    to: to.clone(),
                    file: s.file.clone(),
                    line,
                });
            }
        }
    }
    out
}

/// Every use of a file of a module directory by another file of it (beside `mod.rs`:
/// the parent, which may use its files, and which they may use), through paths into the
/// sibling or the items `mod.rs` re-exports from it. Named `dir::file`.
fn sibling_uses(src: &Path) -> Vec<Use> {
    let sources = sources(src);
    let none = BTreeMap::new();
    let mut out = Vec::new();
    for parent in sources.iter().filter(|s| !s.module.is_empty()) {
        let depth = parent.module.len();
        let children: Vec<&Source> = sources
            .iter()
            .filter(|s| s.module.len() == depth + 1 && s.module.starts_with(&parent.module))
            .collect();
        if children.is_empty() {
            continue;
        }
        let is_child = |m: &str| children.iter().any(|c| c.module[depth] == m);
        let name = parent.module.join("::");
        // The items `mod.rs` brings in from its files, by the file.
        let mut from_child = BTreeMap::new();
        for (path, _) in use_trees(&parent.code) {
            let path: Vec<&String> = match path.first().map(String::as_str) {
                Some("crate") if path[1..].starts_with(&parent.module) => path[1 + depth..].iter(),
                _ => path.iter(),
            }
            .collect();
            if path.len() > 1 && is_child(path[0]) {
                from_child.insert(path[path.len() - 1].clone(), path[0].clone());
            }
        }
        for child in &children {
            for (path, line) in paths_in(&child.code, &child.module, &none) {
                if path.len() < depth + 1 || !path.starts_with(&parent.module) {
                    continue;
                }
                let to = match is_child(&path[depth]) {
                    true => &path[depth],
                    false => match from_child.get(&path[depth]) {
                        Some(c) => c,
                        None => continue,
                    },
                };
                if *to != child.module[depth] {
                    out.push(Use {
                        from: format!("{name}::{}", child.module[depth]),
                        to: format!("{name}::{to}"),
                        file: child.file.clone(),
                        line,
                    });
                }
            }
        }
    }
    out
}

/// The `.rs` files under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("directory is readable") {
        let path = entry.expect("directory is readable").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module behind each name `lib.rs` re-exports (`pub use m::{A, B}`) and
/// each macro it defines (the modules the macro's body names), from its blanked text.
fn exports(lib: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for stmt in lib.split(';') {
        let stmt = stmt.trim();
        let Some(rest) = stmt
            .strip_prefix("pub use ")
            .or_else(|| stmt.strip_prefix("pub(crate) use "))
        else {
            continue;
        };
        let Some((module, names)) = rest.split_once("::") else {
            continue;
        };
        for name in names.trim_matches(|c| c == '{' || c == '}').split(',') {
            let name = name.trim();
            if !name.is_empty() {
                out.insert(name.to_string(), module.trim().to_string());
            }
        }
    }
    // A macro counts as the first module its body names through `crate::`.
    let mut rest = lib;
    while let Some(at) = rest.find("macro_rules!") {
        rest = &rest[at + "macro_rules!".len()..];
        let name: String = rest
            .trim_start()
            .chars()
            .take_while(|&c| is_ident(c))
            .collect();
        let body = &rest[..rest.find("macro_rules!").unwrap_or(rest.len())];
        if let Some(module) = body
            .match_indices("crate::")
            .map(|(i, _)| ident_at(&body[i + "crate::".len()..]))
            .find(|m| m.chars().next().is_some_and(|c| c.is_lowercase()))
        {
            out.insert(name, module);
        }
    }
    out
}

/// The paths that `code` (blanked), the file of module `module`, names from the crate
/// root (`crate::` paths, and `super::` paths resolved from `module`), each with its
/// line: one path per leaf of a `use` tree, as far as its leading names go (`crate::a::{b,
/// c::D}`: `a::b`, `a::c::D`). A call of a macro that `lib.rs` defines (`exports`) is a
/// path of its name.
fn paths_in(
    code: &str,
    module: &[String],
    exports: &BTreeMap<String, String>,
) -> Vec<(Vec<String>, usize)> {
    let line_of = |at: usize| code[..at].matches('\n').count() + 1;
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < code.len() {
        let rest = &code[i..];
        let starts = i == 0 || !is_ident(bytes[i - 1] as char) && !b":$".contains(&bytes[i - 1]);
        let name = ident_at(rest);
        if !starts || name.is_empty() {
            i += rest.chars().next().map_or(1, char::len_utf8);
            continue;
        }
        let after = &rest[name.len()..];
        let root: Option<(Vec<String>, &str)> = match name.as_str() {
            "crate" => after.strip_prefix("::").map(|p| (Vec::new(), p)),
            "super" => {
                let mut p = after;
                let mut k = 1;
                while let Some(q) = p.strip_prefix("::super") {
                    p = q;
                    k += 1;
                }
                let base = module[..module.len().saturating_sub(k)].to_vec();
                p.strip_prefix("::").map(|p| (base, p))
            }
            _ if after.starts_with('!') && exports.contains_key(&name) => {
                out.push((vec![name.clone()], line_of(i)));
                None
            }
            _ => None,
        };
        if let Some((base, p)) = root {
            let at = code.len() - p.len();
            for (mut path, off) in tree(p) {
                let mut full = base.clone();
                full.append(&mut path);
                out.push((full, line_of(at + off)));
            }
            i = at;
        } else {
            i += name.len();
        }
    }
    out
}

/// The trees of the `use` declarations in `code` (blanked), as [`tree`] gives them.
fn use_trees(code: &str) -> Vec<(Vec<String>, usize)> {
    let bytes = code.as_bytes();
    code.match_indices("use ")
        .filter(|&(i, _)| i == 0 || !is_ident(bytes[i - 1] as char))
        .flat_map(|(i, _)| tree(&code[i + 4..]))
        .collect()
}

/// The leaves of the path or `use` tree at the start of `p` (after a `crate::`): each as
/// its names, with the offset in `p` where it starts.
fn tree(p: &str) -> Vec<(Vec<String>, usize)> {
    let mut out = Vec::new();
    tree_at(p, 0, Vec::new(), &mut out);
    out
}

/// [`tree`] from offset `at` of `p`, under the names `prefix`; returns where it ends.
fn tree_at(p: &str, at: usize, prefix: Vec<String>, out: &mut Vec<(Vec<String>, usize)>) -> usize {
    let skip = |k: usize| k + p[k..].len() - p[k..].trim_start().len();
    let mut k = skip(at);
    if p[k..].starts_with('{') {
        k += 1;
        loop {
            k = skip(k);
            if k >= p.len() || p[k..].starts_with('}') {
                return k + 1;
            }
            let next = tree_at(p, k, prefix.clone(), out);
            // Past what is no name (`*`).
            k = skip(next.max(k + 1));
            if p[k..].starts_with(',') {
                k += 1;
            }
        }
    }
    let name = ident_at(&p[k..]);
    if name.is_empty() {
        return k;
    }
    let start = k;
    k += name.len();
    let mut path = prefix;
    if name != "self" {
        path.push(name);
    }
    if p[k..].starts_with("::") {
        let before = out.len();
        let end = tree_at(p, k + 2, path.clone(), out);
        // A leaf whose next part is no name (`a::*`, `a::<T>`): the path so far.
        if out.len() == before && !path.is_empty() {
            out.push((path, start));
        }
        return end;
    }
    // A leaf renamed (`a as b`) keeps its own name.
    if !path.is_empty() {
        out.push((path, start));
    }
    k
}

/// The identifier at the start of `s` (empty when none).
fn ident_at(s: &str) -> String {
    s.chars().take_while(|&c| is_ident(c)).collect()
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// `text` with comments, string and character literals and `#[cfg(test)]` items
/// replaced by spaces (line breaks kept, so that offsets keep their lines).
fn blank(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out: Vec<char> = chars.clone();
    let wipe = |out: &mut Vec<char>, from: usize, to: usize| {
        for c in &mut out[from..to.min(chars.len())] {
            if *c != '\n' {
                *c = ' ';
            }
        }
    };
    let n = chars.len();
    let at = |i: usize, s: &str| {
        s.chars()
            .enumerate()
            .all(|(k, c)| chars.get(i + k) == Some(&c))
    };
    let mut i = 0;
    while i < n {
        let start = i;
        if at(i, "//") {
            while i < n && chars[i] != '\n' {
                i += 1;
            }
            wipe(&mut out, start, i);
        } else if at(i, "/*") {
            let mut depth = 0;
            while i < n {
                if at(i, "/*") {
                    depth += 1;
                    i += 2;
                } else if at(i, "*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            wipe(&mut out, start, i);
        } else if chars[i] == 'r'
            && (i == 0 || !is_ident(chars[i - 1]))
            && matches!(chars.get(i + 1), Some('"' | '#'))
        {
            // A raw string: r"..." or r#"..."#.
            let mut j = i + 1;
            while chars.get(j) == Some(&'#') {
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat_n('#', j - i - 1))
                .collect();
            i = j + 1;
            while i < n && !at(i, &close) {
                i += 1;
            }
            i += close.chars().count();
            wipe(&mut out, start + 1, i);
        } else if chars[i] == '"' {
            i += 1;
            while i < n && chars[i] != '"' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            wipe(&mut out, start + 1, i - 1);
        } else if chars[i] == '\'' {
            // A character literal ('x', '\n', '\u{..}'), else a lifetime.
            if chars.get(i + 1) == Some(&'\\') {
                i += 2;
                while i < n && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
                wipe(&mut out, start + 1, i - 1);
            } else if chars.get(i + 2) == Some(&'\'') {
                i += 3;
                wipe(&mut out, start + 1, i - 1);
            } else {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    // Test items: the item after `#[cfg(test)]` (and any further attributes), to its
    // `;` or its closing brace.
    let mut s: String = out.into_iter().collect();
    while let Some(at) = s.find("#[cfg(test)]") {
        let b = s.as_bytes();
        let mut j = at;
        let mut depth = 0i32;
        let mut seen_brace = false;
        while j < b.len() {
            match b[j] {
                b'{' | b'(' | b'[' => {
                    depth += 1;
                    seen_brace |= b[j] == b'{';
                }
                b'}' | b')' | b']' => {
                    depth -= 1;
                    // The end of the enclosing item: the test item was a field.
                    if depth < 0 {
                        break;
                    }
                    if depth == 0 && b[j] == b'}' && seen_brace {
                        j += 1;
                        break;
                    }
                }
                b';' | b',' if depth == 0 => {
                    j += 1;
                    break;
                }
                _ => {}
            }
            j += 1;
        }
        let wiped: String = s[at..j]
            .chars()
            .map(|c| if c == '\n' { '\n' } else { ' ' })
            .collect();
        s.replace_range(at..j, &wiped);
    }
    s
}
