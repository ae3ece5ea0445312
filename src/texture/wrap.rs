//! What an image texture shows outside `[0, 1]`, along each of its axes: itself again
//! (repeat), its edge texels stretched (clamp), or itself mirrored every other time (glTF's
//! three sampler wrap modes, OpenGL's REPEAT, CLAMP_TO_EDGE and MIRRORED_REPEAT).

/// One axis's wrap mode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// The image again, and again.
    #[default]
    Repeat,
    /// The edge texels, stretched.
    Clamp,
    /// The image mirrored every other time, so its edges meet themselves.
    Mirror,
}

impl Wrap {
    /// The texel index that index `i` of an axis of `n` texels reads.
    #[inline]
    pub fn index(self, i: i64, n: i64) -> i64 {
        if (0..n).contains(&i) {
            return i;
        }
        match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        }
    }
}

/// The wrap modes of an image's two axes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Wraps {
    /// Along u (across the image).
    pub u: Wrap,
    /// Along v (down the image).
    pub v: Wrap,
}

impl Wraps {
    /// Repeat both ways: the default.
    pub const REPEAT: Wraps = Wraps {
        u: Wrap::Repeat,
        v: Wrap::Repeat,
    };

    /// The same mode on both axes.
    pub fn both(w: Wrap) -> Wraps {
        Wraps { u: w, v: w }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_outside_the_axis_repeat_clamp_or_mirror() {
        let n = 4;
        let got = |w: Wrap| (-5..9).map(|i| w.index(i, n)).collect::<Vec<_>>();
        assert_eq!(
            got(Wrap::Repeat),
            [3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0]
        );
        assert_eq!(got(Wrap::Clamp), [0, 0, 0, 0, 0, 0, 1, 2, 3, 3, 3, 3, 3, 3]);
        // 0 1 2 3 | 3 2 1 0 | 0 1 2 3 ...: -1 is 0's mirror, 4 is 3's.
        assert_eq!(
            got(Wrap::Mirror),
            [3, 3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0]
        );
        // Far away, as a planar mapping on a distant hit gives: still inside.
        for w in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
            for i in [i64::MIN / 4, i64::MAX / 4] {
                assert!((0..n).contains(&w.index(i, n)), "{w:?} {i}");
            }
        }
    }
}
