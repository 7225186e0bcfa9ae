//! No import cycle among the modules of `src/`, at file level.
//!
//! Reads every `.rs` file under `src/`, takes every path that starts with `crate::`, `super::` or
//! `self::` in its code (in `use` items, grouped or not, and inline in expressions and types),
//! resolves each to the deepest module file it names and fails if the resulting graph of files has
//! a strongly connected component of more than one file. `mod x;` declarations are not edges;
//! `pub use x::Y;` re-exports are. Comments, string and character literals are ignored, and a
//! file is read only up to a line `#[cfg(test)]` (unit tests may import anything).
//!
//! Std only, and independent of the slipfront crate, so it also compiles on its own:
//! `rustc --edition 2024 --test tests/module_graph.rs -o /tmp/mg && CARGO_MANIFEST_DIR=. /tmp/mg --nocapture`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// One source file: its path relative to the crate's directory (`src/a/b.rs`) and its text.
type SourceFile = (String, String);

/// The graph of files: `files[i]` imports `files[j]` for every `j` in `edges[i]`, and
/// `via[(i, j)]` is one path in `files[i]` that makes that edge (for the report).
struct ModuleGraph {
    files: Vec<String>,
    edges: Vec<BTreeSet<usize>>,
    via: BTreeMap<(usize, usize), String>,
}

impl ModuleGraph {
    fn edge_count(&self) -> usize {
        self.edges.iter().map(BTreeSet::len).sum()
    }
}

/// Reads every `.rs` file under `dir`, sorted, with paths relative to `root` and `/` separators.
fn read_rs_files(root: &Path, dir: &Path, out: &mut Vec<SourceFile>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            read_rs_files(root, &path, out);
        } else if path.extension().is_some_and(|x| x == "rs") {
            let rel = path.strip_prefix(root).expect("under the root");
            let rel = rel.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/");
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {rel}: {e}"));
            out.push((rel, text));
        }
    }
}

/// The module path of a file: `src/lib.rs` and `src/main.rs` are the crate root (`[]`),
/// `src/a/mod.rs` is `[a]`, `src/a/b.rs` is `[a, b]`. `None` for a file outside `src/`.
fn module_path_of(file: &str) -> Option<Vec<String>> {
    let rest = file.strip_prefix("src/")?.strip_suffix(".rs")?;
    if rest == "lib" || rest == "main" {
        return Some(Vec::new());
    }
    let mut parts: Vec<String> = rest.split('/').map(str::to_owned).collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    Some(parts)
}

/// The end (exclusive) of a raw string literal that starts at `i` (`r"`, `r#"`, `br##"`, `cr"`),
/// or `None` if no raw string starts there. Proves raw strings are skipped whole even when they
/// hold `"` or `//`.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    let mut j = i;
    if matches!(c.get(j), Some('b' | 'c')) {
        j += 1;
    }
    if c.get(j) != Some(&'r') || (i > 0 && is_ident_char(c[i - 1])) {
        return None;
    }
    j += 1;
    let hashes = c[j..].iter().take_while(|&&ch| ch == '#').count();
    j += hashes;
    if c.get(j) != Some(&'"') {
        return None;
    }
    j += 1;
    while j < c.len() {
        if c[j] == '"' && c[j + 1..].iter().take(hashes).filter(|&&ch| ch == '#').count() == hashes {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(c.len())
}

/// The end (exclusive) of the comment, string or character literal that starts at `i`, or `None`
/// if code starts there (a lifetime `'a` is code). Nested block comments are skipped whole.
fn literal_or_comment_end(c: &[char], i: usize) -> Option<usize> {
    let at = |k: usize| c.get(k).copied();
    match (c[i], at(i + 1)) {
        ('/', Some('/')) => Some(c[i..].iter().position(|&ch| ch == '\n').map_or(c.len(), |p| i + p)),
        ('/', Some('*')) => {
            let (mut depth, mut j) = (0usize, i);
            while j < c.len() {
                if c[j] == '/' && at(j + 1) == Some('*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && at(j + 1) == Some('/') {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        return Some(j);
                    }
                } else {
                    j += 1;
                }
            }
            Some(c.len())
        }
        ('"', _) => {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            Some((j + 1).min(c.len()))
        }
        ('\'', Some('\\')) => Some(c[i + 3..].iter().position(|&ch| ch == '\'').map_or(c.len(), |p| i + 4 + p)),
        ('\'', Some(_)) if at(i + 2) == Some('\'') => Some(i + 3),
        ('r' | 'b' | 'c', _) => raw_string_end(c, i),
        _ => None,
    }
}

