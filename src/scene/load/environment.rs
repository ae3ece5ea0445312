//! `[environment]` to an [`Environment`]: the image loaded (as textures are, within the
//! texture limit) and its density built, a sky (sky.rs), or one colour.

use super::Builder;
use crate::light::sky::Sky;
use crate::light::{Environment, EnvironmentMap, EnvironmentSource};
use crate::scene::diag::DocPath;
use crate::scene::format::EnvironmentDef;
use crate::texture::ColorSpace;

impl Builder<'_> {
    pub(super) fn environment(
        &mut self,
        d: &EnvironmentDef,
        path: &DocPath,
    ) -> Option<Environment> {
        match d {
            EnvironmentDef::Sky { visible, .. } => Some(Environment {
                source: EnvironmentSource::Sky(Box::new(Sky::new(&self.sky(d, path)?))),
                visible: *visible,
            }),
            EnvironmentDef::Constant { color, visible } => Some(Environment {
                source: EnvironmentSource::Constant(self.color(*color, &path.key("color"))),
                visible: *visible,
            }),
            EnvironmentDef::Image {
                file,
                rotate,
                scale,
                visible,
            } => {
                let rotate = self.point(*rotate, &path.key("rotate"));
                let scale = self.color(*scale, &path.key("scale"));
                let full = self.base_dir.join(file);
                self.files.push(full.clone());
                // Float files (.hdr, .exr) are linear whatever this says; 8-bit ones are
                // photographs, sRGB.
                match self.image(&full, ColorSpace::Srgb, false) {
                    Ok(img) => {
                        let mut map = EnvironmentMap::new(img, rotate, scale);
                        map.file = Some(file.clone());
                        Some(Environment {
                            source: EnvironmentSource::Map(Box::new(map)),
                            visible: *visible,
                        })
                    }
                    Err(e) => {
                        self.error_help(
                            path.key("file"),
                            e.to_string(),
                            "the path is relative to the scene file's folder; Radiance .hdr, OpenEXR, PNG and JPEG are read",
                        );
                        None
                    }
                }
            }
        }
    }
}
