//! OBJ and MTL text, line by line: comments stripped, `\` continuations joined, numbers read
//! with messages that say what was expected.

use std::path::{Path, PathBuf};

pub(super) fn count_ignored(slot: &mut (usize, usize), line: usize) {
    if slot.0 == 0 {
        slot.1 = line;
    }
    slot.0 += 1;
}

/// The folder relative file names are resolved against (`.` for a bare file name).
pub(super) fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

pub(super) fn number(token: &str) -> Result<f32, String> {
    token
        .parse::<f32>()
        .map_err(|_| format!("`{token}` is not a number"))
}

pub(super) fn finite(token: &str) -> Result<f32, String> {
    let x = number(token)?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("`{token}` is not a finite number"))
    }
}

/// The first whitespace-separated word of `s` and everything after it.
pub(super) fn split_first(s: &str) -> Option<(&str, &str)> {
    let s = s.trim_start_matches(|c: char| c.is_ascii_whitespace());
    if s.is_empty() {
        return None;
    }
    let end = s.find(|c: char| c.is_ascii_whitespace()).unwrap_or(s.len());
    Some(s.split_at(end))
}

/// Cuts a `#` comment: at the start of the line or after whitespace, so that file names
/// such as `part#2.mtl` survive.
pub(super) fn strip_comment(line: &str) -> &str {
    let bytes = line.as_bytes();
    let mut from = 0;
    while let Some(i) = bytes
        .get(from..)
        .and_then(|b| b.iter().position(|&c| c == b'#'))
    {
        let at = from + i;
        if at == 0 || bytes.get(at - 1).is_some_and(u8::is_ascii_whitespace) {
            return line.get(..at).unwrap_or(line);
        }
        from = at + 1;
    }
    line
}

/// Calls `f` with each logical line and the number of its first physical line. CR before
/// LF is dropped, and a line ending in `\` is joined with the next (except in comments,
/// where a trailing backslash is just text).
pub(super) fn for_each_line<E>(
    text: &str,
    mut f: impl FnMut(usize, &str) -> Result<(), E>,
) -> Result<(), E> {
    let mut joined = String::new();
    let mut joined_from = None;
    for (i, raw) in text.split('\n').enumerate() {
        let n = i + 1;
        let raw = raw.strip_suffix('\r').unwrap_or(raw);
        let head = raw.trim_end_matches(|c: char| c.is_ascii_whitespace());
        if let Some(head) = head.strip_suffix('\\')
            && (joined_from.is_some() || !raw.trim_start().starts_with('#'))
        {
            if joined_from.is_none() {
                joined_from = Some(n);
                joined.clear();
            }
            joined.push_str(head);
            joined.push(' ');
            continue;
        }
        match joined_from.take() {
            Some(first) => {
                joined.push_str(raw);
                f(first, &joined)?;
            }
            None => f(n, raw)?,
        }
    }
    if let Some(first) = joined_from {
        f(first, &joined)?;
    }
    Ok(())
}
