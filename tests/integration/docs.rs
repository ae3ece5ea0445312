//! The README's claims about the shipped scenes hold: the seed scene's caption names the size
//! and samples the scene file renders by default, and the picture shown is that size.

use super::repo;

#[test]
fn the_readme_caption_matches_the_seed_scene_and_its_picture() {
    let readme = std::fs::read_to_string(repo("README.md")).unwrap();
    let caption = readme
        .split_once("*The seed scene (`scenes/seed.toml`, ")
        .map(|(_, rest)| rest)
        .expect("the README has the seed scene's caption");
    let (size, rest) = caption.split_once(", ").unwrap();
    let (w, h) = size.split_once(" x ").unwrap();
    let spp = rest.split_once(" samples per pixel").unwrap().0;
    let (w, h, spp): (u32, u32, u32) =
        (w.parse().unwrap(), h.parse().unwrap(), spp.parse().unwrap());
    let scene = snell::scene::load(&repo("scenes/seed.toml")).unwrap();
    let s = &scene.settings;
    assert_eq!(
        (s.width, s.height, s.spp),
        (w, h, spp),
        "the caption says {size}, {spp} spp"
    );
    let picture = image::open(repo("docs/images/seed.png")).unwrap();
    assert_eq!((picture.width(), picture.height()), (w, h));
}

/// The samples per pixel a caption gives: the number before its first ` spp`.
fn caption_spp(caption: &str) -> Option<u32> {
    let before = &caption[..caption.find(" spp")?];
    let digits: String = before
        .chars()
        .rev()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.chars().rev().collect::<String>().parse().ok()
}

/// Whether `view` names a strategy image of `--aov strategies`: `s1-t2`, `s1-t2-unweighted`.
fn is_strategy(view: &str) -> bool {
    let view = view.strip_suffix("-unweighted").unwrap_or(view);
    view.split_once("-t").is_some_and(|(s, t)| {
        s.strip_prefix('s')
            .is_some_and(|s| s.parse::<u32>().is_ok())
            && t.parse::<u32>().is_ok()
    })
}

/// One line of docs/images/make.sh: `render NAME SCENE [FLAGS...]`.
struct Made {
    name: String,
    scene: String,
    flags: Vec<String>,
}

impl Made {
    fn flag(&self, name: &str) -> Option<u32> {
        let i = self.flags.iter().position(|f| f == name)?;
        self.flags.get(i + 1)?.parse().ok()
    }
}

fn made() -> Vec<Made> {
    let script = std::fs::read_to_string(repo("docs/images/make.sh")).unwrap();
    script
        .lines()
        .filter_map(|l| l.strip_prefix("render "))
        .map(|l| {
            let mut words = l.split_whitespace().map(str::to_string);
            Made {
                name: words.next().unwrap(),
                scene: words.next().unwrap(),
                flags: words.collect(),
            }
        })
        .collect()
}

