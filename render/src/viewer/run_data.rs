//! A run as the page receives it: the chain's fixed geometry (tile width, the RI, the magnet
//! paths in closed form) and what moves (every magnet's travel and every folding joint's
//! angle as [`Track`]s), packed small. Tracks of the same shape are stored once and shared
//! (on the event engine's serpentines nearly all are), so the page carries per magnet a
//! start time (f64), a shape and a path number, and per folding joint the same; the typed
//! arrays travel as base64.

use std::collections::HashMap;

use foldchain::timeline::{RunSource, Track};
use foldchain::Pose;
use rustc_hash::FxHashMap;

use crate::viewer::typed_arrays::{encode_f32, encode_f64, encode_uint};
use crate::viewer::{PathForm, RunView};

/// A packed integer array: bytes per value (1, 2 or 4) and the little-endian bytes in base64.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PackedInts {
    /// Bytes per value.
    pub width: u8,
    /// The values, base64.
    pub data: String,
}

impl PackedInts {
    fn new(values: &[u32]) -> PackedInts {
        let (width, data) = encode_uint(values);
        PackedInts { width, data }
    }
}

/// Everything the page draws of one run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RunData {
    /// Short label (`engine`, `reference`).
    pub label: String,
    /// Title line.
    pub title: String,
    /// The outcome in words.
    pub note: String,
    /// Tiles.
    pub tiles: usize,
    /// Tile width (across flats), mm.
    pub w: f64,
    /// The RI's position in tile 0's frame, mm.
    pub ri: (f64, f64),
    /// Magnet radius, mm.
    pub magnet_r: f64,
    /// When the run ends, s.
    pub end: f64,
    /// The first collision: `(time s or None for the final shape only, (tile, tile))`.
    pub collision: Option<(Option<f64>, (usize, usize))>,
    /// The box holding the whole run, world mm: `[min x, min y, max x, max y]`.
    pub view: [f64; 4],
    /// Target outline rings, world mm (empty when the chain was not planned from a shape).
    pub target: Vec<Vec<(f64, f64)>>,
    /// The distinct magnet paths.
    pub paths: Vec<PathForm>,
    /// Each magnet's path (an index into `paths`).
    pub magnet_path: PackedInts,
    /// Each magnet's track shape (an index into the shapes).
    pub magnet_shape: PackedInts,
    /// Each magnet's start time, s (f64, base64).
    pub magnet_start: String,
    /// The joints that turn at some time.
    pub joint: PackedInts,
    /// Their track shapes.
    pub joint_shape: PackedInts,
    /// Their start times, s (f64, base64).
    pub joint_start: String,
    /// Shape `i` has points `shape_offset[i]..shape_offset[i + 1]`.
    pub shape_offset: PackedInts,
    /// Seconds after the start of each shape point (f32, base64).
    pub shape_dt: String,
    /// Value of each shape point (f32, base64): mm of travel or radians.
    pub shape_value: String,
}

/// Tracks stored once per distinct shape (points rounded to f32, as the page reads them).
#[derive(Default)]
struct Shapes {
    index: HashMap<Vec<(u32, u32)>, u32>,
    offset: Vec<u32>,
    dt: Vec<f32>,
    value: Vec<f32>,
}

impl Shapes {
    fn add(&mut self, track: &Track) -> u32 {
        let key: Vec<(u32, u32)> = track
            .points
            .iter()
            .map(|&(t, v)| ((t as f32).to_bits(), (v as f32).to_bits()))
            .collect();
        let next = self.index.len() as u32;
        *self.index.entry(key).or_insert_with(|| {
            self.offset.push(self.dt.len() as u32);
            for &(t, v) in &track.points {
                self.dt.push(t as f32);
                self.value.push(v as f32);
            }
            next
        })
    }
}

impl RunData {
    /// The page's data for `view`.
    pub fn from_view(view: &RunView<'_>) -> RunData {
        let src = view.source;
        let g = src.geometry();
        let tiles = src.tiles();
        let mut shapes = Shapes::default();
        shapes.add(&Track::constant(0.0));
        let (mut m_shape, mut m_start) = (Vec::new(), Vec::new());
        // each travel law sampled once: the shape of the first magnet of a key serves all
        let mut by_key: FxHashMap<[u64; 4], u32> = FxHashMap::default();
        for k in 0..g.magnets() {
            let key = src.magnet_travel_key(k);
            if let Some(&id) = key.as_ref().and_then(|(key, _)| by_key.get(key)) {
                m_shape.push(id);
                m_start.push(key.map_or(0.0, |(_, start)| start));
                continue;
            }
            let tr = src.magnet_travel(k);
            let id = shapes.add(&tr);
            if let Some((key, _)) = key {
                by_key.insert(key, id);
            }
            m_shape.push(id);
            m_start.push(tr.start);
        }
        let (mut joints, mut j_shape, mut j_start) = (Vec::new(), Vec::new(), Vec::new());
        let mut j_tracks = Vec::new();
        for j in 0..tiles.saturating_sub(1) {
            let tr = src.joint_angle(j);
            if tr.is_constant() && tr.value_at(0.0) == 0.0 {
                continue;
            }
            joints.push(j as u32);
            j_shape.push(shapes.add(&tr));
            j_start.push(tr.start);
            j_tracks.push((j, tr));
        }
        let paths: Vec<PathForm> = g.path_table().iter().map(PathForm::from_path).collect();
        let m_path: Vec<u32> = (0..g.magnets()).map(|k| g.path_id(k)).collect();
        let mut offset = shapes.offset.clone();
        offset.push(shapes.dt.len() as u32);
        let bounds = run_box(src, &j_tracks, &view.target);
        RunData {
            label: view.label.clone(),
            title: view.title.clone(),
            note: view.note.clone(),
            tiles,
            w: g.w,
            ri: g.ri_position(),
            magnet_r: 0.5 * g.design(0).magnet_diameter,
            end: src.end_time(),
            collision: view.collision,
            view: bounds,
            target: view.target.clone(),
            paths,
            magnet_path: PackedInts::new(&m_path),
            magnet_shape: PackedInts::new(&m_shape),
            magnet_start: encode_f64(&m_start),
            joint: PackedInts::new(&joints),
            joint_shape: PackedInts::new(&j_shape),
            joint_start: encode_f64(&j_start),
            shape_offset: PackedInts::new(&offset),
            shape_dt: encode_f32(&shapes.dt),
            shape_value: encode_f32(&shapes.value),
        }
    }
}

