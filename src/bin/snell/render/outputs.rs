//! The refusal of any output of a render (its picture, partial picture, debug views or
//! checkpoint) that would replace a file the render reads.

use crate::args::RenderArgs;
use crate::usage_error;
use snell::render::to_files::Outputs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Refuses (exit 2, before any work) a render whose picture, its partial picture, a view
/// (`--aov`) or its checkpoint would replace a file the render reads: the scene file, its
/// textures, meshes, glTF buffers and images, environment map, or the checkpoint it
/// resumes.
pub(super) fn refuse_outputs_over_inputs(
    args: &RenderArgs,
    scene: &snell::Scene,
    scene_path: &Path,
    out_path: &Path,
) -> Option<ExitCode> {
    let mut outputs = vec![
        out_path.to_path_buf(),
        snell::output::partial_path(out_path),
    ];
    for list in &args.aov {
        for &a in list.views() {
            let p = Outputs::view_path(out_path, a);
            outputs.push(snell::output::partial_path(&p));
            outputs.push(p);
        }
    }
    let mut inputs: Vec<&Path> = vec![scene_path];
    inputs.extend(scene.files.iter().map(PathBuf::as_path));
    if let Some(r) = &args.resume {
        inputs.push(r);
    }
    // A checkpoint may replace the one it resumes (that is how --resume goes on).
    if let Some(c) = &args.checkpoint
        && args.resume.as_ref() != Some(c)
    {
        outputs.push(c.clone());
    }
    let (out, input) = snell::output::inputs::output_over_input(
        outputs.iter().map(PathBuf::as_path),
        inputs.iter().copied(),
    )?;
    Some(usage_error(
        &format!(
            "the output {} is {}, which this render reads: writing it would destroy it",
            out.display(),
            input.display()
        ),
        Some("name another output (-o FILE)"),
    ))
}
