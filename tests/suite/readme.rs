//! The documents must match the code: README.md is the front door and the
//! guides in `docs/` hold the rest, so each check reads the document that
//! now holds what it checks. SCENES.md's scene example parses, DEBUGGER.md's
//! key table lists every row of the keymap, README keeps the two commands,
//! and every command line shown in README.md and `docs/*.md` is parsed by
//! raystep's own argument parser, the files it reads existing. Docs cannot
//! go stale.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use clap::{CommandFactory, Parser};
use raystep::cli::Cli;

fn doc(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn scenes_guide_example_is_valid() {
    let scenes = doc("docs/SCENES.md");
    let open = "```toml\n# A glass ball and a red ball on a floor.\n";
    let start = scenes.find(open).expect("SCENES.md's complete example") + "```toml\n".len();
    let end = start + scenes[start..].find("```").unwrap();
    let scene =
        raystep_engine::scene::parse(Path::new("docs/SCENES.md"), &scenes[start..end]).unwrap();
    assert_eq!(scene.objects.len(), 7);
    assert_eq!(scene.objects[4].name, "smooth card");
    assert_eq!(
        scene
            .materials
            .iter()
            .find(|m| m.name == "glass")
            .unwrap()
            .specular,
        Some(raystep_engine::scene::SpecularModel::Phong)
    );
}

/// The keys column of the key table in `text`, row by row, backticks and
/// commas dropped.
fn key_rows(text: &str) -> Vec<String> {
    let start = text.find("| keys | what they do |").expect("the key table");
    text[start..]
        .lines()
        .skip(2)
        .take_while(|line| line.starts_with('|'))
        .map(|line| {
            let keys = line.split('|').nth(1).unwrap().replace(['`', ','], " ");
            keys.split_whitespace().collect::<Vec<_>>().join(" ")
        })
        .collect()
}

#[test]
fn debugger_guide_key_table_lists_every_row_of_the_keymap() {
    let table: Vec<String> = raystep::tui::keymap::rows().map(|r| r.keys()).collect();
    assert_eq!(
        key_rows(&doc("docs/DEBUGGER.md")),
        table,
        "DEBUGGER.md's keys, in the help's order"
    );
    // Spot check by hand: the keys the README used to leave out.
    for keys in ["PageUp PageDown", "g Home e End", "Enter Space", "Ctrl+C"] {
        assert!(table.iter().any(|k| k == keys), "{keys}");
    }
}

#[test]
fn readme_keeps_the_two_commands() {
    let readme = doc("README.md");
    let block = "```sh\ncargo run --release          # the debugger, on the built-in seven-rays scene\n\
                 cargo test --release         # every test";
    assert!(readme.contains(block), "README's two commands, as written");
    assert_eq!(
        raystep_engine::scene::builtin::NAME,
        "seven-rays.toml (built in)",
        "the scene the first command opens"
    );
    // A front door, not the manual.
    let lines = readme.lines().count();
    assert!(lines <= 260, "README has {lines} lines");
}

/// Every Markdown document a reader is sent to: README and the guides.
fn documents() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut docs = vec!["README.md".to_string()];
    let mut guides: Vec<String> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    guides.sort();
    assert!(
        [
            "STUDENTS", "TEACHERS", "DEBUGGER", "SCENES", "MODEL", "RAYLOG"
        ]
        .iter()
        .all(|g| guides.contains(&format!("docs/{g}.md"))),
        "{guides:?}"
    );
    docs.extend(guides);
    docs
}

/// A command line found in a document: where, and the text as shown.
#[derive(Debug)]
struct Shown {
    at: String,
    line: String,
    /// In a code block (a whole command), not a span inside a sentence,
    /// which may name a command without all it needs (`raystep grade`).
    whole: bool,
}

