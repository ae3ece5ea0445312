//! `snell lab`: a material's sampling (or a scene's lights') against its density, printed as
//! a chi-square test and drawn as histograms (snell::lab).

use clap::{Args, Subcommand};
use snell::lab::{BINS, WarpTest, leaving_at, light_test, material_bsdf, warp_test};
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
    /// Sample a scene's lights from a point as next-event estimation does (a light chosen
    /// by power, a point of it) and test the directions against the density the path
    /// tracer reports for them; draw both histograms and their difference.
    ///
    /// Point, spot and directional lights are deltas, counted apart. Exits 0 when the
    /// samples follow the density, 1 when they do not, 2 on bad input.
    Light(LightArgs),
    /// List what the lab samples: the material types, and the lights it tests in a scene.
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

/// `snell lab light`.
#[derive(Args, Debug)]
pub(crate) struct LightArgs {
    /// The scene file (.toml or .json) whose lights are sampled.
    scene: PathBuf,
    /// The point the lights are seen from, world space.
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_negative_numbers = true)]
    from: [f32; 3],
    /// Samples drawn.
    #[arg(long, value_name = "N", default_value_t = 1 << 20)]
    samples: usize,
    /// Where to draw the histograms (PNG or EXR), theta down from straight up (+y).
    #[arg(short, long, value_name = "OUT")]
    output: Option<PathBuf>,
}

fn point(s: &str) -> Result<[f32; 3], String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|x| x.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{s}` is not a point: give X,Y,Z"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([x, y, z]),
        _ => Err(format!(
            "`{s}` is not a point: give three finite numbers X,Y,Z"
        )),
    }
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
            println!(
                "lights (snell lab light SCENE --from X,Y,Z): rectangle, disk, triangle and sphere area lights, environment images, the sky; point, spot and directional lights are deltas"
            );
            ExitCode::SUCCESS
        }
        LabCommand::Bsdf(args) => bsdf(args),
        LabCommand::Light(args) => light(args),
    }
}

/// Bad input: the message, exit 2.
fn fail(message: String) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(2)
}

/// Refuses sample counts too few to test or too many to wait for.
fn check_samples(samples: usize) -> Result<(), ExitCode> {
    if (1_000..=1 << 26).contains(&samples) {
        return Ok(());
    }
    Err(fail(format!(
        "--samples {samples} is not between 1000 and {}",
        1u64 << 26
    )))
}

/// The picture's file, reserved before the work so that a bad path fails at once.
fn reserve(
    output: Option<&std::path::Path>,
) -> Result<Option<snell::output::PendingOutput>, ExitCode> {
    output
        .map(snell::output::PendingOutput::create)
        .transpose()
        .map_err(|e| fail(e.to_string()))
}

fn bsdf(args: BsdfArgs) -> ExitCode {
    if !(0.0..=89.0).contains(&args.angle) {
        return fail(format!(
            "--angle {} is not between 0 and 89 degrees from the normal",
            args.angle
        ));
    }
    if let Err(code) = check_samples(args.samples) {
        return code;
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
    let out = match reserve(args.output.as_deref()) {
        Ok(out) => out,
        Err(code) => return code,
    };
    let t = warp_test(&lab.bsdf, leaving_at(args.angle), args.samples, BINS);
    let title = format!(
        "{}, light leaving at {}° from the normal",
        lab.title, args.angle
    );
    report(
        &title,
        t,
        out,
        "deltas: mirror or smooth-glass lobes",
        "theta down from the normal",
    )
}

fn light(args: LightArgs) -> ExitCode {
    if let Err(code) = check_samples(args.samples) {
        return code;
    }
    let scene = match snell::scene::load(&args.scene) {
        Ok(s) => s,
        Err(e) => {
            crate::print_scene_error(&e);
            return ExitCode::from(2);
        }
    };
    let out = match reserve(args.output.as_deref()) {
        Ok(out) => out,
        Err(code) => return code,
    };
    let [x, y, z] = args.from;
    let t = light_test(&scene, snell::math::Vec3A::new(x, y, z), args.samples, BINS);
    let title = format!(
        "the {} light(s) of {} seen from ({x}, {y}, {z})",
        scene.lights.len(),
        args.scene.display()
    );
    report(
        &title,
        t,
        out,
        "deltas: point, spot and directional lights",
        "theta down from straight up (+y)",
    )
}

/// Prints what an experiment found, draws it to `out`, and gives the exit code.
fn report(
    title: &str,
    t: Result<WarpTest, String>,
    out: Option<snell::output::PendingOutput>,
    deltas: &str,
    axes: &str,
) -> ExitCode {
    let t = match t {
        Ok(t) => t,
        Err(e) => {
            println!("{title}: {e}");
            return ExitCode::from(1);
        }
    };
    println!("{title}");
    let binned = t.samples - t.specular - t.absorbed;
    println!(
        "{} samples: {binned} in the histogram, {} on {deltas} (not drawn), {} absorbed",
        t.samples, t.specular, t.absorbed
    );
    if binned == 0 {
        println!("no sample has a density to test (all deltas or absorbed)");
    }
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
        let (band, sector) = (bin / BINS.phi, bin % BINS.phi);
        println!(
            "the bin that strays most: theta {:.1}° to {:.1}°, phi {:.1}° to {:.1}°: {o} samples where {e:.1} are expected",
            band as f32 * 180.0 / BINS.theta as f32,
            (band + 1) as f32 * 180.0 / BINS.theta as f32,
            sector as f32 * 360.0 / BINS.phi as f32,
            (sector + 1) as f32 * 360.0 / BINS.phi as f32,
        );
    }
    if let Some(e) = &t.inconsistent {
        println!("and the sampling disagrees with the density it reports: {e}");
    }
    if let Some(out) = out {
        let path = out.path().to_path_buf();
        if let Err(e) = out.commit(&t.image(6)) {
            return fail(e.to_string());
        }
        println!(
            "wrote {}: the samples' histogram | the density's | their difference (red more, blue fewer, in standard deviations); {axes}, phi across",
            path.display()
        );
    }
    if t.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