/// The code of a file: read up to the first line that is `#[cfg(test)]`, with comments, string
/// and character literals replaced by blanks (newlines kept), so that no path in a comment, doc
/// comment or string can make an edge.
fn strip_code(text: &str) -> String {
    let mut kept = String::new();
    for line in text.lines() {
        if line.trim() == "#[cfg(test)]" {
            break;
        }
        kept.push_str(line);
        kept.push('\n');
    }
    let c: Vec<char> = kept.chars().collect();
    let mut out = String::with_capacity(c.len());
    let mut i = 0;
    while i < c.len() {
        match literal_or_comment_end(&c, i) {
            Some(end) => {
                out.extend(c[i..end].iter().map(|&ch| if ch == '\n' { '\n' } else { ' ' }));
                i = end;
            }
            None => {
                out.push(c[i]);
                i += 1;
            }
        }
    }
    out
}

fn is_ident_char(ch: char) -> bool {
    ch.is_alphanumeric() || ch == '_'
}

/// Splits code into identifiers (`r#x` becomes `x`), `::` and single punctuation characters.
fn tokenize(code: &str) -> Vec<String> {
    let c: Vec<char> = code.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < c.len() {
        if c[i].is_whitespace() {
            i += 1;
        } else if is_ident_char(c[i]) {
            let start = i;
            while i < c.len() && is_ident_char(c[i]) {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            if word == "r" && c.get(i) == Some(&'#') && c.get(i + 1).is_some_and(|&ch| is_ident_char(ch)) {
                i += 1;
                continue; // raw identifier: the next word is the name
            }
            tokens.push(word);
        } else if c[i] == ':' && c.get(i + 1) == Some(&':') {
            tokens.push("::".to_owned());
            i += 2;
        } else {
            tokens.push(c[i].to_string());
            i += 1;
        }
    }
    tokens
}

/// Parses the path (or `use` tree) that starts at `tokens[i]` after `prefix`, pushing every full
/// path it names into `out` (`a::{b::{C, D}, e}` gives `a::b::C`, `a::b::D`, `a::e`). Returns
/// the index after the tree. A path ends at the first token that is neither a segment nor `::`
/// (`<`, `(`, `;`, `as`…), so inline paths like `crate::a::B::<T>::new()` give `crate::a::B`.
fn parse_tree(tokens: &[String], mut i: usize, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
    let mut path = prefix.to_vec();
    loop {
        match tokens.get(i).map(String::as_str) {
            Some("{") => {
                i += 1;
                while i < tokens.len() && tokens[i] != "}" {
                    i = parse_tree(tokens, i, &path, out);
                    while i < tokens.len() && tokens[i] != "," && tokens[i] != "}" {
                        i += 1; // `as Name`, or anything unexpected
                    }
                    if tokens.get(i).is_some_and(|t| t == ",") {
                        i += 1;
                    }
                }
                return i + 1;
            }
            Some(t) if t.chars().next().is_some_and(is_ident_char) => {
                if t != "self" || path.is_empty() {
                    path.push(t.to_owned()); // `a::{self, B}`: `self` is `a` itself
                }
                i += 1;
                if tokens.get(i).is_some_and(|t| t == "::") {
                    i += 1;
                    continue;
                }
            }
            Some("*") => i += 1,
            _ => {}
        }
        out.push(path);
        return i;
    }
}

/// Every path in the code that starts with `crate`, `super` or `self` followed by `::`, or with
/// the name of a child module of the file's own module (`pub use wilson::Wilson;` in a mod.rs,
/// which the 2018+ editions read as `self::wilson::Wilson`), given back with `self` in front.
/// A tree is read once: a `super` after `::` or a name inside a group starts no path of its
/// own, nor does a method's turbofish (`.name::<T>()`). `mod x;` names no path: no edge.
fn relative_paths(code: &str, children: &BTreeSet<String>) -> Vec<Vec<String>> {
    let tokens = tokenize(code);
    let mut out = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let before = if i == 0 { "" } else { tokens[i - 1].as_str() };
        let followed_by_path = tokens.get(i + 1).is_some_and(|t| t == "::");
        let keyword = matches!(tokens[i].as_str(), "crate" | "super" | "self");
        let child = children.contains(&tokens[i]) && before != "." && tokens.get(i + 2).is_none_or(|t| t != "<");
        if followed_by_path && before != "::" && (keyword || child) {
            let prefix = if keyword { Vec::new() } else { vec!["self".to_owned()] };
            i = parse_tree(&tokens, i, &prefix, &mut out);
        } else {
            i += 1;
        }
    }
    out
}