/// Every command line of `text`: the lines of its code blocks (a `$ `
/// prompt dropped, `\` continuations joined) and its inline code spans.
/// Only raystep's own are parsed; the others' repository paths are checked.
fn command_lines(name: &str, text: &str) -> Vec<Shown> {
    let mut shown = Vec::new();
    let mut prose = String::new();
    let mut in_block = false;
    let mut pending = String::new();
    for (number, line) in text.lines().enumerate() {
        let at = format!("{name}:{}", number + 1);
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            prose.push('\n');
            continue;
        }
        if !in_block {
            prose.push_str(line);
            prose.push('\n');
            continue;
        }
        prose.push('\n'); // keeps the spans' line numbers
        let line = line.trim_start();
        let line = line.strip_prefix("$ ").unwrap_or(line);
        if let Some(head) = line.strip_suffix('\\') {
            pending.push_str(head);
            continue;
        }
        let whole = std::mem::take(&mut pending) + line;
        if is_command(&whole) {
            shown.push(Shown {
                at,
                line: whole,
                whole: true,
            });
        }
    }
    // Inline spans: the text between backticks, outside code blocks.
    let mut line_of = 1;
    for (i, piece) in prose.split('`').enumerate() {
        if i % 2 == 1 && is_command(piece) {
            shown.push(Shown {
                at: format!("{name}:{line_of}"),
                line: piece.replace('\n', " "),
                whole: false,
            });
        }
        line_of += piece.matches('\n').count();
    }
    shown
}

/// A line that runs something we check: raystep, or any command naming a
/// file of the repository.
fn is_command(line: &str) -> bool {
    let line = line.trim_start();
    let line = line.strip_prefix("time ").unwrap_or(line);
    line.starts_with("raystep")
        || line.starts_with("cargo run --release")
        || (line.starts_with("python3 ") && !line.contains('\n'))
}

/// The placeholders the documents use in command templates, and a value
/// each stands for when the template is parsed.
fn placeholders() -> BTreeMap<&'static str, &'static str> {
    BTreeMap::from([
        ("SCENE", "scenes/glass.toml"),
        ("ORIGINAL", "scenes/glass.toml"),
        ("X,Y", "1,1"),
        ("WxH", "64x48"),
        ("N", "2"),
        ("F", "2"),
        ("E", "0.1"),
        ("NAME", "shadow-acne"),
        ("KEY=VALUE", "settings.max_depth=2"),
        ("GEOMETRY", "1e-4,0.002"),
        ("IMAGE.png", "yours.png"),
        ("OUT.png", "out.png"),
        ("DIFF.png", "diff.png"),
        ("FIG.svg", "fig.svg"),
        ("LOG.jsonl", "rays.jsonl"),
        ("LOG", "rays.jsonl"),
        ("DIR", "student/"),
        ("ASSIGNMENT.toml", "scenes/assignments/a5.toml"),
        ("SUBMISSIONS/", "submissions/"),
        ("REPORT/", "report/"),
        ("RESULTS.json", "results.json"),
        ("COMMAND", "render"),
        ("ARGS", ""),
    ])
}

/// A word that reads as a placeholder: capitals (and punctuation) before
/// any extension, no small letter.
fn looks_like_placeholder(word: &str) -> bool {
    let stem = word.split('.').next().unwrap_or(word);
    stem.chars().any(|c| c.is_ascii_uppercase()) && !stem.chars().any(|c| c.is_ascii_lowercase())
}

