//! A render's output files beyond its one picture: where each debug view (`--aov`) goes,
//! the refusal of any output that would replace a file the render reads, and the writing
//! of the picture together with its views (one EXR, or a PNG each).

use super::Outcome;
use crate::args::RenderArgs;
use crate::usage_error;
use snell::integrator::aov::Aov;
use snell::output::{ExrLayer, OutputFormat, PendingOutput, encode_exr_layers};
use snell::render::render_aovs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `out.png` with a view's name before the extension: `out.normal.png`.
pub(super) fn aov_path(out: &Path, aov: Aov) -> PathBuf {
    let mut name = out.file_stem().unwrap_or_default().to_os_string();
    name.push(format!(".{}.", aov.name()));
    name.push(out.extension().unwrap_or_default());
    out.with_file_name(name)
}

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
        for &a in list {
            let p = aov_path(out_path, a);
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

/// Writes the picture and its debug views: one multi-layer EXR, or a PNG per view.
pub(super) fn write_aovs(
    scene: &snell::Scene,
    threads: Option<usize>,
    outcome: &Outcome,
    pending: PendingOutput,
    aovs: &[Aov],
    pngs: Vec<(Aov, PendingOutput)>,
) -> Result<(), String> {
    let image = &outcome.image;
    let mut buffers = render_aovs(scene, threads).map_err(|e| e.to_string())?;
    if let Some(film) = &outcome.film {
        buffers.set_variance(film);
    }
    if pending.format() == OutputFormat::Exr {
        let layers: Vec<ExrLayer> = aovs
            .iter()
            .map(|&a| (a.name(), buffers.channels(a)))
            .collect();
        let bytes = encode_exr_layers(image, &layers, pending.path()).map_err(|e| e.to_string())?;
        return pending.commit_bytes(&bytes).map_err(|e| e.to_string());
    }
    pending
        .commit_toned(image, &scene.settings.tone)
        .map_err(|e| e.to_string())?;
    for (a, out) in pngs {
        out.commit(&buffers.display(a, scene.settings.max_depth))
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}
