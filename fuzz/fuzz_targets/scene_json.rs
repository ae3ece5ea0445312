//! A JSON scene file: parsed, checked and built (or refused with a located message).
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("scene_common.rs");

fuzz_target!(|data: &[u8]| check_scene(data, Format::Json, "fuzz.json"));
