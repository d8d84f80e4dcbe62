//! One printable tile: the octagon plate of the design's width, open channels that follow
//! its two magnet paths down to a floor, and the engraved mark, as a closed mesh in mm.
//!
//! Frame: the tile's own (as the engine's): the chain runs along +x through the centre, the
//! first path (towards the reaction initiator) on the -x side, z up from the bed. The magnet
//! stands on the channel floor, poles up; the channel is open on top.

use foldchain::magnet_path::{MagnetPath, PathEnd};
use foldchain::{Design, Octagon, Tile};

use crate::channel::Channel;
use crate::mark;
use crate::mesh::Mesh;
use crate::options::PartOptions;
use crate::region::{self, Contour, Region};
use crate::solid::{prism_with_pockets, Pocket};
use crate::PrintError;

/// The smallest capital height engraved, mm: below it the mark is left out.
pub const MIN_MARK_HEIGHT: f64 = 1.0;

/// The thinnest wall of a part and where it is.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Wall {
    /// Where: e.g. `second channel to the tile's edge`.
    pub place: String,
    /// Thickness, mm.
    pub thickness: f64,
}

/// A tile type built to a design, ready to print.
#[derive(Clone, Debug)]
pub struct TilePart {
    /// The tile type (the part lying with its first path towards the RI).
    pub tile: Tile,
    /// The design it is built to.
    pub design: Design,
    /// How it is built.
    pub options: PartOptions,
    /// The octagon, counter-clockwise, mm.
    pub outline: Contour,
    /// The first path's channel (-x side), then the second's (+x side).
    pub channels: [Channel; 2],
    /// The engraved mark (empty when the tile has no room for it).
    pub mark: Region,
    /// The capital height of the mark, mm (0 without a mark).
    pub mark_height: f64,
    /// The thinnest wall.
    pub thinnest_wall: Wall,
    /// The closed mesh.
    pub mesh: Mesh,
}

impl TilePart {
    /// Builds tile type `tile` to `design` with `options`.
    pub fn new(tile: Tile, design: &Design, options: &PartOptions) -> Result<TilePart, PrintError> {
        options.validate()?;
        design.validate()?;
        let path = |kind, end| {
            MagnetPath::new(kind, end, design).map_err(|source| PrintError::Path { tile, source })
        };
        let tol = options.arc_tolerance;
        let channel = |p| Channel::new(p, design.magnet_diameter, options.clearance, tol);
        let channels = [
            channel(path(tile.first, PathEnd::First)?),
            channel(path(tile.second, PathEnd::Second)?),
        ];
        let centre = options.floor + 0.5 * design.magnet_height;
        if centre >= options.height {
            return Err(PrintError::MagnetTooTall {
                tile,
                centre,
                top: options.height,
            });
        }
        let outline: Contour = Octagon::new(design.tile_width)
            .vertices()
            .iter()
            .map(|&(x, y)| [x, y])
            .collect();
        let outline_set = [outline.clone()];
        let names = ["first", "second"];
        let mut walls: Vec<Wall> = Vec::new();
        for (ch, name) in channels.iter().zip(names) {
            let d = region::boundary_distance(region::contours(&ch.region), outline_set.iter());
            let p = ch.path.rest();
            let inside = region::inside(outline_set.iter(), [p.0, p.1]);
            walls.push(Wall {
                place: format!("the {name} channel's wall to the tile's edge"),
                thickness: if inside { d } else { 0.0 },
            });
        }
        let between = region::boundary_distance(
            region::contours(&channels[0].region),
            region::contours(&channels[1].region),
        );
        let apart = {
            let p = channels[0].path.rest();
            !region::inside(region::contours(&channels[1].region), [p.0, p.1])
        };
        walls.push(Wall {
            place: "the wall between the two channels".into(),
            thickness: if apart { between } else { 0.0 },
        });
        for w in &walls {
            if w.thickness < options.min_wall {
                return Err(PrintError::ThinWall {
                    tile,
                    what: w.place.clone(),
                    thickness: w.thickness,
                    min: options.min_wall,
                    hint: "use a thicker design wall or c, a smaller clearance, smaller magnets or wider tiles",
                });
            }
        }
        let (mark, mark_height) = fit_mark(tile, design, options, &channels, &outline);
        if !mark.is_empty() {
            let d = region::boundary_distance(
                region::contours(&mark),
                channels
                    .iter()
                    .flat_map(|c| region::contours(&c.region))
                    .chain(outline_set.iter()),
            );
            walls.push(Wall {
                place: "the wall between the engraved mark and a channel or the edge".into(),
                thickness: d,
            });
        }
        let mut pockets: Vec<Pocket> = channels
            .iter()
            .map(|c| Pocket {
                floor: options.floor,
                region: c.region.clone(),
            })
            .collect();
        if !mark.is_empty() {
            pockets.push(Pocket {
                floor: options.height - options.mark_depth,
                region: mark.clone(),
            });
        }
        let mesh = prism_with_pockets(&outline, options.height, &pockets).map_err(|e| {
            PrintError::Triangulation {
                tile,
                face: e.face,
                reason: e.reason,
            }
        })?;
        let thinnest_wall = walls
            .into_iter()
            .min_by(|a, b| a.thickness.total_cmp(&b.thickness))
            .unwrap_or(Wall {
                place: String::new(),
                thickness: f64::INFINITY,
            });
        Ok(TilePart {
            tile,
            design: *design,
            options: *options,
            outline,
            channels,
            mark,
            mark_height,
            thinnest_wall,
            mesh,
        })
    }

