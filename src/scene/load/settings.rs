//! `[image]`, `[integrator]` and `[fog]` to the render's settings: image size, samples and
//! depth within the limits, the reconstruction filter, exposure, the integrator's options,
//! and the fog's mode with the keys that mode reads.

use super::Builder;
use crate::film::Filter;
use crate::sampler::SamplerKind;
use crate::scene::diag::{DocPath, Problem};
use crate::scene::format::{FogDef, FogMode, ImageDef, IntegratorDef, IntegratorKind, SamplerDef};
use crate::scene::{Fog, IntegratorSettings, RenderSettings};

impl Builder<'_> {
    pub(super) fn settings(
        &mut self,
        d: &ImageDef,
        integrator: &IntegratorDef,
        path: &DocPath,
    ) -> RenderSettings {
        if let Err(e) = RenderSettings::check_side("width", d.width) {
            self.error(path.key("width"), e);
        }
        if let Err(e) = RenderSettings::check_side("height", d.height) {
            self.error(path.key("height"), e);
        }
        let limits = self.limits;
        for (key, check) in [
            ("width", limits.check_pixels(d.width, d.height)),
            (
                "samples",
                limits.check_spp(d.samples, integrator.kind == IntegratorKind::Whitted),
            ),
            ("max_depth", limits.check_depth(d.max_depth)),
        ] {
            if let Err((e, help)) = check {
                self.problems.push(Problem {
                    help,
                    ..Problem::new(path.key(key), e)
                });
            }
        }
        let fpath = path.key("filter");
        let radius = d.filter.radius.map(|r| {
            let r = self.positive(r, &fpath.key("radius"));
            if r > 8.0 {
                self.error(
                    fpath.key("radius"),
                    format!("must be at most 8 pixels, not {r}"),
                );
            }
            r
        });
        RenderSettings {
            width: d.width,
            height: d.height,
            spp: d.samples,
            max_depth: d.max_depth,
            seed: d.seed,
            filter: Filter::new(d.filter.kind, radius),
            integrator: self.integrator(integrator),
            tone: crate::output::tone::Tone {
                exposure: self.exposure(d.exposure, &path.key("exposure")),
                curve: d.tonemap,
            },
            filter_textures: d.filter_textures,
            noise: d.noise.filter(|&v| match RenderSettings::check_noise(v) {
                Ok(()) => true,
                Err(e) => {
                    self.error(path.key("noise"), e);
                    false
                }
            }),
        }
    }

    /// An exposure in stops, within what a picture can use (2^±20 is a millionfold).
    fn exposure(&mut self, x: f32, path: &DocPath) -> f32 {
        self.in_range(x, -20.0, 20.0, path)
    }

    fn integrator(&mut self, d: &IntegratorDef) -> IntegratorSettings {
        let path = DocPath::default().key("integrator");
        if d.rr_depth == 0 {
            self.error(
                path.key("rr_depth"),
                "must be 1 or more (the camera ray is depth 1)",
            );
        }
        if d.kind == IntegratorKind::Bdpt && d.clamp.is_some() {
            self.error_help(
                path.key("clamp"),
                "bdpt does not clamp: a clamp cuts a sample's colour, and bidirectional samples add to many pixels",
                "remove `clamp`, or render with `type = \"path\"`",
            );
        }
        if d.kind != IntegratorKind::Bdpt && d.mis.is_some() {
            self.error_help(
                path.key("mis"),
                "only `type = \"bdpt\"` weighs strategies by `mis`",
                "remove `mis`, or set `type = \"bdpt\"`",
            );
        }
        IntegratorSettings {
            kind: d.kind,
            mis: d.mis.unwrap_or_default(),
            sampler: match d.sampler {
                SamplerDef::Sobol => SamplerKind::Sobol,
                SamplerDef::Independent => SamplerKind::Independent,
            },
            rr_depth: d.rr_depth.max(1),
            clamp: d.clamp.map(|c| self.positive(c, &path.key("clamp"))),
        }
    }

    pub(super) fn fog(&mut self, d: &FogDef, path: &DocPath) -> Fog {
        let color = self.color(d.color, &path.key("color"));
        match d.mode {
            FogMode::Linear => {
                let start = self.non_negative(d.start, &path.key("start"));
                let Some(end) = d.end else {
                    self.error_help(
                        path.clone(),
                        "linear fog needs `end`",
                        "add `end = DISTANCE` where the fog becomes complete",
                    );
                    return Fog::Linear {
                        color,
                        start,
                        end: start + 1.0,
                    };
                };
                let end = self.finite(end, &path.key("end"));
                if end <= start {
                    self.error(
                        path.key("end"),
                        format!("must be greater than start ({start}), not {end}"),
                    );
                }
                if d.density.is_some() {
                    self.error_help(
                        path.key("density"),
                        "density belongs to exponential fog",
                        "use mode = \"exponential\" or remove density",
                    );
                }
                Fog::Linear {
                    color,
                    start,
                    end: end.max(start + 1e-3),
                }
            }
            FogMode::Exponential => {
                let density = match d.density {
                    Some(x) => self.positive(x, &path.key("density")),
                    None => {
                        self.error_help(
                            path.clone(),
                            "exponential fog needs `density`",
                            "add `density = 0.01` (per scene unit)",
                        );
                        1.0
                    }
                };
                if d.end.is_some() {
                    self.error_help(
                        path.key("end"),
                        "end belongs to linear fog",
                        "use mode = \"linear\" or remove end",
                    );
                }
                let start = self.non_negative(d.start, &path.key("start"));
                Fog::Exponential {
                    color,
                    start,
                    density,
                }
            }
        }
    }
}
