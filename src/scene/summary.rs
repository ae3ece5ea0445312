//! What a user is told about a scene as a whole: its summary in a few lines (`snell
//! check`), and the warning, among the scene's warnings, when its integrator finds no
//! light to light it by.

use super::{IntegratorKind, Scene};
use crate::light::Light;
use crate::math::Color;
use std::collections::BTreeMap;

impl Scene {
    /// What its integrator cannot light: Whitted lights surfaces by point, spot and
    /// directional lights only (an environment shows, and emitting surfaces glow, but
    /// neither lights anything); the path tracer finds no light in a scene without lights,
    /// emitting surfaces, environment or background.
    pub fn lighting_warning(&self) -> Option<String> {
        if self.lights.iter().any(Light::is_delta) {
            return None;
        }
        let emits = self.materials.iter().any(|m| m.emission.is_some());
        match self.settings.integrator.kind {
            IntegratorKind::Whitted => {
                let others = match (self.environment().is_some(), emits) {
                    (true, true) => " (Whitted shows the environment and emitting surfaces but lights nothing by them; the path tracer does: --integrator path)",
                    (true, false) => " (Whitted shows the environment but does not light with it; the path tracer does: --integrator path)",
                    (false, true) => " (Whitted shows emitting surfaces but lights nothing by them; the path tracer does: --integrator path)",
                    (false, false) => "",
                };
                Some(format!(
                    "the scene has no lights Whitted uses: only ambient light will show{others}"
                ))
            }
            IntegratorKind::Path | IntegratorKind::Bdpt => (!emits
                && self.background == Color::ZERO
                && self.environment().is_none())
            .then(|| {
                "the scene has no lights and a black background: the image will be black"
                    .into()
            }),
            IntegratorKind::Light => (!emits && self.environment().is_none()).then(|| {
                "the scene has no lights, glowing surfaces or environment: light tracing starts its paths there (not at the background), so its image will be black"
                    .into()
            }),
        }
    }

    /// [`Scene::lighting_warning`] again after its settings changed (an integrator given on
    /// the command line): `before` was the warning for the settings it was built with.
    pub fn recheck_lighting(&mut self, before: Option<String>) {
        let after = self.lighting_warning();
        if before != after {
            if let Some(b) = before {
                self.warnings.retain(|w| *w != b);
            }
            self.warnings.extend(after);
        }
    }

    /// A short human summary: counts of objects by type, lights, textures, materials.
    pub fn summary(&self) -> String {
        let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
        for o in &self.objects {
            *kinds.entry(o.shape.kind()).or_default() += 1;
        }
        let kinds: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let mut lights: BTreeMap<&str, usize> = BTreeMap::new();
        // The environment has a line of its own.
        let counted = self
            .lights
            .iter()
            .filter(|l| !matches!(l, Light::Environment(_)));
        for l in counted.clone() {
            *lights.entry(l.kind_name()).or_default() += 1;
        }
        let count = counted.count();
        let lights = if count == 0 {
            "none".to_string()
        } else {
            let kinds: Vec<String> = lights.iter().map(|(k, n)| format!("{n} {k}")).collect();
            format!("{count} ({})", kinds.join(", "))
        };
        let s = &self.settings;
        // Lines for an animation and for meshes, where the scene has them.
        let mut extra = String::new();
        let st = &self.stats;
        if let (Some(env), Some(i)) = (self.environment(), self.environment_light) {
            extra += &format!(
                "\nenvironment: {}; {:.0} % of light samples",
                env.describe(),
                100.0 * self.light_sampler.probability(i)
            );
        }
        if let Some(a) = self.animation {
            extra += &format!(
                "\nanimation: {} frames at {} frames a second ({:.2} s)",
                a.frames,
                a.fps,
                a.frames as f32 / a.fps
            );
        }
        if st.meshes > 0 {
            extra += &format!(
                "\nmeshes:    {} ({} triangles loaded, {} placed)",
                st.meshes, st.unique_triangles, st.instanced_triangles
            );
            for m in &st.per_mesh {
                // A glTF file's meshes by name, with the nodes that place them.
                let part = m
                    .label
                    .as_ref()
                    .map_or_else(String::new, |l| format!(": {l}"));
                extra += &format!(
                    "\n  {}{part}: {} triangles, placed {} time{} ({} triangles)",
                    m.file,
                    m.triangles,
                    m.placements,
                    if m.placements == 1 { "" } else { "s" },
                    m.triangles * m.placements
                );
            }
        }
        // The named textures, then the images each glTF file's materials read.
        let mut files: Vec<(&str, usize)> = vec![];
        for m in st.per_mesh.iter().filter(|m| m.file_images > 0) {
            if !files.iter().any(|(f, _)| *f == m.file) {
                files.push((&m.file, m.file_images));
            }
        }
        let count = self.texture_names.len() + files.iter().map(|(_, n)| n).sum::<usize>();
        let mut names: Vec<String> = self.texture_names.keys().cloned().collect();
        names.extend(
            files
                .iter()
                .map(|(f, n)| format!("{n} image{} of {f}", if *n == 1 { "" } else { "s" })),
        );
        let textures = if names.is_empty() {
            count.to_string()
        } else {
            format!("{count} ({})", names.join(", "))
        };
        format!(
            "image:     {} x {}, {} spp, max depth {}, seed {}\nobjects:   {} ({})\nlights:    {lights}\nmaterials: {}\ntextures:  {textures}{extra}",
            s.width,
            s.height,
            s.spp,
            s.max_depth,
            s.seed,
            self.objects.len(),
            kinds.join(", "),
            self.material_names.len(),
        )
    }
}
