//! Files written whole or not at all: the bytes go to a temporary file beside the destination,
//! which is flushed and renamed over it, so a failed or interrupted write never leaves a
//! broken file and never destroys the old one. Every temporary file that exists is listed, so
//! a process that must exit at once (a second Ctrl-C) can remove them first.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// The temporary files of this process that are not yet renamed or removed.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// Makes each temporary file's name unique within the process.
static NEXT: AtomicU64 = AtomicU64::new(0);

fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A thread that panicked while holding the lock left the list whole (each change is one
    // push or remove), so its poison is no reason to stop.
    PENDING.lock().unwrap_or_else(|p| p.into_inner())
}

/// Removes every temporary file this process has reserved and not yet renamed into place.
/// For an exit that skips destructors, such as a second Ctrl-C.
pub fn remove_pending_files() {
    remove_pending_where(|_| true);
}

/// Removes the listed temporary files that `which` picks.
fn remove_pending_where(which: impl Fn(&Path) -> bool) {
    pending().retain(|tmp| {
        if which(tmp) {
            let _ = std::fs::remove_file(tmp);
            false
        } else {
            true
        }
    });
}

/// A destination reserved before the work that fills it: its temporary file is created up
/// front, so a destination that cannot be written fails at once, not after a long render.
/// Dropping it without [`PendingFile::commit`] removes the temporary file.
#[derive(Debug)]
pub struct PendingFile {
    path: PathBuf,
    tmp: PathBuf,
    file: Option<File>,
}

impl PendingFile {
    /// Checks that `path` can be written (it is no folder, its folder exists) and creates the
    /// temporary file beside it.
    pub fn create(path: &Path) -> io::Result<Self> {
        let invalid = |kind, msg: String| Err(io::Error::new(kind, msg));
        if path.is_dir() {
            return invalid(io::ErrorKind::IsADirectory, "it is a folder".into());
        }
        let Some(name) = path.file_name() else {
            return invalid(io::ErrorKind::InvalidInput, "it names no file".into());
        };
        let dir = folder_of(path);
        if !dir.is_dir() {
            let what = if dir.exists() {
                "is not a folder"
            } else {
                "does not exist"
            };
            return invalid(
                io::ErrorKind::NotFound,
                format!("the folder {} {what}", dir.display()),
            );
        }
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(
            ".{}-{}.tmp",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        ));
        let tmp = dir.join(tmp_name);
        // Listed before it exists, so that no moment has the file and not the entry.
        pending().push(tmp.clone());
        match File::create(&tmp) {
            Ok(file) => Ok(PendingFile {
                path: path.to_path_buf(),
                tmp,
                file: Some(file),
            }),
            Err(e) => {
                forget(&tmp);
                Err(e)
            }
        }
    }

    /// The destination.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Sends the bytes to another destination in the same folder (an interrupted render's
    /// `NAME.partial.png` beside `NAME.png`), so that the rename stays within one folder.
    pub fn redirect(&mut self, name: &std::ffi::OsStr) {
        self.path = self.path.with_file_name(name);
    }

    /// Writes `bytes` to the temporary file, flushes it to disk and renames it over the
    /// destination. On failure the temporary file is removed and any old file is kept.
    pub fn commit(mut self, bytes: &[u8]) -> io::Result<()> {
        let mut file = self.file.take().expect("commit runs once");
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&self.tmp, &self.path)?;
        forget(&self.tmp);
        Ok(())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        // After a successful commit the entry is gone and the rename moved the file away;
        // removing the temporary name then fails harmlessly (it names nothing).
        if pending().contains(&self.tmp) {
            drop(self.file.take());
            let _ = std::fs::remove_file(&self.tmp);
            forget(&self.tmp);
        }
    }
}

/// Writes `bytes` to `path` through a temporary file renamed into place.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    PendingFile::create(path)?.commit(bytes)
}

/// The folder a path's file lives in (`.` for a bare name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn forget(tmp: &Path) {
    pending().retain(|p| p != tmp);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("snell-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_folder_or_a_missing_folder_is_refused_before_any_work() {
        let dir = scratch("refused");
        std::fs::create_dir(dir.join("taken.png")).unwrap();
        let e = PendingFile::create(&dir.join("taken.png")).unwrap_err();
        assert_eq!(e.to_string(), "it is a folder");
        let e = PendingFile::create(&dir.join("no/such/x.png")).unwrap_err();
        assert!(e.to_string().ends_with("no/such does not exist"), "{e}");
        std::fs::write(dir.join("file"), b"").unwrap();
        let e = PendingFile::create(&dir.join("file/x.png")).unwrap_err();
        assert!(e.to_string().ends_with("file is not a folder"), "{e}");
        assert_eq!(entries(&dir), ["file", "taken.png"]);
    }

    #[test]
    fn commit_replaces_whole_and_drop_keeps_the_old_file() {
        let dir = scratch("commit");
        let out = dir.join("a.bin");
        std::fs::write(&out, b"old").unwrap();
        let p = PendingFile::create(&out).unwrap();
        assert_eq!(entries(&dir).len(), 2, "the temporary file exists");
        drop(p);
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
        assert_eq!(entries(&dir), ["a.bin"]);
        write_atomically(&out, b"new").unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"new");
        assert_eq!(entries(&dir), ["a.bin"]);
    }

    #[test]
    fn redirect_writes_beside_and_leaves_the_destination_alone() {
        let dir = scratch("redirect");
        let out = dir.join("keep.png");
        std::fs::write(&out, b"good").unwrap();
        let mut p = PendingFile::create(&out).unwrap();
        p.redirect("keep.partial.png".as_ref());
        assert_eq!(p.path(), dir.join("keep.partial.png"));
        p.commit(b"half").unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"good");
        assert_eq!(
            std::fs::read(dir.join("keep.partial.png")).unwrap(),
            b"half"
        );
    }

    #[test]
    fn pending_files_can_all_be_removed_at_once() {
        let dir = scratch("remove-all");
        let a = PendingFile::create(&dir.join("a.png")).unwrap();
        let b = PendingFile::create(&dir.join("b.png")).unwrap();
        assert_eq!(entries(&dir).len(), 2);
        // Only this test's files: the other tests' run beside it in this process.
        remove_pending_where(|p| p.starts_with(&dir));
        assert!(entries(&dir).is_empty(), "{:?}", entries(&dir));
        // Their owners may still drop them (or the process exits first): nothing breaks.
        drop((a, b));
        assert!(entries(&dir).is_empty());
    }
}
