//! The corpus of broken scenes under tests/bad: every file must be refused by `snell check`
//! with exit code 2, its expected messages, a location in the file, and no panic. Expected
//! messages are `# expect: ...` lines at the top of TOML files, or a `NAME.expect` file beside
//! JSON ones (JSON has no comments).

use super::repo;
use std::process::Command;

#[test]
fn every_bad_scene_gets_its_message_a_location_and_exit_2() {
    let dir = repo("tests/bad");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml" || e == "json"))
        .collect();
    files.sort();
    // 142 TOML files and 5 JSON ones today: more may come, none may go.
    assert!(
        files.len() >= 147,
        "the corpus shrank: {} files",
        files.len()
    );
    let mut failures = vec![];
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(path).unwrap();
        let expect_text = if name.ends_with(".json") {
            std::fs::read_to_string(path.with_file_name(format!("{name}.expect"))).unwrap()
        } else {
            text.clone()
        };
        let expected: Vec<&str> = expect_text
            .lines()
            .filter_map(|l| l.trim_start_matches("# ").strip_prefix("expect: "))
            .collect();
        assert!(
            !expected.is_empty(),
            "{name} says nothing about what it expects"
        );
        let out = Command::new(env!("CARGO_BIN_EXE_snell"))
            .args(["check", &name])
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let mut problems = vec![];
        if out.status.code() != Some(2) {
            problems.push(format!("exit code {:?}", out.status.code()));
        }
        if err.contains("panicked") {
            problems.push("panicked".to_string());
        }
        if !err.contains(&format!("[{name}:")) {
            problems.push("no file:line:column".to_string());
        }
        // The messages without the lines of the file they quote (which hold the `# expect:`
        // comments themselves).
        let messages: String = err
            .lines()
            .filter(|l| {
                let t = l.trim_start();
                let digits = t.chars().take_while(char::is_ascii_digit).count();
                !(digits > 0 && t[digits..].starts_with(" │"))
            })
            .collect::<Vec<_>>()
            .join("\n");
        for e in expected {
            if !messages.contains(e) {
                problems.push(format!("missing `{e}`"));
            }
        }
        if !problems.is_empty() {
            failures.push(format!("{name}: {}\n{err}", problems.join(", ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
