//! The library's modules import one way only: each module may use the modules listed before it in
//! `LAYERS`, never one after it (the data flow of the model: parameters → surfaces → contact →
//! junctions → wear → sliding → run files → outputs → studies). A new module gets a place in this list.

use std::collections::BTreeSet;
use std::path::Path;

const LAYERS: [&str; 17] = [
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
    "junctions",
    "wear",
    "sliding",
    "config",
    "output",
    "study",
];

/// Top-level modules named by `crate::…` paths in `text`, including `use crate::{a, b::c}`.
fn references(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = text;
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // Top-level names of a brace group: split at commas outside nested braces.
            let mut depth = 0;
            let mut name = String::new();
            let mut at_start = true;
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        at_start = true;
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 && at_start {
                    if c.is_alphanumeric() || c == '_' {
                        name.push(c);
                    } else if !name.is_empty() {
                        out.insert(std::mem::take(&mut name));
                        at_start = false;
                    }
                }
            }
            if !name.is_empty() {
                out.insert(name);
            }
        } else {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            out.insert(name);
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
    let mut violations = Vec::new();
    for file in files {
        let relative = file.strip_prefix(&src).unwrap();
        let module = relative
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        if module == "lib" {
            continue;
        }
        let layer = LAYERS
            .iter()
            .position(|m| *m == module)
            .unwrap_or_else(|| panic!("module `{module}` ({}) has no place in LAYERS", relative.display()));
        let text = std::fs::read_to_string(&file).unwrap();
        for name in references(&text) {
            if name == "VERSION" || name == module {
                continue;
            }
            match LAYERS.iter().position(|m| *m == name) {
                Some(l) if l < layer => {}
                Some(_) => violations.push(format!("{} uses crate::{name}, a layer above it", relative.display())),
                None => violations.push(format!(
                    "{} uses crate::{name}: use the module, not a re-export",
                    relative.display()
                )),
            }
        }
    }
    assert!(
        violations.is_empty(),
        "imports pointing up or around:\n{}",
        violations.join("\n")
    );
}

#[test]
fn the_reference_scanner_reads_grouped_imports() {
    let names = references("use crate::{error::{Error, Result}, io::read_text};\nlet x = crate::fft::FftPlan::new(4);");
    assert_eq!(names.into_iter().collect::<Vec<_>>(), ["error", "fft", "io"]);
}
