//! Scene errors that point at the line: every problem carries a path into the document
//! (`objects[3].radius`), which is located in the source text to give file, line, column
//! and a snippet, rendered by miette.

use miette::{NamedSource, SourceSpan};
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One step of a path into a scene document.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Seg {
    /// A key in a table.
    Key(String),
    /// An index in an array.
    Index(usize),
}

/// A path into the document, such as `objects[3].radius`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DocPath(pub Vec<Seg>);

impl DocPath {
    /// This path extended by a key.
    pub fn key(&self, k: &str) -> DocPath {
        let mut p = self.clone();
        p.0.push(Seg::Key(k.to_string()));
        p
    }

    /// This path extended by an index.
    pub fn index(&self, i: usize) -> DocPath {
        let mut p = self.clone();
        p.0.push(Seg::Index(i));
        p
    }
}

impl fmt::Display for DocPath {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        for (i, s) in self.0.iter().enumerate() {
            match s {
                Seg::Key(k) if i == 0 => write!(f, "{k}")?,
                Seg::Key(k) => write!(f, ".{k}")?,
                Seg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// What is wrong, where, and (maybe) how to fix it, before it is located in the text.
#[derive(Clone, Debug)]
pub struct Problem {
    /// Where in the document.
    pub path: DocPath,
    /// Point at the key itself rather than its value (unknown keys).
    pub at_key: bool,
    /// What is wrong.
    pub message: String,
    /// A hint.
    pub help: Option<String>,
    /// An exact byte range, when the parser gave one.
    pub span: Option<Range<usize>>,
}

impl Problem {
    /// A problem with the value at `path`.
    pub fn new(path: DocPath, message: impl Into<String>) -> Self {
        Problem {
            path,
            at_key: false,
            message: message.into(),
            help: None,
            span: None,
        }
    }

    /// With a hint.
    pub fn help(mut self, h: impl Into<String>) -> Self {
        self.help = Some(h.into());
        self
    }

    /// With a hint, if there is one.
    pub fn with_help(mut self, h: Option<String>) -> Self {
        self.help = h;
        self
    }
}

/// One located problem, ready to print.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("{message}")]
pub struct SceneDiagnostic {
    message: String,
    #[source_code]
    src: NamedSource<Arc<String>>,
    #[label("{label}")]
    span: Option<SourceSpan>,
    label: String,
    #[help]
    help: Option<String>,
    /// 1-based line and column, when located.
    pub line_col: Option<(usize, usize)>,
}

impl SceneDiagnostic {
    /// The message without location.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// What to do about it, where the loader knows.
    pub fn help(&self) -> Option<&str> {
        self.help.as_deref()
    }
}

/// A scene that could not be loaded: its file and every problem found.
#[derive(Debug)]
pub struct SceneError {
    /// The scene file.
    pub file: PathBuf,
    /// The problems, in document order where known.
    pub diagnostics: Vec<SceneDiagnostic>,
    /// The files the scene named and the build read or tried to read before it gave up
    /// (textures, meshes, MTL files), for a watcher: creating a missing one may mend it.
    pub files: Vec<PathBuf>,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        for (i, d) in self.diagnostics.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            match d.line_col {
                Some((l, c)) => write!(f, "{}:{l}:{c}: {}", self.file.display(), d.message)?,
                None => write!(f, "{}", d.message)?,
            }
            if let Some(h) = &d.help {
                write!(f, " ({h})")?;
            }
        }
        Ok(())
    }
}

impl std::error::Error for SceneError {}

impl SceneError {
    /// An error about the file as a whole (cannot read it, unknown extension).
    pub fn whole_file(file: &Path, message: impl Into<String>) -> Self {
        SceneError {
            file: file.to_path_buf(),
            diagnostics: vec![SceneDiagnostic {
                message: format!("{}: {}", file.display(), message.into()),
                src: NamedSource::new(file.display().to_string(), Arc::new(String::new())),
                span: None,
                label: String::new(),
                help: None,
                line_col: None,
            }],
            files: vec![],
        }
    }

