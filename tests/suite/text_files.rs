//! The repository's text is text: a source, document, scene or snapshot
//! holding a control byte such as NUL is taken for binary by grep (which
//! then prints "binary file matches" instead of the line) and by tools that
//! look for duplicated code, so such a byte is written as an escape
//! (`\0`, `\u{0}`) where a test needs it.

use std::path::{Path, PathBuf};

/// The endings of the files that must be text; images and the like are not.
const TEXT: [&str; 10] = [
    "rs", "md", "toml", "py", "snap", "nff", "obj", "mtl", "dict", "sh",
];

/// Every file under `dir` whose name ends in one of `TEXT`, leaving out
/// build output and git's own folder.
fn text_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy();
        if path.is_dir() {
            if !matches!(&*name, "target" | ".git" | "corpus" | "artifacts") {
                files.extend(text_files(&path));
            }
        } else if path
            .extension()
            .is_some_and(|e| TEXT.iter().any(|t| e == *t))
        {
            files.push(path);
        }
    }
    files
}

/// The first control byte of `bytes` other than tab, line feed and carriage
/// return, with its line.
fn first_control_byte(bytes: &[u8]) -> Option<(usize, u8)> {
    let at = bytes
        .iter()
        .position(|&b| b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r') || b == 0x7f)?;
    let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
    Some((line, bytes[at]))
}

#[test]
fn no_text_file_holds_a_control_byte() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = text_files(root);
    assert!(files.len() > 100, "the walk found the sources: {files:?}");
    let found: Vec<String> = (files.iter())
        .filter_map(|file| {
            let (line, byte) = first_control_byte(&std::fs::read(file).unwrap())?;
            let file = file.strip_prefix(root).unwrap().display();
            Some(format!("{file}:{line}: byte {byte:#04x}"))
        })
        .collect();
    assert!(found.is_empty(), "write these as escapes: {found:#?}");
}

#[test]
fn the_finder_sees_a_nul_and_its_line_and_passes_tabs_and_line_ends() {
    assert_eq!(first_control_byte(b"a\tb\r\nc\0d"), Some((2, 0)));
    assert_eq!(first_control_byte(b"a\x7f"), Some((1, 0x7f)));
    assert_eq!(first_control_byte(b"a\tb\r\n\"\\0\"\n"), None);
}