    /// The channel at `end`.
    pub fn channel(&self, end: PathEnd) -> &Channel {
        match end {
            PathEnd::First => &self.channels[0],
            PathEnd::Second => &self.channels[1],
        }
    }

    /// The printed volume, mm^3.
    pub fn volume(&self) -> f64 {
        self.mesh.volume()
    }
}

/// The mark at the largest capital height up to the asked one that fits between the
/// channels, at least `min_wall` from them and from the edge; empty below
/// [`MIN_MARK_HEIGHT`].
fn fit_mark(
    tile: Tile,
    design: &Design,
    options: &PartOptions,
    channels: &[Channel; 2],
    outline: &Contour,
) -> (Region, f64) {
    let xs = |c: &Channel| {
        region::contours(&c.region)
            .flatten()
            .map(|p| p[0])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let free = (-xs(&channels[0]).1).min(xs(&channels[1]).0);
    let stroke = options.mark_stroke;
    let half = free - options.min_wall - 0.5 * stroke;
    let (upper, lower) = (tile.to_string(), tile.turned().to_string());
    let width_at = |cap: f64| mark::label_width(&upper, cap).max(mark::label_width(&lower, cap));
    let mut cap = options.mark_height;
    if half <= 0.0 {
        return (Vec::new(), 0.0);
    }
    let w = width_at(cap);
    if w > 2.0 * half {
        cap *= 2.0 * half / w;
    }
    let gap = |cap: f64| 0.3 * cap + 0.5 * stroke + 0.5 * options.min_wall;
    // the octagon's half height over the strip, less the wall: the labels stand in it
    let half_side = 0.5 * design.tile_width * (std::f64::consts::SQRT_2 - 1.0);
    let room = (0.5 * design.tile_width).min(0.5 * design.tile_width + half_side - half)
        - options.min_wall
        - 0.5 * stroke;
    if gap(cap) + cap > room {
        cap = (room - 0.5 * stroke - 0.5 * options.min_wall) / 1.3;
    }
    for _ in 0..8 {
        if cap < MIN_MARK_HEIGHT {
            break;
        }
        let m = mark::part_mark(&upper, &lower, cap, gap(cap), stroke, options.arc_tolerance);
        let d = region::boundary_distance(
            region::contours(&m),
            channels
                .iter()
                .flat_map(|c| region::contours(&c.region))
                .chain(std::iter::once(outline)),
        );
        let centre_inside = m
            .first()
            .and_then(|s| s.first())
            .and_then(|c| c.first())
            .is_some_and(|&p| region::inside(std::iter::once(outline), p));
        if d >= options.min_wall && centre_inside {
            return (m, cap);
        }
        cap *= 0.85;
    }
    (Vec::new(), 0.0)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn every_thesis_tile_is_sound() {
        for tile in Tile::ALL {
            let p = TilePart::new(tile, &Design::thesis(), &PartOptions::default()).unwrap();
            let topo = p.mesh.topology();
            assert!(topo.is_sound(), "{tile}: {topo:?}");
            assert!(p.mark_height > 2.0, "{tile}: {}", p.mark_height);
            assert!(p.volume() > 0.0);
        }
    }

    #[test]
    fn a_wall_too_thin_is_refused() {
        let d = Design {
            wall: 0.1,
            ..Design::thesis()
        };
        let e = TilePart::new("SL".parse().unwrap(), &d, &PartOptions::default()).unwrap_err();
        assert!(e.to_string().contains("mm thick"), "{e}");
    }
}