/// The absolute module path (segments from the crate root, items included) of `path` seen from
/// module `from`: `crate::` is the root, `self::` is `from`, each `super::` its parent.
fn absolute(path: &[String], from: &[String]) -> Option<Vec<String>> {
    let mut base = from.to_vec();
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        Some("self") => rest = &rest[1..],
        _ => {}
    }
    while rest.first().is_some_and(|s| s == "super") {
        base.pop()?; // `super` above the crate root: not a module of this crate
        rest = &rest[1..];
    }
    base.extend(rest.iter().cloned());
    Some(base)
}

/// The file of the deepest module that `abs` names: `dynamics::wilson::Wilson` is
/// `src/dynamics/wilson.rs` if that module has a file, else `src/dynamics/mod.rs`, else the root.
fn deepest_module(abs: &[String], modules: &BTreeMap<Vec<String>, usize>) -> Option<usize> {
    (0..=abs.len()).rev().find_map(|n| modules.get(&abs[..n]).copied())
}

/// Builds the file-level import graph of `sources`. The crate root is `src/lib.rs` when it exists,
/// else `src/main.rs`; edges from a file to itself are dropped.
fn build_graph(sources: &[SourceFile]) -> ModuleGraph {
    let files: Vec<String> = sources.iter().map(|(f, _)| f.clone()).collect();
    let mut modules = BTreeMap::new();
    for (i, f) in files.iter().enumerate() {
        if let Some(m) = module_path_of(f)
            && !(m.is_empty() && f == "src/main.rs" && modules.contains_key(&m))
        {
            modules.insert(m, i); // lib.rs wins over main.rs, whichever comes first
        }
    }
    let mut edges = vec![BTreeSet::new(); files.len()];
    let mut via = BTreeMap::new();
    for (i, (file, text)) in sources.iter().enumerate() {
        let Some(from) = module_path_of(file) else { continue };
        let children = modules.keys().filter(|m| m.len() == from.len() + 1 && m.starts_with(&from));
        let children: BTreeSet<String> = children.map(|m| m[from.len()].clone()).collect();
        for path in relative_paths(&strip_code(text), &children) {
            let target = absolute(&path, &from).and_then(|abs| deepest_module(&abs, &modules));
            if let Some(j) = target.filter(|&j| j != i) {
                edges[i].insert(j);
                via.entry((i, j)).or_insert_with(|| path.join("::"));
            }
        }
    }
    ModuleGraph { files, edges, via }
}

