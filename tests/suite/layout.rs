//! The layout, where the compiler does not keep it. The walls between the
//! floors are the workspace's crates (issue 37: model, accel, engine,
//! tools, and this package), which the compiler keeps; what is checked
//! here is what it cannot see: no import circle between the top-level
//! modules of any one crate (a circle means neither module can be read,
//! tested or moved without the other; the shared thing belongs in the lower
//! one), nor between the files of any one folder (issue 25: `super::` and
//! `crate::<folder>::`); in the debugger, the state and the views know no
//! pane; CONTRIBUTING.md's Layout section names every folder of the
//! debugger; no floor below the binary pulls in a terminal, signals, file
//! watching or C++ (`cargo tree`); a `pub` item is used outside its crate.
//!
//! Module A depends on B when any file of A names `crate::B` (in a `use`,
//! a path or a doc link) outside its unit tests. This reads the source, not
//! the compiler's view, so it errs towards seeing a dependency where a doc
//! link names one.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

type Graph = BTreeMap<String, BTreeSet<String>>;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The library crates below the binary and the web page, by folder under
/// `crates/` (flip stands apart: it depends on nothing).
const FLOORS: [&str; 5] = ["model", "accel", "engine", "tools", "flip"];

/// The web page's crate: a top like the binary, whose public calls are
/// made by the page's JavaScript.
const PAGE: &str = "web";

/// Each crate's source folder: the floors', the page's and this package's.
fn crate_sources() -> Vec<PathBuf> {
    let mut sources: Vec<PathBuf> = FLOORS
        .iter()
        .chain([&PAGE])
        .map(|floor| root().join("crates").join(floor).join("src"))
        .collect();
    sources.push(root().join("src"));
    sources
}

/// Every `.rs` file under `path` (or `path` itself when it is a file).
fn rust_files(path: &Path) -> Vec<PathBuf> {
    if path.is_file() {
        return vec![path.to_path_buf()];
    }
    let mut files = Vec::new();
    for entry in fs::read_dir(path).unwrap() {
        files.extend(rust_files(&entry.unwrap().path()));
    }
    files.retain(|f| f.extension().is_some_and(|e| e == "rs"));
    files
}

/// The modules named right after each `crate::` in `text`, including each
/// head of a `crate::{a, b::c}` group.
fn crate_references(text: &str) -> BTreeSet<String> {
    references_after(text, "crate::")
}

/// The names right after each `prefix` in `text`, including each head of a
/// `prefix{a, b::c}` group.
fn references_after(text: &str, prefix: &str) -> BTreeSet<String> {
    let ident = |s: &str| -> String {
        s.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut names = BTreeSet::new();
    for (at, _) in text.match_indices(prefix) {
        let rest = &text[at + prefix.len()..];
        let Some(group) = rest.strip_prefix('{') else {
            names.insert(ident(rest));
            continue;
        };
        let (mut depth, mut start) = (0, 0);
        for (i, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    names.insert(ident(&group[start..]));
                    break;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    names.insert(ident(&group[start..]));
                    start = i + 1;
                }
                _ => {}
            }
        }
    }
    names
}

/// Top-level module -> the other top-level modules it names.
fn module_graph(src: &Path) -> Graph {
    let mut modules: BTreeMap<String, PathBuf> = BTreeMap::new();
    for entry in fs::read_dir(src).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let is_module = path.is_dir() || path.extension().is_some_and(|e| e == "rs");
        if is_module && name != "lib" && name != "main" {
            modules.insert(name, path);
        }
    }
    let mut graph = Graph::new();
    for (name, path) in &modules {
        let mut uses = BTreeSet::new();
        for file in rust_files(path) {
            let library = library_part(&file);
            uses.extend(crate_references(&library));
            // In a file at the crate's root, `super::` is the crate.
            if file.parent() == Some(src) {
                uses.extend(references_after(&library, "super::"));
            }
        }
        uses.retain(|used| used != name && modules.contains_key(used));
        graph.insert(name.clone(), uses);
    }
    graph
}

/// The library part of a file: its unit tests (its `#[cfg(test)]` module,
/// last by custom) may build a whole scene and are not the layout.
fn library_part(file: &Path) -> String {
    library_part_of(&fs::read_to_string(file).unwrap())
}

