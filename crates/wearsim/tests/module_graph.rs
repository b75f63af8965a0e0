//! The library's modules import one way only: each module may use the modules listed before it in
//! `LAYERS`, never one after it (the data flow of the model: parameters → surfaces → contact →
//! junctions → wear → sliding → run files → outputs → a run → studies). A new module gets a place in this
//! list. Inside a folder module the submodules are layered the same way (`SUBLAYERS`).
//!
//! Paths are resolved as the compiler resolves them: `crate::a::b` names module `a` (and its
//! submodule `b`), `super::x` in `src/a/b.rs` names `a::x` and in `src/a.rs` the top-level `x`
//! (inside a file's `mod tests`, `super` is the file itself). A name that is not a module (an item
//! of the crate root such as `crate::VERSION`) is a re-export and refused.
//!
//! Beside the imports, two rules of the workspace's sources: the front ends build runs through the
//! validating builder only, and no function is longer than 80 lines.

use std::collections::BTreeSet;
use std::path::Path;

const LAYERS: [&str; 22] = [
    "error",
    "check",
    "io",
    "fft",
    "stats",
    "grid",
    "influence",
    "material",
    "surface",
    "topography",
    "contact",
    "volume",
    "junctions",
    "wear",
    "sliding",
    "estimate",
    "model",
    "config",
    "cost",
    "output",
    "run",
    "study",
];

/// The order of the submodules of each folder module; a submodule uses only those before it.
const SUBLAYERS: [(&str, &[&str]); 10] = [
    ("io", &["atomic", "npy", "zarr"]),
    ("stats", &["fit", "interval", "judge"]),
    (
        "contact",
        &["backend", "options", "cpu", "conformance", "spy", "profile"],
    ),
    ("topography", &["formats", "prepare", "load", "spectrum", "fit"]),
    ("wear", &["shear", "rule", "overlap", "interacting", "registry"]),
    (
        "sliding",
        &["schedule", "records", "breakdown", "fit", "checkpoint", "state"],
    ),
    ("estimate", &["samples", "calibration", "rule", "reach", "estimator"]),
    ("config", &["raw", "source", "record"]),
    (
        "output",
        &[
            "provenance",
            "series",
            "units",
            "tables",
            "summary",
            "jobs",
            "study_table",
            "figure_data",
            "fields",
        ],
    ),
    (
        "study",
        &["expand", "store", "run", "collect", "compare", "findings", "figures"],
    ),
];

/// Module paths (up to two components) named by `prefix…` paths in `text`, including grouped
/// imports such as `use crate::{a, b::{c, d}}`.
fn paths_after(text: &str, prefix: &str) -> BTreeSet<Vec<String>> {
    let mut out = BTreeSet::new();
    let mut rest = text;
    while let Some(at) = rest.find(prefix) {
        // `super::` inside `super::super::` is counted once, from the first.
        let before = &rest[..at];
        rest = &rest[at + prefix.len()..];
        if prefix == "super::" && before.ends_with("super::") {
            continue;
        }
        collect_group(rest, Vec::new(), &mut out);
    }
    out
}

/// Reads one path (or a brace group of paths) at the start of `text`, appending what it names to
/// `head`, and records paths of at most two components.
fn collect_group(text: &str, head: Vec<String>, out: &mut BTreeSet<Vec<String>>) {
    if let Some(group) = text.strip_prefix('{') {
        let mut depth = 0;
        let mut start = 0;
        for (i, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    collect_group(group[start..i].trim(), head.clone(), out);
                    return;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    collect_group(group[start..i].trim(), head.clone(), out);
                    start = i + 1;
                }
                _ => {}
            }
        }
        return;
    }
    let name: String = text.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
    if name.is_empty() || name == "self" {
        if !head.is_empty() {
            out.insert(head);
        }
        return;
    }
    let mut path = head;
    path.push(name.clone());
    let rest = &text[name.len()..];
    match rest.strip_prefix("::") {
        Some(next) if path.len() < 2 => collect_group(next, path, out),
        _ => {
            out.insert(path);
        }
    }
}