/// Tarjan's strongly connected components, iteratively. Each returned component has more than
/// one file (self-edges are dropped when the graph is built), so each one is an import cycle.
fn cycles(graph: &ModuleGraph) -> Vec<Vec<usize>> {
    let n = graph.files.len();
    let adj: Vec<Vec<usize>> = graph.edges.iter().map(|s| s.iter().copied().collect()).collect();
    let (mut index, mut low, mut on_stack) = (vec![usize::MAX; n], vec![0; n], vec![false; n]);
    let (mut stack, mut found, mut next) = (Vec::new(), Vec::new(), 0);
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        let mut call = vec![(root, 0usize)];
        (index[root], low[root], on_stack[root]) = (next, next, true);
        stack.push(root);
        next += 1;
        while let Some(&mut (v, ref mut k)) = call.last_mut() {
            if let Some(&w) = adj[v].get(*k) {
                *k += 1;
                if index[w] == usize::MAX {
                    (index[w], low[w], on_stack[w]) = (next, next, true);
                    stack.push(w);
                    next += 1;
                    call.push((w, 0));
                } else if on_stack[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            call.pop();
            if let Some(&(parent, _)) = call.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut component = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 {
                    component.sort_unstable();
                    found.push(component);
                }
            }
        }
    }
    found
}

/// A readable account of the cycles: each component's files, then its internal edges with one
/// path that makes each edge.
fn describe(graph: &ModuleGraph, found: &[Vec<usize>]) -> String {
    let mut s = String::new();
    for (k, component) in found.iter().enumerate() {
        let names: Vec<&str> = component.iter().map(|&i| graph.files[i].as_str()).collect();
        s += &format!("cycle {} ({} files): {}\n", k + 1, names.len(), names.join(", "));
        for &i in component {
            for &j in graph.edges[i].iter().filter(|j| component.contains(j)) {
                s += &format!("    {} -> {}   ({})\n", graph.files[i], graph.files[j], graph.via[&(i, j)]);
            }
        }
    }
    s
}

/// Checks a module set: returns the graph and its cycles, and prints the counts to stderr.
fn check(label: &str, sources: &[SourceFile]) -> (ModuleGraph, Vec<Vec<usize>>) {
    let graph = build_graph(sources);
    let found = cycles(&graph);
    let in_cycles: usize = found.iter().map(Vec::len).sum();
    eprintln!(
        "module graph of {label}: {} files, {} edges, {} cycles, {} files in cycles",
        graph.files.len(),
        graph.edge_count(),
        found.len(),
        in_cycles
    );
    (graph, found)
}

#[test]
fn no_import_cycle_among_src_modules() {
    // Cargo sets it at run time; a standalone `rustc --test` build reads it (or `.`) then too.
    let root = std::env::var("CARGO_MANIFEST_DIR")
        .unwrap_or_else(|_| option_env!("CARGO_MANIFEST_DIR").unwrap_or(".").to_owned());
    let root = Path::new(&root);
    let mut sources = Vec::new();
    read_rs_files(root, &root.join("src"), &mut sources);
    assert!(!sources.is_empty(), "no .rs file under {}", root.join("src").display());
    let (graph, found) = check(&root.join("src").display().to_string(), &sources);
    let report = describe(&graph, &found);
    assert!(found.is_empty(), "import cycles among the modules of src/:\n{report}");
}

fn synthetic(files: &[(&str, &str)]) -> Vec<SourceFile> {
    files.iter().map(|(f, t)| (f.to_string(), t.to_string())).collect()
}

/// The file names of each cycle found in a synthetic module set.
fn cycle_files(files: &[(&str, &str)]) -> Vec<Vec<String>> {
    let (graph, found) = check("a synthetic module set", &synthetic(files));
    found.iter().map(|c| c.iter().map(|&i| graph.files[i].clone()).collect()).collect()
}

#[test]
fn checker_detects_a_known_cycle() {
    let found = cycle_files(&[
        ("src/lib.rs", "pub mod a;\npub mod b;\npub mod c;\n"),
        ("src/a.rs", "use crate::b;\npub struct X;\n"),
        ("src/b.rs", "pub fn f() -> crate::a::X { crate::a::X }\n"),
        ("src/c.rs", "use crate::a::X;\n"),
    ]);
    assert_eq!(found, vec![vec!["src/a.rs".to_owned(), "src/b.rs".to_owned()]]);
}