    /// Locates each problem in `text` and builds the error.
    pub fn located(file: &Path, text: &str, format: Format, problems: Vec<Problem>) -> Self {
        let src = Arc::new(text.to_string());
        let name = file.display().to_string();
        let mut located: Vec<(usize, SceneDiagnostic)> = problems
            .into_iter()
            .map(|p| {
                let span = p
                    .span
                    .clone()
                    .or_else(|| locate(text, format, &p.path, p.at_key));
                let line_col = span.as_ref().map(|s| line_col(text, s.start));
                let label = if p.at_key { "this key" } else { "here" };
                let order = span.as_ref().map_or(usize::MAX, |s| s.start);
                (
                    order,
                    SceneDiagnostic {
                        message: if p.path.0.is_empty() {
                            p.message
                        } else {
                            format!("{}: {}", p.path, p.message)
                        },
                        src: NamedSource::new(name.clone(), src.clone()).with_language(
                            match format {
                                Format::Toml => "toml",
                                Format::Json => "json",
                            },
                        ),
                        span: span.map(|s| SourceSpan::from(s.start..s.end.max(s.start))),
                        label: label.to_string(),
                        help: p.help,
                        line_col,
                    },
                )
            })
            .collect();
        located.sort_by_key(|(o, _)| *o);
        SceneError {
            file: file.to_path_buf(),
            diagnostics: located.into_iter().map(|(_, d)| d).collect(),
            files: vec![],
        }
    }
}

/// The two scene languages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML (`.toml`).
    Toml,
    /// JSON (`.json`).
    Json,
}

