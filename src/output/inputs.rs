//! Outputs that would replace a file the render reads: a render whose output is its own
//! texture, scene file or mesh would destroy it (the picture written over the texture),
//! so every output is compared with every input before any work, by what the paths name,
//! not how they are spelt (`./tex.png`, `../x/tex.png` and a symbolic link to it are one
//! file).

use std::path::{Path, PathBuf};

/// The first output that names one of `inputs`, with the input it names.
pub fn output_over_input<'a>(
    outputs: impl IntoIterator<Item = &'a Path>,
    inputs: impl IntoIterator<Item = &'a Path>,
) -> Option<(&'a Path, &'a Path)> {
    let inputs: Vec<(&Path, FileId)> = inputs
        .into_iter()
        .filter_map(|p| Some((p, FileId::of(p)?)))
        .collect();
    for out in outputs {
        let Some(id) = FileId::of(out) else { continue };
        if let Some((input, _)) = inputs.iter().find(|(_, i)| *i == id) {
            return Some((out, input));
        }
    }
    None
}

/// What a path names: an existing file's device and inode (so links and every spelling
/// agree), else the canonical folder it would be made in and its name.
#[derive(Debug, PartialEq, Eq)]
enum FileId {
    #[cfg(unix)]
    Inode(u64, u64),
    Path(PathBuf),
}

impl FileId {
    fn of(path: &Path) -> Option<FileId> {
        #[cfg(unix)]
        if let Ok(m) = std::fs::metadata(path) {
            use std::os::unix::fs::MetadataExt;
            return Some(FileId::Inode(m.dev(), m.ino()));
        }
        if let Ok(p) = std::fs::canonicalize(path) {
            return Some(FileId::Path(p));
        }
        // A file not made yet: its folder's canonical path and its name.
        let name = path.file_name()?;
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        Some(FileId::Path(std::fs::canonicalize(parent).ok()?.join(name)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("snell-inputs-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("x")).unwrap();
        d
    }

    /// Every spelling of an input is caught, and outputs elsewhere pass.
    #[test]
    fn every_spelling_of_an_input_is_caught() {
        let d = scratch("spell");
        let tex = d.join("x").join("tex.png");
        std::fs::write(&tex, b"texture").unwrap();
        let inputs = [tex.as_path()];
        let spellings = [
            tex.clone(),
            d.join("x").join(".").join("tex.png"),
            d.join("x").join("..").join("x").join("tex.png"),
        ];
        let mut caught = 0;
        for s in &spellings {
            assert_eq!(
                output_over_input([s.as_path()], inputs).map(|(_, i)| i),
                Some(tex.as_path()),
                "{}",
                s.display()
            );
            caught += 1;
        }
        #[cfg(unix)]
        {
            let link = d.join("link.png");
            std::os::unix::fs::symlink(&tex, &link).unwrap();
            assert!(output_over_input([link.as_path()], inputs).is_some());
            caught += 1;
        }
        assert!(caught >= 3);
        for other in [
            d.join("x").join("out.png"),
            d.join("tex.png"),
            d.join("no/such/dir/tex.png"),
        ] {
            assert_eq!(
                output_over_input([other.as_path()], inputs),
                None,
                "{}",
                other.display()
            );
        }
        std::fs::remove_dir_all(&d).unwrap();
    }
}
