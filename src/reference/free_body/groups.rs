//! The chain as rigid groups ([`Groups`]): the tiles between two turning joints move as one
//! body, since every other joint is held (a straight or LR joint is rigid; a folding joint is
//! held straight by its shared face before it starts and closed by its walls after it
//! ends). A group's mass and linear drag are sums over its tiles, kept with their suffix
//! sums (the tiles of a group from one of them to its end: what a held joint carries), in
//! the frame of the group's first tile. Groups are built again whenever a joint starts or
//! stops turning: O(tiles), a handful of times per fold.

use std::f64::consts::FRAC_PI_2;

use crate::model::{Mode, Model};
use crate::reference::free_body::tile_body::TileBodies;
use crate::tile_frame::TileFrame;

/// Mass (or drag) moments about a point in some frame: total `m`, first moment `s`, second
/// moment `j` (SI units).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Moments {
    pub(crate) m: f64,
    pub(crate) s: [f64; 2],
    pub(crate) j: f64,
}

impl Moments {
    /// The moments of a body (moments `(m, s, j)` about its own origin, in its own frame)
    /// whose frame sits at `o` (m) turned by `(sin, cos)`, about the origin.
    pub(crate) fn placed(m: f64, s: [f64; 2], j: f64, o: [f64; 2], sin: f64, cos: f64) -> Moments {
        let rs = [cos * s[0] - sin * s[1], sin * s[0] + cos * s[1]];
        Moments {
            m,
            s: [m * o[0] + rs[0], m * o[1] + rs[1]],
            j: j + 2.0 * (o[0] * rs[0] + o[1] * rs[1]) + m * (o[0] * o[0] + o[1] * o[1]),
        }
    }

    /// Both together.
    pub(crate) fn plus(self, o: Moments) -> Moments {
        Moments {
            m: self.m + o.m,
            s: [self.s[0] + o.s[0], self.s[1] + o.s[1]],
            j: self.j + o.j,
        }
    }

    /// The first moment turned by `(sin, cos)`.
    pub(crate) fn turned_s(&self, sin: f64, cos: f64) -> [f64; 2] {
        [
            cos * self.s[0] - sin * self.s[1],
            sin * self.s[0] + cos * self.s[1],
        ]
    }
}

/// The rigid groups of the chain at one set of joint modes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Groups {
    /// First and last tile of each group.
    pub(crate) first: Vec<usize>,
    pub(crate) last: Vec<usize>,
    /// The group of each tile.
    pub(crate) of_tile: Vec<usize>,
    /// Each tile's frame in its group's (the group's first tile's) frame, mm.
    pub(crate) rel: Vec<TileFrame>,
    /// Each group's mass and linear drag moments about its first tile's centre, in its frame.
    pub(crate) mass: Vec<Moments>,
    pub(crate) drag: Vec<Moments>,
    /// For each tile, the moments of the tiles from it to its group's end (group frame).
    pub(crate) suffix_mass: Vec<Moments>,
    pub(crate) suffix_drag: Vec<Moments>,
}

impl Groups {
    /// The groups when the joints turn as `modes` say, the held ones at the angles of `y`
    /// (0 straight, 1 closed). `hinges` are the left and right hinges in a tile's frame (mm).
    pub(crate) fn build(
        model: &Model,
        bodies: &TileBodies,
        modes: &[Mode],
        y: &[f64],
        hinges: [kurbo::Point; 2],
    ) -> Groups {
        let tiles = model.geometry.tiles();
        let half = 0.5 * model.geometry.w;
        let mut g = Groups {
            rel: vec![TileFrame::IDENTITY; tiles],
            of_tile: vec![0; tiles],
            suffix_mass: vec![Moments::default(); tiles],
            suffix_drag: vec![Moments::default(); tiles],
            ..Groups::default()
        };
        g.first.push(0);
        for t in 0..tiles {
            if t > 0 {
                let j = t - 1;
                let turning = model.joint_var(j).filter(|&v| modes[v] == Mode::Free);
                if turning.is_some() {
                    g.last.push(j);
                    g.first.push(t);
                    g.rel[t] = TileFrame::IDENTITY;
                } else {
                    let a = model.joint_var(j).map_or(0.0, |v| {
                        model.joint_sign(j) * y[v].clamp(0.0, 1.0) * FRAC_PI_2
                    });
                    let h = hinges[usize::from(model.joint_sign(j) < 0.0)];
                    g.rel[t] = g.rel[j].across_joint(a, h, half);
                }
            }
            g.of_tile[t] = g.first.len() - 1;
        }
        g.last.push(tiles - 1);
        for (&first, &last) in g.first.iter().zip(&g.last) {
            let (mut m, mut d) = (Moments::default(), Moments::default());
            for t in (first..=last).rev() {
                let f = &g.rel[t];
                let b = &bodies.tiles[t];
                let o = [f.x * 1e-3, f.y * 1e-3];
                m = m.plus(Moments::placed(b.m, b.s, b.j, o, f.sin, f.cos));
                d = d.plus(Moments::placed(
                    b.drag,
                    [0.0, 0.0],
                    b.rotational_drag,
                    o,
                    f.sin,
                    f.cos,
                ));
                g.suffix_mass[t] = m;
                g.suffix_drag[t] = d;
            }
            g.mass.push(m);
            g.drag.push(d);
        }
        g
    }

    /// Number of groups.
    pub(crate) fn len(&self) -> usize {
        self.first.len()
    }
}