/// Every picture of the README and docs/ is made by docs/images/make.sh from a scene file
/// (but Mitsuba's and the browser's, which the script names), at the size it has, and each
/// caption's samples per pixel are the ones the script renders with: the pictures and their
/// captions cannot drift apart.
#[test]
fn every_picture_is_made_by_the_script_with_the_samples_its_caption_gives() {
    let lines = made();
    let (mut sized, mut captions) = (0, 0);
    for m in &lines {
        // The script writes the far checker read at points from a copy it makes.
        let scene_path = repo(&m.scene.replace(".point.toml", ".toml"));
        let scene = snell::scene::load(&scene_path).unwrap_or_else(|e| panic!("{}: {e}", m.scene));
        let s = &scene.settings;
        let (w, h) = (
            m.flag("--width").unwrap_or(s.width),
            m.flag("--height").unwrap_or(s.height),
        );
        let spp = m.flag("--spp").unwrap_or(s.spp);
        let picture = image::open(repo(&format!("docs/images/{}.png", m.name)))
            .unwrap_or_else(|e| panic!("docs/images/{}.png: {e}", m.name));
        assert_eq!((picture.width(), picture.height()), (w, h), "{}", m.name);
        sized += 1;
        // The caption: the lines after the picture's, up to the next line with a picture.
        let readme = std::fs::read_to_string(repo("README.md")).unwrap();
        let needle = format!("docs/images/{}.png", m.name);
        if let Some(at) = readme.find(&needle) {
            let after = &readme[at..];
            let after = &after[after.find('\n').unwrap_or(after.len())..];
            let caption = after.split("\n![").next().unwrap();
            if let Some(n) = caption_spp(caption) {
                assert_eq!(
                    n, spp,
                    "{}: the caption says {n} spp, the script renders {spp}",
                    m.name
                );
                captions += 1;
            }
        }
    }
    assert_eq!(sized, lines.len());
    assert_eq!(
        (lines.len(), captions),
        (30, 7),
        "pictures made, captions with samples"
    );
    // The lab's pictures (`lab NAME ARGS...`): three panels of 80 x 40 bins, 6 pixels a bin,
    // with gaps of 6.
    let script = std::fs::read_to_string(repo("docs/images/make.sh")).unwrap();
    let labs: Vec<&str> = script
        .lines()
        .filter_map(|l| l.strip_prefix("lab lab-"))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    for name in &labs {
        let picture = image::open(repo(&format!("docs/images/lab-{name}.png")))
            .unwrap_or_else(|e| panic!("docs/images/lab-{name}.png: {e}"));
        assert_eq!(
            (picture.width(), picture.height()),
            (1452, 240),
            "lab-{name}"
        );
    }
    assert_eq!(labs.len(), 4, "lab pictures made");
    // Every picture the pages show is one of the script's (or one it names).
    let mut shown = 0;
    for page in [
        "README.md",
        "docs/debugging.md",
        "docs/scene-format.md",
        "docs/preview.md",
        "docs/lab.md",
        "docs/lpe.md",
        "docs/bdpt.md",
    ] {
        let text = std::fs::read_to_string(repo(page)).unwrap();
        for (i, _) in text.match_indices("images/") {
            let rest = &text[i + "images/".len()..];
            let Some(end) = rest.find(".png") else {
                continue;
            };
            let name = &rest[..end];
            if name.contains(['(', ')', ' ', '[']) {
                continue;
            }
            shown += 1;
            // A debug view's picture: `NAME.VIEW` beside NAME's, from `--aov`; or a light
            // path expression's, from `--lpe VIEW` or `--lpe VIEW=EXPR`.
            let view = name.split_once('.').is_some_and(|(base, view)| {
                lines.iter().any(|m| {
                    m.name == base
                        && m.flags.windows(2).any(|w| {
                            (w[0] == "--aov"
                                && (w[1] == "all" || w[1].split(',').any(|v| v == view)))
                                || (w[0] == "--aov"
                                    && w[1].split(',').any(|v| v == "strategies")
                                    && is_strategy(view))
                                || (w[0] == "--lpe" && w[1].split('=').next() == Some(view))
                        })
                })
            });
            let lab = name.strip_prefix("lab-").is_some_and(|n| labs.contains(&n));
            assert!(
                view || lab
                    || lines.iter().any(|m| m.name == name)
                    || script.contains(&format!("{name}.png")),
                "{page} shows docs/images/{name}.png, which docs/images/make.sh does not make"
            );
        }
    }
    assert!(shown >= 30, "{shown} pictures shown");
}

/// The options a subcommand's `--help` lists (not the flags its prose mentions).
fn options_of(command: &str) -> Vec<String> {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(command.split_whitespace())
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    let mut options: Vec<String> = help
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l
                .strip_prefix('-')
                .filter(|r| !r.starts_with('-'))
                .map_or(l, |r| r.split_once(", ").map_or(l, |(_, rest)| rest));
            let name = l.strip_prefix("--")?;
            let end = name
                .find(|c: char| !(c.is_ascii_lowercase() || c == '-'))
                .unwrap_or(name.len());
            Some(format!("--{}", &name[..end]))
        })
        .filter(|o| o != "--help")
        .collect();
    options.sort();
    options.dedup();
    options
}