/// The module path of a source file relative to `src`: `a.rs` → [a], `a/mod.rs` → [a], `a/b.rs` → [a, b].
fn module_of(relative: &Path) -> Vec<String> {
    let mut parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

fn layer(name: &str) -> Option<usize> {
    LAYERS.iter().position(|m| *m == name)
}

fn sublayer(module: &str, name: &str) -> Option<usize> {
    SUBLAYERS
        .iter()
        .find(|(m, _)| *m == module)
        .and_then(|(_, subs)| subs.iter().position(|s| *s == name))
}

/// Why the file of module `from` may not use the module path `to` (absolute, from the crate root),
/// or None when it may.
fn refusal(from: &[String], to: &[String]) -> Option<String> {
    let target = to.first()?;
    let Some(to_layer) = layer(target) else {
        return Some(format!(
            "crate::{target} is not a module: use the module, not a re-export"
        ));
    };
    let from_layer = layer(&from[0]).expect("the file's module is in LAYERS");
    if to_layer > from_layer {
        return Some(format!("crate::{target} is a layer above {}", from[0]));
    }
    if to_layer < from_layer {
        return None;
    }
    // Within one module: submodules use only the submodules before them.
    let (Some(from_sub), Some(to_sub)) = (from.get(1), to.get(1)) else {
        return None;
    };
    if from_sub == to_sub || SUBLAYERS.iter().all(|(m, _)| *m != from[0]) {
        return None;
    }
    match (sublayer(&from[0], from_sub), sublayer(&from[0], to_sub)) {
        (Some(a), Some(b)) if b < a => None,
        (Some(_), Some(_)) => Some(format!(
            "{}::{to_sub} is a layer above {}::{from_sub}",
            from[0], from[0]
        )),
        (None, _) => Some(format!("submodule {}::{from_sub} has no place in SUBLAYERS", from[0])),
        (_, None) => Some(format!(
            "{}::{to_sub} is not a submodule: use the submodule, not a re-export",
            from[0]
        )),
    }
}

/// The imports of one source file (`relative` to `src`) that point up or around.
fn violations(relative: &Path, text: &str) -> Vec<String> {
    let module = module_of(relative);
    if module.first().is_none_or(|m| m == "lib") {
        return Vec::new();
    }
    if layer(&module[0]).is_none() {
        return vec![format!(
            "module `{}` ({}) has no place in LAYERS",
            module[0],
            relative.display()
        )];
    }
    // `super` of a folder's `mod.rs` or of a top-level file is the crate root; of a submodule, its folder.
    let is_mod_rs = relative.file_name().is_some_and(|f| f == "mod.rs");
    let parent: Vec<String> = if is_mod_rs || module.len() == 1 {
        Vec::new()
    } else {
        module[..module.len() - 1].to_vec()
    };
    // Inside the file's own `mod tests`, `super` is the file itself; only the code before it counts.
    let outside_tests = text.split("#[cfg(test)]\nmod tests {").next().unwrap_or(text);
    let mut targets: Vec<Vec<String>> = paths_after(text, "crate::").into_iter().collect();
    for path in paths_after(outside_tests, "super::") {
        let mut absolute = parent.clone();
        absolute.extend(path);
        targets.push(absolute);
    }
    let mut out = Vec::new();
    for to in targets {
        if let Some(why) = refusal(&module, &to) {
            out.push(format!("{} uses {}: {why}", relative.display(), to.join("::")));
        }
    }
    out
}

fn visit(dir: &Path, files: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            visit(&path, files);
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
}

#[test]
fn modules_import_only_the_layers_below_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    visit(&src, &mut files);
    let mut found = Vec::new();
    for file in files {
        let relative = file.strip_prefix(&src).unwrap();
        found.extend(violations(relative, &std::fs::read_to_string(&file).unwrap()));
    }
    assert!(found.is_empty(), "imports pointing up or around:\n{}", found.join("\n"));
}

#[test]
fn the_reference_scanner_reads_grouped_imports() {
    let names = paths_after(
        "use crate::{error::{Error, Result}, io::read_text};\nlet x = crate::fft::FftPlan::new(4);",
        "crate::",
    );
    let names: Vec<String> = names.into_iter().map(|p| p.join("::")).collect();
    assert_eq!(
        names,
        ["error::Error", "error::Result", "fft::FftPlan", "io::read_text"]
    );
}

#[test]
fn the_checker_refuses_upward_imports_and_re_exports() {
    let refused = |file: &str, text: &str| !violations(Path::new(file), text).is_empty();
    // Between top-level modules, through `crate::` and through `super::` of a top-level file.
    assert!(refused("sliding.rs", "use crate::config::RunConfig;"));
    assert!(refused("sliding.rs", "use super::config::RunConfig;"));
    assert!(!refused("config.rs", "use crate::sliding::SlidingConfig;"));
    // An item of the crate root is a re-export, VERSION included.
    assert!(refused("output/provenance.rs", "crate::VERSION"));
    assert!(refused("output/provenance.rs", "use crate::Grid;"));
    // Between the submodules of a folder, through `super::` and `crate::`.
    assert!(refused("study/expand.rs", "use super::run::run_job;"));
    assert!(refused("study/expand.rs", "use crate::study::store::Stored;"));
    assert!(!refused(
        "study/run.rs",
        "use crate::study::{expand::Job, store::Stored};"
    ));
    assert!(!refused("study/run.rs", "use super::expand::Job;"));
    assert!(refused("study/run.rs", "use super::Job;"));
    // A folder's mod.rs: `super` is the crate root; a file's tests may use the file itself.
    assert!(refused("io/mod.rs", "use super::output::Table;"));
    assert!(!refused(
        "study/expand.rs",
        "fn f() {}\n#[cfg(test)]\nmod tests {\n    use super::*;\n}"
    ));
    assert!(refused("nowhere.rs", ""));
}