/// Splits `line` as a shell would (quotes, a `#` comment), then reads a
/// synopsis' grammar: `[...]` optional parts kept, the first of `a | b`
/// alternatives, the first of `text|json` values, `...` dropped, and each
/// placeholder replaced. Stops at a pipe or a redirection. Returns the
/// words and whether any was a placeholder.
fn words(line: &str) -> Result<(Vec<String>, bool), String> {
    let line = line.replace("GEOMETRY[,COLOUR]", "GEOMETRY");
    let mut raw = Vec::new();
    let mut word = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    let mut quote = None;
    while let Some(c) = chars.next() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some('"'), '\\') => word.extend(chars.next()),
            (Some(_), c) => word.push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                quoted = true;
            }
            (None, '#') if word.is_empty() => break,
            (None, c) if c.is_whitespace() => {
                if !word.is_empty() || quoted {
                    raw.push((std::mem::take(&mut word), quoted));
                }
                quoted = false;
            }
            (None, c) => word.push(c),
        }
    }
    if quote.is_some() {
        return Err("an unclosed quote".into());
    }
    if !word.is_empty() || quoted {
        raw.push((word, quoted));
    }
    let placeholders = placeholders();
    let mut out = Vec::new();
    let mut templated = false;
    let mut depth = 0usize;
    let mut skip_below = None;
    for (word, quoted) in raw {
        if quoted {
            if skip_below.is_none() {
                out.push(word);
            }
            continue;
        }
        if depth == 0 && matches!(word.as_str(), "|" | ">" | "<" | "&&" | ";") {
            break;
        }
        let mut w = word.as_str();
        while let Some(rest) = w.strip_prefix('[') {
            depth += 1;
            w = rest;
        }
        let w = w.strip_suffix("...").unwrap_or(w);
        let mut closes = 0;
        let mut w = w;
        while let Some(rest) = w.strip_suffix(']') {
            closes += 1;
            w = rest;
        }
        if depth == 0 && closes > 0 {
            return Err(format!("`]` without `[` in {word:?}"));
        }
        if w == "|" {
            // `[a | b]`: the first alternative stands for the group.
            skip_below.get_or_insert(depth);
        } else if skip_below.is_none() && !w.is_empty() && w != "..." {
            let value = if let Some(value) = placeholders.get(w) {
                templated = true;
                value.to_string()
            } else if looks_like_placeholder(w) {
                return Err(format!("an unknown placeholder {w:?}"));
            } else if w.contains('|') && !w.starts_with('-') {
                w.split('|').next().unwrap().to_string()
            } else {
                w.to_string()
            };
            if !value.is_empty() {
                out.push(value);
            }
        }
        if closes > depth {
            return Err(format!("`]` without `[` in {word:?}"));
        }
        depth -= closes;
        if skip_below.is_some_and(|d| depth < d) {
            skip_below = None;
        }
    }
    if depth != 0 {
        return Err("a `[` never closed".into());
    }
    Ok((out, templated))
}

/// What is wrong with one command line as shown, if anything: raystep's
/// parser refuses it, a file it reads is missing, a repository path it
/// names is missing, or its pixel is outside the scene's image.
fn check(shown: &Shown) -> Result<(), String> {
    let (words, templated) = words(&shown.line)?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for word in &words {
        for part in word.split('=') {
            let repo_path = ["scenes/", "docs/", "src/", "tests/", "benches/", "fuzz/"]
                .iter()
                .any(|r| part.starts_with(r));
            if repo_path && !root.join(part).exists() {
                return Err(format!("{part} does not exist"));
            }
        }
    }
    let words: Vec<&str> = words.iter().map(String::as_str).collect();
    let words = match words.as_slice() {
        ["time", rest @ ..] => rest,
        all => all,
    };
    let argv: Vec<&str> = match words {
        ["raystep", rest @ ..] => std::iter::once("raystep")
            .chain(rest.iter().copied())
            .collect(),
        ["cargo", "run", "--release"] => vec!["raystep"],
        ["cargo", "run", "--release", "--", rest @ ..] => std::iter::once("raystep")
            .chain(rest.iter().copied())
            .collect(),
        ["cargo", "run", "--release", ..] => {
            return Err("cargo run --release takes raystep's arguments after `--`".into());
        }
        _ => return Ok(()), // another program: its repository paths were checked
    };
    if let Err(error) = Cli::try_parse_from(&argv) {
        use clap::error::ErrorKind::*;
        let fragment = !shown.whole && error.kind() == MissingRequiredArgument;
        let help = matches!(error.kind(), DisplayHelp | DisplayVersion);
        if !(fragment || help) {
            return Err(format!("raystep's parser refuses {argv:?}: {error}"));
        }
        return Ok(());
    }
    let matches = Cli::command().try_get_matches_from(&argv).unwrap();
    let (command, args) = matches.subcommand().unwrap_or(("debug", &matches));
    // The ids read below are clap's names of `Cli`'s fields: a renamed one
    // must fail here, not skip the checks.
    let id = if command == "grade" {
        "assignment"
    } else {
        "scene"
    };
    args.try_get_one::<PathBuf>(id)
        .map_err(|e| format!("raystep {command} has no argument `{id}`: {e}"))?;
    // The files the command reads that the documents must provide (the
    // student's image, log and submissions are the reader's own, and so is
    // an absolute path: an autograder's container).
    for id in ["scene", "diff_against", "assignment"] {
        if let Ok(Some(path)) = args.try_get_one::<PathBuf>(id)
            && path.is_relative()
            && !root.join(path).is_file()
        {
            return Err(format!("it reads {}, which does not exist", path.display()));
        }
    }
    let pixel = args.try_get_one::<(u32, u32)>("pixel").ok().flatten();
    let scene = args.try_get_one::<PathBuf>("scene").ok().flatten();
    let traced_at_image = args
        .try_get_one::<PathBuf>("compare")
        .ok()
        .flatten()
        .is_some();
    if let (Some(&(x, y)), Some(scene), false) = (pixel, scene, traced_at_image) {
        let loaded = raystep_engine::scene::load(&root.join(scene)).map_err(|e| e.to_string())?;
        let size = args.try_get_one::<(u32, u32)>("size").ok().flatten();
        let (w, h) = size.copied().unwrap_or((loaded.width, loaded.height));
        if !templated && (x >= w || y >= h) {
            return Err(format!(
                "pixel {x},{y} is outside {}'s {w}x{h}",
                scene.display()
            ));
        }
    }
    Ok(())
}

