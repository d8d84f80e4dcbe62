//! The viewer's packed data: sampling each travel law once (the keys of
//! `RunSource::magnet_travel_key`) gives the page the same tracks as sampling every magnet.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::collections::HashSet;

use foldchain::engine::{
    run, EnergySample, EngineMethod, EngineOptions, FoldRecord, Geometry, Timeline,
};
use foldchain::timeline::{ChainState, RunSource, TileDesigns, Track, TransitionData};
use foldchain::Chain;
use foldchain_render::viewer::{RunData, RunView};

/// A timeline that does not say which magnets travel alike: every track sampled.
struct NoKeys<'a>(&'a Timeline);

impl RunSource for NoKeys<'_> {
    fn tiles(&self) -> usize {
        self.0.tiles()
    }
    fn end_time(&self) -> f64 {
        RunSource::end_time(self.0)
    }
    fn geometry(&self) -> &Geometry {
        RunSource::geometry(self.0)
    }
    fn state_at(&self, t: f64) -> ChainState {
        self.0.state_at(t)
    }
    fn final_state(&self) -> ChainState {
        self.0.final_state()
    }
    fn transition(&self, first: usize, last: usize) -> TransitionData {
        self.0.transition(first, last)
    }
    fn energy(&self, samples: usize) -> Vec<EnergySample> {
        self.0.energy(samples)
    }
    fn folds(&self) -> &[FoldRecord] {
        RunSource::folds(self.0)
    }
    fn timeline_json(&self) -> String {
        RunSource::timeline_json(self.0)
    }
    fn magnet_travel(&self, k: usize) -> Track {
        self.0.magnet_travel(k)
    }
    fn joint_angle(&self, j: usize) -> Track {
        self.0.joint_angle(j)
    }
}

#[test]
fn travel_laws_sampled_once_give_the_page_every_magnets_track() {
    for (word, method) in [
        ("S*40 LL S*40 RR S*40", EngineMethod::Local),
        ("S*60 RR S*30", EngineMethod::Kinematic),
    ] {
        let tl = run(
            &Chain::parse(word).unwrap(),
            &TileDesigns::default(),
            &EngineOptions::default().with_method(method),
        )
        .unwrap();
        let magnets = tl.geometry.magnets();
        // the sharing is real: a serpentine's magnets travel by a few laws. Since both sides
        // of a turning joint turn (8a098cf), the magnets near each fold, whose sides differ,
        // travel by laws of their own: S*40 LL S*40 RR S*40 has 63 laws for 250 magnets (it
        // had fewer than a quarter before), so the bound is a third
        let keys: HashSet<_> = (0..magnets)
            .filter_map(|k| tl.magnet_travel_key(k).map(|(key, _)| key))
            .collect();
        assert!(
            !keys.is_empty() && 3 * keys.len() < magnets,
            "{word}: {} keys for {magnets} magnets",
            keys.len()
        );
        for k in 0..magnets {
            if let Some((_, start)) = tl.magnet_travel_key(k) {
                assert_eq!(start, tl.magnet_travel(k).start, "{word}: magnet {k}");
            }
        }
        let shared = RunData::from_view(&RunView::new(&tl, "run"));
        let each = RunData::from_view(&RunView::new(&NoKeys(&tl), "run"));
        assert_eq!(shared, each, "{word}");
    }
}
