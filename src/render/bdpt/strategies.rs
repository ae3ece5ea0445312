//! Strategy images (`--aov strategies`): for the paths of up to [`STRATEGY_DEPTH`] segments,
//! the light each bidirectional strategy `(s, t)` found, weighted by its MIS weight (these
//! add up to the picture's light of those lengths) and unweighted (each an estimate of all
//! of it, some far noisier than others): what pbrt's BDPT writes to show how multiple
//! importance sampling shares out each path. Box-filtered, whatever the render's filter:
//! a camera strategy's light goes to its own pixel, a splat to the pixel it lands in.

use crate::film::{Filter, FilterKind, Image, SplatFilm};
use crate::integrator::Strategy;

/// The longest paths (in segments) the images show.
pub const STRATEGY_DEPTH: u32 = 4;

/// The strategies imaged for a scene of `max_depth`: `(s, t)` for paths of 1 to
/// `min(max_depth, 4)` segments (`s + t - 1` of them), by length, then by `s`; `(1, 1)`, which
/// bdpt does not take, left out.
pub fn strategy_list(max_depth: u32) -> Vec<(usize, usize)> {
    let mut list = vec![];
    for len in 1..=max_depth.min(STRATEGY_DEPTH) as usize {
        for s in 0..=len {
            let t = len + 1 - s;
            if (s, t) != (1, 1) {
                list.push((s, t));
            }
        }
    }
    list
}

/// The images' names, in [`strategy_list`]'s order, each strategy's weighted image
/// (`s1-t2`) then its unweighted one (`s1-t2-unweighted`).
pub fn strategy_names(max_depth: u32) -> Vec<String> {
    strategy_list(max_depth)
        .into_iter()
        .flat_map(|(s, t)| [format!("s{s}-t{t}"), format!("s{s}-t{t}-unweighted")])
        .collect()
}

/// Each strategy's sums, weighted and not.
pub(super) struct StrategyFilms {
    list: Vec<(usize, usize)>,
    films: Vec<SplatFilm>,
}

impl StrategyFilms {
    /// Empty films of `width` x `height` for a scene of `max_depth`.
    pub fn new(width: u32, height: u32, max_depth: u32) -> Self {
        let list = strategy_list(max_depth);
        let pixel = Filter::new(FilterKind::Box, None);
        let films = (0..2 * list.len())
            .map(|_| SplatFilm::new(width, height, &pixel))
            .collect();
        StrategyFilms { list, films }
    }

    /// Adds what strategy `st` of a sample of pixel `(x, y)` found.
    pub fn add(&self, st: &Strategy, x: u32, y: u32) {
        let Some(i) = self.list.iter().position(|&k| k == (st.s, st.t)) else {
            return;
        };
        let (px, py) = st.film.unwrap_or((x as f32 + 0.5, y as f32 + 0.5));
        self.films[2 * i].add(px, py, st.light * st.weight);
        self.films[2 * i + 1].add(px, py, st.light);
    }

    /// The sums as they are now.
    pub fn snapshot(&self) -> Vec<Vec<[i64; 3]>> {
        self.films.iter().map(SplatFilm::snapshot).collect()
    }

    /// Puts the sums back as `snapshot` had them.
    pub fn restore(&self, snapshot: &[Vec<[i64; 3]>]) {
        for (f, s) in self.films.iter().zip(snapshot) {
            f.restore(s);
        }
    }

    /// The images, in [`strategy_names`]' order, for `spp` samples a pixel.
    pub fn images(&self, spp: u32) -> Vec<Image> {
        let scale = 1.0 / spp.max(1) as f32;
        self.films.iter().map(|f| f.image(scale)).collect()
    }
}
