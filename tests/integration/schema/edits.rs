//! Thousands of small edits of real scenes, each judged by the schema of the types and by the
//! parser, which must agree.

use super::every_key::{EVERY_KEY, schema_words};
use super::*;

/// Calls `check` with each small edit of `scene`: at every table, an unknown key and each
/// key removed; every value replaced by values of each JSON type, and every string (a `type`
/// tag, a mode, a name) by each word the schema knows.
pub(super) fn for_each_edit(scene: &Value, check: &mut dyn FnMut(String, &Value)) {
    let mut pointers = vec![];
    collect_pointers(scene, String::new(), &mut pointers);
    let (mut keys, mut consts) = (vec![], vec![]);
    schema_words(&snell::scene::schema(), &mut keys, &mut consts);
    let mut tags = vec![];
    for c in consts {
        if !tags.contains(&c) {
            tags.push(c);
        }
    }
    let probes = [
        json!("x"),
        json!(1),
        json!(0.5),
        json!(-1),
        json!(true),
        json!(null),
        json!([]),
        json!([1, 2]),
        json!([1, 2, 3]),
        json!({}),
        json!({ "type": "uv" }),
    ];
    for p in &pointers {
        let mut edited = |what: String, edit: &dyn Fn(&mut Value)| {
            let mut copy = scene.clone();
            edit(copy.pointer_mut(p).unwrap());
            check(format!("{p} {what}"), &copy);
        };
        if let Value::Object(map) = scene.pointer(p).unwrap() {
            edited("+ bogus".to_string(), &|n| {
                n.as_object_mut().unwrap().insert("bogus".into(), json!(1));
            });
            for key in map.keys() {
                edited(format!("- {key}"), &|n| {
                    n.as_object_mut().unwrap().remove(key);
                });
            }
        }
        if p.is_empty() {
            edited("+ $schema".to_string(), &|n| {
                n.as_object_mut()
                    .unwrap()
                    .insert("$schema".into(), json!("./snell.schema.json"));
            });
            continue;
        }
        let words = if scene.pointer(p).unwrap().is_string() {
            &tags[..]
        } else {
            &[]
        };
        for v in probes.iter().chain(words) {
            edited(format!("= {v}"), &|n| *n = v.clone());
        }
    }
}

pub(super) fn collect_pointers(v: &Value, at: String, out: &mut Vec<String>) {
    let escape = |k: &str| k.replace('~', "~0").replace('/', "~1");
    match v {
        Value::Object(map) => {
            for (k, child) in map {
                collect_pointers(child, format!("{at}/{}", escape(k)), out);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                collect_pointers(child, format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
    out.push(at);
}

/// The two known differences, where the parser takes an edit the schema refuses: serde
/// takes more than the format says, and the schema does not follow it (nobody should write
/// these; docs/scene-format.md does not offer them).
/// - A struct may be written as an array of its fields in order, so the parser takes
///   `image = [800, 600]` as width and height, and `transform = []` as no transform.
/// - In JSON, the tag of a tagged table inside another one (a texture's `mapping`) may be
///   the variant's index: `"type": 1` is `"spherical"`.
pub(super) fn known_difference(scene: &Value, edited: &Value, label: &str) -> bool {
    let pointer = label.split(' ').next().unwrap();
    let (before, after) = (scene.pointer(pointer), edited.pointer(pointer));
    let table_as_array = before.is_some_and(Value::is_object) && after.is_some_and(Value::is_array);
    let tag_as_index = pointer.ends_with("/mapping/type") && after.is_some_and(Value::is_u64);
    table_as_array || tag_as_index
}

#[test]
fn the_schema_and_the_parser_agree_on_every_small_edit_of_every_scene() {
    let mut scenes: Vec<(String, Value)> = shipped_scenes()
        .iter()
        .map(|p| (p.display().to_string(), scene_value(p)))
        .collect();
    scenes.push(("the test scene".to_string(), toml_value(SCENE)));
    scenes.push(("EVERY_KEY".to_string(), toml_value(EVERY_KEY)));
    let (mut checked, mut refused, mut in_toml, mut disagree) = (0, 0, 0, vec![]);
    for (name, scene) in &scenes {
        for_each_edit(scene, &mut |label, edited| {
            checked += 1;
            let schema = type_problems(edited);
            let differ = |parsed: bool| {
                schema.is_empty() != parsed && !(parsed && known_difference(scene, edited, &label))
            };
            let parser = parses(edited);
            if differ(parser.is_ok()) {
                disagree.push(format!(
                    "{name}: {label}: schema {schema:?}, parser {parser:?}"
                ));
            }
            refused += usize::from(parser.is_err());
            // The same edit as a TOML file, where TOML can write it (it has no null).
            if let Ok(text) = toml::to_string(edited) {
                let parser = toml::from_str::<SceneFile>(&text).map(|_| ());
                if differ(parser.is_ok()) {
                    disagree.push(format!(
                        "{name}: {label} (TOML): schema {schema:?}, parser {parser:?}"
                    ));
                }
                in_toml += 1;
            }
        });
    }
    assert!(
        checked > 10_000 && refused > 5_000 && in_toml > 10_000,
        "only {checked} edits ({refused} refused, {in_toml} also as TOML)"
    );
    assert!(
        disagree.is_empty(),
        "{} of {checked} edits:\n{}",
        disagree.len(),
        disagree[..disagree.len().min(30)].join("\n")
    );
}