impl RunData {
    /// This data with the label, title, note and first collision of `view`, a view of the
    /// same run: the page's data made before the run's outcome was known (the tracks, paths
    /// and box, the bulk of the work, do not depend on it).
    pub fn with_outcome_of(mut self, view: &RunView<'_>) -> RunData {
        self.label = view.label.clone();
        self.title = view.title.clone();
        self.note = view.note.clone();
        self.collision = view.collision;
        self
    }
}

/// The box holding the chain over the whole run (tile centres padded by a tile width) and
/// the target: the chain at [`box_times`].
fn run_box(src: &dyn RunSource, joints: &[(usize, Track)], target: &[Vec<(f64, f64)>]) -> [f64; 4] {
    let w = src.geometry().w;
    let times = box_times(src.end_time(), joints);
    let mut b = centres_box(src.tiles(), w, joints, times);
    for &(x, y) in target.iter().flatten() {
        b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
    if !b[0].is_finite() {
        b = [0.0; 4];
    }
    let pad = 1.2 * w;
    [b[0] - 2.0 * pad, b[1] - pad, b[2] + pad, b[3] + pad]
}

/// The times the run's box looks at: 129 evenly spaced from 0 to `end`, and the middle and
/// end of each of the first 64 folds, whose long tails sweep the widest arcs.
fn box_times(end: f64, joints: &[(usize, Track)]) -> Vec<f64> {
    let mut times: Vec<f64> = (0..=128).map(|i| end * i as f64 / 128.0).collect();
    let mut by_start: Vec<&Track> = joints.iter().map(|(_, t)| t).collect();
    by_start.sort_by(|a, b| a.start.total_cmp(&b.start));
    for tr in by_start.iter().take(64) {
        times.push(0.5 * (tr.start + tr.end()));
        times.push(tr.end());
    }
    times
}

/// The box `[min x, min y, max x, max y]` of the centres of `tiles` tiles of width `w` at
/// `times`, the joints that turn following `joints` (the rest straight): the box of
/// [`foldchain::kinematics::poses_at_angles`] at every time, bit for bit, without every pass.
fn centres_box(tiles: usize, w: f64, joints: &[(usize, Track)], mut times: Vec<f64>) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut grow = |p: Pose| {
        b = [b[0].min(p.x), b[1].min(p.y), b[2].max(p.x), b[3].max(p.y)];
    };
    // the times in order, so that a pass changes few joints: it recomputes only the tiles
    // after the first joint that turned since the pass before, the tiles up to it being where
    // they were then (their poses depend on the joints before them only), already in the box
    times.sort_by(f64::total_cmp);
    let mut angles = vec![0.0_f64; tiles.saturating_sub(1)];
    let mut poses: Vec<Pose> = Vec::new();
    for t in times {
        let mut first = poses.is_empty().then_some(0);
        for (j, tr) in joints {
            let a = tr.value_at(t);
            if a.to_bits() != angles[*j].to_bits() {
                angles[*j] = a;
                first = Some(first.map_or(*j, |f: usize| f.min(*j)));
            }
        }
        match first {
            None => {}
            Some(_) if poses.is_empty() => Pose::for_each_at_angles(&angles, w, |p| {
                grow(p);
                poses.push(p);
            }),
            Some(first) => {
                let mut i = first;
                poses[first].compose_at_angles(&angles[first..], w, |p| {
                    i += 1;
                    grow(p);
                    poses[i] = p;
                });
            }
        }
    }
    b
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::engine::{run, EngineOptions};
    use foldchain::timeline::TileDesigns;
    use foldchain::Chain;

    #[test]
    fn the_box_is_every_passes_poses_bit_for_bit() {
        for word in ["S*30 LL S*30 RR S*30", "LSLLSR", "S*12 L S*5 R S*12", "S"] {
            let chain = Chain::parse(word).unwrap();
            let tl = run(&chain, &TileDesigns::default(), &EngineOptions::default()).unwrap();
            let tiles = tl.tiles();
            let joints: Vec<(usize, Track)> = (0..tiles.saturating_sub(1))
                .map(|j| (j, RunSource::joint_angle(&tl, j)))
                .filter(|(_, tr)| !tr.is_constant())
                .collect();
            let w = tl.geometry.w;
            let times = box_times(tl.duration(), &joints);
            let mut expect = [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ];
            for &t in &times {
                let mut angles = vec![0.0; tiles.saturating_sub(1)];
                for (j, tr) in &joints {
                    angles[*j] = tr.value_at(t);
                }
                for p in Pose::chain_at_angles(&angles, w) {
                    expect = [
                        expect[0].min(p.x),
                        expect[1].min(p.y),
                        expect[2].max(p.x),
                        expect[3].max(p.y),
                    ];
                }
            }
            let got = centres_box(tiles, w, &joints, times);
            assert_eq!(got.map(f64::to_bits), expect.map(f64::to_bits), "{word}");
        }
    }
}