#[test]
fn every_command_line_shown_is_one_raystep_takes() {
    let mut count = 0;
    let mut wrong = Vec::new();
    for name in documents() {
        for shown in command_lines(&name, &doc(&name)) {
            count += 1;
            if let Err(why) = check(&shown) {
                wrong.push(format!("{}: `{}`: {why}", shown.at, shown.line));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{} of {count} command lines are wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    println!("{count} command lines checked");
    // README's synopsis, the tour, the guides' examples and templates.
    assert!(count >= 60, "only {count} command lines found");
}

#[test]
fn the_command_line_check_catches_broken_lines() {
    let bad = [
        // A misspelt flag, a mistake that is not in the catalogue, a value
        // clap refuses, a scene that is not there, a pixel off the image,
        // a path of the repository that is not there, a bad synopsis.
        "raystep render scenes/glass.toml -o out.png --mistakes shadow-acne",
        "raystep render scenes/glass.toml -o out.png --mistake shadow-akne",
        "raystep inspect scenes/glass.toml --pixel 10,10 --format svg",
        "raystep explain scenes/glas.toml --pixel 10,10",
        "raystep explain scenes/glass.toml --pixel 160,10",
        "python3 benches/no_such_script.py",
        "raystep render SCENE -o OUT.png [--size WxH",
        "raystep render SCENE -o OUT.png --tint COLOUR",
        "cargo run --release scenes/glass.toml",
        "raystep diagram scenes/glass.toml --pixel 1,1 -o fig.svg --plane sideways",
    ];
    for line in bad {
        let shown = Shown {
            at: "test".into(),
            line: line.into(),
            whole: true,
        };
        assert!(check(&shown).is_err(), "passed: {line}");
    }
    let good = [
        "raystep render SCENE -o OUT.png [--size WxH] [--threads N] [--stats | --timings] [--mistake NAME]...",
        "raystep compare SCENE [IMAGE.png] --rays LOG.jsonl [--tolerance GEOMETRY[,COLOUR]] [--format text|json]",
        "raystep explain scenes/glass.toml --pixel 135,58 --set settings.max_depth=2",
        "cargo run --release -- scenes/two-lights.toml # a comment",
        "raystep inspect --set 'materials.\"a.b\".kd=0.5' scenes/glass.toml --pixel 1,1",
    ];
    for line in good {
        let shown = Shown {
            at: "test".into(),
            line: line.into(),
            whole: true,
        };
        assert_eq!(check(&shown), Ok(()), "{line}");
    }
    // A span in a sentence may name a command without its arguments, but
    // not misspell it.
    let span = |line: &str| Shown {
        at: "test".into(),
        line: line.into(),
        whole: false,
    };
    assert_eq!(check(&span("raystep grade")), Ok(()));
    assert!(check(&span("raystep grades")).is_err());
    let found = command_lines(
        "x.md",
        "Run `raystep explain SCENE\n--pixel X,Y`.\n```sh\n$ raystep grade A.toml \\\n    S/ -o R/\n```\n",
    );
    let lines: Vec<_> = found.iter().map(|s| (s.line.as_str(), s.whole)).collect();
    assert_eq!(
        lines,
        [
            ("raystep grade A.toml S/ -o R/", true),
            ("raystep explain SCENE --pixel X,Y", false)
        ]
    );
}

/// GitHub's anchor for a heading: small letters, spaces to `-`, the other
/// punctuation but `-` and `_` dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[test]
fn every_link_between_the_documents_leads_somewhere() {
    // Moving text from README into the guides moved its headings: a link
    // to a file or a heading that is not there is a dead end.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut links = 0;
    let mut dead = Vec::new();
    for name in documents() {
        let text = doc(&name);
        let dir = Path::new(&name).parent().unwrap().to_path_buf();
        for piece in text.split("](").skip(1) {
            let target = &piece[..piece.find(')').unwrap_or(piece.len())];
            if target.starts_with("http") {
                continue;
            }
            links += 1;
            let (file, heading) = target.split_once('#').unwrap_or((target, ""));
            let file = if file.is_empty() {
                PathBuf::from(&name)
            } else {
                dir.join(file)
            };
            let Ok(linked) = std::fs::read_to_string(root.join(&file)) else {
                if !root.join(&file).exists() {
                    dead.push(format!("{name}: {target}"));
                }
                continue;
            };
            let headings: Vec<String> = linked
                .lines()
                .filter(|l| l.starts_with('#'))
                .map(|l| anchor(l.trim_start_matches('#')))
                .collect();
            if !heading.is_empty() && !headings.iter().any(|h| h == heading) {
                dead.push(format!("{name}: {target} (no such heading)"));
            }
        }
    }
    assert!(dead.is_empty(), "{dead:#?}");
    assert!(links >= 20, "only {links} links");
    assert_eq!(
        anchor(" Your tracer's rays beside ours (`compare --rays`)"),
        "your-tracers-rays-beside-ours-compare---rays"
    );
}

/// A scene with one of each table, every key left out that a test sets.
fn defaults_scene(
    camera: &str,
    image: &str,
    settings: &str,
    material: &str,
    light: &str,
    mesh: &str,
    sphere: &str,
) -> String {
    // `[image]` takes both sizes or is left out.
    let image = if image.is_empty() {
        String::new()
    } else {
        format!("[image]\n{image}\n")
    };
    format!(
        "[camera]\neye = [0, 1, 6]\nlook_at = [0, 0, 0]\n{camera}\n\
         {image}[settings]\n{settings}\n\
         [materials.m]\n{material}\n\
         [[light]]\nposition = [2, 4, 4]\n{light}\n\
         [[object]]\nname = \"ball\"\nmaterial = \"m\"\nsphere = {{ center = [0, 0, 0], radius = 1{sphere} }}\n\
         [[object]]\nname = \"box\"\nmesh = {{ file = \"cornell/cornell.obj\"{mesh} }}\n"
    )
}

#[test]
fn scenes_guide_defaults_are_the_readers() {
    // Each row of SCENES.md's table of defaults: the key written with the
    // default the table gives reads as the same scene as the key left out.
    let scenes = doc("docs/SCENES.md");
    let start = scenes
        .find("| key | default |")
        .expect("the table of defaults");
    let rows: BTreeMap<String, String> = scenes[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            (cells[1].to_string(), cells[2].to_string())
        })
        .collect();
    // (row's key, what its default says, the section and line that write it)
    let literal = [
        ("`camera.up`", "`[0, 1, 0]`", 0, "up = [0, 1, 0]"),
        ("`camera.fov`", "45 ", 0, "fov = 45"),
        (
            "`image.width` x `image.height`",
            "320 x 240",
            1,
            "width = 320\nheight = 240",
        ),
        (
            "`settings.background`",
            "`[0, 0, 0]`",
            2,
            "background = [0, 0, 0]",
        ),
        (
            "`settings.ambient` (I_a)",
            "`[0, 0, 0]`",
            2,
            "ambient = [0, 0, 0]",
        ),
        (
            "`settings.light_attenuation`",
            "`[1, 0, 0]`",
            2,
            "light_attenuation = [1, 0, 0]",
        ),
        (
            "`settings.ray_attenuation`",
            "`[1, 0, 0]`",
            2,
            "ray_attenuation = [1, 0, 0]",
        ),
        ("`settings.max_depth`", "5", 2, "max_depth = 5"),
        (
            "`settings.min_weight`",
            "0.001953125",
            2,
            "min_weight = 0.001953125",
        ),
        ("`settings.max_rays`", "4096", 2, "max_rays = 4096"),
        (
            "`settings.specular`",
            "`\"blinn\"`",
            2,
            "specular = \"blinn\"",
        ),
        (
            "material `color` (O_d)",
            "`[1, 1, 1]`",
            3,
            "color = [1, 1, 1]",
        ),
        ("material `kd`", "1", 3, "kd = 1"),
        ("material `ks`", "0", 3, "ks = 0"),
        ("material `n`", "20", 3, "n = 20"),
        ("material `kt`", "0 ", 3, "kt = 0"),
        ("material `ior`", "1", 3, "ior = 1"),
        ("material `ka`", "1", 3, "ka = 1"),
        ("material `reflect`", "`true`", 3, "reflect = true"),
        (
            "`settings.profile`",
            "`\"lecture\"`",
            2,
            "profile = \"lecture\"",
        ),
        (
            "material `emission` (E)",
            "`[0, 0, 0]`",
            3,
            "emission = [0, 0, 0]",
        ),
        (
            "material `specular_color` (O_s)",
            "`[1, 1, 1]`",
            3,
            "specular_color = [1, 1, 1]",
        ),
        ("light `name`", "`\"light 0\"`", 4, "name = \"light 0\""),
        ("light `color` (I_p)", "`[1, 1, 1]`", 4, "color = [1, 1, 1]"),
        ("mesh `scale`", "1", 5, ", scale = 1"),
        ("mesh `rotate`", "`[0, 0, 0]`", 5, ", rotate = [0, 0, 0]"),
        (
            "mesh `translate`",
            "`[0, 0, 0]`",
            5,
            ", translate = [0, 0, 0]",
        ),
        ("sphere `scale`", "`[1, 1, 1]`", 6, ", scale = [1, 1, 1]"),
        ("sphere `rotate`", "`[0, 0, 0]`", 6, ", rotate = [0, 0, 0]"),
    ];
    // Rows whose default is no value a file could write the same way.
    let described = [
        "`camera.eye`, `camera.look_at`",
        "material `specular`",
        "material `ambient`",
        "light `attenuation`",
        "object `name`",
        "object `material`",
        "light `position` or `direction`",
        "mesh `material`",
        "a mesh alone",
    ];
    let read = |parts: [&str; 7]| {
        let [c, i, s, m, l, x, o] = parts;
        let text = defaults_scene(c, i, s, m, l, x, o);
        let scene = raystep_engine::scene::parse(Path::new("scenes/defaults.toml"), &text)
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        format!("{scene:?}")
    };
    let bare = read([""; 7]);
    for (key, default, section, line) in literal {
        let cell = rows.get(key).unwrap_or_else(|| panic!("no row {key}"));
        assert!(
            cell.starts_with(default)
                || cell.contains(&format!(" {default}"))
                || cell.contains(&format!("= {default}")),
            "{key}: {cell}"
        );
        let mut parts = [""; 7];
        parts[section] = line;
        assert_eq!(read(parts), bare, "{key} = its default in SCENES.md");
    }
    // The comparison sees a change: a depth of 6 is not the default.
    assert_ne!(read(["", "", "max_depth = 6", "", "", "", ""]), bare);
    let covered: Vec<&str> = literal.iter().map(|r| r.0).chain(described).collect();
    for key in rows.keys() {
        assert!(
            covered.contains(&key.as_str()),
            "the row {key} is checked by no one"
        );
    }
    assert_eq!(rows.len(), covered.len());
}