fn library_part_of(text: &str) -> String {
    text.split("#[cfg(test)]\nmod ")
        .next()
        .unwrap_or_default()
        .to_string()
}

/// Within one folder of src/ (module path `module`, e.g. `record` or
/// `tui::app`): each file or subfolder -> the siblings it names, through
/// `super::` or `crate::<module>::`. `mod.rs` is the folder itself, not a
/// sibling. A `super::` from deeper down may be read as naming a sibling
/// it does not: this errs towards seeing a dependency.
fn folder_graph(folder: &Path, module: &str) -> Graph {
    let mut siblings: BTreeMap<String, PathBuf> = BTreeMap::new();
    for entry in fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let is_module = path.is_dir() || path.extension().is_some_and(|e| e == "rs");
        if is_module && name != "mod" {
            siblings.insert(name, path);
        }
    }
    let absolute = format!("crate::{module}::");
    let mut graph = Graph::new();
    for (name, path) in &siblings {
        let mut uses = BTreeSet::new();
        for file in rust_files(path) {
            let library = library_part(&file);
            uses.extend(references_after(&library, "super::"));
            uses.extend(references_after(&library, &absolute));
        }
        uses.retain(|used| used != name && siblings.contains_key(used));
        graph.insert(name.clone(), uses);
    }
    graph
}

/// Every folder under `src/` (src itself has its own test), with its module path.
fn folders(src: &Path) -> Vec<(PathBuf, String)> {
    let mut found = Vec::new();
    let mut stack = vec![(src.to_path_buf(), String::new())];
    while let Some((dir, module)) = stack.pop() {
        for entry in fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                let inner = if module.is_empty() {
                    name
                } else {
                    format!("{module}::{name}")
                };
                found.push((path.clone(), inner.clone()));
                stack.push((path, inner));
            }
        }
    }
    found
}

/// One circle through `start`, as the path back to it, if there is one.
fn circle_through(graph: &Graph, start: &str) -> Option<Vec<String>> {
    let mut seen = BTreeSet::new();
    let mut stack = vec![vec![start.to_string()]];
    while let Some(path) = stack.pop() {
        for next in &graph[path.last().unwrap()] {
            let mut longer = path.clone();
            longer.push(next.clone());
            if next == start {
                return Some(longer);
            }
            if seen.insert(next.clone()) {
                stack.push(longer);
            }
        }
    }
    None
}

fn circles(graph: &Graph) -> Vec<String> {
    graph
        .keys()
        .filter_map(|m| circle_through(graph, m))
        .map(|c| c.join(" -> "))
        .collect()
}

#[test]
fn no_import_circle_between_top_level_modules() {
    let mut found = Vec::new();
    for src in crate_sources() {
        let graph = module_graph(&src);
        found.extend(
            circles(&graph)
                .into_iter()
                .map(|c| format!("{}: {c}", src.display())),
        );
    }
    let engine = module_graph(&root().join("crates/engine/src"));
    assert!(engine["record"].contains("trace"), "{engine:#?}");
    // accel's files name each other as `super::` too.
    let accel = module_graph(&root().join("crates/accel/src"));
    assert!(accel["packet"].contains("node"), "{accel:#?}");
    assert!(found.is_empty(), "import circles: {found:#?}");
}

#[test]
fn no_import_circle_between_the_files_of_a_folder() {
    let folders: Vec<_> = crate_sources()
        .iter()
        .flat_map(|src| folders(src))
        .collect();
    assert!(folders.iter().any(|(_, m)| m == "tui::app"), "{folders:?}");
    assert!(
        folders.iter().any(|(_, m)| m == "divergence::kind"),
        "{folders:?}"
    );
    let mut found = Vec::new();
    for (folder, module) in &folders {
        let graph = folder_graph(folder, module);
        found.extend(
            circles(&graph)
                .into_iter()
                .map(|c| format!("{module}: {c}")),
        );
    }
    assert!(
        found.is_empty(),
        "import circles inside folders: {found:#?}"
    );
}

