//! The README's claims about the shipped scenes hold: the seed scene's caption names the size
//! and samples the scene file renders by default, and the picture shown is that size.

use super::repo;

#[test]
fn the_readme_caption_matches_the_seed_scene_and_its_picture() {
    let readme = std::fs::read_to_string(repo("README.md")).unwrap();
    let caption = readme
        .split_once("*The seed scene (`scenes/seed.toml`, ")
        .map(|(_, rest)| rest)
        .expect("the README has the seed scene's caption");
    let (size, rest) = caption.split_once(", ").unwrap();
    let (w, h) = size.split_once(" x ").unwrap();
    let spp = rest.split_once(" samples per pixel").unwrap().0;
    let (w, h, spp): (u32, u32, u32) =
        (w.parse().unwrap(), h.parse().unwrap(), spp.parse().unwrap());
    let scene = snell::scene::load(&repo("scenes/seed.toml")).unwrap();
    let s = &scene.settings;
    assert_eq!(
        (s.width, s.height, s.spp),
        (w, h, spp),
        "the caption says {size}, {spp} spp"
    );
    let picture = image::open(repo("docs/images/seed.png")).unwrap();
    assert_eq!((picture.width(), picture.height()), (w, h));
}