/// 1-based line and column (in characters) of byte offset `at`.
pub fn line_col(text: &str, at: usize) -> (usize, usize) {
    let at = at.min(text.len());
    let before = &text[..floor_char_boundary(text, at)];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Byte offset of 1-based `line` and `col` (as serde_json counts them: bytes).
pub fn offset_of(text: &str, line: usize, col: usize) -> usize {
    let mut off = 0;
    for (i, l) in text.split_inclusive('\n').enumerate() {
        if i + 1 == line {
            return floor_char_boundary(text, off + col.saturating_sub(1).min(l.len()));
        }
        off += l.len();
    }
    text.len()
}

fn floor_char_boundary(text: &str, mut i: usize) -> usize {
    while i > 0 && !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Every value below `path` (recursively), with its path and byte range, in document
/// order: used to find which value an error message describes when serde could not say
/// (inside tagged tables it buffers the values and loses their positions).
pub fn values_below(text: &str, format: Format, path: &DocPath) -> Vec<(DocPath, Range<usize>)> {
    let mut out = vec![];
    match format {
        Format::Toml => {
            use toml::de::{DeTable, DeValue};
            fn walk(
                v: &toml::Spanned<DeValue>,
                p: &DocPath,
                out: &mut Vec<(DocPath, Range<usize>)>,
            ) {
                match v.get_ref() {
                    DeValue::Table(t) => {
                        for (k, v) in t.iter() {
                            walk(v, &p.key(k.get_ref()), out);
                        }
                    }
                    DeValue::Array(a) => {
                        out.push((p.clone(), v.span()));
                        for (i, v) in a.iter().enumerate() {
                            walk(v, &p.index(i), out);
                        }
                    }
                    _ => out.push((p.clone(), v.span())),
                }
            }
            let Ok(root) = DeTable::parse(text) else {
                return out;
            };
            let mut table = root.get_ref();
            let mut value = None;
            for seg in &path.0 {
                match seg {
                    Seg::Key(k) => {
                        let t = value.map_or(Some(table), |v: &toml::Spanned<DeValue>| {
                            v.get_ref().as_table()
                        });
                        let Some((_, v)) = t.and_then(|t| {
                            t.iter()
                                .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                        }) else {
                            return out;
                        };
                        value = Some(v);
                    }
                    Seg::Index(i) => {
                        let Some(v) = value
                            .and_then(|v| v.get_ref().as_array())
                            .and_then(|a| a.get(*i))
                        else {
                            return out;
                        };
                        value = Some(v);
                    }
                }
                if let Some(t) = value.and_then(|v| v.get_ref().as_table()) {
                    table = t;
                }
            }
            match value {
                Some(v) => walk(v, path, &mut out),
                None => {
                    for (k, v) in table.iter() {
                        walk(v, &path.key(k.get_ref()), &mut out);
                    }
                }
            }
        }
        Format::Json => {
            fn walk(n: &json::Node, p: &DocPath, out: &mut Vec<(DocPath, Range<usize>)>) {
                match n {
                    json::Node::Object(entries, _) => {
                        for (k, _, v) in entries {
                            walk(v, &p.key(k), out);
                        }
                    }
                    json::Node::Array(items, s) => {
                        out.push((p.clone(), s.clone()));
                        for (i, v) in items.iter().enumerate() {
                            walk(v, &p.index(i), out);
                        }
                    }
                    json::Node::Scalar(s) => out.push((p.clone(), s.clone())),
                }
            }
            let Some(root) = json::parse(text) else {
                return out;
            };
            if let Some(n) = json::find(&root, path) {
                walk(n, path, &mut out);
            }
        }
    }
    out
}

/// Byte range of the value (or key) at `path`, or of the nearest enclosing thing found.
fn locate(text: &str, format: Format, path: &DocPath, at_key: bool) -> Option<Range<usize>> {
    match format {
        Format::Toml => locate_toml(text, path, at_key),
        Format::Json => {
            let root = json::parse(text)?;
            json::locate(&root, path, at_key)
        }
    }
}

fn locate_toml(text: &str, path: &DocPath, at_key: bool) -> Option<Range<usize>> {
    use toml::de::{DeTable, DeValue};
    let root = DeTable::parse(text).ok()?;
    let mut best = None;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut value: Option<&toml::Spanned<DeValue>> = None;
    let last = path.0.len().saturating_sub(1);
    // Walk as far as the document goes; a key that is absent (a default) leaves the span of
    // the table that would hold it.
    for (i, seg) in path.0.iter().enumerate() {
        let found = match seg {
            Seg::Key(k) => table
                .or_else(|| value.and_then(|v| v.get_ref().as_table()))
                .and_then(|t| {
                    t.iter()
                        .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                })
                .map(|(key, v)| {
                    (
                        if at_key && i == last {
                            key.span()
                        } else {
                            v.span()
                        },
                        v,
                    )
                }),
            Seg::Index(n) => value
                .and_then(|v| v.get_ref().as_array())
                .and_then(|a| a.get(*n))
                .map(|v| (v.span(), v)),
        };
        let Some((span, v)) = found else {
            break;
        };
        // Tables opened by a header have an empty span; keep the last real one.
        if !span.is_empty() {
            best = Some(span);
        }
        value = Some(v);
        table = None;
    }
    best
}

/// A tiny JSON reader that keeps byte spans, only for locating errors.
mod json {
    use super::{DocPath, Seg};
    use std::ops::Range;

    pub enum Node {
        Object(Vec<(String, Range<usize>, Node)>, Range<usize>),
        Array(Vec<Node>, Range<usize>),
        Scalar(Range<usize>),
    }

    impl Node {
        fn span(&self) -> Range<usize> {
            match self {
                Node::Object(_, s) | Node::Array(_, s) | Node::Scalar(s) => s.clone(),
            }
        }
    }

    pub fn parse(text: &str) -> Option<Node> {
        let mut p = Parser {
            b: text.as_bytes(),
            i: 0,
            depth: 0,
        };
        p.value()
    }

    pub fn find<'a>(root: &'a Node, path: &DocPath) -> Option<&'a Node> {
        let mut node = root;
        for seg in &path.0 {
            node = match (seg, node) {
                (Seg::Key(k), Node::Object(entries, _)) => {
                    &entries.iter().find(|(name, _, _)| name == k)?.2
                }
                (Seg::Index(n), Node::Array(items, _)) => items.get(*n)?,
                _ => return None,
            };
        }
        Some(node)
    }

    pub fn locate(root: &Node, path: &DocPath, at_key: bool) -> Option<Range<usize>> {
        let mut node = root;
        let mut best = None;
        let last = path.0.len().saturating_sub(1);
        for (i, seg) in path.0.iter().enumerate() {
            match (seg, node) {
                (Seg::Key(k), Node::Object(entries, _)) => {
                    let Some((_, ks, v)) = entries.iter().find(|(name, _, _)| name == k) else {
                        return best;
                    };
                    best = Some(if at_key && i == last {
                        ks.clone()
                    } else {
                        v.span()
                    });
                    node = v;
                }
                (Seg::Index(n), Node::Array(items, _)) => {
                    let Some(item) = items.get(*n) else {
                        return best;
                    };
                    node = item;
                    best = Some(node.span());
                }
                _ => return best,
            }
        }
        best.or_else(|| Some(root.span()))
    }

    struct Parser<'a> {
        b: &'a [u8],
        i: usize,
        depth: usize,
    }

    impl Parser<'_> {
        fn ws(&mut self) {
            while self.i < self.b.len() && self.b[self.i].is_ascii_whitespace() {
                self.i += 1;
            }
        }

        fn value(&mut self) -> Option<Node> {
            self.ws();
            self.depth += 1;
            if self.depth > 256 {
                return None;
            }
            let start = self.i;
            let node = match *self.b.get(self.i)? {
                b'{' => {
                    self.i += 1;
                    let mut entries = vec![];
                    loop {
                        self.ws();
                        if self.b.get(self.i) == Some(&b'}') {
                            self.i += 1;
                            break;
                        }
                        let ks = self.i;
                        let key = self.string()?;
                        let key_span = ks..self.i;
                        self.ws();
                        (self.b.get(self.i) == Some(&b':')).then_some(())?;
                        self.i += 1;
                        let v = self.value()?;
                        entries.push((key, key_span, v));
                        self.ws();
                        match self.b.get(self.i)? {
                            b',' => self.i += 1,
                            b'}' => {
                                self.i += 1;
                                break;
                            }
                            _ => return None,
                        }
                    }
                    Node::Object(entries, start..self.i)
                }
                b'[' => {
                    self.i += 1;
                    let mut items = vec![];
                    loop {
                        self.ws();
                        if self.b.get(self.i) == Some(&b']') {
                            self.i += 1;
                            break;
                        }
                        items.push(self.value()?);
                        self.ws();
                        match self.b.get(self.i)? {
                            b',' => self.i += 1,
                            b']' => {
                                self.i += 1;
                                break;
                            }
                            _ => return None,
                        }
                    }
                    Node::Array(items, start..self.i)
                }
                b'"' => {
                    self.string()?;
                    Node::Scalar(start..self.i)
                }
                _ => {
                    while self.i < self.b.len() && !b",]} \t\r\n".contains(&self.b[self.i]) {
                        self.i += 1;
                    }
                    Node::Scalar(start..self.i)
                }
            };
            self.depth -= 1;
            Some(node)
        }

        fn string(&mut self) -> Option<String> {
            (self.b.get(self.i) == Some(&b'"')).then_some(())?;
            let start = self.i;
            self.i += 1;
            while *self.b.get(self.i)? != b'"' {
                if self.b[self.i] == b'\\' {
                    self.i += 1;
                }
                self.i += 1;
            }
            self.i += 1;
            serde_json::from_slice(&self.b[start..self.i]).ok()
        }
    }
}

