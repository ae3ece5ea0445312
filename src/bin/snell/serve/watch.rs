//! Watching the scene and the files it reads, with `notify`. Each file's folder is watched
//! (not the file): editors that save by writing a new file and renaming it over the old one
//! (vim, VS Code) replace the file a watch on it would follow, and a deleted file that comes
//! back is seen too. Events for other files in those folders (an editor's swap files) are
//! ignored.

use notify::{EventKind, RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The watcher and what it watches.
pub(crate) struct Watch {
    watcher: Mutex<notify::RecommendedWatcher>,
    /// The folders watched.
    folders: Mutex<BTreeSet<PathBuf>>,
    /// The files whose changes count, as the events name them (canonical folder, name).
    files: Arc<Mutex<BTreeSet<PathBuf>>>,
}

impl Watch {
    /// A watcher that calls `changed` (from its own thread) when a watched file changes.
    pub(crate) fn new(changed: impl Fn() + Send + 'static) -> notify::Result<Watch> {
        let files: Arc<Mutex<BTreeSet<PathBuf>>> = Arc::default();
        let seen = files.clone();
        let watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
            let Ok(event) = event else { return };
            // Opening and reading a file is no change.
            if matches!(event.kind, EventKind::Access(_)) {
                return;
            }
            let files = seen.lock().unwrap_or_else(|e| e.into_inner());
            if event.paths.iter().any(|p| files.contains(p)) {
                drop(files);
                changed();
            }
        })?;
        Ok(Watch {
            watcher: Mutex::new(watcher),
            folders: Mutex::default(),
            files,
        })
    }

    /// Watches `files` (absolute) from now on, instead of what it watched before. A folder
    /// that cannot be watched (it does not exist) is left out.
    pub(crate) fn set(&self, files: &[PathBuf]) {
        let mut named = BTreeSet::new();
        let mut folders = BTreeSet::new();
        for f in files {
            let (Some(folder), Some(name)) = (f.parent(), f.file_name()) else {
                continue;
            };
            let folder = std::fs::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
            named.insert(folder.join(name));
            folders.insert(folder);
        }
        *self.files.lock().unwrap_or_else(|e| e.into_inner()) = named;
        let mut watcher = self.watcher.lock().unwrap_or_else(|e| e.into_inner());
        let mut watched = self.folders.lock().unwrap_or_else(|e| e.into_inner());
        for gone in watched.difference(&folders) {
            let _ = watcher.unwatch(gone);
        }
        let mut now = BTreeSet::new();
        for folder in folders {
            let ok = watched.contains(&folder)
                || watcher
                    .watch(Path::new(&folder), RecursiveMode::NonRecursive)
                    .is_ok();
            if ok {
                now.insert(folder);
            }
        }
        *watched = now;
    }
}
