//! Expressions against hand-written paths of a small scene: what each matches, every
//! mistake that needs the scene (its labels, paths it cannot match), and the presets.

use super::*;
use crate::bsdf::Lobe;
use crate::scene::{Format, load_str};

/// A scene with a diffuse `white`, a `mirror`, a `glass`, a point light `sun`, a glowing
/// sphere `lamp` and an environment.
fn scene() -> Scene {
    let text = "[image]\nwidth = 8\nheight = 8\n[integrator]\ntype = \"path\"\n\
                [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\
                [environment]\ntype = \"constant\"\ncolor = [0.1, 0.1, 0.1]\n\
                [materials.white]\ntype = \"diffuse\"\ncolor = 0.5\n\
                [materials.mirror]\ntype = \"conductor\"\nmetal = \"Ag\"\n\
                [materials.glass]\ntype = \"dielectric\"\nior = 1.5\n\
                [materials.glow]\ntype = \"diffuse\"\ncolor = 0\nemission = 3\n\
                [[lights]]\ntype = \"point\"\nname = \"sun\"\nposition = [0, 4, 0]\n\
                [[lights]]\ntype = \"point\"\nposition = [0, 4, 2]\n\
                [[objects]]\ntype = \"sphere\"\nname = \"lamp\"\ncenter = [0, 3, 0]\nradius = 0.5\nmaterial = \"glow\"\n\
                [[objects]]\ntype = \"sphere\"\nradius = 0.5\nmaterial = \"glass\"\n\
                [[objects]]\ntype = \"sphere\"\ncenter = [1, 0, 0]\nradius = 0.5\nmaterial = \"mirror\"\n\
                [[objects]]\ntype = \"plane\"\npoint = [0, -1, 0]\nmaterial = \"white\"\n";
    load_str(
        text,
        std::path::Path::new("t.toml"),
        std::path::Path::new("."),
        Format::Toml,
    )
    .unwrap()
}

/// The events of a path, written as words: `RD:white` (a lobe at a material), `L:sun` (a
/// light's name, `lamp` for the glowing object, `environment`, `background`; `_` for a
/// space).
fn symbols(set: &LpeSet, scene: &Scene, path: &str) -> Vec<Symbol> {
    let a = &set.alphabet;
    let material = |m: &str| scene.material_names.iter().position(|n| n == m).unwrap();
    path.split_whitespace()
        .map(|w| {
            let (kind, name) = w.split_once(':').unwrap_or((w, ""));
            let name = &name.replace('_', " ");
            match kind {
                "C" => a.camera(),
                "RD" => a.scatter(Lobe::DiffuseReflection, material(name)),
                "RG" => a.scatter(Lobe::GlossyReflection, material(name)),
                "RS" => a.scatter(Lobe::SpecularReflection, material(name)),
                "TG" => a.scatter(Lobe::GlossyTransmission, material(name)),
                "TS" => a.scatter(Lobe::SpecularTransmission, material(name)),
                "L" => match name.as_str() {
                    "lamp" => {
                        a.object(scene.objects.iter().position(|o| o.name == "lamp").unwrap())
                    }
                    "environment" => a.sky(true),
                    "background" => a.sky(false),
                    light => a.light(scene.light_names.iter().position(|n| n == light).unwrap()),
                },
                other => panic!("no event {other}"),
            }
        })
        .collect()
}

fn matches(expr: &str, path: &str) -> bool {
    let scene = scene();
    let named = [Named {
        name: "x".into(),
        expr: expr.into(),
    }];
    let set = LpeSet::new(&scene, &named).unwrap_or_else(|e| panic!("{expr}: {e:?}"));
    let dfa = &set.dfas[0];
    let mut state = 1;
    for s in symbols(&set, &scene, path) {
        state = dfa.step(state, s);
    }
    dfa.accepts(state)
}