#[test]
fn the_folder_reader_sees_super_and_absolute_paths() {
    // record/dot.rs names its siblings both ways; its unit tests don't count.
    let graph = folder_graph(&root().join("crates/engine/src/record"), "record");
    assert!(graph.contains_key("dot") && !graph.contains_key("mod"));
    let text = "use super::{tree::RayTree, text};\nlet x = crate::record::lines::f();\n";
    let mut names = references_after(text, "super::");
    names.extend(references_after(text, "crate::record::"));
    assert_eq!(
        names.into_iter().collect::<Vec<_>>(),
        ["lines", "text", "tree"]
    );
}

#[test]
fn the_reader_sees_paths_groups_and_circles() {
    let text = "use crate::a::B;\nuse crate::{b, c::{D, E}};\nlet x = crate::d::f();";
    let names: Vec<_> = crate_references(text).into_iter().collect();
    assert_eq!(names, ["a", "b", "c", "d"]);
    // a -> b -> c -> a is a circle; d -> a alone is not on one.
    let graph: Graph = [("a", "b"), ("b", "c"), ("c", "a"), ("d", "a")]
        .into_iter()
        .map(|(from, to)| (from.to_string(), BTreeSet::from([to.to_string()])))
        .collect();
    assert_eq!(circle_through(&graph, "a").unwrap(), ["a", "b", "c", "a"]);
    assert_eq!(circle_through(&graph, "d"), None);
    assert_eq!(circles(&graph).len(), 3);
}

/// The module names in `text`'s `use` declarations and inline paths
/// (`a::b::c` gives a, b and c), outside its unit tests.
fn path_segments(text: &str) -> BTreeSet<String> {
    let library = text.split("#[cfg(test)]\nmod ").next().unwrap_or_default();
    let mut names = BTreeSet::new();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    for (at, _) in library.match_indices("use ") {
        // Only a declaration: `use` first on its line, or after `pub(..)`.
        let line_start = library[..at].rfind('\n').map_or(0, |i| i + 1);
        let lead = library[line_start..at].trim();
        if !(lead.is_empty() || lead.starts_with("pub")) {
            continue;
        }
        let statement = &library[at..at + library[at..].find(';').unwrap_or(0)];
        names.extend(statement.split(|c| !ident(c)).map(String::from));
    }
    for (at, _) in library.match_indices("::") {
        let before = library[..at].rsplit(|c| !ident(c)).next().unwrap_or("");
        names.insert(before.to_string());
    }
    names.retain(|n| !n.is_empty());
    names
}

/// The `src/tui/` folders that `folder` names.
fn tui_folders_named(folder: &str) -> BTreeSet<String> {
    let tui = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/tui");
    let mut named = BTreeSet::new();
    for file in rust_files(&tui.join(folder)) {
        let segments = path_segments(&fs::read_to_string(&file).unwrap());
        for other in ["app", "pane", "view"] {
            if other != folder && segments.contains(other) {
                named.insert(format!("{} names {other}", file.display()));
            }
        }
    }
    named
}

#[test]
fn the_debuggers_state_and_views_know_no_pane() {
    // The state reads views (layout, tree rows, stepping) but never how a
    // pane is drawn; the views know neither the state nor the panes.
    let app: Vec<_> = tui_folders_named("app")
        .into_iter()
        .filter(|n| !n.ends_with("view"))
        .collect();
    assert!(app.is_empty(), "{app:#?}");
    let view = tui_folders_named("view");
    assert!(view.is_empty(), "{view:#?}");
}

#[test]
fn the_path_reader_sees_uses_groups_and_inline_paths() {
    let text = "use super::view::{layout, tree};\npub use crate::tui::pane;\n\
                // because it is;\nfn f() { super::super::app::x() }\n\
                #[cfg(test)]\nmod tests { use crate::other; }";
    let names: Vec<_> = path_segments(text).into_iter().collect();
    assert_eq!(
        names,
        [
            "app", "crate", "layout", "pane", "super", "tree", "tui", "use", "view"
        ]
    );
}

#[test]
fn contributing_layout_names_every_folder_of_the_debugger() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let guide = fs::read_to_string(root.join("docs/CONTRIBUTING.md")).unwrap();
    let start = guide
        .find("## Layout")
        .expect("CONTRIBUTING.md has a Layout section");
    let section = &guide[start..];
    let section = &section[..section[1..].find("\n## ").map_or(section.len(), |i| i + 1)];
    let mut folders = vec!["src/tui/".to_string()];
    for entry in fs::read_dir(root.join("src/tui")).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            folders.push(format!("src/tui/{name}/"));
        }
    }
    assert!(folders.len() >= 4, "app, view and pane: {folders:?}");
    for folder in folders {
        assert!(
            section.contains(&format!("`{folder}`")),
            "CONTRIBUTING.md's Layout section does not say what `{folder}` holds"
        );
    }
}

