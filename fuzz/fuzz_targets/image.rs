//! An image texture file (PNG, JPEG, BMP or OpenEXR, told apart by content): decoded,
//! turned into snell's linear texels and sampled.
#![no_main]

use glam::Vec2;
use image::Limits;
use libfuzzer_sys::fuzz_target;
use snell::texture::{ColorSpace, ImageData, Wrap, Wraps};
use std::sync::Once;

fuzz_target!(|data: &[u8]| {
    // snell catches a decoder's panic and reports the file as corrupt; libfuzzer-sys's hook
    // would abort on it first. Every other panic still goes to that hook.
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let fuzzer_hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !snell::texture::in_guarded_decoder() {
                fuzzer_hook(info)
            }
        }));
    });
    // A header may claim any size: stay well inside the fuzzer's memory limit (ImageData
    // then takes 12 bytes a pixel on top of the decoded image). snell itself decodes with
    // `Limits::default()` (512 MiB).
    let mut limits = Limits::default();
    limits.max_image_width = Some(4096);
    limits.max_image_height = Some(4096);
    limits.max_alloc = Some(64 << 20);
    let Ok(img) = snell::texture::decode(data, limits) else {
        return;
    };
    if img.width() as u64 * img.height() as u64 > 1 << 20 {
        return;
    }
    for space in [ColorSpace::Srgb, ColorSpace::Linear] {
        let tex = ImageData::from_dynamic(&img, space);
        assert_eq!((tex.width(), tex.height()), (img.width(), img.height()));
        // Inside, on the edges, repeated, and far away (a texture mapping can hand back any
        // finite uv).
        for uv in [
            Vec2::new(0.0, 0.0),
            Vec2::new(0.5, 0.5),
            Vec2::new(1.0, 1.0),
            Vec2::new(-0.25, 1.75),
            Vec2::new(1e7, -1e7),
            Vec2::new(1e30, -1e30),
            Vec2::new(f32::MAX, f32::MIN),
            Vec2::new(f32::NAN, 0.5),
        ] {
            for wrap in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
                let _ = tex.sample_bilinear(uv, Wraps::both(wrap));
            }
        }
    }
});