#[test]
fn checker_passes_an_acyclic_set() {
    let found = cycle_files(&[
        ("src/lib.rs", "pub mod a;\npub mod b;\npub use a::X;\n"),
        ("src/a.rs", "pub struct X;\n"),
        ("src/b.rs", "use crate::{a::X, self as root};\npub fn f(_: X) {}\n"),
        ("src/main.rs", "fn main() { slipfront::b::f(slipfront::a::X) }\n"),
    ]);
    assert!(found.is_empty(), "{found:?}");
}

/// Every rule of the brief, each on a cycle that exists only if the rule is followed (or only
/// if it is broken), so that the checker's reading of a file is proven piece by piece.
#[test]
fn checker_reads_paths_as_the_compiler_does() {
    let edges_of = |files: &[(&str, &str)]| -> BTreeSet<(String, String)> {
        let graph = build_graph(&synthetic(files));
        let mut set = BTreeSet::new();
        for (i, targets) in graph.edges.iter().enumerate() {
            for &j in targets {
                set.insert((graph.files[i].clone(), graph.files[j].clone()));
            }
        }
        set
    };
    let e = |a: &str, b: &str| (a.to_owned(), b.to_owned());
    let dynamics = [
        ("src/lib.rs", "pub mod dynamics;\npub mod scene;\n"),
        ("src/dynamics/mod.rs", "mod body;\nmod wilson;\npub use wilson::Wilson;\npub struct State;\n"),
        ("src/dynamics/body.rs", "pub struct LinearBody;\n"),
        (
            "src/dynamics/wilson.rs",
            "use super::{\n    body::LinearBody,\n    State,\n};\n// use crate::scene::Frame;\n/// [`crate::scene`]\n\
             fn f() -> &'static str { let _c = '\"'; \"crate::scene::Frame\" }\n\
             const R: &str = r#\"use crate::scene; \"# ;\n/* crate::scene /* nested */ crate::scene */\n\
             #[cfg(test)]\nmod tests { use crate::scene::Frame; }\n",
        ),
        ("src/scene/mod.rs", "pub mod point;\npub struct Frame;\n"),
        (
            "src/scene/point.rs",
            "fn g() { let s = crate::dynamics::wilson::Wilson::<f64>::new(); let _ = super::Frame; }\n",
        ),
    ];
    let expected: BTreeSet<_> = [
        e("src/dynamics/mod.rs", "src/dynamics/wilson.rs"),
        e("src/dynamics/wilson.rs", "src/dynamics/body.rs"),
        e("src/dynamics/wilson.rs", "src/dynamics/mod.rs"),
        e("src/scene/point.rs", "src/dynamics/wilson.rs"),
        e("src/scene/point.rs", "src/scene/mod.rs"),
    ]
    .into_iter()
    .collect();
    assert_eq!(edges_of(&dynamics), expected);
    // `super::` inside a mod.rs is the parent of its folder.
    let up = [
        ("src/lib.rs", "pub mod a;\npub fn root() {}\n"),
        ("src/a/mod.rs", "use super::root;\nuse self::b::Y;\n"),
        ("src/a/b.rs", ""),
    ];
    assert_eq!(edges_of(&up), [e("src/a/mod.rs", "src/a/b.rs"), e("src/a/mod.rs", "src/lib.rs")].into_iter().collect());
    // A child module's name starts a path, but not inside a group nor as a method's turbofish.
    let names = [
        ("src/lib.rs", "pub mod a;\npub mod b;\n"),
        ("src/b.rs", "pub struct Z;\n"),
        ("src/a/mod.rs", "mod b;\nuse crate::{\n    b::Z,\n};\nfn f(v: V) { v.b::<u8>(); }\n"),
        ("src/a/b.rs", ""),
    ];
    assert_eq!(edges_of(&names), [e("src/a/mod.rs", "src/b.rs")].into_iter().collect());
}
