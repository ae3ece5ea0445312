//! `snell merge`: region files (`render --region ... -o PART.exr`) back into the whole
//! image: a PNG of the same bytes as one render's, or an EXR of the same pixels.

use snell::output::PendingOutput;
use snell::output::merge::{merge, read_region};
use snell::output::tone::Tone;
use std::path::PathBuf;
use std::process::ExitCode;

/// `snell merge`'s arguments.
#[derive(clap::Args, Debug)]
pub(crate) struct MergeArgs {
    /// The region files (EXR), in any order.
    #[arg(required = true, value_name = "PART.exr")]
    pub(crate) parts: Vec<PathBuf>,
    /// The whole image: .png (toned as the render's PNG would be) or .exr (linear).
    #[arg(short, long, value_name = "FILE")]
    pub(crate) output: PathBuf,
}

pub(crate) fn merge_command(args: MergeArgs) -> ExitCode {
    // The output first, as a render does: a bad destination fails before the reading.
    if let Some((out, part)) = snell::output::inputs::output_over_input(
        [args.output.as_path()],
        args.parts.iter().map(PathBuf::as_path),
    ) {
        eprintln!(
            "error: the output {} is the region file {}: writing it would destroy it",
            out.display(),
            part.display()
        );
        return ExitCode::from(2);
    }
    // As render: a name of no known format is a bad command line (2), a folder that cannot
    // be written a failure to write (1).
    let pending = match PendingOutput::create(&args.output) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            let code = match e {
                snell::output::OutputError::UnknownFormat(_) => 2,
                _ => 1,
            };
            return ExitCode::from(code);
        }
    };
    let mut files = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        match read_region(p, snell::scene::Limits::default().max_pixels) {
            Ok(f) => files.push(f),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    }
    let (image, tone): (_, Tone) = match merge(&files) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Err(e) = pending.commit_toned(&image, &tone) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    outln!(
        "wrote {}: {} x {} from {} region files",
        args.output.display(),
        image.width,
        image.height,
        files.len()
    );
    ExitCode::SUCCESS
}
