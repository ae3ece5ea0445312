//! `snell lab`: a material's sampling against its density, printed as a chi-square test and
//! drawn as histograms (snell::lab).

use clap::{Args, Subcommand};
use snell::lab::{leaving_at, material_bsdf, warp_test};
use snell::math::chi2::SphereBins;
use snell::scene::format::MaterialKind;
use std::path::PathBuf;
use std::process::ExitCode;

/// `snell lab`'s experiments.
#[derive(Subcommand, Debug)]
pub(crate) enum LabCommand {
    /// Sample a material's BSDF from one direction and test the samples against its
    /// density (chi-square, p below 0.01 fails); draw both histograms and their difference.
    ///
    /// Exits 0 when the samples follow the density, 1 when they do not, 2 on bad input.
    Bsdf(BsdfArgs),
    /// List the material types the lab samples, with the keys each takes.
    List,
}

/// `snell lab bsdf`.
#[derive(Args, Debug)]
pub(crate) struct BsdfArgs {
    /// The material's type, as a scene file's `type`: diffuse, plastic, conductor, dielectric,
    /// thin, metallic or phong (`snell lab list`).
    #[arg(value_name = "TYPE")]
    kind: String,
    /// The material's roughness (its `roughness` key).
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    roughness: Option<String>,
    /// The material's index of refraction (its `ior` key).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    ior: Option<String>,
    /// Any key of the material, with its value as a scene file writes it:
    /// `--param metal='"Au"'`, `--param eta=[0.2,0.4,1.4]` (repeatable).
    #[arg(long = "param", value_name = "KEY=VALUE", value_parser = key_value)]
    params: Vec<(String, String)>,
    /// The angle between the normal and the direction light leaves along (toward the
    /// viewer), degrees, 0 to 89.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 40.0,
        allow_negative_numbers = true
    )]
    angle: f32,
    /// Samples drawn.
    #[arg(long, value_name = "N", default_value_t = 1 << 20)]
    samples: usize,
    /// Where to draw the histograms (PNG or EXR): the samples', the density's, and their
    /// difference in standard deviations (red: more samples than the density predicts).
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
}

fn key_value(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((k, v)) if !k.trim().is_empty() => Ok((k.trim().to_string(), v.trim().to_string())),
        _ => Err(format!("`{s}` is not KEY=VALUE")),
    }
}

/// Runs a `snell lab` command.
pub(crate) fn lab(command: LabCommand) -> ExitCode {
    match command {
        LabCommand::List => {
            println!("material types (snell lab bsdf TYPE; their keys in docs/scene-format.md):");
            for k in MaterialKind::ALL {
                println!("  {}", k.name());
            }
            ExitCode::SUCCESS
        }
        LabCommand::Bsdf(args) => bsdf(args),
    }
}

fn bsdf(args: BsdfArgs) -> ExitCode {
    let fail = |message: String| {
        eprintln!("error: {message}");
        ExitCode::from(2)
    };
    if !(0.0..=89.0).contains(&args.angle) {
        return fail(format!(
            "--angle {} is not between 0 and 89 degrees from the normal",
            args.angle
        ));
    }
    if !(1_000..=1 << 26).contains(&args.samples) {
        return fail(format!(
            "--samples {} is not between 1000 and {}",
            args.samples,
            1u64 << 26
        ));
    }
    let mut params = args.params.clone();
    for (key, value) in [("roughness", &args.roughness), ("ior", &args.ior)] {
        if let Some(v) = value {
            params.push((key.to_string(), v.clone()));
        }
    }
    let lab = match material_bsdf(&args.kind, &params) {
        Ok(lab) => lab,
        Err(e) => return fail(format!("the material cannot be built:\n{e}")),
    };
    // Reserve the picture's file before the work, so a bad path fails at once.
    let out = match args
        .output
        .as_deref()
        .map(snell::output::PendingOutput::create)
    {
        Some(Err(e)) => return fail(e.to_string()),
        Some(Ok(o)) => Some(o),
        None => None,
    };
    let bins = SphereBins { theta: 40, phi: 80 };
    let t = match warp_test(&lab.bsdf, leaving_at(args.angle), args.samples, bins) {
        Ok(t) => t,
        Err(e) => {
            println!("{}: {e}", lab.title);
            return ExitCode::from(1);
        }
    };
    println!(
        "{}, light leaving at {}° from the normal",
        lab.title, args.angle
    );
    let binned = t.samples - t.specular - t.absorbed;
    println!(
        "{} samples: {binned} in the histogram, {} on mirror or smooth-glass lobes (deltas, not drawn), {} absorbed",
        t.samples, t.specular, t.absorbed
    );
    let c = &t.chi2;
    let verdict = if c.passed() {
        "the samples follow the density"
    } else {
        "the samples do NOT follow the density"
    };
    println!(
        "chi^2 = {:.1} with {} degrees of freedom, p = {:.3}: {verdict}",
        c.chi2, c.dof, c.p
    );
    if c.stray > 10.0 {
        println!("{} samples fell where the density is 0", c.stray);
    }
    if let (false, Some((bin, o, e))) = (c.passed(), c.worst) {
        let (band, sector) = (bin / bins.phi, bin % bins.phi);
        println!(
            "the bin that strays most: theta {:.1}° to {:.1}°, phi {:.1}° to {:.1}°: {o} samples where {e:.1} are expected",
            band as f32 * 180.0 / bins.theta as f32,
            (band + 1) as f32 * 180.0 / bins.theta as f32,
            sector as f32 * 360.0 / bins.phi as f32,
            (sector + 1) as f32 * 360.0 / bins.phi as f32,
        );
    }
    if let Some(e) = &t.inconsistent {
        println!("and the sampling disagrees with the BSDF: {e}");
    }
    if let Some(out) = out {
        let path = out.path().to_path_buf();
        if let Err(e) = out.commit(&t.image(6)) {
            return fail(e.to_string());
        }
        println!(
            "wrote {}: the samples' histogram | the density's | their difference (red more, blue fewer, in standard deviations); theta down from the normal, phi across",
            path.display()
        );
    }
    if t.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