/// The packages in the normal (not dev or build) dependency tree of
/// `package`, with its default features, by name.
fn normal_dependencies(package: &str) -> BTreeSet<String> {
    let output = std::process::Command::new(env!("CARGO"))
        .current_dir(root())
        .args(["tree", "--offline", "-e", "normal", "--prefix", "none"])
        .args(["--format", "{p}", "-p", package])
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .filter_map(|line| line.split_whitespace().next())
        .map(String::from)
        .collect()
}

#[test]
fn no_floor_below_the_binary_needs_a_terminal_signals_file_watching_or_cpp() {
    // The web page builds the floors for WebAssembly: none may need
    // crossterm, ratatui, signal-hook, notify or nv-flip (C++). The binary
    // and the page turn on the tools' `flip` feature, which is in Rust.
    let binary_only = ["crossterm", "ratatui", "signal-hook", "notify", "nv-flip"];
    for floor in FLOORS.iter().chain([&PAGE]) {
        let package = format!("raystep-{floor}");
        let tree = normal_dependencies(&package);
        assert!(tree.contains(&package), "{package}: {tree:?}");
        let found: Vec<_> = binary_only.iter().filter(|p| tree.contains(**p)).collect();
        assert!(found.is_empty(), "{package} depends on {found:?}");
    }
    // The check sees them where they are; FLIP is in Rust (crates/flip),
    // so no C++ is left even in the binary.
    let binary = normal_dependencies("raystep");
    let terminal = &binary_only[..4];
    assert!(terminal.iter().all(|p| binary.contains(*p)), "{binary:?}");
    assert!(
        !binary.contains("nv-flip") && binary.contains("raystep-flip"),
        "{binary:?}"
    );
}

/// The `src/`, `tests/`, `benches/`, `docs/` and `scenes/` paths that `text`
/// names in backticks (`src/figure/view.rs`, `src/tui/app/`).
fn named_paths(text: &str) -> BTreeSet<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|quoted| {
            ["src/", "crates/", "tests/", "benches/", "docs/", "scenes/"]
                .iter()
                .any(|root| quoted.starts_with(root))
        })
        .filter(|quoted| !quoted.contains(['*', ' ', '<']))
        .map(String::from)
        .collect()
}

#[test]
fn every_path_that_the_documents_name_exists() {
    // MODEL.md's "where in the code" lines, CONTRIBUTING.md's Layout
    // section, README's floors and the guides are read by newcomers to
    // find things: a moved file must take them along.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut docs: Vec<PathBuf> = vec![root.join("README.md")];
    for entry in fs::read_dir(root.join("docs")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            docs.push(path);
        }
    }
    assert!(docs.len() >= 8, "README and the guides: {docs:?}");
    for doc in &docs {
        let name = doc.strip_prefix(root).unwrap().display().to_string();
        let paths = named_paths(&fs::read_to_string(doc).unwrap());
        if ["docs/MODEL.md", "docs/CONTRIBUTING.md", "README.md"].contains(&name.as_str()) {
            assert!(
                paths.contains("crates/engine/src/trace/tracer.rs")
                    || paths.contains("crates/engine/src/trace/"),
                "{name}: {paths:?}"
            );
        }
        let missing: Vec<_> = paths.iter().filter(|p| !root.join(p).exists()).collect();
        assert!(
            missing.is_empty(),
            "{name} names paths that do not exist: {missing:?}"
        );
    }
    let example = "see `src/a.rs` and `tests/b/`, not `cargo test` or `scenes/*.toml`";
    assert_eq!(
        named_paths(example).into_iter().collect::<Vec<_>>(),
        ["src/a.rs", "tests/b/"]
    );
}