/// The closest of `candidates` to `word`, if it is close enough to be a likely typo.
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|(d, c)| *d <= (c.len().max(word.len()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// The help for `name`, which names none of `known`: the known name it is likely a
/// misspelling of; else, where nothing is known, `none` (how to define one); else every
/// known name after `listed` (`defined meshes: a, b`).
pub fn name_help<'a>(
    name: &str,
    known: impl IntoIterator<Item = &'a str>,
    listed: &str,
    none: &str,
) -> String {
    let known: Vec<&str> = known.into_iter().collect();
    match did_you_mean(name, known.iter().copied()) {
        Some(s) => format!("did you mean `{s}`?"),
        None if known.is_empty() => none.to_string(),
        None => format!("{listed}: {}", known.join(", ")),
    }
}

/// Edit distance counting insertions, deletions, substitutions and swaps of neighbours
/// (optimal string alignment), so `scael` is one step from `scale`.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_for_typos() {
        assert_eq!(did_you_mean("radus", ["center", "radius"]), Some("radius"));
        assert_eq!(did_you_mean("colour", ["color", "texture"]), Some("color"));
        assert_eq!(did_you_mean("zzzzzz", ["center", "radius"]), None);
        assert_eq!(
            did_you_mean("scael", ["scale", "rotate", "translate"]),
            Some("scale")
        );
    }

    #[test]
    fn locates_toml_and_json_paths() {
        let toml =
            "[camera]\nlook_at = [0, 0, -1]\n\n[[objects]]\ntype = \"sphere\"\nradius = -2\n";
        let p = DocPath::default().key("objects").index(0).key("radius");
        let s = locate(toml, Format::Toml, &p, false).unwrap();
        assert_eq!(&toml[s.clone()], "-2");
        assert_eq!(line_col(toml, s.start), (6, 10));
        let json = "{\"objects\": [\n  {\"type\": \"sphere\", \"radius\": -2}\n]}";
        let s = locate(json, Format::Json, &p, true).unwrap();
        assert_eq!(&json[s.clone()], "\"radius\"");
        assert_eq!(line_col(json, s.start), (2, 22));
    }

    #[test]
    fn paths_print_like_the_document() {
        let p = DocPath::default().key("objects").index(3).key("radius");
        assert_eq!(p.to_string(), "objects[3].radius");
    }
}