/// The flags a synopsis writes for `snell COMMAND`: its line and the lines under it, with
/// `[LIMITS]` standing for the limit flags the synopsis spells out below.
fn synopsis_flags(text: &str, command: &str) -> Vec<String> {
    let block = text
        .split("```text\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .unwrap_or("");
    let start = format!("snell {command} ");
    let mut lines = block
        .lines()
        .skip_while(|l| !l.starts_with(&start) && *l != format!("snell {command}"));
    let mut text = String::new();
    if let Some(first) = lines.next() {
        text += first;
        for l in lines.take_while(|l| l.starts_with(' ')) {
            text += l;
        }
    }
    if text.contains("[LIMITS]") {
        text += block.split("LIMITS:").nth(1).unwrap_or("");
    }
    let mut flags: Vec<String> = text
        .split(|c: char| !(c.is_ascii_lowercase() || c == '-'))
        .filter(|w| w.starts_with("--") && w.len() > 2)
        .map(str::to_string)
        .collect();
    if text.contains(" -o ") || text.contains("[-o ") {
        flags.push("--output".into());
    }
    if text.contains("[-q]") {
        flags.push("--quiet".into());
    }
    flags.sort();
    flags.dedup();
    flags
}

/// The README's synopsis (and the preview page's) name exactly the options each command's
/// `--help` lists, no more and no fewer.
#[test]
fn the_synopses_give_every_option_and_no_other() {
    let readme = std::fs::read_to_string(repo("README.md")).unwrap();
    let mut checked = 0;
    for command in [
        "render",
        "check",
        "merge",
        "explain",
        "serve",
        "schema",
        "lab bsdf",
        "lab light",
        "lab list",
    ] {
        assert_eq!(
            synopsis_flags(&readme, command),
            options_of(command),
            "the README's `snell {command}` against its --help"
        );
        checked += 1;
    }
    let preview = std::fs::read_to_string(repo("docs/preview.md")).unwrap();
    assert_eq!(
        synopsis_flags(&preview, "serve"),
        options_of("serve"),
        "preview.md"
    );
    assert_eq!(checked, 9);
}

/// The source folders docs/ARCHITECTURE.md maps file by file, with the file names each holds
/// (the extensions that are code there).
const MAPPED: &[(&str, &[&str])] = &[
    ("src", &["rs"]),
    ("tests/integration", &["rs"]),
    ("benches", &["rs"]),
    ("examples", &["rs"]),
    ("bench", &["sh", "py"]),
    ("fuzz/fuzz_targets", &["rs"]),
    ("python/snell_farm", &["py"]),
    ("python/tests", &["py"]),
    ("snell-py/src", &["rs"]),
    ("snell-py/python/snell", &["py", "pyi"]),
    ("snell-py/tests", &["py"]),
    ("src/bin/snell/serve/page", &["html", "js", "css"]),
];

/// The files of `dir` and of its folders below (those `MAPPED` does not name itself), as
/// (folder, file name), for the extensions given.
fn source_files(dir: &str, exts: &[&str], out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = std::fs::read_dir(repo(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            let sub = format!("{dir}/{name}");
            let mapped_apart = MAPPED.iter().any(|(d, _)| *d == sub);
            // Python's caches and the tests' data folders hold no source.
            if !mapped_apart && !name.starts_with("__") && !dir.starts_with("python") {
                source_files(&sub, exts, out);
            }
        } else if exts.iter().any(|x| name.ends_with(&format!(".{x}"))) {
            out.push((dir.to_string(), name));
        }
    }
}

/// The map's entries: (folder, file name) for every `- \`NAME\`:` line under a
/// `### \`FOLDER/\`` heading.
fn map_entries(arch: &str) -> Vec<(String, String)> {
    let mut entries = Vec::new();
    let mut folder: Option<String> = None;
    for line in arch.lines() {
        if let Some(h) = line.strip_prefix("### ") {
            folder = h
                .strip_prefix('`')
                .and_then(|h| h.strip_suffix("/`"))
                .map(str::to_string);
        } else if line.starts_with("## ") {
            folder = None;
        } else if let (Some(dir), Some((name, _))) = (
            &folder,
            line.strip_prefix("- `")
                .and_then(|rest| rest.split_once("`:")),
        ) {
            entries.push((dir.clone(), name.to_string()));
        }
    }
    entries
}

#[test]
fn the_architecture_map_names_every_source_file_and_no_other() {
    let arch = std::fs::read_to_string(repo("docs/ARCHITECTURE.md")).unwrap();
    let mut files = Vec::new();
    for (dir, exts) in MAPPED {
        source_files(dir, exts, &mut files);
    }
    let mapped = map_entries(&arch);
    let missing: Vec<_> = files.iter().filter(|f| !mapped.contains(f)).collect();
    let stale: Vec<_> = mapped.iter().filter(|m| !files.contains(m)).collect();
    assert!(
        missing.is_empty(),
        "docs/ARCHITECTURE.md's map lacks these files (folder, name): {missing:?}"
    );
    assert!(
        stale.is_empty(),
        "docs/ARCHITECTURE.md's map names files that are not there: {stale:?}"
    );
    // Every library module, binary module, test module and script of the repository.
    assert!(files.len() > 230, "only {} source files found", files.len());
    assert_eq!(files.len(), mapped.len());
}