#[test]
fn the_diagram_is_assembled_once_and_the_media_only_draw_it() {
    // The tools' diagram/ assembles the ray diagram knowing neither medium:
    // no file of it outside svg/ names the SVG writer (the debugger and
    // ratatui it cannot reach: they are the binary's). The two media (svg/
    // and the debugger's diagram pane) take the assembled diagram: neither
    // projects rays or picks the objects itself, as each did when they
    // drifted apart.
    let diagram = root().join("crates/tools/src/diagram");
    for file in rust_files(&diagram) {
        if file.starts_with(diagram.join("svg")) {
            continue;
        }
        let segments = path_segments(&fs::read_to_string(&file).unwrap());
        assert!(
            !segments.contains("svg"),
            "{} names the SVG writer",
            file.display()
        );
    }
    let mut media = rust_files(&diagram.join("svg"));
    media.push(root().join("src/tui/pane/diagram.rs"));
    for file in media {
        let text = fs::read_to_string(&file).unwrap();
        let library = text.split("#[cfg(test)]\nmod ").next().unwrap_or_default();
        for assembling in ["ray_segments", "involved_objects", "Projection"] {
            assert!(
                !library.contains(assembling),
                "{} assembles the diagram itself ({assembling})",
                file.display()
            );
        }
    }
}

/// The names of the `pub` items and fields declared in `text` (not `pub mod`
/// or `pub use`, and not `pub(crate)`).
fn public_names(text: &str) -> Vec<String> {
    let mut names = Vec::new();
    for line in text.lines() {
        let Some(rest) = line.trim_start().strip_prefix("pub ") else {
            continue;
        };
        let mut words = rest.split(|c: char| !(c.is_alphanumeric() || c == '_'));
        let first = words.next().unwrap_or_default();
        let name = match first {
            "fn" | "struct" | "enum" | "const" | "static" | "type" | "trait" | "union" => {
                words.find(|w| !w.is_empty())
            }
            "unsafe" | "async" => words.find(|w| !w.is_empty() && *w != "fn"),
            "mod" | "use" | "" => None,
            field if rest[field.len()..].trim_start().starts_with(':') => Some(field),
            _ => None,
        };
        names.extend(name.map(String::from));
    }
    names
}

/// What `pub` items of `text` show of other items: each `pub` line's
/// signature (up to its `{` or `;`, less the name it declares) and the
/// variants of a `pub enum`.
fn public_interfaces(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut shown = String::new();
    for (i, line) in lines.iter().enumerate() {
        if !line.trim_start().starts_with("pub ") {
            continue;
        }
        let declared = public_names(line);
        let mut signature = String::new();
        for next in &lines[i..] {
            let end = next.find(['{', ';']);
            signature += &next[..end.unwrap_or(next.len())];
            signature.push(' ');
            if end.is_some() {
                break;
            }
        }
        if line.trim_start().starts_with("pub enum") || line.trim_start().starts_with("pub trait") {
            let indent = line.len() - line.trim_start().len();
            for next in &lines[i + 1..] {
                if next.len() - next.trim_start().len() <= indent
                    && next.trim_start().starts_with('}')
                {
                    break;
                }
                signature += next;
                signature.push(' ');
            }
        }
        for word in signature.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
            if !declared.iter().any(|d| d == word) {
                shown += word;
                shown.push(' ');
            }
        }
    }
    shown
}

/// The words of `files`, their unit tests included.
fn words_of(files: impl IntoIterator<Item = PathBuf>) -> BTreeSet<String> {
    let mut words = BTreeSet::new();
    for file in files {
        let text = fs::read_to_string(&file).unwrap();
        words.extend(
            text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .map(String::from),
        );
    }
    words
}

