//! Every file of a crate's tests/ folder is named in its tests/main.rs (with `autotests = false` a
//! file left out is never compiled). The library's and the command-line program's test binaries
//! both include this file; `CARGO_MANIFEST_DIR` is the crate that compiles it.

#[test]
fn every_file_in_tests_is_compiled() {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let main = std::fs::read_to_string(here.join("main.rs")).unwrap();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&here).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        let is_module = path.extension().is_some_and(|e| e == "rs") || path.join("mod.rs").is_file();
        if is_module && name != "main" && !main.contains(&format!("\nmod {name};\n")) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "test files not named in tests/main.rs (never compiled): {missing:?}"
    );
}