/// Each expression against paths it must and must not match.
#[test]
fn expressions_match_the_paths_they_say() {
    let cases: &[(&str, &str, bool)] = &[
        ("CL", "C L:sun", true),
        ("CL", "C RD:white L:sun", false),
        ("C<RD>L", "C RD:white L:sun", true),
        ("C<RD>L", "C RG:white L:sun", false),
        ("C<RD>L", "C RD:white RD:white L:sun", false),
        ("CD*L", "C L:lamp", true),
        ("CD*L", "C RD:white RD:white RD:white L:lamp", true),
        ("CD*L", "C RD:white RS:mirror L:lamp", false),
        ("C<RD>.+L", "C RD:white TS:glass TS:glass L:lamp", true),
        ("C<RD>.+L", "C RD:white L:lamp", false),
        ("C[^D].*L", "C RS:mirror RD:white L:sun", true),
        ("C[^D].*L", "C RD:white RS:mirror L:sun", false),
        ("C<RD>S+L", "C RD:white TS:glass TS:glass L:sun", true),
        ("C<RD>S+L", "C RD:white L:sun", false),
        ("C<T.>+L", "C TS:glass TG:glass L:environment", true),
        ("C<RD'white'>L", "C RD:white L:sun", true),
        ("C<RD'white'>L", "C RS:mirror L:sun", false),
        ("C 'mirror'.*L", "C RS:mirror RD:white L:sun", true),
        ("C 'mirror'.*L", "C RD:white RS:mirror L:sun", false),
        ("C.*L'sun'", "C RD:white L:sun", true),
        ("C.*L'sun'", "C RD:white L:point_#1", false),
        ("C.*L'point #1'", "C RD:white L:point_#1", true),
        ("C.*O", "C RD:white L:lamp", true),
        ("C.*O", "C RD:white L:sun", false),
        ("C.*B", "C RS:mirror L:environment", true),
        ("C.*B", "C L:background", true),
        ("C.*B", "C L:lamp", false),
        ("C(D|G){2}L", "C RD:white RG:white L:sun", true),
        ("C(D|G){2}L", "C RD:white L:sun", false),
        ("CD{1,2}L", "C RD:white RD:white L:sun", true),
        ("CD{1,2}L", "C RD:white RD:white RD:white L:sun", false),
        ("CD{2,}L", "C RD:white RD:white RD:white L:sun", true),
        ("C[DG]?L", "C L:sun", true),
        ("C[DG]?L", "C RG:mirror L:sun", true),
        ("C <R D> L", "C RD:white L:sun", true),
        ("C.*L|CL", "C L:sun", true),
    ];
    for &(expr, path, want) in cases {
        assert_eq!(matches(expr, path), want, "{expr} on {path}");
    }
    assert_eq!(cases.len(), 36);
}

/// Mistakes that need the scene: unknown labels, and expressions no path matches, each at
/// its column with a hint.
#[test]
fn mistakes_against_the_scene_point_at_their_column() {
    let scene = scene();
    let cases = [
        ("C.*L'moon'", 5, "no light is named 'moon'", "'sun'"),
        (
            "C<RD'marble'>L",
            5,
            "no material is named 'marble'",
            "'white'",
        ),
        ("C 'nothing'L", 3, "no material or light", "materials:"),
        ("C.*L'white'", 5, "no light is named 'white'", "'lamp'"),
        ("C'x'", 2, "the camera", "put a space"),
        ("LC", 1, "starts at the camera", "begin with `C`"),
        ("DL", 1, "starts at the camera", "begin with `C`"),
        ("C<RD>", 2, "ends at a light", "end the expression"),
        ("CLL", 1, "no path matches", "order"),
    ];
    for (expr, column, words, hint) in cases {
        let named = [Named {
            name: "x".into(),
            expr: expr.into(),
        }];
        let e = LpeSet::new(&scene, &named).expect_err(expr).error;
        assert_eq!(e.column, column, "{expr}: {e:?}");
        assert!(e.message.contains(words), "{expr}: {e:?}");
        assert!(e.help.contains(hint), "{expr}: {e:?}");
    }
    assert_eq!(cases.len(), 9);
}

/// Presets expand to their expressions, `per-light` to one per source of light that can
/// shine (the environment here; no black background), each named after it.
#[test]
fn presets_expand_to_their_expressions() {
    let scene = scene();
    let all: Vec<Request> = Preset::ALL.iter().map(|&p| Request::Preset(p)).collect();
    let named = expand(&all, &scene);
    let names: Vec<&str> = named.iter().map(|n| n.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "emission",
            "direct",
            "indirect",
            "specular",
            "caustics",
            "lamp",
            "sun",
            "point_1",
            "environment"
        ]
    );
    assert_eq!(named[7].expr, "C.*L'point #1'");
    let set = LpeSet::new(&scene, &named).unwrap();
    assert_eq!(set.len(), 9);
    assert_eq!(request("direct"), Ok(Request::Preset(Preset::Direct)));
    assert!(request("nope").unwrap_err().contains("per-light"));
    assert!(request("9x=CL").unwrap_err().contains("cannot name"));
    assert_eq!(
        request("mine=C<RD>L"),
        Ok(Request::Expr(Named {
            name: "mine".into(),
            expr: "C<RD>L".into()
        }))
    );
}