#[test]
fn each_crate_makes_public_only_what_is_used_outside_it() {
    // Issue 25, then 37: an item is `pub(crate)` unless another crate (a
    // floor above, the binary), a test, bench or fuzz target needs it, so
    // that the compiler finds dead code. A `pub` item whose name nothing
    // outside its crate mentions is needed by nobody there (a method,
    // field or type the outside reaches is named).
    let mut everywhere: Vec<PathBuf> = ["tests", "benches", "fuzz/fuzz_targets"]
        .iter()
        .flat_map(|dir| rust_files(&root().join(dir)))
        .collect();
    for src in crate_sources() {
        everywhere.extend(rust_files(&src));
    }
    let mut unneeded = Vec::new();
    // The binary and the page are tops: what they make public, their own
    // tests or the page's script call.
    let page = root().join("crates").join(PAGE);
    for src in crate_sources()
        .into_iter()
        .filter(|s| !s.starts_with(&page))
    {
        let files = rust_files(&src);
        let outside = everywhere
            .iter()
            .filter(|f| !f.starts_with(&src) || f.ends_with("src/main.rs"));
        let mentioned = words_of(outside.cloned());
        // A type that a public signature, field or enum variant names is
        // needed wherever that item is: the compiler refuses it more private.
        let mut interfaces = String::new();
        for file in &files {
            interfaces += &public_interfaces(&library_part(file));
        }
        let in_interfaces: BTreeSet<&str> = interfaces
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .collect();
        for file in &files {
            for name in public_names(&library_part(file)) {
                if !mentioned.contains(&name) && !in_interfaces.contains(name.as_str()) {
                    unneeded.push(format!("{}: {name}", file.display()));
                }
            }
        }
    }
    assert!(
        unneeded.is_empty(),
        "pub, but named nowhere outside its crate: {unneeded:#?}"
    );
    let example = "pub fn a() {}\npub(crate) fn b() {}\npub struct C {\n    pub d: u8,\n}\npub mod e;\npub use f::G;\npub unsafe fn h() {}";
    assert_eq!(public_names(example), ["a", "C", "d", "h"]);
}

#[test]
fn a_file_name_says_one_thing() {
    // Issue 25: four files were called mistakes.rs, two recorder.rs, three
    // tree.rs. A name is used once in the workspace's sources, except for a
    // debugger pane's pair (what it shows, in view/, and how, in pane/), a
    // command's body in cli/ (named after its command), and each crate's
    // lib.rs.
    let mut by_name: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for src in crate_sources() {
        for file in rust_files(&src) {
            let name = file.file_name().unwrap().to_string_lossy().into_owned();
            let relative = file
                .strip_prefix(&src)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            if !["mod.rs", "lib.rs"].contains(&name.as_str()) && !relative.starts_with("cli/") {
                by_name.entry(name).or_default().push(relative);
            }
        }
    }
    let shared: Vec<_> = by_name
        .into_iter()
        .filter(|(name, files)| {
            let pane_pair = [format!("tui/pane/{name}"), format!("tui/view/{name}")];
            files.len() > 1 && !(files.len() == 2 && pane_pair.iter().all(|p| files.contains(p)))
        })
        .collect();
    assert!(shared.is_empty(), "one name, several things: {shared:#?}");
}

#[test]
fn switches_and_mistakes_enter_the_tracer_only_through_its_rules() {
    // Issue 25: the ambient switch went through `Rules` while shadows,
    // reflection and transmission were read from the settings in the
    // tracer: one mechanism now, `trace/rules.rs`.
    let tracer = fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/engine/src/trace/tracer.rs"),
    )
    .unwrap();
    let code: String = library_part_of(&tracer)
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect();
    // (It may ask whether there are mistakes at all, to pick the tracer
    // whose rules are constants; never which ones, nor any switch.)
    for reach in ["switches", "Mistake::", "mistakes.contains"] {
        assert!(!code.contains(reach), "the tracer reads {reach} itself");
    }
}

#[test]
fn the_integration_tests_are_one_binary_and_snapshots_go_through_one_helper() {
    // Issue 25: 29 test binaries each linked the whole crate. tests/ holds
    // the suite and signals.rs (which forks the debugger into ptys); every
    // snapshot is taken by support's snapshot! or json_snapshot!.
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let mut binaries: Vec<String> = fs::read_dir(&tests)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs") || p.join("main.rs").exists())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    binaries.sort();
    assert_eq!(binaries, ["signals.rs", "suite"]);
    for file in rust_files(&tests.join("suite")) {
        if file.ends_with("support/mod.rs") {
            continue;
        }
        let text = fs::read_to_string(&file).unwrap();
        for direct in [
            "assert_snapshot!",
            "assert_json_snapshot!",
            "set_snapshot_path",
        ] {
            assert!(
                !text.contains(&format!("insta::{direct}")),
                "{} takes a snapshot without support's helper",
                file.display()
            );
        }
    }
}
