//! Scene text to a [`SceneFile`]: TOML or JSON read into the format's serde types, and a
//! serde error turned into a [`Problem`] located at the value or key it is about, with a hint
//! (a suggested key or variant, what a number may be). Kept apart from the checks of values,
//! which start only once the text has parsed.

use crate::scene::diag::{DocPath, Format, Problem, Seg, did_you_mean, offset_of, values_below};
use crate::scene::format::SceneFile;

/// The scene file in `text`, or the first problem that stops serde, located.
pub(super) fn parse(text: &str, format: Format) -> Result<SceneFile, Problem> {
    parse_unrefined(text, format).map_err(|p| refine(text, format, p))
}

/// Inside tagged tables (objects, lights, textures, mappings) serde buffers values and loses
/// their positions, so a type error is reported at the whole table. Find the value the
/// message describes (`invalid type: string "big"`, `invalid length 2`) below it.
fn refine(text: &str, format: Format, p: Problem) -> Problem {
    if p.at_key {
        // An unknown key in a table nested inside a tagged one (an object's `transform`)
        // comes with the tagged table's path: find the key below it.
        let Some((parent, Seg::Key(field))) = p
            .path
            .0
            .split_last()
            .map(|(l, r)| (DocPath(r.to_vec()), l.clone()))
        else {
            return p;
        };
        let below = values_below(text, format, &parent);
        if below.iter().any(|(q, _)| *q == p.path) {
            return p;
        }
        let nested = below
            .into_iter()
            .find(|(q, _)| q.0.last() == Some(&Seg::Key(field.clone())));
        return match nested {
            Some((path, _)) => Problem { path, ..p },
            None => p,
        };
    }
    if !p.message.contains("invalid ") {
        return p;
    }
    let Some(described) = p.message.split("invalid ").nth(1) else {
        return p;
    };
    let matches = |raw: &str| -> bool {
        let raw = raw.trim();
        if let Some(rest) = described.strip_prefix("type: string ") {
            let want = rest
                .split(", expected")
                .next()
                .unwrap_or("")
                .trim_matches('"');
            (raw.starts_with('"') || raw.starts_with('\''))
                && raw.trim_matches(|c| c == '"' || c == '\'') == want
        } else if let Some(rest) = described
            .strip_prefix("type: integer `")
            .or_else(|| described.strip_prefix("value: integer `"))
            .or_else(|| described.strip_prefix("type: floating point `"))
            .or_else(|| described.strip_prefix("value: floating point `"))
        {
            let want = rest.split('`').next().unwrap_or("");
            raw.parse::<f64>()
                .ok()
                .zip(want.parse::<f64>().ok())
                .is_some_and(|(a, b)| a == b)
        } else if let Some(rest) = described.strip_prefix("type: boolean `") {
            raw == rest.split('`').next().unwrap_or("")
        } else if described.starts_with("type: sequence") {
            raw.starts_with('[')
        } else if let Some(rest) = described.strip_prefix("length ") {
            let n: usize = rest
                .split(',')
                .next()
                .unwrap_or("")
                .parse()
                .unwrap_or(usize::MAX);
            raw.starts_with('[') && count_items(raw) == Some(n)
        } else {
            false
        }
    };
    // Only a value the message singles out: with two arrays (or two equal strings) in the
    // table, the message could mean either, and the table itself is the honest answer.
    let mut found = values_below(text, format, &p.path)
        .into_iter()
        .filter(|(_, span)| text.get(span.clone()).is_some_and(matches));
    let first = found.next();
    let unique = found.next().is_none();
    match first.filter(|_| unique) {
        Some((path, span)) if path != p.path => {
            let message = p.message.clone();
            Problem {
                span: Some(span),
                ..Problem::new(path, message)
            }
            .with_help(p.help)
        }
        _ => p,
    }
}

/// Number of items in a flat array literal such as `[1, 2]` (`None` if it nests).
fn count_items(raw: &str) -> Option<usize> {
    let inner = raw.strip_prefix('[')?.strip_suffix(']')?;
    if inner.contains('[') || inner.contains('{') {
        return None;
    }
    Some(inner.split(',').filter(|x| !x.trim().is_empty()).count())
}