#[test]
fn front_ends_build_runs_through_the_validating_builder_only() {
    // `RunConfig`'s one field is private and its `RunSettings` are `#[non_exhaustive]`: the
    // compiler refuses a struct literal of either outside the library, and a built run has no
    // mutable access. This keeps the sources of the front ends free of one too (a `..run.clone()`
    // update included), so that every run they make passes `RunBuilder::build`, the checks of a
    // run file.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut found = Vec::new();
    for front in ["wearsim-cli/src", "wearsim-py/src"] {
        let mut files = Vec::new();
        visit(&root.join(front), &mut files);
        assert!(!files.is_empty(), "{front}");
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            for (k, line) in text.lines().enumerate() {
                if (line.contains("RunConfig {") || line.contains("RunSettings {"))
                    && !line.contains("-> RunConfig {")
                    && !line.trim_start().starts_with("//")
                {
                    found.push(format!("{}:{}: {}", file.display(), k + 1, line.trim()));
                }
            }
        }
    }
    assert!(found.is_empty(), "runs assembled field by field: {found:#?}");
}

/// The longest a function may be, from the line of `fn` to the line of its closing brace.
const MAX_FUNCTION_LINES: usize = 80;

/// The functions of `text` longer than [`MAX_FUNCTION_LINES`]: (first line, lines, name). Read in
/// rustfmt's layout: the signature ends at the first line ending in `{` (a body), `;` (a
/// declaration) or `}` (a one-line body), and the body at the next line that is its closing brace
/// alone at the indentation of `fn`.
fn long_functions(text: &str) -> Vec<(usize, usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        let mut rest = trimmed;
        for prefix in [
            "pub(crate) ",
            "pub(super) ",
            "pub ",
            "const ",
            "async ",
            "unsafe ",
            "extern \"C\" ",
        ] {
            rest = rest.strip_prefix(prefix).unwrap_or(rest);
        }
        let Some(name) = rest.strip_prefix("fn ") else { continue };
        let name: String = name.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let indent = &line[..line.len() - trimmed.len()];
        let Some(open) = (i..lines.len()).find(|&j| lines[j].trim_end().ends_with(['{', ';', '}'])) else {
            continue;
        };
        if !lines[open].trim_end().ends_with('{') {
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(end) = (open + 1..lines.len()).find(|&j| lines[j].trim_end() == close) {
            if end - i + 1 > MAX_FUNCTION_LINES {
                found.push((i + 1, end - i + 1, name));
            }
        }
    }
    found
}

#[test]
fn the_function_length_check_counts_from_fn_to_its_brace() {
    let body = |n: usize| "        x += 1;\n".repeat(n);
    let text = format!(
        "impl A {{\n    pub(crate) fn long(\n        x: u8,\n    ) -> u8 {{\n{}        x\n    }}\n    fn short() {{}}\n}}\n\
         trait B {{\n    fn declared(\n        x: u8,\n    ) -> u8;\n    fn fits() {{\n{}    }}\n}}\n",
        body(76),
        body(78)
    );
    assert_eq!(long_functions(&text), [(2, 81, "long".to_string())]);
}

#[test]
fn no_function_is_longer_than_80_lines() {
    // A longer function is split into named steps, each saying what it does.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut found = Vec::new();
    for krate in ["wearsim/src", "wearsim-cli/src", "wearsim-py/src"] {
        let mut files = Vec::new();
        visit(&root.join(krate), &mut files);
        assert!(!files.is_empty(), "{krate}");
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            for (line, length, name) in long_functions(&text) {
                let file = file.strip_prefix(&root).unwrap_or(&file).display().to_string();
                found.push(format!("{file}:{line}: `{name}`, {length} lines"));
            }
        }
    }
    found.sort();
    assert!(
        found.is_empty(),
        "functions over {MAX_FUNCTION_LINES} lines:\n{}",
        found.join("\n")
    );
}
