//! `snell render --frames A..B`: the frames of a scene's animation, one after another, each
//! to its own file named by the output's pattern; the images and meshes are read once.

use super::{overrides, render_job};
use crate::args::{FrameRange, RenderArgs};
use crate::{job_error, usage_error};
use snell::job::RenderJob;
use snell::scene::AssetCache;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// `pattern` with each run of `#` in its file name replaced by `frame`, zero-padded to the
/// run's length (`frame_####.png`, 7: `frame_0007.png`).
pub(crate) fn frame_path(pattern: &Path, frame: u32) -> PathBuf {
    let Some(name) = pattern.file_name().and_then(|n| n.to_str()) else {
        return pattern.to_path_buf();
    };
    let mut out = String::new();
    let mut run = 0;
    for c in name.chars().chain(std::iter::once('\0')) {
        if c == '#' {
            run += 1;
            continue;
        }
        if run > 0 {
            out.push_str(&format!("{frame:0run$}"));
            run = 0;
        }
        if c != '\0' {
            out.push(c);
        }
    }
    pattern.with_file_name(out)
}

/// Whether a pattern's file name has a run of `#` for the frame number.
fn has_pattern(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.contains('#'))
}

pub(crate) fn render_frames(args: &RenderArgs, range: FrameRange) -> ExitCode {
    let given = [
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
    ];
    if let Some((_, flag)) = given.iter().find(|(g, _)| *g) {
        return usage_error(
            &format!("--frames cannot be combined with {flag} yet"),
            Some(
                "render the frames without it; --skip-existing resumes a stopped job frame by frame",
            ),
        );
    }
    let Some(scene_path) = args.scene.clone() else {
        return usage_error("give a scene file", None);
    };
    let pattern = match &args.output {
        Some(p) => p.clone(),
        None if range.count() == 1 => RenderJob::default_output(&scene_path),
        None => {
            let mut name = scene_path.file_stem().unwrap_or_default().to_os_string();
            name.push("_####.png");
            PathBuf::from(name)
        }
    };
    if range.count() > 1 && !has_pattern(&pattern) {
        return usage_error(
            &format!(
                "{} frames would all be written to {}",
                range.count(),
                pattern.display()
            ),
            Some("put a run of # in the output's name for the frame number: -o frames/f_####.png"),
        );
    }
    // A sequence's folder is made for it (a single render's must exist: a typo there is
    // caught before the work).
    if let Some(parent) = pattern.parent().filter(|p| !p.as_os_str().is_empty())
        && let Err(e) = std::fs::create_dir_all(parent)
    {
        eprintln!("error: cannot make the folder {}: {e}", parent.display());
        return ExitCode::from(1);
    }
    let limits = match args.limits.get() {
        Ok(l) => l,
        Err(code) => return code,
    };
    let overrides = overrides(args);
    let mut assets = AssetCache::default();
    let start = Instant::now();
    let (mut rendered, mut skipped) = (0u32, 0u32);
    for frame in range.first..=range.last {
        let out = frame_path(&pattern, frame);
        if args.skip_existing && out.exists() {
            if !args.quiet {
                eprintln!("frame {frame}: {} exists, skipped", out.display());
            }
            skipped += 1;
            continue;
        }
        let job = match RenderJob::prepare_frame(
            &scene_path,
            &overrides,
            &limits,
            None,
            frame,
            &mut assets,
        ) {
            Ok(job) => job,
            Err(e) => return job_error(e),
        };
        let frames = job.scene.animation.map_or(1, |a| a.frames);
        if range.last >= frames {
            let help = match job.scene.animation {
                Some(_) => format!("its frames are 0..{}", frames - 1),
                None => "it has no [animation]: it is one frame, 0".to_string(),
            };
            return usage_error(
                &format!(
                    "--frames {}..{} goes past the scene's last frame, {}",
                    range.first,
                    range.last,
                    frames - 1
                ),
                Some(&help),
            );
        }
        let code = render_job(args, job, &out, None);
        if code != ExitCode::SUCCESS {
            return code;
        }
        rendered += 1;
    }
    if !args.quiet && range.count() > 1 {
        outln!(
            "rendered {}{} in {:.2} s",
            crate::count(rendered as u64, "frame"),
            if skipped > 0 {
                format!(" ({skipped} skipped: their files exist)")
            } else {
                String::new()
            },
            start.elapsed().as_secs_f64()
        );
    }
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_hashes_become_the_zero_padded_frame() {
        let p = |s: &str, f| frame_path(Path::new(s), f);
        assert_eq!(p("out/frame_####.png", 7), Path::new("out/frame_0007.png"));
        assert_eq!(p("f#.exr", 12), Path::new("f12.exr"));
        assert_eq!(p("a##_b###.png", 5), Path::new("a05_b005.png"));
        assert_eq!(p("still.png", 3), Path::new("still.png"));
        // A folder's # is left alone: only the file name is a pattern.
        assert_eq!(p("#dir/x_##.png", 1), Path::new("#dir/x_01.png"));
        assert!(has_pattern(Path::new("x/f_##.png")) && !has_pattern(Path::new("#/f.png")));
    }
}