/// The scene file in `text`, or serde's first problem as serde located it (see [`refine`]).
fn parse_unrefined(text: &str, format: Format) -> Result<SceneFile, Problem> {
    match format {
        Format::Toml => {
            let table = toml::de::DeTable::parse(text).map_err(|e| Problem {
                span: e.span(),
                ..Problem::new(
                    DocPath::default(),
                    format!("TOML syntax: {}", e.message().trim_end()),
                )
            })?;
            serde_path_to_error::deserialize(toml::de::Deserializer::from(table)).map_err(|e| {
                let span = e.inner().span();
                serde_problem(e.path(), e.inner().message(), span)
            })
        }
        Format::Json => {
            let mut de = serde_json::Deserializer::from_str(text);
            let result: Result<SceneFile, _> = serde_path_to_error::deserialize(&mut de);
            let syntax = |inner: &serde_json::Error| {
                let at = offset_of(text, inner.line(), inner.column());
                let msg = inner.to_string();
                // serde_json appends " at line L column C"; the location is shown anyway.
                let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
                (at, msg)
            };
            if let Ok(v) = result {
                return de.end().map(|_| v).map_err(|e| {
                    let (at, msg) = syntax(&e);
                    Problem {
                        span: Some(at..at),
                        ..Problem::new(DocPath::default(), format!("JSON syntax: {msg}"))
                    }
                });
            }
            result.map_err(|e| {
                let inner = e.inner();
                let (at, msg) = syntax(inner);
                if inner.is_syntax() || inner.is_eof() {
                    Problem {
                        span: Some(at..at),
                        ..Problem::new(DocPath::default(), format!("JSON syntax: {msg}"))
                    }
                } else {
                    let mut p = serde_problem(e.path(), &msg, None);
                    if p.path.0.is_empty() && p.span.is_none() {
                        p.span = Some(at..at);
                    }
                    p
                }
            })
        }
    }
}

/// Turns a serde error at a path into a problem with a hint.
fn serde_problem(
    path: &serde_path_to_error::Path,
    message: &str,
    span: Option<std::ops::Range<usize>>,
) -> Problem {
    use serde_path_to_error::Segment;
    let mut doc = DocPath::default();
    for seg in path.iter() {
        match seg {
            Segment::Seq { index } => doc = doc.index(*index),
            Segment::Map { key } => doc = doc.key(key),
            Segment::Enum { .. } => {}
            Segment::Unknown => break,
        }
    }
    let message = message.trim_end().to_string();
    if let Some(field) = between(&message, "unknown field `", "`") {
        let expected = backticked(message.split_once("expected").map_or("", |x| x.1));
        // serde_path_to_error records the unknown key itself for plain structs, not for
        // tagged ones.
        let path = if doc.0.last() == Some(&Seg::Key(field.to_string())) {
            doc
        } else {
            doc.key(field)
        };
        let mut p = Problem::new(path, format!("unknown key `{field}`"));
        p.at_key = true;
        p.help = Some(
            match did_you_mean(field, expected.iter().map(String::as_str)) {
                Some(s) => format!("did you mean `{s}`?"),
                None if expected.is_empty() => "no other key belongs here".to_string(),
                None => format!("known keys here: {}", expected.join(", ")),
            },
        );
        return p;
    }
    if let Some(variant) = between(&message, "unknown variant `", "`") {
        let expected = backticked(message.split_once("expected").map_or("", |x| x.1));
        // A `type` names a kind of thing; other keys (a sampler, a tone curve) take values.
        let what = match doc.0.last() {
            Some(Seg::Key(k)) if k == "type" => "type",
            _ => "value",
        };
        let mut p = Problem::new(doc, format!("unknown {what} `{variant}`"));
        p.span = span;
        p.help = Some(
            match did_you_mean(variant, expected.iter().map(String::as_str)) {
                Some(s) => format!("did you mean `{s}`?"),
                None => format!("expected one of: {}", expected.join(", ")),
            },
        );
        return p;
    }
    if let Some(field) = between(&message, "missing field `", "`") {
        let mut p = Problem::new(doc.clone(), format!("missing key `{field}`"));
        p.span = span;
        // The file's top level holds tables (`[camera]`); keys go inside them.
        p.help = Some(if doc.0.is_empty() {
            format!("add a `[{field}]` table (see docs/scene-format.md)")
        } else {
            format!("add `{field} = ...` here (see docs/scene-format.md)")
        });
        return p;
    }
    // A whole number of the wrong sign or size: say what the key takes, where a key says
    // more than its type does (a width of 0 is refused too).
    if let Some(n) = between(&message, "invalid value: integer `", "`") {
        let key = match doc.0.last() {
            Some(Seg::Key(k)) => k.as_str(),
            _ => "",
        };
        let range = match key {
            "width" | "height" => {
                format!(
                    "from 1 to {} pixels",
                    crate::scene::RenderSettings::MAX_SIDE
                )
            }
            "samples" | "max_depth" | "rr_depth" => "from 1".to_string(),
            _ => "from 0".to_string(),
        };
        let mut p = Problem::new(
            doc,
            format!("`{n}` is not allowed here: a whole number {range}"),
        );
        p.span = span;
        return p;
    }
    let mut p = Problem::new(
        doc,
        message
            .replace("f32", "a number")
            .replace("u32", "a whole number ≥ 0")
            .replace("u64", "a whole number ≥ 0"),
    );
    p.span = span;
    p
}

/// The text of `s` between the first `start` and the `end` after it (a name in a serde message).
fn between<'a>(s: &'a str, start: &str, end: &str) -> Option<&'a str> {
    let rest = &s[s.find(start)? + start.len()..];
    Some(&rest[..rest.find(end)?])
}

/// The `backticked` names in `s`, in order (the keys or variants a serde message lists).
fn backticked(s: &str) -> Vec<String> {
    s.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}
