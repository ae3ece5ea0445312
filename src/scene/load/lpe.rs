//! `[[image.lpe]]` to the light path expressions a render writes beside the picture: each
//! a name and an expression, or a preset, checked against the built scene (its materials
//! and lights name the labels), with a mistake reported at the expression's key and its
//! column within it.

use super::Builder;
use crate::lpe::{self, LpeSet, Request};
use crate::scene::Scene;
use crate::scene::diag::DocPath;
use crate::scene::format::LpeDef;

impl Builder<'_> {
    pub(super) fn light_path_expressions(
        &mut self,
        defs: &[LpeDef],
        image: &DocPath,
        scene: &Scene,
    ) -> Vec<Request> {
        let mut out = vec![];
        let mut names: Vec<String> = vec![];
        for (i, d) in defs.iter().enumerate() {
            let path = image.key("lpe").index(i);
            let (request, key) = match (&d.name, &d.expr, &d.preset) {
                (Some(name), Some(expr), None) => {
                    if let Err(e) = lpe::check_name(name) {
                        self.error(path.key("name"), e);
                        continue;
                    }
                    let named = lpe::Named {
                        name: name.clone(),
                        expr: expr.clone(),
                    };
                    (Request::Expr(named), "expr")
                }
                (None, None, Some(preset)) => match lpe::request(preset) {
                    Ok(r @ Request::Preset(_)) => (r, "preset"),
                    Ok(Request::Expr(_)) | Err(_) => {
                        let known: Vec<&str> = lpe::Preset::ALL.iter().map(|p| p.name()).collect();
                        self.error_help(
                            path.key("preset"),
                            format!("`{preset}` is not a preset"),
                            format!("presets: {}", known.join(", ")),
                        );
                        continue;
                    }
                },
                _ => {
                    self.error_help(
                        path,
                        "an expression needs `name` and `expr`, or `preset` alone",
                        "name = \"direct\", expr = \"C<RD>L\" (or preset = \"direct\")",
                    );
                    continue;
                }
            };
            let expanded = lpe::expand(std::slice::from_ref(&request), scene);
            if let Err(e) = LpeSet::new(scene, &expanded) {
                self.error_help(path.key(key), e.error.to_string(), e.error.help);
                continue;
            }
            for n in &expanded {
                if names.contains(&n.name) {
                    self.error_help(
                        path.clone(),
                        format!("a second image named `{}`", n.name),
                        "give each expression a name of its own",
                    );
                }
                names.push(n.name.clone());
            }
            out.push(request);
        }
        out
    }
}
